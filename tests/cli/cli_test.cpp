// The `fresnel` executable end to end: exit codes (0 ok, 1 bad input, 2 bad usage),
// error message format, `info --json` counts and `render` output files.
// FRESNEL_EXE is the built program ($<TARGET_FILE:fresnel>).
#include "cli_harness.h"
#include "gltf_builders.h"
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fresnel/core/image.h"
#include "fresnel/core/metrics.h"
#include "fresnel/core/version.h"

namespace fs = std::filesystem;

namespace {

const fs::path kShared = FRESNEL_SHARED_DIR;

using fresnel::test::command_line;
using fresnel::test::quote;
using fresnel::test::run_captured;
using fresnel::test::show;
using fresnel::test::Result;
using fresnel::test::slurp;

class Cli : public fresnel::test::TempDirTest {
protected:
    Cli() : TempDirTest("fresnel_cli") {}

    // Runs the program with `args`, capturing stdout, stderr and the exit status;
    // `cache`, when given, becomes its XDG_CACHE_HOME.
    Result run(const std::vector<std::string>& args, const fs::path& cache = {}) {
        std::string program = cache.empty() ? std::string() : "XDG_CACHE_HOME=" + quote(cache.string()) + " ";
        program.append(quote(FRESNEL_EXE));
        return run_captured(command_line(program, args), dir_);
    }
};


TEST_F(Cli, HelpExitsZero) {
    Result r = run({"--help"});
    EXPECT_EQ(r.exit_code, 0) << show(r);
    EXPECT_NE(r.out.find("render"), std::string::npos) << show(r);
    EXPECT_NE(r.out.find("info"), std::string::npos) << show(r);

    r = run({"render", "--help"});
    EXPECT_EQ(r.exit_code, 0) << show(r);
    EXPECT_NE(r.out.find("--size"), std::string::npos) << show(r);

    r = run({"info", "--help"});
    EXPECT_EQ(r.exit_code, 0) << show(r);
    EXPECT_NE(r.out.find("--json"), std::string::npos) << show(r);
}

// Every --help is grouped by topic and wrapped at 100 columns; `fresnel help COMMAND` is the
// same text; an unknown topic is a usage error that names the nearest command.
TEST_F(Cli, HelpIsGroupedWrappedAndReachableByHelp) {
    const std::vector<std::string> commands = {"render", "info", "bake", "compare", "trace", "batch",
                                               "fit", "convert", "view", "settings", "help"};
    for (const std::string& c : commands) {
        Result r = run({c, "--help"});
        ASSERT_EQ(r.exit_code, 0) << c << show(r);
        std::istringstream lines(r.out);
        for (std::string line; std::getline(lines, line);) EXPECT_LE(line.size(), 100u) << c << ": " << line;
        if (c == "help") continue;
        Result h = run({"help", c});
        EXPECT_EQ(h.exit_code, 0) << show(h);
        EXPECT_EQ(h.out, r.out) << c;
    }
    Result r = run({"render", "--help"});
    for (const char* group : {"\nCamera:\n", "\nModel:\n", "\nAnimation:\n", "\nLights:\n", "\nEnvironment and background:\n",
                              "\nOutput:\n", "\nGraphics API:\n"})
        EXPECT_NE(r.out.find(group), std::string::npos) << group << r.out;
    Result top = run({"--help"});
    for (std::istringstream lines(top.out); !lines.eof();) {
        std::string line;
        std::getline(lines, line);
        EXPECT_LE(line.size(), 100u) << line;
    }
    Result bad = run({"help", "rendr"});
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err.find("did you mean 'render'"), std::string::npos) << show(bad);
    // One meaning per flag name: view's "exit after N frames" is --exit-after; --frames is render's.
    Result view = run({"view", "--help"});
    EXPECT_NE(view.out.find("--exit-after"), std::string::npos);
    EXPECT_EQ(view.out.find("\n  --frames"), std::string::npos) << view.out;
}

// convert says what it wrote: each file of the set with its size.
TEST_F(Cli, ConvertListsTheFilesItWrote) {
    const fs::path model = kShared / "assets" / "models" / "Duck" / "Duck.glb";
    if (!fs::exists(model)) GTEST_SKIP() << "needs " << model;
    Result r = run({"convert", model.string(), (dir_ / "duck.gltf").string()});
    ASSERT_EQ(r.exit_code, 0) << show(r);
    for (const char* f : {"duck.gltf", "duck.bin"}) {
        const std::string line_end = (dir_ / f).string() + "\n";
        EXPECT_NE(r.err.find(line_end), std::string::npos) << f << show(r);
    }
    EXPECT_NE(r.err.find(" KiB  in 2 files"), std::string::npos) << show(r);  // the GLB's texture stays in the .bin
}

