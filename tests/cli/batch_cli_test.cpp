// Scene files and `fresnel batch` end to end, through the built program (FRESNEL_EXE):
//   - one scene (two models, a camera, two lights, an environment file) renders the same image
//     through `render SCENE`, the equivalent flags, and as a batch job (PSNR >= 50 dB);
//   - broken scene files exit 1 with "fresnel: error: FILE: /pointer: ..."; none crashes;
//   - a batch of good and broken jobs renders every good one, reports every bad one, exits 1;
//   - shards 0/3, 1/3, 2/3 (and --shard auto from Slurm's variables) cover every job once;
//   - --resume renders only the missing outputs; a folder of models gives a thumbnail each;
//   - render --turntable N writes N numbered frames.
// Images are tiny (32-64 px) and the environment is baked small so the whole file takes seconds.
#include "cli_harness.h"
#include "gltf_builders.h"
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fresnel/core/image.h"
#include "fresnel/core/metrics.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

const fs::path kShared = FRESNEL_SHARED_DIR;

using fresnel::test::command_line;
using fresnel::test::quote;
using fresnel::test::run_captured;
using fresnel::test::show;
using fresnel::test::Result;
using fresnel::test::slurp;


// A UV sphere of radius 1 whose node sits at (x, y, z), one material of colour (r, g, b).
void write_sphere(const fs::path& path, float x, float y, float z, float r, float g, float b, float roughness = 0.4f) {
    const json material = {{"name", "paint"},
                           {"pbrMetallicRoughness", {{"baseColorFactor", {r, g, b, 1.0}}, {"metallicFactor", 0.0},
                                                     {"roughnessFactor", roughness}}}};
    std::ofstream(path) << fresnel::test::uv_sphere_gltf(32, 16, material, {x, y, z}).dump();
}

// A small equirectangular sky: blue above, warm below, a bright spot at the +Z centre.
void write_sky(const fs::path& path) {
    const int w = 64, h = 32;
    fresnel::ImageF img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float t = float(y) / float(h - 1);
            float* p = img.at(x, y);
            p[0] = 0.3f + 0.7f * t;
            p[1] = 0.4f + 0.3f * t;
            p[2] = 1.0f - 0.6f * t;
            p[3] = 1.0f;
            if (std::abs(x - w / 2) < 3 && std::abs(y - h / 3) < 3) p[0] = p[1] = p[2] = 20.0f;
        }
    fresnel::write_hdr(path, img);
}

class BatchCli : public fresnel::test::TempDirTest {
protected:
    BatchCli() : TempDirTest("fresnel_batch") {}
    void SetUp() override {
        TempDirTest::SetUp();
        fs::create_directories(dir_ / "models" / "sub");
        write_sphere(dir_ / "models" / "red.gltf", -1.2f, 0, 0, 0.9f, 0.2f, 0.1f);
        write_sphere(dir_ / "models" / "sub" / "blue.gltf", 1.2f, 0.3f, 0, 0.1f, 0.3f, 0.9f, 0.8f);
        write_sky(dir_ / "sky.hdr");
    }
    // Runs the program in dir_ with `args` (and `env`, "NAME=value" words, before it).
    Result run(const std::vector<std::string>& args, const std::vector<std::string>& env = {}) {
        std::string program = "cd ";
        program.append(quote(dir_.string())).append(" && ");
        for (const auto& e : env) program.append(e).append(" ");
        program.append(quote(FRESNEL_EXE));
        return run_captured(command_line(program, args), dir_);
    }
    void write(const std::string& name, const std::string& text) { std::ofstream(dir_ / name) << text; }
    // The JSON lines of a batch's stdout.
    static std::vector<json> lines(const Result& r) {
        std::vector<json> out;
        std::stringstream ss(r.out);
        std::string l;
        while (std::getline(ss, l))
            if (!l.empty()) out.push_back(json::parse(l));
        return out;
    }
};

double psnr(const fs::path& a, const fs::path& b) {
    fresnel::Image8 x = fresnel::read_image8(a), y = fresnel::read_image8(b);
    if (x.width != y.width || x.height != y.height) return 0.0;
    return fresnel::compare_images(x, y, false).psnr_db;
}

