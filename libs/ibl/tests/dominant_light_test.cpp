// The environment's dominant light (split_dominant_light) on panoramas whose answer is known:
//  - a uniform sky has none, and is left as it is;
//  - a small, very bright disk on a uniform sky is found: its direction, its irradiance (the
//    disk's radiance above the sky times its solid angle), its angular radius, and the
//    panorama left uniform, so the
//    light taken out plus the light left is the light there was;
//  - a large bright region (an overcast sky's brighter half) is sky, not a light;
//  - a bake asked to split returns the light and, from the cache, the same light again.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>
#include <filesystem>

#include <glm/geometric.hpp>

#include "fresnel/ibl/bake.h"
#include "fresnel/ibl/cubemap.h"
#include "fresnel/ibl/dominant_light.h"

using namespace fresnel;
using namespace fresnel::ibl;

namespace {

constexpr double kPi = 3.14159265358979323846;

ImageF uniform(int w, float value) {
    ImageF p;
    p.width = w;
    p.height = w / 2;
    p.pixels.assign(std::size_t(p.width) * p.height * 4, value);
    for (std::size_t i = 3; i < p.pixels.size(); i += 4) p.pixels[i] = 1.0f;
    return p;
}

double texel_solid_angle(const ImageF& p, int y) {
    return (2.0 * kPi / p.width) * (kPi / p.height) * std::sin((y + 0.5) * kPi / p.height);
}

// Sum of radiance x solid angle (channel c).
double light_of(const ImageF& p, int c) {
    double s = 0.0;
    for (int y = 0; y < p.height; ++y)
        for (int x = 0; x < p.width; ++x) s += double(p.at(x, y)[c]) * texel_solid_angle(p, y);
    return s;
}

// Texels within `radius` radians of `dir` set to `value` (RGB); returns their solid angle.
double paint_disk(ImageF& p, glm::vec3 dir, double radius, glm::vec3 value) {
    double omega = 0.0;
    for (int y = 0; y < p.height; ++y)
        for (int x = 0; x < p.width; ++x) {
            const glm::vec3 d = equirect_to_direction({(x + 0.5f) / float(p.width), (y + 0.5f) / float(p.height)});
            if (std::acos(std::clamp(double(glm::dot(d, dir)), -1.0, 1.0)) > radius) continue;
            float* t = p.at(x, y);
            t[0] = value.x;
            t[1] = value.y;
            t[2] = value.z;
            omega += texel_solid_angle(p, y);
        }
    return omega;
}

}  // namespace

TEST(DominantLight, AUniformSkyHasNone) {
    ImageF p = uniform(256, 1.5f);
    const ImageF before = p;
    EXPECT_FALSE(split_dominant_light(p).has_value());
    EXPECT_EQ(p.pixels, before.pixels);
}

TEST(DominantLight, ASmallBrightDiskIsTakenOutWhole) {
    ImageF p = uniform(512, 1.0f);
    const glm::vec3 dir = glm::normalize(glm::vec3(0.5f, 0.6f, -0.62f));
    const double omega = paint_disk(p, dir, 3.0 * kPi / 180.0, glm::vec3(4000.0f, 3000.0f, 2000.0f));
    const double before[3] = {light_of(p, 0), light_of(p, 1), light_of(p, 2)};
    const std::optional<DominantLight> l = split_dominant_light(p);
    ASSERT_TRUE(l.has_value());
    EXPECT_GT(glm::dot(l->direction, dir), std::cos(0.5 * kPi / 180.0)) << "within half a degree";
    EXPECT_NEAR(l->irradiance.x, 3999.0 * omega, 1e-3 * 3999.0 * omega);
    EXPECT_NEAR(l->irradiance.z, 1999.0 * omega, 1e-3 * 1999.0 * omega);
    const double excess = (0.2126 * 3999.0 + 0.7152 * 2999.0 + 0.0722 * 1999.0) * omega;
    const double total = 0.2126 * before[0] + 0.7152 * before[1] + 0.0722 * before[2];
    EXPECT_NEAR(l->share, excess / total, 1e-3);
    EXPECT_GE(l->solid_angle, float(omega));  // grown by two texels: the filtered edge goes too
    // Its angular radius: the 3-degree disk's, from the light's spread (the grown texels carry
    // none of it), within the texels' own size (0.35 degrees here).
    EXPECT_NEAR(l->angular_radius, 3.0 * kPi / 180.0, 0.35 * kPi / 180.0);
    for (float v : p.pixels) EXPECT_EQ(v, 1.0f);  // the sky left, alpha included
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(light_of(p, c) + l->irradiance[c], before[c], 1e-4 * before[c]) << "channel " << c;
}

