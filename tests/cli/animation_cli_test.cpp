// `fresnel render --time / --animation / --frames / --fps` and `fresnel info`'s animation list,
// end to end on the shared animated models (AnimatedMorphCube, CesiumMan, BrainStem; each
// skipped when absent): frames at different times differ, stay the same size on screen,
// hold no NaN or infinity, repeat exactly, and clamp past the last keyframe.
// FRESNEL_EXE is the built program ($<TARGET_FILE:fresnel>).
#include "cli_harness.h"
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fresnel/core/image.h"
#include "fresnel/core/metrics.h"

namespace fs = std::filesystem;

namespace {

const fs::path kModels = fs::path(FRESNEL_SHARED_DIR) / "assets" / "models";

using fresnel::test::command_line;
using fresnel::test::quote;
using fresnel::test::run_captured;
using fresnel::test::show;
using fresnel::test::Result;
using fresnel::test::slurp;


// Coverage (mean alpha) and the check that every value is finite.
struct Stats {
    double coverage = 0;
    bool finite = true;
};
Stats stats(const fresnel::ImageF& img) {
    Stats s;
    for (std::size_t i = 0; i < img.pixels.size(); ++i) {
        if (!std::isfinite(img.pixels[i])) s.finite = false;
        if (i % 4 == 3) s.coverage += img.pixels[i];
    }
    s.coverage /= double(img.width) * img.height;
    return s;
}

double mean_abs_difference(const fresnel::ImageF& a, const fresnel::ImageF& b) {
    if (a.pixels.size() != b.pixels.size() || a.pixels.empty()) return 1e9;
    double d = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) d += std::abs(double(a.pixels[i]) - b.pixels[i]);
    return d / double(a.pixels.size());
}

class AnimationCli : public fresnel::test::TempDirTest {
protected:
    AnimationCli() : TempDirTest("fresnel_anim") {}
    Result run(const std::vector<std::string>& args) { return run_captured(command_line(quote(FRESNEL_EXE), args), dir_); }
    // Renders `model` (128x128, transparent background, linear EXR) with extra flags.
    fresnel::ImageF render(const fs::path& model, const std::string& name, std::vector<std::string> extra) {
        fs::path out = dir_ / (name + ".exr");
        std::vector<std::string> args = {"render", model.string(), "-o", out.string(), "--size", "128x128",
                                         "--background", "transparent", "--yaw", "30", "--pitch", "15"};
        args.insert(args.end(), extra.begin(), extra.end());
        Result r = run(args);
        EXPECT_EQ(r.exit_code, 0) << show(r);
        if (r.exit_code != 0) return {};
        return fresnel::read_image_float(out);
    }
};

struct AnimatedModel {
    const char* file;
    float duration;  // seconds, as the file's keyframes say
    std::vector<float> times;
};

const std::vector<AnimatedModel> kAnimated = {
    {"AnimatedMorphCube/AnimatedMorphCube.glb", 4.2f, {0.5f, 1.5f, 3.0f}},
    {"CesiumMan/CesiumMan.glb", 2.0f, {0.25f, 0.75f, 1.5f}},
    {"BrainStem/BrainStem.glb", 34.88f, {2.0f, 6.0f, 12.0f}},
};

}  // namespace

TEST_F(AnimationCli, FramesAtSeveralTimesDifferSensibly) {
    int found = 0;
    for (const auto& m : kAnimated) {
        fs::path model = kModels / m.file;
        if (!fs::exists(model)) continue;
        ++found;
        SCOPED_TRACE(m.file);
        fresnel::ImageF rest = render(model, "rest", {});
        Stats rs = stats(rest);
        ASSERT_TRUE(rs.finite);
        ASSERT_GT(rs.coverage, 0.01) << "the rest pose is (nearly) empty";
        std::vector<fresnel::ImageF> frames;
        for (std::size_t k = 0; k < m.times.size(); ++k) {
            frames.push_back(render(model, std::to_string(k) + "_t", {"--time", std::to_string(m.times[k])}));
            Stats s = stats(frames.back());
            EXPECT_TRUE(s.finite) << "NaN or infinity at t = " << m.times[k];
            // The model moves but stays on screen at about its size: no exploded or vanished vertices.
            EXPECT_GT(s.coverage, rs.coverage * 0.4) << "t = " << m.times[k];
            EXPECT_LT(s.coverage, rs.coverage * 2.5) << "t = " << m.times[k];
        }
        for (std::size_t a = 0; a < frames.size(); ++a)
            for (std::size_t b = a + 1; b < frames.size(); ++b)
                EXPECT_GT(mean_abs_difference(frames[a], frames[b]), 1e-3)
                    << "t = " << m.times[a] << " and " << m.times[b] << " look the same";
        // The same time twice is the same picture; past the last keyframe is the last keyframe.
        fresnel::ImageF again = render(model, "again", {"--time", std::to_string(m.times[0]), "--animation", "0"});
        EXPECT_LT(mean_abs_difference(again, frames[0]), 1e-6);
        fresnel::ImageF end = render(model, "end", {"--time", std::to_string(m.duration)});
        fresnel::ImageF past = render(model, "past", {"--time", std::to_string(m.duration + 5.0f)});
        EXPECT_LT(mean_abs_difference(end, past), 1e-6);
    }
    if (found == 0) GTEST_SKIP() << "no animated models under " << kModels;
}

