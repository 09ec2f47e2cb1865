// Compressed variants of the shared models render like their originals: each model is
// converted by @gltf-transform/cli (`draco`, `meshopt`, `quantize`, `webp --lossless`; set
// up under the build folder by scripts/setup-gltf-transform.sh), rendered by `fresnel
// render` and compared with `fresnel compare` (PSNR >= 45 dB over all pixels). The variant
// must really use the extension (extensionsUsed, and `fresnel info` calls it supported),
// so a loader that ignored it could not pass. Skips without ../shared or gltf-transform.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace fs = std::filesystem;

namespace {

const fs::path kShared = FRESNEL_SHARED_DIR;
const fs::path kBuild = FRESNEL_BINARY_DIR;

std::string quote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

struct Result {
    int exit_code = -1;
    std::string out;
};

Result exec(const std::string& program, const std::vector<std::string>& args, const fs::path& log) {
    std::string cmd = program;
    for (const auto& a : args) {
        cmd.append(" ");
        cmd.append(quote(a));
    }
    cmd.append(" >");
    cmd.append(quote(log.string()));
    cmd.append(" 2>&1 </dev/null");
    int status = std::system(cmd.c_str());
    Result r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128;
    r.out = slurp(log);
    return r;
}

// The GLB's JSON chunk.
nlohmann::json glb_json(const fs::path& p) {
    std::string s = slurp(p);
    if (s.size() < 20) return {};
    std::uint32_t len = 0;
    std::memcpy(&len, s.data() + 12, 4);
    return nlohmann::json::parse(s.substr(20, len), nullptr, false);
}

struct Case {
    const char* model;    // folder and file stem under ../shared/assets/models
    const char* command;  // gltf-transform command
    const char* extension;
};

class CompressedModels : public ::testing::TestWithParam<Case> {};

TEST_P(CompressedModels, RenderLikeTheOriginal) {
    const Case& c = GetParam();
    fs::path original = kShared / "assets" / "models" / c.model / (std::string(c.model) + ".glb");
    if (!fs::exists(original)) GTEST_SKIP() << original << " is absent";
    fs::path tools = kBuild / "node-tools";
    fs::path gt = tools / "node_modules" / ".bin" / "gltf-transform";
    if (!fs::exists(gt)) std::system((quote(std::string(FRESNEL_SOURCE_DIR) + "/scripts/setup-gltf-transform.sh") + " " +
                                      quote(tools.string()) + " >/dev/null 2>&1").c_str());
    if (!fs::exists(gt)) GTEST_SKIP() << "gltf-transform is not available (npm, scripts/setup-gltf-transform.sh)";

    // The variants stay in the build folder between runs (they take seconds each to make).
    fs::path dir = kBuild / "compressed-models";
    fs::create_directories(dir);
    std::string stem = std::string(c.model) + "_" + c.command;
    fs::path variant = dir / (stem + ".glb");
    fs::path log = dir / (stem + ".log");
    if (!fs::exists(variant)) {
        std::vector<std::string> args = {c.command, original.string(), (dir / (stem + ".tmp.glb")).string()};
        if (std::string(c.command) == "webp") args.push_back("--lossless");
        Result r = exec(gt.string(), args, log);
        ASSERT_EQ(r.exit_code, 0) << r.out;
        fs::rename(dir / (stem + ".tmp.glb"), variant);
    }
    nlohmann::json j = glb_json(variant);
    ASSERT_TRUE(j.contains("extensionsUsed")) << variant;
    bool uses = false;
    for (const auto& e : j["extensionsUsed"]) uses = uses || e == c.extension;
    ASSERT_TRUE(uses) << variant << " does not use " << c.extension << ": " << j["extensionsUsed"].dump();

    // info lists it as supported.
    Result info = exec(FRESNEL_EXE, {"info", variant.string(), "--json"}, dir / (stem + ".info.json"));
    ASSERT_EQ(info.exit_code, 0) << info.out;
    auto ij = nlohmann::json::parse(info.out.substr(info.out.find('{')), nullptr, false);
    bool listed = false;
    for (const auto& e : ij["extensions"])
        if (e["name"] == c.extension) {
            listed = true;
            EXPECT_EQ(e["support"], "supported");
        }
    EXPECT_TRUE(listed) << info.out;

    auto render = [&](const fs::path& model, const fs::path& png) {
        Result r = exec(FRESNEL_EXE, {"render", model.string(), "-o", png.string(), "--size", "384x384", "--yaw", "30",
                                      "--pitch", "15"},
                        png.string() + ".log");
        EXPECT_EQ(r.exit_code, 0) << r.out;
    };
    fs::path ref = dir / (std::string(c.model) + "_original.png"), out = dir / (stem + ".png");
    if (!fs::exists(ref)) render(original, ref);
    render(variant, out);
    Result cmp = exec(FRESNEL_EXE, {"compare", out.string(), ref.string(), "--json"}, dir / (stem + ".compare.json"));
    ASSERT_EQ(cmp.exit_code, 0) << cmp.out;
    auto cj = nlohmann::json::parse(cmp.out.substr(cmp.out.find('{')), nullptr, false);
    double psnr = cj["psnr_db"].get<double>();
    RecordProperty("psnr_db", std::to_string(psnr));
    std::printf("%s %s: %.2f dB\n", c.model, c.command, psnr);
    EXPECT_GE(psnr, 45.0) << out << " against " << ref;
}

const Case kCases[] = {
    {"DamagedHelmet", "draco", "KHR_draco_mesh_compression"},
    {"DamagedHelmet", "meshopt", "EXT_meshopt_compression"},
    {"DamagedHelmet", "quantize", "KHR_mesh_quantization"},
    {"DamagedHelmet", "webp", "EXT_texture_webp"},
    {"Duck", "draco", "KHR_draco_mesh_compression"},
    {"Duck", "meshopt", "EXT_meshopt_compression"},
    {"Duck", "quantize", "KHR_mesh_quantization"},
    {"Duck", "webp", "EXT_texture_webp"},
    {"2CylinderEngine", "draco", "KHR_draco_mesh_compression"},
    {"2CylinderEngine", "meshopt", "EXT_meshopt_compression"},
    {"2CylinderEngine", "quantize", "KHR_mesh_quantization"},
};

INSTANTIATE_TEST_SUITE_P(Variants, CompressedModels, ::testing::ValuesIn(kCases), [](const auto& info) {
    return std::string(info.param.model) + "_" + info.param.command;
});

}  // namespace
