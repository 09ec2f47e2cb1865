// Shadows of punctual lights (issue 31), through the program as a user runs it: the rasteriser's
// shadows fall where the path tracer's do. tests/data/shadows (scripts/make-shadow-scenes.py): a
// ground plane with two spheres, a box and a thin pole under one directional, point or spot
// light. `fresnel render` with each filter and with --shadows off against `fresnel trace
// --max-bounces 1` (direct light only, which is all the rasteriser computes for punctual lights):
// measured 37-42 dB with soft shadows, 23-24 dB without (384^2, 64 spp). Here at 160^2 and
// 48 spp: the floors leave ~3 dB for the tracer's noise.
#include "cli_harness.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "fresnel/core/image.h"
#include "fresnel/core/metrics.h"

namespace fs = std::filesystem;

namespace {

using fresnel::test::command_line;
using fresnel::test::quote;
using fresnel::test::Result;
using fresnel::test::run_captured;
using fresnel::test::show;

const fs::path kScenes = fs::path(FRESNEL_SOURCE_DIR) / "tests" / "data" / "shadows";

class Shadows : public fresnel::test::TempDirTest {
protected:
    Shadows() : TempDirTest("fresnel_shadows") {}
    Result run(const std::vector<std::string>& args) {
        return run_captured(command_line(quote(FRESNEL_EXE), args), dir_);
    }
    // PSNR of two PNGs (RGB over every pixel).
    static double psnr(const fs::path& a, const fs::path& b) {
        return fresnel::compare_images(fresnel::read_image8(a), fresnel::read_image8(b), false).psnr_db;
    }
};

const std::vector<std::string> kView = {"--env", "none", "--size", "160", "--yaw", "20", "--pitch", "30"};

std::vector<std::string> with(std::vector<std::string> head, const std::vector<std::string>& tail) {
    head.insert(head.end(), tail.begin(), tail.end());
    return head;
}

}  // namespace

TEST_F(Shadows, FallWhereTheTracersDo) {
    for (const char* light : {"directional", "point", "spot"}) {
        const fs::path scene = kScenes / (std::string("shadow-") + light + ".gltf");
        ASSERT_TRUE(fs::exists(scene)) << scene;
        const fs::path truth = dir_ / "trace.png", soft = dir_ / "soft.png", hard = dir_ / "hard.png",
                       off = dir_ / "off.png";
        Result r = run(with({"trace", scene.string(), "-o", truth.string(), "--spp", "48", "--max-bounces", "1"}, kView));
        ASSERT_EQ(r.exit_code, 0) << show(r);
        r = run(with({"render", scene.string(), "-o", soft.string()}, kView));
        ASSERT_EQ(r.exit_code, 0) << show(r);
        r = run(with({"render", scene.string(), "-o", hard.string(), "--shadows", "hard"}, kView));
        ASSERT_EQ(r.exit_code, 0) << show(r);
        r = run(with({"render", scene.string(), "-o", off.string(), "--shadows", "off"}, kView));
        ASSERT_EQ(r.exit_code, 0) << show(r);
        const double p_soft = psnr(soft, truth), p_hard = psnr(hard, truth), p_off = psnr(off, truth);
        std::printf("%s: soft %.2f dB, hard %.2f dB, off %.2f dB against trace --max-bounces 1\n", light, p_soft,
                    p_hard, p_off);
        EXPECT_GE(p_soft, 33.0) << light;
        EXPECT_GE(p_hard, 32.0) << light;
        EXPECT_GE(p_soft, p_off + 8.0) << light;
    }
}