TEST_F(AnimationCli, NumberedFramesAndJson) {
    fs::path model = kModels / "CesiumMan" / "CesiumMan.glb";
    if (!fs::exists(model)) GTEST_SKIP() << "not found: " << model;
    fs::path out = dir_ / "walk.png";
    Result r = run({"render", model.string(), "-o", out.string(), "--size", "64x64", "--frames", "3", "--fps", "4",
                    "--time", "0.5", "--json"});
    ASSERT_EQ(r.exit_code, 0) << show(r);
    for (const char* f : {"walk-000.png", "walk-001.png", "walk-002.png"}) EXPECT_TRUE(fs::exists(dir_ / f)) << f;
    EXPECT_FALSE(fs::exists(out));
    nlohmann::json j = nlohmann::json::parse(r.out);
    ASSERT_EQ(j.at("times").size(), 3u);
    EXPECT_NEAR(j["times"][0].get<double>(), 0.5, 1e-6);
    EXPECT_NEAR(j["times"][2].get<double>(), 1.0, 1e-6);
    EXPECT_EQ(j["outputs"][1].get<std::string>(), (dir_ / "walk-001.png").string());
    fresnel::Image8 a = fresnel::read_image8(dir_ / "walk-000.png"), b = fresnel::read_image8(dir_ / "walk-002.png");
    EXPECT_NE(a.pixels, b.pixels);
}