// --version prints the version written once in CMakeLists.txt (project(VERSION)).
TEST_F(Cli, VersionIsTheProjectVersion) {
    Result r = run({"--version"});
    EXPECT_EQ(r.exit_code, 0) << show(r);
    EXPECT_EQ(r.out, std::string("fresnel ") + FRESNEL_VERSION_STRING + "\n") << show(r);
    EXPECT_EQ(fresnel::version(), FRESNEL_VERSION_STRING);
}

TEST_F(Cli, InfoJsonCountsDamagedHelmet) {
    fs::path model = kShared / "assets" / "models" / "DamagedHelmet" / "DamagedHelmet.glb";
    if (!fs::exists(model)) GTEST_SKIP() << "shared assets not found: " << model.string() << " (FRESNEL_SHARED_DIR)";
    Result r = run({"info", model.string(), "--json"});
    ASSERT_EQ(r.exit_code, 0) << show(r);
    nlohmann::json j;
    ASSERT_NO_THROW(j = nlohmann::json::parse(r.out)) << show(r);
    EXPECT_EQ(j.at("vertices").get<long>(), 14556);
    EXPECT_EQ(j.at("triangles").get<long>(), 15452);
    EXPECT_EQ(j.at("meshes").get<long>(), 1);
    EXPECT_EQ(j.at("primitives").get<long>(), 1);
    EXPECT_TRUE(j.contains("bounds")) << show(r);
    // Each material with its texture slots, the file's size and its decoded geometry.
    const auto& m = j.at("material_list").at(0);
    EXPECT_EQ(m.at("name"), "Material_MR");
    EXPECT_EQ(m.at("alpha_mode"), "OPAQUE");
    EXPECT_EQ(m.at("textures").size(), 5u) << m.dump();
    EXPECT_EQ(j.at("image_list").size(), 5u);
    // Each image's format and size from its header, and what it takes in files and loaded.
    const auto& images = j.at("image_details");
    ASSERT_EQ(images.size(), 5u);
    std::size_t in_files = 0;
    for (const auto& im : images) {
        EXPECT_EQ(im.at("format"), "JPEG") << im.dump();
        EXPECT_EQ(im.at("width"), 2048) << im.dump();
        EXPECT_EQ(im.at("height"), 2048) << im.dump();
        EXPECT_EQ(im.at("memory_bytes").get<std::size_t>(), std::size_t(2048) * 2048 * 4 * 4 / 3) << im.dump();
        in_files += im.at("file_bytes").get<std::size_t>();
    }
    EXPECT_EQ(j.at("image_file_bytes").get<std::size_t>(), in_files);
    EXPECT_GT(in_files, std::size_t(3) << 20);  // the helmet's 3.6 MiB are mostly its textures
    Result text = run({"info", model.string()});
    EXPECT_NE(text.out.find("image       0 image 0: JPEG, 2048x2048, "), std::string::npos) << show(text);
    EXPECT_EQ(j.at("file_bytes").get<std::size_t>(), fs::file_size(model));
    EXPECT_GT(j.at("geometry_bytes").get<std::size_t>(), std::size_t(14556) * 12);
}

TEST_F(Cli, RenderDemoWritesPng) {
    fs::path png = dir_ / "demo.png";
    Result r = run({"render", "-o", png.string(), "--size", "96x64", "--json"});
    ASSERT_EQ(r.exit_code, 0) << show(r);
    ASSERT_TRUE(fs::exists(png)) << show(r);
    fresnel::Image8 img = fresnel::read_image8(png);
    EXPECT_EQ(img.width, 96);
    EXPECT_EQ(img.height, 64);
    std::size_t lit = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const std::uint8_t* p = img.at(x, y);
            lit += p[0] > 8 || p[1] > 8 || p[2] > 8;
        }
    EXPECT_GT(lit, std::size_t(96 * 64 / 20)) << "the demo render is (nearly) blank";
    nlohmann::json j;
    ASSERT_NO_THROW(j = nlohmann::json::parse(r.out)) << show(r);
    EXPECT_EQ(j.at("width").get<int>(), 96);
    EXPECT_EQ(j.at("height").get<int>(), 64);
    EXPECT_EQ(j.at("model").get<std::string>(), "(demo)");
}

TEST_F(Cli, MissingModelIsBadInput) {
    fs::path missing = dir_ / "no_such_model.glb";
    fs::path png = dir_ / "out.png";
    Result r = run({"render", missing.string(), "-o", png.string(), "--size", "32x32"});
    EXPECT_EQ(r.exit_code, 1) << show(r);
    EXPECT_EQ(r.err.rfind("fresnel: error:", 0), 0u) << show(r);
    EXPECT_FALSE(fs::exists(png)) << "an output was written for a model that does not exist";

    r = run({"info", missing.string()});
    EXPECT_EQ(r.exit_code, 1) << show(r);
    EXPECT_EQ(r.err.rfind("fresnel: error:", 0), 0u) << show(r);
}