// The scene of the issue's check: two models, a camera, two lights and an environment.
const char* kScene = R"({
  "fresnel": 1,
  "models": [{"path": "models/red.gltf"}, {"path": "models/sub/blue.gltf"}],
  "camera": {"yaw": 25, "pitch": 15, "fov": 40},
  "lights": [
    {"type": "directional", "azimuth": 30, "elevation": 45, "intensity": 2},
    {"type": "point", "position": [0, 3, 3], "intensity": 20, "color": [1, 0.8, 0.6]}
  ],
  "environment": {"file": "sky.hdr", "rotation": 40, "intensity": 0.8, "bakeSize": 16, "bakeSamples": 64},
  "background": "blur",
  "render": {"size": [64, 48], "msaa": 4, "toneMapping": "agx", "exposure": 0.5},
  "output": "from_scene.png"
})";

TEST_F(BatchCli, SceneFileFlagsAndBatchRenderTheSameImage) {
    write("two.fresnel.json", kScene);
    Result r = run({"render", "two.fresnel.json"});
    ASSERT_EQ(r.exit_code, 0) << show(r);
    ASSERT_TRUE(fs::exists(dir_ / "from_scene.png")) << "the scene file's output, relative to it";

    r = run({"render", "models/red.gltf", "models/sub/blue.gltf", "-o", "from_flags.png", "--yaw", "25", "--pitch", "15",
             "--fov", "40", "--light", "dir:30,45,2", "--light", "point:0,3,3,20,1,0.8,0.6", "--env", "sky.hdr",
             "--env-rotation", "40", "--env-intensity", "0.8", "--env-size", "16", "--env-samples", "64",
             "--background", "blur", "--size", "64x48", "--tonemap", "agx", "--exposure", "0.5"});
    ASSERT_EQ(r.exit_code, 0) << show(r);

    write("jobs.jsonl", "\"two.fresnel.json\"\n");
    r = run({"batch", "jobs.jsonl", "--out", "batch", "--json"});
    ASSERT_EQ(r.exit_code, 0) << show(r);
    ASSERT_TRUE(fs::exists(dir_ / "batch" / "two.png")) << show(r);

    // The same job inline (paths relative to the job list).
    json inline_job = json::parse(kScene);
    inline_job.erase("fresnel");
    inline_job["output"] = "inline.png";
    write("inline.jsonl", inline_job.dump() + "\n");
    r = run({"batch", "inline.jsonl", "--out", "batch"});
    ASSERT_EQ(r.exit_code, 0) << show(r);

    const fs::path ref = dir_ / "from_scene.png";
    std::printf("PSNR scene vs flags %.1f dB, vs batch %.1f dB, vs inline %.1f dB\n", psnr(ref, dir_ / "from_flags.png"),
                psnr(ref, dir_ / "batch" / "two.png"), psnr(ref, dir_ / "batch" / "inline.png"));
    EXPECT_GE(psnr(ref, dir_ / "from_flags.png"), 50.0);
    EXPECT_GE(psnr(ref, dir_ / "batch" / "two.png"), 50.0);
    EXPECT_GE(psnr(ref, dir_ / "batch" / "inline.png"), 50.0);

    // The comparison can fail: the scene with one light fewer is another picture.
    json other = json::parse(kScene);
    other["lights"].erase(1);
    other["output"] = "other.png";
    write("other.fresnel.json", other.dump());
    r = run({"render", "other.fresnel.json"});
    ASSERT_EQ(r.exit_code, 0) << show(r);
    std::printf("PSNR against one light fewer: %.1f dB\n", psnr(ref, dir_ / "other.png"));
    EXPECT_LT(psnr(ref, dir_ / "other.png"), 45.0);

    // `info` reads the scene file as `render` does.
    r = run({"info", "two.fresnel.json", "--json"});
    ASSERT_EQ(r.exit_code, 0) << show(r);
    json info = json::parse(r.out);
    EXPECT_EQ(info.at("models").size(), 2u) << r.out;
    EXPECT_EQ(info.at("lights").get<int>(), 2) << r.out;
    EXPECT_EQ(info.at("camera").get<std::string>(), "orbit");

    // Flags given override the file; those not given do not.
    r = run({"render", "two.fresnel.json", "-o", "override.png", "--size", "32x24", "--json"});
    ASSERT_EQ(r.exit_code, 0) << show(r);
    json j = json::parse(r.out);
    EXPECT_EQ(j.at("width").get<int>(), 32);
    EXPECT_EQ(j.at("lights").get<int>(), 2) << "the file's lights stay";
}