// The time is a setting (animation.time, animation.index: fresnel/job/settings.h), so every
// front end poses the scene alike: a scene file's "animation", a batch job and a batch sweep of
// --time give render --time's picture (CPU posing where render poses on the GPU: >= 45 dB, as
// GpuAndCpuPosingAgree), trace --time traces the posed scene, and the camera stays fitted to
// the rest pose (the same view at every time).
TEST_F(AnimationCli, TimeIsASettingOfEveryFrontEnd) {
    fs::path model = kModels / "CesiumMan" / "CesiumMan.glb";
    if (!fs::exists(model)) GTEST_SKIP() << "not found: " << model;
    auto png = [&](const std::string& name) { return fresnel::read_image8(dir_ / name); };
    auto psnr = [&](const std::string& a, const std::string& b) {
        return fresnel::compare_images(png(a), png(b), false).psnr_db;
    };
    const std::vector<std::string> view = {"--size", "96x96", "--yaw", "30", "--env", "color:0.6,0.6,0.6", "--env-size", "16",
                                           "--allow-external-files"};  // the scene file and jobs name the model by its absolute path
    auto with = [&](std::vector<std::string> args) {
        args.insert(args.end(), view.begin(), view.end());
        return args;
    };
    ASSERT_EQ(run(with({"render", model.string(), "-o", (dir_ / "r.png").string(), "--time", "0.75", "--posing", "cpu"})).exit_code, 0);
    ASSERT_EQ(run(with({"render", model.string(), "-o", (dir_ / "rest.png").string()})).exit_code, 0);
    EXPECT_LT(psnr("r.png", "rest.png"), 35.0);
    {
        nlohmann::json scene = {{"fresnel", 1}, {"model", model.string()}, {"animation", {{"time", 0.75}, {"index", 0}}}};
        std::ofstream(dir_ / "walk.fresnel.json") << scene.dump();
        Result r = run(with({"render", (dir_ / "walk.fresnel.json").string(), "-o", (dir_ / "s.png").string()}));
        ASSERT_EQ(r.exit_code, 0) << show(r);
        std::printf("scene file vs render --time: %.1f dB\n", psnr("s.png", "r.png"));
        EXPECT_GE(psnr("s.png", "r.png"), 45.0) << "scene file";
    }
    {
        std::ofstream(dir_ / "jobs.jsonl") << nlohmann::json({{"model", model.string()}, {"animation", {{"time", 0.75}}},
                                                              {"output", "b.png"}}).dump()
                                           << "\n";
        Result r = run(with({"batch", (dir_ / "jobs.jsonl").string(), "--out", (dir_ / "batch").string()}));
        ASSERT_EQ(r.exit_code, 0) << show(r);
        std::printf("batch job vs render --time: %.1f dB\n", psnr("batch/b.png", "r.png"));
        EXPECT_GE(psnr("batch/b.png", "r.png"), 45.0) << "batch";
        // A sweep over time: the frames of an animation as a batch.
        std::ofstream(dir_ / "one.jsonl") << nlohmann::json({{"model", model.string()}, {"sweep", {{"time", {0, 1.5, 3}}}},
                                                             {"output", "walk.png"}}).dump()
                                          << "\n";
        r = run(with({"batch", (dir_ / "one.jsonl").string(), "--out", (dir_ / "sweep").string()}));
        ASSERT_EQ(r.exit_code, 0) << show(r);
        std::vector<fs::path> frames;
        for (const auto& e : fs::recursive_directory_iterator(dir_ / "sweep"))
            if (e.path().extension() == ".png") frames.push_back(e.path());
        std::sort(frames.begin(), frames.end());
        ASSERT_EQ(frames.size(), 3u) << show(r);
        EXPECT_GE(fresnel::compare_images(fresnel::read_image8(frames[1]), png("r.png"), false).psnr_db, 45.0)
            << frames[1] << ": the sweep's t = 0.75";
    }
    {
        auto trace = [&](const std::string& out, std::vector<std::string> extra) {
            std::vector<std::string> args = {"trace", model.string(), "-o", (dir_ / out).string(), "--spp", "4", "--seed", "3",
                                             "--size", "96x96", "--yaw", "30", "--env", "color:0.6,0.6,0.6"};
            args.insert(args.end(), extra.begin(), extra.end());
            return run(args);
        };
        ASSERT_EQ(trace("t.png", {"--time", "0.75"}).exit_code, 0);
        ASSERT_EQ(trace("t_rest.png", {}).exit_code, 0);
        std::printf("trace --time vs the rest pose's trace %.1f dB, vs render --time %.1f dB\n", psnr("t.png", "t_rest.png"),
                    psnr("t.png", "r.png"));
        EXPECT_LT(psnr("t.png", "t_rest.png"), 30.0) << "trace --time poses the scene";
        EXPECT_GT(psnr("t.png", "r.png"), 20.0) << "trace and render agree on the pose";
    }
}

TEST_F(AnimationCli, InfoListsAnimationsWithDurations) {
    int found = 0;
    for (const auto& m : kAnimated) {
        fs::path model = kModels / m.file;
        if (!fs::exists(model)) continue;
        ++found;
        Result r = run({"info", model.string(), "--json"});
        ASSERT_EQ(r.exit_code, 0) << show(r);
        nlohmann::json j = nlohmann::json::parse(r.out);
        ASSERT_EQ(j.at("animations").size(), 1u) << m.file;
        EXPECT_NEAR(j["animations"][0].at("duration").get<double>(), m.duration, 1e-3) << m.file;
        EXPECT_GT(j["animations"][0].at("channels").get<int>(), 0) << m.file;
        r = run({"info", model.string()});
        EXPECT_NE(r.out.find("animations  1"), std::string::npos) << show(r);
    }
    if (found == 0) GTEST_SKIP() << "no animated models under " << kModels;
}

TEST_F(AnimationCli, BadAnimationFlags) {
    fs::path out = dir_ / "x.png";
    Result r = run({"render", "-o", out.string(), "--size", "16x16", "--fps", "0", "--frames", "2"});
    EXPECT_EQ(r.exit_code, 2) << show(r);
    r = run({"render", "-o", out.string(), "--size", "16x16", "--frames", "0"});
    EXPECT_EQ(r.exit_code, 2) << show(r);
    // The demo has no animations: --animation 0 does not exist (exit 1, named in the message).
    r = run({"render", "-o", out.string(), "--size", "16x16", "--animation", "0"});
    EXPECT_EQ(r.exit_code, 1) << show(r);
    EXPECT_NE(r.err.find("--animation 0"), std::string::npos) << show(r);
    // --time on a file without animations renders, with a warning.
    r = run({"render", "-o", out.string(), "--size", "16x16", "--time", "1"});
    EXPECT_EQ(r.exit_code, 0) << show(r);
    EXPECT_NE(r.err.find("no animations"), std::string::npos) << show(r);
}