// An output that cannot be written is found before the work whose result it would hold: the
// missing folder is named, though the model (missing too) would have failed later.
TEST_F(Cli, AnUnwritableOutputIsFoundFirst) {
    for (const char* command : {"render", "trace"}) {
        Result r = run({command, (dir_ / "no_such_model.glb").string(), "-o", (dir_ / "nofolder" / "x.png").string()});
        EXPECT_EQ(r.exit_code, 1) << show(r);
        EXPECT_NE(r.err.find("nofolder does not exist"), std::string::npos) << show(r);
        EXPECT_EQ(r.err.find("no_such_model"), std::string::npos) << show(r);
    }
}

// Ctrl+C during a trace ends it after the pass in progress and writes what was traced (exit 130,
// "interrupted" in --json), instead of losing every sample.
TEST_F(Cli, InterruptedTraceWritesWhatItTraced) {
    const fs::path png = dir_ / "partial.png";
    const std::string program = "sh -c " + quote(quote(FRESNEL_EXE) + " trace -o " + quote(png.string()) +
                                                 " --size 48x32 --spp 1000000 --json & p=$!; sleep 3; kill -INT $p; "
                                                 "wait $p");
    Result r = run_captured(program, dir_);
    EXPECT_EQ(r.exit_code, 130) << show(r);
    ASSERT_TRUE(fs::exists(png)) << show(r);
    EXPECT_EQ(fresnel::read_image8(png).width, 48);
    nlohmann::json j;
    ASSERT_NO_THROW(j = nlohmann::json::parse(r.out)) << show(r);
    EXPECT_TRUE(j.at("interrupted").get<bool>());
    EXPECT_GE(j.at("spp").get<int>(), 1);
    EXPECT_LT(j.at("spp").get<int>(), 1000000);
    EXPECT_NE(r.err.find("interrupted"), std::string::npos) << show(r);
}

// OBJ -> glTF: a material without specular stays matte (no specular lobe, roughness 1) under
// both intents; the default (albedo) keeps Kd as the base colour; Kd above 1 is clamped with a
// warning naming the material; convert says what it wrote.
TEST_F(Cli, ConvertKeepsMatteMaterialsMatte) {
    std::ofstream(dir_ / "m.obj") << "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\n"
                                     "usemtl matte\nf 1//1 2//1 3//1\nusemtl hot\nf 1//1 3//1 2//1\n";
    std::ofstream(dir_ / "m.mtl") << "newmtl matte\nKd 0.8 0 0\nKs 0 0 0\nNs 10\nillum 2\n"
                                     "newmtl hot\nKd 2 0.5 0.5\nKs 0.5 0.5 0.5\nNs 32\nillum 2\n";
    auto material = [&](const fs::path& gltf, int i) {
        return nlohmann::json::parse(slurp(gltf)).at("materials").at(i);
    };
    Result r = run({"convert", (dir_ / "m.obj").string(), (dir_ / "a.gltf").string()});
    ASSERT_EQ(r.exit_code, 0) << show(r);
    EXPECT_NE(r.err.find("Kd outside [0, 1] is clamped"), std::string::npos) << show(r);
    EXPECT_NE(r.err.find("'hot'"), std::string::npos) << show(r);
    EXPECT_NE(r.err.find("wrote " + (dir_ / "a.gltf").string() + ": 1 meshes (2 primitives, 2 triangles), 2 materials"),
              std::string::npos)
        << show(r);
    nlohmann::json m = material(dir_ / "a.gltf", 0);
    EXPECT_NEAR(m["pbrMetallicRoughness"]["baseColorFactor"][0].get<double>(), 0.8, 1e-6) << m.dump();
    EXPECT_EQ(m["pbrMetallicRoughness"].value("roughnessFactor", 1.0), 1.0) << m.dump();
    EXPECT_EQ(m["extensions"]["KHR_materials_specular"]["specularFactor"].get<double>(), 0.0) << m.dump();
    EXPECT_NEAR(material(dir_ / "a.gltf", 1)["pbrMetallicRoughness"]["baseColorFactor"][0].get<double>(), 1.0, 1e-6);

    r = run({"convert", (dir_ / "m.obj").string(), (dir_ / "b.gltf").string(), "--match", "opengl1", "--quiet"});
    ASSERT_EQ(r.exit_code, 0) << show(r);
    m = material(dir_ / "b.gltf", 0);
    EXPECT_EQ(m["pbrMetallicRoughness"].value("roughnessFactor", 1.0), 1.0) << m.dump();
    EXPECT_EQ(m["extensions"]["KHR_materials_specular"]["specularFactor"].get<double>(), 0.0) << m.dump();
    EXPECT_EQ(run({"convert", (dir_ / "m.obj").string(), (dir_ / "c.gltf").string(), "--match", "blender"}).exit_code, 2);
}