TEST_F(BatchCli, BrokenSceneFilesExitOneAndNameThePointer) {
    struct Case {
        const char* name;
        std::string text;
        const char* expect;  // in stderr
    };
    const Case cases[] = {
        {"type.fresnel.json", R"({"fresnel": 1, "camera": {"yaw": "west"}})", "/camera/yaw"},
        {"missing.fresnel.json", R"({"fresnel": 1, "model": "models/none.glb"})", "/model"},
        {"outside.fresnel.json", R"({"fresnel": 1, "model": "../elsewhere.glb"})", "/model"},
        {"syntax.fresnel.json", R"({"fresnel": 1, )", "byte"},
        {"deep.fresnel.json", std::string(5000, '[') + std::string(5000, ']'), "deeper"},
        {"nan.fresnel.json", R"({"fresnel": 1, "render": {"exposure": NaN}})", "byte"},
        {"huge.fresnel.json", R"({"fresnel": 1, "render": {"size": [1e20, 4]}})", "/render/size/0"},
        {"version.fresnel.json", R"({"fresnel": 99})", "/fresnel"},
    };
    for (const Case& c : cases) {
        write(c.name, c.text);
        Result r = run({"render", c.name, "-o", "x.png", "--size", "16x16"});
        EXPECT_EQ(r.exit_code, 1) << c.name << "\n" << show(r);
        EXPECT_EQ(r.err.rfind("fresnel: error: ", 0), 0u) << c.name << "\n" << show(r);
        EXPECT_NE(r.err.find(c.name), std::string::npos) << c.name << "\n" << show(r);
        EXPECT_NE(r.err.find(c.expect), std::string::npos) << c.name << "\n" << show(r);
    }
    EXPECT_FALSE(fs::exists(dir_ / "x.png"));
    // An unknown key is a warning with its pointer, and the render goes on.
    write("typo.fresnel.json", R"({"fresnel": 1, "model": "models/red.gltf", "camra": {"yaw": 3}})");
    Result r = run({"render", "typo.fresnel.json", "-o", "typo.png", "--size", "16x16"});
    EXPECT_EQ(r.exit_code, 0) << show(r);
    EXPECT_NE(r.err.find("warning: typo.fresnel.json: /camra: unknown key"), std::string::npos) << show(r);
}

TEST_F(BatchCli, GoodJobsRenderBadOnesAreReportedExitOne) {
    write("bad_type.fresnel.json", R"({"fresnel": 1, "model": "models/red.gltf", "render": {"msaa": "many"}})");
    write("jobs.jsonl",
          "# thumbnails\n"
          "\"models/red.gltf\"\n"
          "{\"model\": \"models/sub/blue.gltf\", \"camera\": {\"yaw\": 90}}\n"
          "{\"model\": \"models/absent.glb\"}\n"
          "this is not json\n"
          "\"bad_type.fresnel.json\"\n"
          "{\"model\": \"demo\", \"output\": \"../escape.png\"}\n"
          "{\"model\": \"demo\", \"output\": \"named/demo.png\"}\n"
          "\n");
    Result r = run({"batch", "jobs.jsonl", "--out", "out", "--size", "32x32", "--json", "--env", "color:0.5,0.5,0.5",
                    "--env-size", "16"});
    EXPECT_EQ(r.exit_code, 1) << show(r);
    std::vector<json> results = lines(r);
    ASSERT_EQ(results.size(), 7u) << show(r);
    std::map<std::string, std::string> status;
    for (const auto& j : results) status[j.at("job").get<std::string>()] = j.at("status").get<std::string>();
    EXPECT_EQ(status["jobs.jsonl:2"], "ok");
    EXPECT_EQ(status["jobs.jsonl:3"], "ok");
    EXPECT_EQ(status["jobs.jsonl:4"], "failed");
    EXPECT_EQ(status["jobs.jsonl:5"], "failed");
    EXPECT_EQ(status["jobs.jsonl:6"], "failed");
    EXPECT_EQ(status["jobs.jsonl:7"], "failed");
    EXPECT_EQ(status["jobs.jsonl:8"], "ok");
    EXPECT_TRUE(fs::exists(dir_ / "out" / "red.png"));
    EXPECT_TRUE(fs::exists(dir_ / "out" / "blue.png"));
    EXPECT_TRUE(fs::exists(dir_ / "out" / "named" / "demo.png"));
    EXPECT_FALSE(fs::exists(dir_ / "escape.png"));
    for (const auto& j : results)
        if (j.at("status") == "failed") {
            EXPECT_FALSE(j.at("error").get<std::string>().empty()) << j.dump();
        }
    // The bad scene file's error names it and the pointer.
    for (const auto& j : results)
        if (j.at("job") == "jobs.jsonl:6") {
            EXPECT_NE(j.at("error").get<std::string>().find("/render/msaa"), std::string::npos) << j.dump();
        }

    // All good: exit 0.
    write("good.jsonl", "\"models/red.gltf\"\n");
    r = run({"batch", "good.jsonl", "--out", "out2", "--size", "16x16", "--no-ibl"});
    EXPECT_EQ(r.exit_code, 0) << show(r);
}