// The GPU path (vertex shader skinning and morphing, --posing gpu, the default) against the
// CPU reference (fresnel/scene/pose.h, --posing cpu) on the same frames.
TEST_F(AnimationCli, GpuAndCpuPosingAgree) {
    int found = 0;
    for (const auto& m : kAnimated) {
        fs::path model = kModels / m.file;
        if (!fs::exists(model)) continue;
        ++found;
        SCOPED_TRACE(m.file);
        for (float t : {m.times[0], m.times[2]}) {
            std::string time = std::to_string(t);
            fresnel::ImageF gpu = render(model, "gpu", {"--time", time, "--posing", "gpu", "--tonemap", "neutral"});
            fresnel::ImageF cpu = render(model, "cpu", {"--time", time, "--posing", "cpu", "--tonemap", "neutral"});
            ASSERT_EQ(gpu.pixels.size(), cpu.pixels.size());
            // PSNR of the clamped linear frames (alpha included).
            double se = 0;
            for (std::size_t i = 0; i < gpu.pixels.size(); ++i) {
                double d = std::clamp(double(gpu.pixels[i]), 0.0, 1.0) - std::clamp(double(cpu.pixels[i]), 0.0, 1.0);
                se += d * d;
            }
            double mse = se / double(gpu.pixels.size());
            double psnr = mse > 0 ? 10 * std::log10(1.0 / mse) : 99.0;
            std::printf("%s t=%s: GPU vs CPU posing %.1f dB\n", m.file, time.c_str(), psnr);
            EXPECT_GT(psnr, 45.0) << "t = " << t;
        }
    }
    if (found == 0) GTEST_SKIP() << "no animated models under " << kModels;
}

// KHR_animation_pointer end to end: scripts/animation-pointer-scene.py animates Suzanne's base
// colour, emissive and roughness factors and a texture transform; `render --time T` agrees with
// the Khronos Sample Renderer at the same times (tests/refs/khronos/animation_pointer, made by
// build/khronos-ref/render --time T --size 256x256 --yaw 30 --pitch 15 with studio_small_03;
// 40.4 and 41.9 dB when made), while the animation itself moves the image far more (13 dB).
TEST_F(AnimationCli, PointerAnimationMatchesTheKhronosRenderer) {
    const fs::path shared(FRESNEL_SHARED_DIR);
    const fs::path env = shared / "assets" / "env" / "studio_small_03_1k.hdr";
    if (!fs::exists(kModels / "Suzanne" / "Suzanne.gltf") || !fs::exists(env))
        GTEST_SKIP() << "Suzanne or studio_small_03 absent under " << shared;
    if (std::system("command -v python3 >/dev/null 2>&1") != 0) GTEST_SKIP() << "no python3";
    const fs::path scene = dir_ / "scene";
    std::string make = "python3 " + quote(std::string(FRESNEL_SOURCE_DIR) + "/scripts/animation-pointer-scene.py") + " " +
                       quote(scene.string()) + " " + quote(shared.string()) + " >/dev/null";
    ASSERT_EQ(std::system(make.c_str()), 0) << make;
    const fs::path refs = fs::path(FRESNEL_SOURCE_DIR) / "tests" / "refs" / "khronos" / "animation_pointer";
    std::vector<fresnel::Image8> ours;
    for (const char* t : {"0.5", "1.5"}) {
        SCOPED_TRACE(std::string("t = ") + t);
        fs::path out = dir_ / (std::string("f_") + t + ".png");
        Result r = run({"render", (scene / "Suzanne_pointer.gltf").string(), "-o", out.string(), "--env", env.string(),
                        "--size", "256x256", "--yaw", "30", "--pitch", "15", "--no-scene-lights", "--tonemap", "neutral",
                        "--encoding", "gamma2.2", "--background", "0,0,0", "--time", t});
        ASSERT_EQ(r.exit_code, 0) << show(r);
        EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;  // every channel is played
        ours.push_back(fresnel::read_image8(out));
        fresnel::ImageMetrics m = fresnel::compare_images(ours.back(), fresnel::read_image8(refs / ("k_" + std::string(t) + ".png")));
        EXPECT_GT(m.pixels, 5000u);
        EXPECT_GE(m.psnr_db, 37.0) << "against the Khronos renderer";
    }
    // The two times differ by much more than we differ from the reference.
    EXPECT_LT(fresnel::compare_images(ours[0], ours[1]).psnr_db, 25.0);
}