TEST_F(Cli, BadSizeIsUsageError) {
    fs::path png = dir_ / "out.png";
    for (const char* size : {"0x10", "10x0", "abc", "10x", "x10", "10x10x10", "10*10", "20000x10", "0", "-5", "2.5", "20000"}) {
        Result r = run({"render", "-o", png.string(), "--size", size});
        EXPECT_EQ(r.exit_code, 2) << "--size " << size << "\n" << show(r);
        EXPECT_EQ(r.err.rfind("fresnel: error: --size", 0), 0u) << "--size " << size << "\n" << show(r);
    }
    EXPECT_FALSE(fs::exists(png));
    // One number is a square.
    Result r = run({"render", "-o", png.string(), "--size", "24"});
    ASSERT_EQ(r.exit_code, 0) << show(r);
    const fresnel::Image8 img = fresnel::read_image8(png);
    EXPECT_EQ(img.width, 24);
    EXPECT_EQ(img.height, 24);
}

TEST_F(Cli, OtherUsageErrorsExitTwo) {
    EXPECT_EQ(run({}).exit_code, 2);                                              // no subcommand
    EXPECT_EQ(run({"render", "--no-such-option", "-o", "x.png"}).exit_code, 2);  // unknown option
    EXPECT_EQ(run({"render"}).exit_code, 2);                                      // -o missing
    Result r = run({"render", "-o", (dir_ / "x.png").string(), "--tonemap", "sepia"});
    EXPECT_EQ(r.exit_code, 2) << show(r);
    EXPECT_EQ(r.err.rfind("fresnel: error:", 0), 0u) << show(r);
}

// Mistyped commands and options: the program's error prefix, the nearest name, how to get help.
TEST_F(Cli, MistypedNamesSuggestTheNearest) {
    Result r = run({"rendr", "x.glb"});
    EXPECT_EQ(r.exit_code, 2) << show(r);
    EXPECT_EQ(r.err.rfind("fresnel: error: 'rendr' is not a fresnel command; did you mean 'render'?", 0), 0u) << show(r);
    r = run({"render", "--szie", "10x10", "-o", (dir_ / "x.png").string()});
    EXPECT_EQ(r.exit_code, 2) << show(r);
    EXPECT_EQ(r.err.rfind("fresnel: error: unknown option --szie; did you mean --size?", 0), 0u) << show(r);
    EXPECT_NE(r.err.find("fresnel render --help"), std::string::npos) << show(r);
    r = run({"render", "--qqqqqqqqqq", "-o", (dir_ / "x.png").string()});
    EXPECT_EQ(r.err.rfind("fresnel: error: unknown option --qqqqqqqqqq\n", 0), 0u) << show(r);  // nothing near
    EXPECT_FALSE(fs::exists(dir_ / "x.png"));
}

// The legacy shading flags: malformed values are usage errors naming the flag.
TEST_F(Cli, LegacyShadingFlagsAreChecked) {
    const std::string out = (dir_ / "x.png").string();
    for (std::vector<std::string> bad : {std::vector<std::string>{"--shading", "phong"}, {"--fog", "linear:1"},
                                         {"--fog", "exp:-1"}, {"--fog", "mist:1"}, {"--fog", "linear:near,nope"},
                                         {"--ambient", "1,2"}, {"--fog-color", "a,b,c"}}) {
        std::vector<std::string> args = {"render", "-o", out};
        args.insert(args.end(), bad.begin(), bad.end());
        Result r = run(args);
        EXPECT_EQ(r.exit_code, 2) << bad[0] << " " << bad[1] << "\n" << show(r);
        EXPECT_NE(r.err.find(bad[0]), std::string::npos) << show(r);
    }
}

// The files under `dir` (recursively), as paths relative to it.
std::vector<std::string> files_under(const fs::path& dir) {
    std::vector<std::string> out;
    std::error_code ec;
    if (!fs::exists(dir, ec)) return out;
    for (const auto& e : fs::recursive_directory_iterator(dir, ec))
        if (e.is_regular_file()) out.push_back(fs::relative(e.path(), dir).string());
    return out;
}