// Area lights (rect, disk, sphere from --light) over the same scene: the rasteriser's linearly
// transformed cosines and contact-hardening shadows (as of a sphere as wide as the light) against
// the tracer's sampled emitters, direct light only. Measured at 160^2 / 48 spp: 39.0, 42.4, 44.7,
// 33.4 dB with shadows (36.3, 40.0, 40.4, 32.5 dB when the filter only widened by the light's
// size), 28.8, 31.3, 32.4, 27.1 dB without (the tube's trace is the noisiest: a thin light).
TEST_F(Shadows, AreaLightsLightAndShadowAsTheTracersDo) {
    const fs::path scene = kScenes / "shadow-directional.gltf";
    for (const char* light : {"rect:0,2.5,0.5,0,70,1.5,1,6", "disk:0.5,2,0.5,30,60,0.5,8", "sphere:0.3,1.6,0.8,0.3,10",
                              "tube:0,1.8,0.4,90,0,1.6,0.05,40"}) {
        const std::vector<std::string> view = with(kView, {"--no-scene-lights", "--light", light});
        const fs::path truth = dir_ / "trace.png", soft = dir_ / "soft.png", off = dir_ / "off.png";
        Result r = run(with({"trace", scene.string(), "-o", truth.string(), "--spp", "48", "--max-bounces", "1"}, view));
        ASSERT_EQ(r.exit_code, 0) << show(r);
        r = run(with({"render", scene.string(), "-o", soft.string()}, view));
        ASSERT_EQ(r.exit_code, 0) << show(r);
        r = run(with({"render", scene.string(), "-o", off.string(), "--shadows", "off"}, view));
        ASSERT_EQ(r.exit_code, 0) << show(r);
        const double p_soft = psnr(soft, truth), p_off = psnr(off, truth);
        std::printf("%s: shadows %.2f dB, off %.2f dB against trace --max-bounces 1\n", light, p_soft, p_off);
        EXPECT_GE(p_soft, light[0] == 't' ? 31.5 : 37.0) << light;
        EXPECT_GE(p_soft, p_off + 5.0) << light;
    }
}

// A point or spot light with a bulb radius (--light ...,radius=R), a directional light with an
// angular radius (angle=A): the rasteriser's contact-hardening shadows against the tracer's
// shadows of a sphere of that radius or a cone of those directions, direct light only, and the
// same light's shadows without the size (the soft filter alone). Measured at 160^2 / 48 spp: a
// 0.3 m bulb, point 36.8 dB against 32.9 dB, spot 37.9 dB against 35.5 dB; a 6-degree sun 34.1 dB
// against 32.5 dB.
TEST_F(Shadows, LightSizesHardenShadowsAtContactAsTheTracersDo) {
    const fs::path scene = kScenes / "shadow-directional.gltf";
    for (const char* light : {"point:0.6,3,1.2,40", "spot:-1.5,3.5,2.5,-24.8,48,60,20,34", "dir:30,50,3"}) {
        const bool sun = light[0] == 'd';
        const std::string bulb = std::string(light) + (sun ? ",angle=6" : ",radius=0.3");
        const fs::path truth = dir_ / "trace.png", hardening = dir_ / "bulb.png", point = dir_ / "point.png";
        Result r = run(with({"trace", scene.string(), "-o", truth.string(), "--spp", "48", "--max-bounces", "1",
                             "--no-scene-lights", "--light", bulb},
                            kView));
        ASSERT_EQ(r.exit_code, 0) << show(r);
        r = run(with({"render", scene.string(), "-o", hardening.string(), "--no-scene-lights", "--light", bulb}, kView));
        ASSERT_EQ(r.exit_code, 0) << show(r);
        r = run(with({"render", scene.string(), "-o", point.string(), "--no-scene-lights", "--light", light}, kView));
        ASSERT_EQ(r.exit_code, 0) << show(r);
        const double p_bulb = psnr(hardening, truth), p_point = psnr(point, truth);
        std::printf("%s: with the bulb %.2f dB, without %.2f dB against trace --max-bounces 1\n", bulb.c_str(), p_bulb,
                    p_point);
        EXPECT_GE(p_bulb, sun ? 33.5 : 35.5) << bulb;
        EXPECT_GE(p_bulb, p_point + (sun ? 1.0 : 2.0)) << bulb;
    }
}