// Every job exactly once over the shards; --shard auto reads Slurm's and Kubernetes' variables.
TEST_F(BatchCli, ShardsCoverEveryJobOnce) {
    std::string list;
    for (int i = 0; i < 8; ++i) list += "{\"model\": \"demo\", \"camera\": {\"yaw\": " + std::to_string(i * 40) + "}, \"output\": \"j" + std::to_string(i) + ".png\"}\n";
    write("jobs.jsonl", list);
    const std::vector<std::string> common = {"--size", "16x16", "--msaa", "1", "--no-ibl", "--json"};
    std::multiset<std::string> rendered;
    for (int s = 0; s < 3; ++s) {
        std::vector<std::string> args = {"batch", "jobs.jsonl", "--out", "out" + std::to_string(s), "--shard",
                                         std::to_string(s) + "/3"};
        args.insert(args.end(), common.begin(), common.end());
        Result r = run(args);
        ASSERT_EQ(r.exit_code, 0) << show(r);
        for (const auto& j : lines(r)) {
            EXPECT_EQ(j.at("index").get<int>() % 3, s);
            rendered.insert(fs::path(j.at("output").get<std::string>()).filename().string());
        }
    }
    ASSERT_EQ(rendered.size(), 8u);
    for (int i = 0; i < 8; ++i) {
        std::string name = "j";
        name.append(std::to_string(i)).append(".png");
        EXPECT_EQ(rendered.count(name), 1u) << name;
    }

    std::vector<std::string> args = {"batch", "jobs.jsonl", "--out", "slurm", "--shard", "auto"};
    args.insert(args.end(), common.begin(), common.end());
    Result r = run(args, {"SLURM_ARRAY_TASK_ID=5", "SLURM_ARRAY_TASK_MIN=4", "SLURM_ARRAY_TASK_COUNT=3"});
    ASSERT_EQ(r.exit_code, 0) << show(r);
    std::set<int> indices;
    for (const auto& j : lines(r)) indices.insert(j.at("index").get<int>());
    EXPECT_EQ(indices, (std::set<int>{1, 4, 7})) << show(r);

    r = run(args, {"JOB_COMPLETION_INDEX=2", "FRESNEL_SHARD_COUNT=3"});
    ASSERT_EQ(r.exit_code, 0) << show(r);
    indices.clear();
    for (const auto& j : lines(r)) indices.insert(j.at("index").get<int>());
    EXPECT_EQ(indices, (std::set<int>{2, 5})) << show(r);

    r = run(args, {"JOB_COMPLETION_INDEX=2"});
    EXPECT_EQ(r.exit_code, 2) << "an Indexed Job needs the shard count\n" << show(r);
    EXPECT_EQ(run({"batch", "jobs.jsonl", "--shard", "3/3"}).exit_code, 2);
    EXPECT_EQ(run({"batch", "jobs.jsonl", "--shard", "x"}).exit_code, 2);
}