// --no-cache neither reads nor writes $XDG_CACHE_HOME/fresnel: not the baked environment
// and not the BRDF table (the environment's, or the one energy compensation bakes alone
// under --no-ibl). Without it both land in the cache, so the check can fail.
TEST_F(Cli, NoCacheTouchesNoCache) {
    fs::path png = dir_ / "out.png";
    const std::vector<std::string> env = {"--env", "color:0.5,0.5,0.5", "--env-size", "16"};
    const std::vector<std::string> lut_only = {"--no-ibl"};
    for (const auto* extra : {&env, &lut_only}) {
        fs::path cache = dir_ / ("cache" + std::to_string(extra == &env));
        std::vector<std::string> args = {"render", "-o", png.string(), "--size", "16x16", "--msaa", "1"};
        args.insert(args.end(), extra->begin(), extra->end());
        std::vector<std::string> no_cache = args;
        no_cache.push_back("--no-cache");
        Result r = run(no_cache, cache);
        ASSERT_EQ(r.exit_code, 0) << show(r);
        // (The folder itself may hold Mesa's shader cache, which follows XDG_CACHE_HOME too.)
        EXPECT_FALSE(fs::exists(cache / "fresnel"))
            << "--no-cache created " << (cache / "fresnel").string() << " (" << files_under(cache / "fresnel").size()
            << " files)";

        r = run(args, cache);
        ASSERT_EQ(r.exit_code, 0) << show(r);
        std::vector<std::string> files = files_under(cache / "fresnel");
        bool lut = false, baked = false;
        for (const auto& f : files) {
            lut |= f.rfind("brdf_lut-", 0) == 0;
            baked |= f.rfind("env/", 0) == 0 && f.find("manifest.json") != std::string::npos;
        }
        EXPECT_TRUE(lut) << "no BRDF table cached without --no-cache";
        EXPECT_EQ(baked, extra == &env) << "environment cached: " << baked;
    }
}

}  // namespace

// ---------------------------------------------------------------------------
// White furnace through the CLI, as a user measures it: a UV sphere in a uniform white
// environment, `--tonemap none` into a float image. With energy compensation a white
// sphere renders 1.0 at every roughness, metal or not; a grey (0.5) rough dielectric
// renders 0.5 (plus the few percent its Fresnel reflection adds at smoother settings).

namespace {

// A unit UV sphere with one metallic-roughness material, buffer embedded as a data URI.
void write_sphere(const fs::path& path, float base, float metallic, float roughness) {
    const nlohmann::json material = {{"pbrMetallicRoughness", {{"baseColorFactor", {base, base, base, 1.0}},
                                                               {"metallicFactor", metallic},
                                                               {"roughnessFactor", roughness}}}};
    std::ofstream(path) << fresnel::test::uv_sphere_gltf(96, 48, material).dump();
}

// Mean of the sphere's pixels within 60 % of its radius from its centre (where the
// normal faces the camera within ~37 degrees), and how many there were.
std::pair<double, int> interior_mean(const fresnel::ImageF& img) {
    double cx = 0, cy = 0;
    int n = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            if (img.at(x, y)[1] > 0.02f) cx += x, cy += y, ++n;
    if (n == 0) return {0.0, 0};
    cx /= n, cy /= n;
    const double r = std::sqrt(n / M_PI) * 0.6;
    double sum = 0;
    int m = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            if ((x - cx) * (x - cx) + (y - cy) * (y - cy) < r * r) {
                const float* p = img.at(x, y);
                sum += (p[0] + p[1] + p[2]) / 3.0;
                ++m;
            }
    return {m ? sum / m : 0.0, m};
}

}  // namespace

TEST_F(Cli, WhiteFurnaceThroughRender) {
    struct Case {
        float base, metallic, roughness, expected, tolerance;
    };
    const Case cases[] = {
        {1, 0, 0, 1.0f, 0.01f}, {1, 0, 0.5f, 1.0f, 0.01f}, {1, 0, 1, 1.0f, 0.01f},
        {1, 1, 0, 1.0f, 0.01f}, {1, 1, 0.5f, 1.0f, 0.01f}, {1, 1, 1, 1.0f, 0.01f},
        {0.5f, 0, 1, 0.5f, 0.01f},
        // Smoother: the dielectric's Fresnel reflection adds to the diffuse 0.5 (glTF's
        // fresnel_mix), about 3 % at roughness 0.5.
        {0.5f, 0, 0.5f, 0.515f, 0.015f},
    };
    for (const Case& c : cases) {
        fs::path model = dir_ / "sphere.gltf", out = dir_ / "furnace.hdr";
        write_sphere(model, c.base, c.metallic, c.roughness);
        Result r = run({"render", model.string(), "-o", out.string(), "--env", "color:1,1,1", "--tonemap", "none",
                        "--size", "128x128", "--background", "0,0,0"});
        ASSERT_EQ(r.exit_code, 0) << show(r);
        auto [mean, pixels] = interior_mean(fresnel::read_image_float(out));
        ASSERT_GT(pixels, 500);
        EXPECT_NEAR(mean, c.expected, c.expected * c.tolerance)
            << "base " << c.base << " metallic " << c.metallic << " roughness " << c.roughness;
    }
}