// A directional light's cascades: more of them and smaller maps still put the shadows in place;
// the settings are checked (a cascade count outside 1..4 is an error naming the flag).
TEST_F(Shadows, CascadesAndMapSizes) {
    const fs::path scene = kScenes / "shadow-directional.gltf";
    const fs::path a = dir_ / "a.png", b = dir_ / "b.png";
    Result r = run(with({"render", scene.string(), "-o", a.string(), "--shadow-cascades", "1"}, kView));
    ASSERT_EQ(r.exit_code, 0) << show(r);
    r = run(with({"render", scene.string(), "-o", b.string(), "--shadow-cascades", "4", "--shadow-map-size", "512"},
                 kView));
    ASSERT_EQ(r.exit_code, 0) << show(r);
    EXPECT_GE(psnr(a, b), 30.0);
    // Bad values are usage errors (exit 2), naming the flag or the choices.
    r = run(with({"render", scene.string(), "-o", a.string(), "--shadow-cascades", "9"}, kView));
    EXPECT_EQ(r.exit_code, 2) << show(r);
    EXPECT_NE(r.err.find("--shadow-cascades"), std::string::npos) << show(r);
    r = run(with({"render", scene.string(), "-o", a.string(), "--shadows", "sotf"}, kView));
    EXPECT_EQ(r.exit_code, 2) << show(r);
    EXPECT_NE(r.err.find("soft"), std::string::npos) << show(r);
}

// Without a punctual light there is nothing to shadow: the environment-only scene renders the
// same with shadows on and off (no shadow pass, the same shader).
TEST_F(Shadows, EnvironmentOnlyIsUnchanged) {
    const fs::path scene = kScenes / "shadow-environment.gltf";
    const fs::path a = dir_ / "a.png", b = dir_ / "b.png";
    const std::vector<std::string> view = {"--env", "color:0.5,0.6,0.8", "--size", "96"};
    // A first run bakes the environment into the test's cache (a fresh bake and a cached one may
    // differ in the last bit); both compared runs read the cache.
    ASSERT_EQ(run(with({"render", scene.string(), "-o", a.string()}, view)).exit_code, 0);
    ASSERT_EQ(run(with({"render", scene.string(), "-o", a.string()}, view)).exit_code, 0);
    ASSERT_EQ(run(with({"render", scene.string(), "-o", b.string(), "--shadows", "off"}, view)).exit_code, 0);
    EXPECT_TRUE(std::isinf(psnr(a, b)));
}

// Baked occlusion (`--ao baked`, issue 31): the tracer's rays at each vertex darken the light
// the environment sends under the spheres and the box; the frame is otherwise the same, the JSON
// says what was baked, and a wrong value is a usage error naming the choices.
TEST_F(Shadows, BakedOcclusionDarkensWhatTheSceneHides) {
    const fs::path scene = kScenes / "shadow-environment.gltf";
    const fs::path off = dir_ / "off.png", baked = dir_ / "baked.png";
    const std::vector<std::string> view = {"--env", "color:0.5,0.6,0.8", "--size", "96", "--pitch", "20"};
    Result r = run(with({"render", scene.string(), "-o", off.string()}, view));
    ASSERT_EQ(r.exit_code, 0) << show(r);
    r = run(with({"render", scene.string(), "-o", baked.string(), "--ao", "baked", "--ao-rays", "64", "--json"}, view));
    ASSERT_EQ(r.exit_code, 0) << show(r);
    EXPECT_NE(r.out.find("\"ao\":\"baked\""), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\"ao_rays\":64"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\"ao_vertices\":"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("\"ao_vertices\":0"), std::string::npos) << r.out;
    const fresnel::Image8 a = fresnel::read_image8(off), b = fresnel::read_image8(baked);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    double sum_off = 0, sum_baked = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        sum_off += a.pixels[i];
        sum_baked += b.pixels[i];
    }
    const double p = psnr(off, baked);
    std::printf("--ao baked against off: %.2f dB, mean value %.2f -> %.2f\n", p, sum_off / double(a.pixels.size()),
                sum_baked / double(a.pixels.size()));
    EXPECT_LT(sum_baked, sum_off - 0.001 * sum_off) << "occlusion darkens";
    EXPECT_GT(p, 25.0);  // the same frame, darkened where the scene hides the sky
    EXPECT_LT(p, 60.0);
    r = run(with({"render", scene.string(), "-o", baked.string(), "--ao", "sometimes"}, view));
    EXPECT_EQ(r.exit_code, 2) << show(r);
    EXPECT_NE(r.err.find("baked"), std::string::npos) << r.err;
}

