// The presets list's environment pictures: a panorama box-filtered, exposed to a mean luminance
// of 0.18, tone mapped and sRGB-encoded; files that do not read are errors naming them.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "fresnel/core/error.h"
#include "fresnel/ibl/environment.h"
#include "fresnel/viewer/thumbnails.h"

namespace fresnel::viewer {
namespace {

TEST(Thumbnails, APanoramaKeepsItsLayoutAndIsExposed) {
    // Left half red, right half blue, ten times brighter than the exposure wants; one NaN.
    ImageF pano(64, 32);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x) {
            float* p = &pano.pixels[(std::size_t(y) * 64 + std::size_t(x)) * 4];
            p[0] = x < 32 ? 8.0f : 0.0f;
            p[1] = 0.0f;
            p[2] = x < 32 ? 0.0f : 8.0f;
            p[3] = 1.0f;
        }
    pano.pixels[0] = std::nanf("");
    const Image8 t = ibl::panorama_thumbnail(pano, 16);
    ASSERT_EQ(t.width, 16);
    ASSERT_EQ(t.height, 8);
    ASSERT_EQ(t.channels, 3);
    const std::uint8_t* left = t.at(3, 4);
    const std::uint8_t* right = t.at(12, 4);
    EXPECT_GT(left[0], 100);
    EXPECT_EQ(left[2], 0);
    EXPECT_GT(right[2], 100);
    EXPECT_EQ(right[0], 0);
    // Exposed to a mean luminance of 0.18, whatever the panorama's scale: the same picture at a
    // tenth of the radiance.
    for (float& v : pano.pixels) v *= 0.1f;
    const Image8 dim = ibl::panorama_thumbnail(pano, 16);
    for (std::size_t i = 3; i < t.pixels.size(); ++i) EXPECT_NEAR(int(dim.pixels[i]), int(t.pixels[i]), 1) << i;
}

TEST(Thumbnails, PresetsAndErrors) {
    const Image8 studio = environment_thumbnail("studio", 32);
    EXPECT_EQ(studio.width, 32);
    EXPECT_EQ(studio.height, 16);
    int lo = 255, hi = 0;
    for (std::uint8_t v : studio.pixels) lo = std::min<int>(lo, v), hi = std::max<int>(hi, v);
    EXPECT_GT(hi - lo, 60) << "the studio's lights show";
    const std::string missing = ::testing::TempDir() + "no_such_sky.hdr";
    try {
        environment_thumbnail(missing);
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("no_such_sky.hdr"), std::string::npos) << e.what();
    }
    const std::filesystem::path baked = std::filesystem::path(::testing::TempDir()) / "thumb_test.baked";
    std::filesystem::create_directories(baked);
    std::ofstream(baked / "manifest.json") << "{}";
    EXPECT_THROW(environment_thumbnail(baked.string()), Error);  // no previews
    std::filesystem::remove_all(baked);
}

}  // namespace
}  // namespace fresnel::viewer