// An OBJ/MTL model through `fresnel render` and `fresnel info`: a red cube (quads, one
// face a concave hexagon-with-notch, no normals, smoothing off) on a black background must
// cover a good part of the frame, be red, and have no NaN (magenta) pixel; a bad index is
// an error that names the line.
TEST_F(Cli, RendersAndDescribesObj) {
    std::ofstream(dir_ / "cube.mtl") << "newmtl red\nKa 0.2 0.2 0.2\nKd 0.9 0.1 0.1\nKs 0.2 0.2 0.2\nNs 32\nillum 2\n";
    std::ofstream(dir_ / "cube.obj")
        << "mtllib cube.mtl\no cube\n"
           "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
           "v 0 0.5 1\n"  // the notch of the front face
           "usemtl red\n"
           "f 5 6 7 9 8\n"  // front, concave at vertex 9
           "f 2 1 4 3\nf 1 5 8 4\nf 6 2 3 7\nf 4 8 7 3\nf 1 2 6 5\n";
    fs::path png = dir_ / "cube.png";
    Result r = run({"render", (dir_ / "cube.obj").string(), "-o", png.string(), "--size", "96x96", "--yaw", "30",
                    "--pitch", "20", "--background", "0,0,0"});
    ASSERT_EQ(r.exit_code, 0) << show(r);
    fresnel::Image8 img = fresnel::read_image8(png);
    ASSERT_EQ(img.width, 96);
    std::size_t covered = 0, red = 0, magenta = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const std::uint8_t* p = img.at(x, y);
            bool lit = p[0] > 8 || p[1] > 8 || p[2] > 8;
            covered += lit;
            red += lit && p[0] > p[1] + 20 && p[0] > p[2] + 20;
            magenta += p[0] == 255 && p[1] == 0 && p[2] == 255;
        }
    EXPECT_GT(covered, std::size_t(96 * 96 / 5)) << "the cube covers too little of the frame";
    EXPECT_GT(red, covered * 8 / 10) << "the cube is not red (Kd 0.9 0.1 0.1)";
    EXPECT_EQ(magenta, 0u) << "NaN or Inf pixels";

    r = run({"info", (dir_ / "cube.obj").string(), "--json"});
    ASSERT_EQ(r.exit_code, 0) << show(r);
    nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j.at("meshes").get<int>(), 1);
    EXPECT_EQ(j.at("materials").get<int>(), 1);
    EXPECT_EQ(j.at("triangles").get<int>(), 3 + 5 * 2);  // a pentagon and five quads
    EXPECT_NEAR(j.at("bounds").at("radius").get<double>(), std::sqrt(3.0), 1e-5);

    std::ofstream(dir_ / "bad.obj") << "v 0 0 0\nv 1 0 0\n\nf 1 2 3\n";
    r = run({"render", (dir_ / "bad.obj").string(), "-o", (dir_ / "bad.png").string(), "--size", "32x32"});
    EXPECT_EQ(r.exit_code, 1) << show(r);
    EXPECT_NE(r.err.find("bad.obj: line 4: vertex index 3 is out of range"), std::string::npos) << show(r);
    EXPECT_FALSE(fs::exists(dir_ / "bad.png"));
}

// ---------------------------------------------------------------------------
// `fresnel trace`: the same flags as render give the same scene. In the white furnace the
// rasteriser and the path tracer agree to 1 % where the glTF BRDF loses no energy by single
// scattering (the rasteriser's energy compensation adds what the tracer's single-scattering
// BRDF cannot, so rough white metals are not compared): a white mirror-like metal, a
// smooth metal and a Lambertian sphere (KHR_materials_specular with factor 0).

namespace {
// write_sphere, plus KHR_materials_specular { specularFactor: 0 } on its material.
void write_lambert_sphere(const fs::path& path, float base) {
    write_sphere(path, base, 0.0f, 1.0f);
    nlohmann::json j = nlohmann::json::parse(slurp(path));
    j["extensionsUsed"] = {"KHR_materials_specular"};
    j["materials"][0]["extensions"]["KHR_materials_specular"] = {{"specularFactor", 0.0}};
    std::ofstream(path) << j.dump();
}
}  // namespace