TEST_F(BatchCli, ResumeRendersOnlyWhatIsMissing) {
    std::string list;
    for (int i = 0; i < 4; ++i) list += "{\"model\": \"demo\", \"output\": \"f" + std::to_string(i) + ".png\"}\n";
    write("jobs.jsonl", list);
    const std::vector<std::string> args = {"batch", "jobs.jsonl", "--out", "out", "--size", "16x16", "--msaa", "1",
                                           "--no-ibl", "--json", "--resume"};
    Result r = run(args);
    ASSERT_EQ(r.exit_code, 0) << show(r);
    for (const auto& j : lines(r)) EXPECT_EQ(j.at("status"), "ok") << j.dump();
    // An interrupted run: one output never written, one temporary left behind.
    fs::remove(dir_ / "out" / "f2.png");
    std::ofstream(dir_ / "out" / ".f2.partial-1-1.png") << "half";
    r = run(args);
    ASSERT_EQ(r.exit_code, 0) << show(r);
    std::map<std::string, std::string> status;
    for (const auto& j : lines(r)) status[fs::path(j.at("output").get<std::string>()).filename().string()] = j.at("status");
    EXPECT_EQ(status["f0.png"], "skipped");
    EXPECT_EQ(status["f1.png"], "skipped");
    EXPECT_EQ(status["f2.png"], "ok");
    EXPECT_EQ(status["f3.png"], "skipped");
    EXPECT_GT(fs::file_size(dir_ / "out" / "f2.png"), 0u);

    // --resume trusts the log of committed outputs, not a file's existence: an output cut short
    // and one written by something else are rendered again, with a warning.
    const auto f1 = fs::file_size(dir_ / "out" / "f1.png");
    fs::resize_file(dir_ / "out" / "f1.png", f1 / 2);
    std::ofstream(dir_ / "out" / "f3.png") << "not a png";
    r = run(args);
    ASSERT_EQ(r.exit_code, 0) << show(r);
    status.clear();
    for (const auto& j : lines(r)) {
        const std::string name = fs::path(j.at("output").get<std::string>()).filename().string();
        status[name] = j.at("status");
        if (name == "f1.png" || name == "f3.png") {
            EXPECT_NE(j.at("warnings").dump().find("rendered again"), std::string::npos) << j.dump();
        }
    }
    EXPECT_EQ(status["f0.png"], "skipped");
    EXPECT_EQ(status["f1.png"], "ok");
    EXPECT_EQ(status["f2.png"], "skipped");
    EXPECT_EQ(status["f3.png"], "ok");
    EXPECT_EQ(fs::file_size(dir_ / "out" / "f1.png"), f1);
    EXPECT_EQ(fresnel::read_image8(dir_ / "out" / "f3.png").width, 16);
}

// Two spellings of one file are one output: the later job gets its own name.
TEST_F(BatchCli, OutputNamesAreComparedCanonical) {
    write("jobs.jsonl",
          "{\"model\": \"demo\", \"output\": \"a.png\"}\n"
          "{\"model\": \"demo\", \"output\": \"./a.png\"}\n"
          "{\"model\": \"demo\", \"output\": \"sub/../a.png\"}\n"
          "{\"model\": \"demo\", \"output\": \"sub/x.png\"}\n"
          "{\"model\": \"demo\", \"output\": \"sub//x.png\"}\n");
    Result r = run({"batch", "jobs.jsonl", "--out", "out", "--size", "16x16", "--msaa", "1", "--no-ibl", "--json"});
    ASSERT_EQ(r.exit_code, 0) << show(r);
    std::vector<std::string> outputs;
    for (const auto& j : lines(r)) {
        EXPECT_EQ(j.at("status"), "ok") << j.dump();
        outputs.push_back(fs::path(j.at("output").get<std::string>()).lexically_relative("out").generic_string());
    }
    EXPECT_EQ(outputs, (std::vector<std::string>{"a.png", "a-1.png", "a-2.png", "sub/x.png", "sub/x-4.png"}));
    for (const auto& o : outputs) EXPECT_TRUE(fs::is_regular_file(dir_ / "out" / o)) << o;
}