TEST(DominantLight, ALargeBrightRegionIsSkyNotALight) {
    ImageF p = uniform(256, 1.0f);
    paint_disk(p, glm::vec3(0, 1, 0), 40.0 * kPi / 180.0, glm::vec3(200.0f));  // 1.5 sr
    EXPECT_FALSE(split_dominant_light(p).has_value());
    // A faint light (under a quarter of the panorama's) stays in the image-based light too.
    ImageF q = uniform(256, 1.0f);
    paint_disk(q, glm::vec3(1, 0, 0), 2.0 * kPi / 180.0, glm::vec3(100.0f));
    EXPECT_FALSE(split_dominant_light(q).has_value());
}

TEST(DominantLight, ABakeAskedToSplitKeepsTheLightInItsCache) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "fresnel_dominant_light_test";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    ImageF p = uniform(128, 0.5f);
    paint_disk(p, glm::normalize(glm::vec3(-1, 1, 0)), 5.0 * kPi / 180.0, glm::vec3(800.0f));
    write_hdr(dir / "sun.hdr", p);
    const char* old_cache = std::getenv("XDG_CACHE_HOME");
    const std::string restore = old_cache ? old_cache : "";
    setenv("XDG_CACHE_HOME", (dir / "cache").c_str(), 1);
    EnvironmentSource src;
    src.kind = EnvironmentSource::Kind::File;
    src.path = dir / "sun.hdr";
    BakeOptions o;
    o.size = 16;
    o.samples = 16;
    o.irradiance_size = 8;
    o.lut_size = 16;
    o.lut_samples = 64;
    const BakedIbl whole = load_or_bake(src, o);
    EXPECT_FALSE(whole.dominant_light.has_value());
    src.split_dominant_light = true;
    const BakedIbl split = load_or_bake(src, o);
    ASSERT_TRUE(split.dominant_light.has_value());
    EXPECT_FALSE(split.from_cache);
    EXPECT_NE(split.content_hash, whole.content_hash);
    // The background keeps the light: the whole panorama's cube, as the bake without the split has it.
    ASSERT_EQ(split.background.size(), whole.specular.size());
    EXPECT_EQ(split.background.levels[0].faces, whole.specular.levels[0].faces);
    EXPECT_NE(split.specular.levels[0].faces, whole.specular.levels[0].faces);
    EXPECT_GT(glm::dot(split.dominant_light->direction, glm::normalize(glm::vec3(-1, 1, 0))), 0.999f);
    const BakedIbl cached = load_or_bake(src, o);
    EXPECT_TRUE(cached.from_cache);
    ASSERT_TRUE(cached.dominant_light.has_value());
    EXPECT_NEAR(cached.dominant_light->irradiance.x, split.dominant_light->irradiance.x, 1e-3f);
    EXPECT_GT(split.dominant_light->angular_radius, 0.0f);
    EXPECT_FLOAT_EQ(cached.dominant_light->angular_radius, split.dominant_light->angular_radius);
    // The cache holds half floats: the same cubes to half precision.
    ASSERT_EQ(cached.background.size(), split.background.size());
    ASSERT_EQ(cached.background.levels.size(), split.background.levels.size());
    for (std::size_t l = 0; l < cached.background.levels.size(); ++l)
        for (int f = 0; f < 6; ++f)
            for (std::size_t i = 0; i < cached.background.levels[l].faces[std::size_t(f)].size(); ++i) {
                const float x = cached.background.levels[l].faces[std::size_t(f)][i];
                const float y = split.background.levels[l].faces[std::size_t(f)][i];
                ASSERT_NEAR(x, y, 1e-3f * std::abs(y) + 1e-6f) << "background level " << l << " face " << f;
            }
    if (old_cache) setenv("XDG_CACHE_HOME", restore.c_str(), 1);
    else unsetenv("XDG_CACHE_HOME");
    std::filesystem::remove_all(dir);
}
