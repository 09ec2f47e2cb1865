#include "fresnel/core/mipmap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "fresnel/core/color.h"

using namespace fresnel;

namespace {
Image8 random_image(int w, int h, unsigned seed) {
    Image8 img(w, h, 4);
    std::mt19937 rng(seed);
    for (auto& p : img.pixels) p = std::uint8_t(rng() & 0xFF);
    return img;
}
}  // namespace

TEST(Mipmap, LevelCounts) {
    EXPECT_EQ(mip_level_count(1, 1), 1);
    EXPECT_EQ(mip_level_count(2048, 2048), 12);
    EXPECT_EQ(mip_level_count(256, 16), 9);
    EXPECT_EQ(mip_level_count(5, 3), 3);  // 5x3, 2x1, 1x1
    auto chain = build_mip_chain(random_image(5, 3, 1), false);
    ASSERT_EQ(chain.size(), 2u);
    EXPECT_EQ(chain[0].width, 2);
    EXPECT_EQ(chain[0].height, 1);
    EXPECT_EQ(chain[1].width, 1);
    EXPECT_EQ(chain[1].height, 1);
}

TEST(Mipmap, EvenSizesAreTheBoxAverage) {
    Image8 img = random_image(8, 4, 2);
    Image8 half = downsample_half(img, false);
    ASSERT_EQ(half.width, 4);
    ASSERT_EQ(half.height, 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x)
            for (int c = 0; c < 4; ++c) {
                float sum = float(img.at(2 * x, 2 * y)[c]) + img.at(2 * x + 1, 2 * y)[c] + img.at(2 * x, 2 * y + 1)[c] +
                            img.at(2 * x + 1, 2 * y + 1)[c];
                EXPECT_EQ(half.at(x, y)[c], std::lround(sum / 4.0f)) << x << "," << y << " c" << c;
            }
}

TEST(Mipmap, SrgbIsFilteredInLinearLight) {
    // Black and white texels average to linear 0.5, which encodes to sRGB 188, not 128.
    Image8 img(2, 2, 4);
    for (int i = 0; i < 4; ++i) {
        std::uint8_t v = (i % 2) ? 255 : 0;
        img.pixels[std::size_t(i) * 4 + 0] = img.pixels[std::size_t(i) * 4 + 1] = img.pixels[std::size_t(i) * 4 + 2] = v;
        img.pixels[std::size_t(i) * 4 + 3] = v;
    }
    Image8 s = downsample_half(img, true);
    EXPECT_EQ(int(s.pixels[0]), int(std::lround(linear_to_srgb(0.5f) * 255.0f)));
    EXPECT_EQ(int(s.pixels[3]), 128);  // alpha stays linear
    Image8 l = downsample_half(img, false);
    EXPECT_EQ(int(l.pixels[0]), 128);
}

TEST(Mipmap, SrgbEncodingRoundsToNearest) {
    // A uniform image keeps its value through the whole chain, for every byte value.
    for (int v = 0; v < 256; ++v) {
        Image8 img(4, 4, 4);
        std::fill(img.pixels.begin(), img.pixels.end(), std::uint8_t(v));
        for (const auto& level : build_mip_chain(img, true))
            for (auto p : level.pixels) ASSERT_EQ(int(p), v);
    }
}

TEST(Mipmap, OddSizesFilterBilinearlyWithClamp) {
    // A 3-wide row: the 1-wide level samples the centre (x = 1.5 - 0.5 = 1) exactly.
    Image8 img(3, 1, 4);
    std::uint8_t row[3] = {0, 90, 255};
    for (int x = 0; x < 3; ++x)
        for (int c = 0; c < 4; ++c) img.at(x, 0)[c] = row[x];
    Image8 half = downsample_half(img, false);
    ASSERT_EQ(half.width, 1);
    EXPECT_EQ(int(half.pixels[0]), 90);
}

TEST(Mipmap, SrgbBoxMatchesTheExactCurve) {
    // Random 2x2 blocks: the sRGB level is the exact curve, rounded, of the linear mean.
    std::mt19937 rng(7);
    int mismatches = 0;
    for (int n = 0; n < 20000; ++n) {
        Image8 img(2, 2, 4);
        for (auto& p : img.pixels) p = std::uint8_t(rng() & 0xFF);
        Image8 half = downsample_half(img, true);
        for (int c = 0; c < 3; ++c) {
            float mean = 0.0f;
            for (int k = 0; k < 4; ++k) mean += 0.25f * srgb_to_linear(float(img.pixels[std::size_t(k) * 4 + c]) / 255.0f);
            long expect = std::lround(linear_to_srgb(mean) * 255.0f);
            long got = half.pixels[std::size_t(c)];
            ASSERT_LE(std::abs(got - expect), 1);  // only float ties at a threshold may differ
            mismatches += got != expect;
        }
    }
    EXPECT_LE(mismatches, 3);
}