// The environment's dominant light (`--env-light dominant`, issue 31): a grey sky with a small sun
// (a 3-degree disk from azimuth 120, elevation 35, carrying most of the light) lights the shadow
// scene; split out and drawn as a shadowed directional light, the rasteriser's picture comes much
// closer to the tracer's (which shadows the whole environment) than with the sun left in the
// unshadowed image-based light (measured 23.4 -> 28.5 dB at 48 spp). --json reports the light.
TEST_F(Shadows, TheEnvironmentsDominantLightCastsShadows) {
    fresnel::ImageF sky;
    sky.width = 256;
    sky.height = 128;
    sky.pixels.assign(std::size_t(sky.width) * sky.height * 4, 0.4f);
    const float pi = 3.14159265f;
    const float sun_el = 35.0f * pi / 180.0f, sun_az = 120.0f * pi / 180.0f;
    // The panorama's direction convention (fresnel/ibl/cubemap.h): u = 0.5 + atan2(-x, z) / 2pi, v = acos(y) / pi.
    const float sx = std::cos(sun_el) * std::sin(sun_az), sy = std::sin(sun_el), sz = std::cos(sun_el) * std::cos(sun_az);
    for (int y = 0; y < sky.height; ++y)
        for (int x = 0; x < sky.width; ++x) {
            const float phi = ((x + 0.5f) / float(sky.width) - 0.5f) * 2.0f * pi, theta = (y + 0.5f) / float(sky.height) * pi;
            const float dx = -std::sin(theta) * std::sin(phi), dy = std::cos(theta), dz = std::sin(theta) * std::cos(phi);
            if (dx * sx + dy * sy + dz * sz > std::cos(3.0f * pi / 180.0f)) {
                float* t = sky.at(x, y);
                t[0] = t[1] = t[2] = 600.0f;
            }
        }
    const fs::path env = dir_ / "sun.hdr";
    fresnel::write_hdr(env, sky);
    const fs::path scene = kScenes / "shadow-environment.gltf";
    const fs::path truth = dir_ / "trace.png", off = dir_ / "off.png", split = dir_ / "split.png";
    // A black background: the environment drawn behind would lack the sun's glow (the bake's maps do).
    const std::vector<std::string> view = {"--env", env.string(), "--size", "160", "--yaw", "20", "--pitch", "30",
                                           "--no-scene-lights", "--background", "0,0,0"};
    Result r = run(with({"trace", scene.string(), "-o", truth.string(), "--spp", "48", "--max-bounces", "1"}, view));
    ASSERT_EQ(r.exit_code, 0) << show(r);
    r = run(with({"render", scene.string(), "-o", off.string()}, view));
    ASSERT_EQ(r.exit_code, 0) << show(r);
    r = run(with({"render", scene.string(), "-o", split.string(), "--env-light", "dominant", "--json"}, view));
    ASSERT_EQ(r.exit_code, 0) << show(r);
    EXPECT_NE(r.out.find("\"env_light\":\"dominant\""), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\"environment_light\":"), std::string::npos) << r.out;
    const double p_off = psnr(off, truth), p_split = psnr(split, truth);
    std::printf("against the one-bounce trace: the sun in the image-based light %.2f dB, split out %.2f dB\n", p_off, p_split);
    EXPECT_GT(p_split, p_off + 3.0);
    // Behind the scene, the environment drawn as the background (blurred, the default) keeps the
    // sun: the sky is the one drawn without the split.
    std::vector<std::string> sky_view = view;
    sky_view.resize(sky_view.size() - 2);  // without --background 0,0,0
    const fs::path sky_off = dir_ / "sky-off.png", sky_split = dir_ / "sky-split.png";
    ASSERT_EQ(run(with({"render", scene.string(), "-o", sky_off.string()}, sky_view)).exit_code, 0);
    ASSERT_EQ(run(with({"render", scene.string(), "-o", sky_split.string(), "--env-light", "dominant"}, sky_view)).exit_code, 0);
    const fresnel::Image8 a = fresnel::read_image8(sky_off), b = fresnel::read_image8(sky_split);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    int differ = 0;
    for (int y = 0; y < 20; ++y)  // the top rows: sky only
        for (int x = 0; x < a.width; ++x)
            for (int c = 0; c < a.channels; ++c) differ += std::abs(int(a.at(x, y)[c]) - int(b.at(x, y)[c])) > 1;
    EXPECT_EQ(differ, 0) << "top-right " << int(a.at(a.width - 1, 0)[0]) << " vs " << int(b.at(a.width - 1, 0)[0]);
}