TEST_F(Cli, TraceAgreesWithRenderInTheFurnace) {
    struct Case {
        float base, metallic, roughness;
        bool lambert;
    };
    // Every roughness of metals and dielectrics: the tracer applies the rasteriser's multiple-
    // scattering compensation at every bounce (fresnel::EnergyCompensation), so a rough metal is
    // 0.98-1.0 in the tracer, not 0.36. What remains: the table's E read at its last texel centre
    // (roughness and n.v 0.996) is 1.6 % above the lobe's E at roughness 1, and a rough
    // dielectric's diffuse is weighted per direction by the Fresnel of the BRDF in the tracer
    // (as punctual lights are in the rasteriser), by the split sum's 1 - (F0 A + B) under the
    // rasteriser's image-based light (0.970 against 1.000 at roughness 1).
    const Case cases[] = {{1, 1, 0, false},    {1, 1, 0.15f, false}, {1, 1, 0.5f, false}, {1, 1, 1, false},
                          {1, 0, 0.5f, false}, {1, 0, 1, false},     {1, 0, 1, true},     {0.5f, 0, 1, true}};
    for (const Case& c : cases) {
        fs::path model = dir_ / "sphere.gltf", raster = dir_ / "raster.hdr", traced = dir_ / "traced.hdr";
        if (c.lambert) write_lambert_sphere(model, c.base);
        else write_sphere(model, c.base, c.metallic, c.roughness);
        std::vector<std::string> common = {model.string(), "--env", "color:1,1,1", "--tonemap", "none",
                                           "--size", "128x128", "--background", "0,0,0"};
        std::vector<std::string> a = {"render", "-o", raster.string()}, b = {"trace", "-o", traced.string(), "--spp", "16"};
        a.insert(a.end(), common.begin(), common.end());
        b.insert(b.end(), common.begin(), common.end());
        Result ra = run(a), rb = run(b);
        ASSERT_EQ(ra.exit_code, 0) << show(ra);
        ASSERT_EQ(rb.exit_code, 0) << show(rb);
        auto [mr, nr] = interior_mean(fresnel::read_image_float(raster));
        auto [mt, nt] = interior_mean(fresnel::read_image_float(traced));
        ASSERT_GT(nr, 500);
        ASSERT_GT(nt, 500);
        std::printf("furnace: base %.1f metallic %.0f roughness %.2f%s: render %.4f, trace %.4f\n", c.base, c.metallic,
                    c.roughness, c.lambert ? " (Lambertian)" : "", mr, mt);
        const double tol = c.lambert || c.roughness < 0.6f ? 0.01 : c.metallic > 0 ? 0.02 : 0.035;
        EXPECT_NEAR(mt, mr, tol * mr) << "base " << c.base << " metallic " << c.metallic << " roughness " << c.roughness
                                      << (c.lambert ? " (Lambertian)" : "");
        EXPECT_NEAR(mt, c.base, tol * c.base);
    }
}

// One job, one background: with an environment, render and trace both default to the blurred
// environment (the same prefiltered level of the same bake), `--background environment` to the
// sharp one. Compared over the top and bottom rows, which the model leaves uncovered.
TEST_F(Cli, TraceAndRenderDrawTheSameBackground) {
    const fs::path model = kShared / "assets" / "models" / "Duck" / "Duck.glb";
    const fs::path env = kShared / "assets" / "env" / "studio_small_03_1k.hdr";
    if (!fs::exists(model) || !fs::exists(env)) GTEST_SKIP() << "needs " << model << " and " << env;
    auto band_psnr = [](const fresnel::Image8& a, const fresnel::Image8& b) {
        double se = 0;
        std::size_t n = 0;
        for (int y = 0; y < a.height; ++y) {
            if (y >= 8 && y < a.height - 8) continue;
            for (int x = 0; x < a.width; ++x)
                for (int c = 0; c < 3; ++c, ++n) {
                    const double d = (double(a.at(x, y)[c]) - double(b.at(x, y)[c])) / 255.0;
                    se += d * d;
                }
        }
        return se > 0 ? 10.0 * std::log10(double(n) / se) : 99.0;
    };
    double same[2], crossed = 0;
    fresnel::Image8 images[2][2];
    const char* modes[2] = {"automatic", "environment"};
    for (int m = 0; m < 2; ++m) {
        for (int k = 0; k < 2; ++k) {
            fs::path out = dir_ / (std::string(k ? "t_" : "r_") + modes[m] + ".png");
            std::vector<std::string> args = {k ? "trace" : "render", model.string(), "--env", env.string(), "--size",
                                             "128x96", "--background", modes[m], "-o", out.string()};
            if (k) args.insert(args.end(), {"--spp", "4"});
            Result r = run(args);
            ASSERT_EQ(r.exit_code, 0) << show(r);
            images[m][k] = fresnel::read_image8(out);
        }
        same[m] = band_psnr(images[m][0], images[m][1]);
    }
    crossed = band_psnr(images[0][0], images[1][1]);
    std::printf("background render vs trace: blurred %.1f dB, sharp %.1f dB; blurred render vs sharp trace %.1f dB\n", same[0],
                same[1], crossed);
    EXPECT_GE(same[0], 45.0) << "the default (blurred) background";
    EXPECT_GE(same[1], 33.0) << "the sharp background (the renderer's 256 cube against the 1k panorama)";
    EXPECT_LT(crossed, same[0] - 5.0) << "blurred and sharp are different pictures";
}