TEST_F(BatchCli, FolderOfModelsGivesAThumbnailEach) {
    Result r = run({"batch", "models", "--out", "thumbs", "--size", "24x24", "--jobs", "2", "--no-ibl"});
    ASSERT_EQ(r.exit_code, 0) << show(r);
    EXPECT_TRUE(fs::exists(dir_ / "thumbs" / "red.png")) << show(r);
    EXPECT_TRUE(fs::exists(dir_ / "thumbs" / "sub" / "blue.png")) << show(r);
    EXPECT_EQ(fresnel::read_image8(dir_ / "thumbs" / "red.png").width, 24);
}

// Folder mode takes every format the loaders read (.gltf, .glb, .obj) and scene files
// (*.fresnel.json, with their own settings), but not other .json files.
TEST_F(BatchCli, FolderTakesObjAndSceneFiles) {
    std::ofstream(dir_ / "models" / "tri.obj") << "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n";
    std::ofstream(dir_ / "models" / "side.fresnel.json")
        << R"({"fresnel": 1, "model": "red.gltf", "background": [1, 1, 1], "output": "ignored.png"})";
    std::ofstream(dir_ / "models" / "notes.json") << R"({"not": "a job"})";
    Result r = run({"batch", "models", "--out", "thumbs", "--size", "24x24", "--no-ibl", "--json"});
    ASSERT_EQ(r.exit_code, 0) << show(r);
    for (const char* name : {"red.png", "sub/blue.png", "tri.png", "side.png"})
        EXPECT_TRUE(fs::exists(dir_ / "thumbs" / name)) << name << "\n" << show(r);
    EXPECT_FALSE(fs::exists(dir_ / "thumbs" / "notes.png"));
    EXPECT_FALSE(fs::exists(dir_ / "thumbs" / "ignored.png"));
    EXPECT_EQ(lines(r).size(), 4u) << show(r);
    // The scene file's settings apply: the same model on a white background.
    EXPECT_LT(psnr(dir_ / "thumbs" / "side.png", dir_ / "thumbs" / "red.png"), 20.0);
    const auto corner = fresnel::read_image8(dir_ / "thumbs" / "side.png");
    EXPECT_EQ(int(corner.at(0, 0)[0]), 255);
}

TEST_F(BatchCli, SweepAndTurntableNumberTheirFrames) {
    write("jobs.jsonl", "{\"model\": \"models/red.gltf\", \"environment\": \"sky.hdr\", \"sweep\": {\"env-rotation\": [0, 360, 4]}}\n");
    Result r = run({"batch", "jobs.jsonl", "--out", "sweep", "--size", "24x24", "--env-size", "16", "--env-samples", "32"});
    ASSERT_EQ(r.exit_code, 0) << show(r);
    for (int i = 0; i < 4; ++i) EXPECT_TRUE(fs::exists(dir_ / "sweep" / ("red-00" + std::to_string(i) + ".png"))) << show(r);
    // The environment turned: frames differ.
    EXPECT_LT(psnr(dir_ / "sweep" / "red-000.png", dir_ / "sweep" / "red-002.png"), 45.0);

    r = run({"render", "models/red.gltf", "-o", "turn.png", "--turntable", "3", "--size", "24x24", "--no-ibl"});
    ASSERT_EQ(r.exit_code, 0) << show(r);
    for (int i = 0; i < 3; ++i) EXPECT_TRUE(fs::exists(dir_ / ("turn-00" + std::to_string(i) + ".png"))) << show(r);
    EXPECT_FALSE(fs::exists(dir_ / "turn.png"));

    // --video: an MP4 through ffmpeg when it is installed, a clear error when it is not.
    const std::vector<std::string> video = {"render", "-o", "v_%02d.png", "--turntable", "2", "--size", "24x24",
                                            "--no-ibl", "--video", "turn.mp4"};
    r = run(video, {"PATH=/nonexistent"});
    EXPECT_EQ(r.exit_code, 1) << show(r);
    EXPECT_NE(r.err.find("ffmpeg is not installed"), std::string::npos) << show(r);
    if (std::system("command -v ffmpeg >/dev/null 2>&1") == 0) {
        r = run(video);
        ASSERT_EQ(r.exit_code, 0) << show(r);
        EXPECT_TRUE(fs::exists(dir_ / "v_00.png") && fs::exists(dir_ / "v_01.png")) << show(r);
        EXPECT_GT(fs::file_size(dir_ / "turn.mp4"), 0u);
    }
}

}  // namespace