TEST_F(Cli, TraceIsDeterministicAndReportsItsWork) {
    fs::path a = dir_ / "a.png", b = dir_ / "b.png", c = dir_ / "c.png";
    std::vector<std::string> args = {"trace", "--size", "64x48", "--spp", "2", "--max-bounces", "4", "--json", "-o"};
    auto with = [&](const fs::path& out, std::vector<std::string> extra) {
        std::vector<std::string> v = args;
        v.push_back(out.string());
        v.insert(v.end(), extra.begin(), extra.end());
        return v;
    };
    Result ra = run(with(a, {"--seed", "3", "--threads", "1"}));
    Result rb = run(with(b, {"--seed", "3", "--threads", "2"}));
    Result rc = run(with(c, {"--seed", "4"}));
    ASSERT_EQ(ra.exit_code, 0) << show(ra);
    ASSERT_EQ(rb.exit_code, 0) << show(rb);
    ASSERT_EQ(rc.exit_code, 0) << show(rc);
    EXPECT_EQ(slurp(a), slurp(b)) << "same seed, different thread counts";
    EXPECT_NE(slurp(a), slurp(c)) << "another seed";
    nlohmann::json j = nlohmann::json::parse(ra.out);
    EXPECT_EQ(j["spp"], 2);
    EXPECT_EQ(j["camera_paths"], 64 * 48 * 2);
    EXPECT_EQ(j["max_bounces"], 4);
    EXPECT_GT(j["msamples_per_s"].get<double>(), 0.0);
    EXPECT_GT(j["rays"].get<double>(), 64 * 48 * 2 - 1);
    EXPECT_GT(j["trace_ms"].get<double>(), 0.0);
    // --time-limit stops early: a tiny limit ends after the first pass (1 sample).
    Result rt = run({"trace", "--size", "64x48", "--spp", "1000", "--time-limit", "0.001", "--json", "-o", a.string()});
    ASSERT_EQ(rt.exit_code, 0) << show(rt);
    nlohmann::json jt = nlohmann::json::parse(rt.out);
    EXPECT_TRUE(jt["time_limited"].get<bool>());
    EXPECT_LT(jt["spp"].get<int>(), 1000);
    // Usage errors as render's.
    EXPECT_EQ(run({"trace", "-o", (dir_ / "x.jpg").string()}).exit_code, 2);
    EXPECT_EQ(run({"trace", "-o", a.string(), "--spp", "0"}).exit_code, 2);
    EXPECT_EQ(run({"trace", "-o", a.string(), "--tonemap", "nope"}).exit_code, 2);
}

// KHR_materials_pbrSpecularGlossiness as the Khronos Sample Renderer shades it: the specular
// colour as F0, 1 - glossiness as roughness, and (its 1.1.0 reading, against the extension's
// text) the diffuse and specular-glossiness textures' RGB as stored, not decoded from sRGB:
// `--sg-textures khronos`, the default. The references (tests/refs/khronos/specular_glossiness)
// were made by build/khronos-ref/render --size 512x512 --yaw 45 --pitch 20 --tonemap neutral
// under studio_small_03 (2026-12-07): Duck 41.6 dB, BoxTextured 43.7 dB with the default; the
// extension's sRGB reading (`--sg-textures srgb`) gave 27.3 and 16.5 dB.
TEST_F(Cli, SpecularGlossinessAsTheKhronosRenderer) {
    const fs::path env = kShared / "assets" / "env" / "studio_small_03_1k.hdr";
    const fs::path refs = fs::path(FRESNEL_SOURCE_DIR) / "tests" / "refs" / "khronos" / "specular_glossiness";
    int compared = 0;
    for (const char* model : {"Duck", "BoxTextured"}) {
        const fs::path file = kShared / "assets" / "models" / model / "specular-glossiness" / (std::string(model) + ".gltf");
        if (!fs::exists(file) || !fs::exists(env)) continue;
        SCOPED_TRACE(model);
        double psnr[2] = {0, 0};
        for (int srgb = 0; srgb < 2; ++srgb) {
            const fs::path out = dir_ / (std::string(model) + (srgb ? "_srgb.png" : "_khronos.png"));
            std::vector<std::string> args = {"render", file.string(), "-o", out.string(), "--size", "512x512",
                                             "--yaw", "45", "--pitch", "20", "--tonemap", "neutral", "--encoding",
                                             "gamma2.2", "--background", "0,0,0", "--env", env.string(),
                                             "--no-scene-lights", "--shadows", "off"};
            if (srgb) args.insert(args.end(), {"--sg-textures", "srgb"});
            Result r = run(args);
            ASSERT_EQ(r.exit_code, 0) << show(r);
            psnr[srgb] = fresnel::compare_images(fresnel::read_image8(out),
                                                 fresnel::read_image8(refs / (std::string(model) + "_q.png")))
                             .psnr_db;
        }
        std::printf("%s: %.1f dB from the Khronos renderer (--sg-textures srgb: %.1f dB)\n", model, psnr[0], psnr[1]);
        EXPECT_GE(psnr[0], 38.0);
        EXPECT_LT(psnr[1], psnr[0] - 5.0);  // the setting is what makes the difference
        ++compared;
    }
    if (compared == 0) GTEST_SKIP() << "no specular-glossiness models or studio environment under " << kShared;
}
