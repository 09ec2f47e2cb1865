// Tests of our Radiance RGBE (.hdr) decoder: every encoding the format has (flat,
// old repeat records, adaptive run-length), the orientations, agreement with
// stb_image on real panoramas, and hostile files (zero-length runs, overflowing runs,
// truncation at every length) that must fail fast with the byte offset.
#include <gtest/gtest.h>
#include <stb_image.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "fresnel/core/error.h"
#include "fresnel/core/image.h"

using namespace fresnel;
namespace fs = std::filesystem;

namespace {

std::vector<std::uint8_t> header(int w, int h, const std::string& orientation = "-Y %H +X %W",
                                 const std::string& format = "32-bit_rle_rgbe") {
    std::string res = orientation;
    res.replace(res.find("%H"), 2, std::to_string(h));
    res.replace(res.find("%W"), 2, std::to_string(w));
    std::string s = "#?RADIANCE\n# test\nFORMAT=" + format + "\nEXPOSURE=1.0\n\n" + res + "\n";
    return {s.begin(), s.end()};
}

void append(std::vector<std::uint8_t>& out, std::initializer_list<int> bytes) {
    for (int b : bytes) out.push_back(std::uint8_t(b));
}

Error decode_error(const std::vector<std::uint8_t>& bytes) {
    try {
        decode_image_float(bytes, "t.hdr");
    } catch (const Error& e) {
        return e;
    }
    ADD_FAILURE() << "no error thrown";
    return Error("", "", "");
}

}  // namespace

TEST(Radiance, FlatPixelsAndExponentScaling) {
    // 3x2, flat (width < 8 is always flat). RGBE (128,64,32,129) = (1, 0.5, 0.25).
    auto f = header(3, 2);
    append(f, {128, 64, 32, 129, 0, 0, 0, 0, 128, 128, 128, 136});
    append(f, {1, 2, 3, 128, 255, 0, 0, 120, 128, 0, 0, 200});
    ImageF img = decode_image_float(f, "t.hdr");
    ASSERT_EQ(img.width, 3);
    ASSERT_EQ(img.height, 2);
    EXPECT_FLOAT_EQ(img.at(0, 0)[0], 1.0f);
    EXPECT_FLOAT_EQ(img.at(0, 0)[1], 0.5f);
    EXPECT_FLOAT_EQ(img.at(0, 0)[2], 0.25f);
    EXPECT_FLOAT_EQ(img.at(0, 0)[3], 1.0f);
    EXPECT_EQ(img.at(1, 0)[0], 0.0f);  // exponent 0 is black
    EXPECT_FLOAT_EQ(img.at(2, 0)[0], 128.0f);
    EXPECT_FLOAT_EQ(img.at(0, 1)[2], 3.0f / 256.0f);
    EXPECT_FLOAT_EQ(img.at(2, 1)[0], std::ldexp(128.0f, 200 - 136));
}

TEST(Radiance, OldRepeatRecordsShiftByEightBits) {
    // Width 300 (> 8, but the scanline does not start with 2,2: the old encoding).
    // One pixel, then repeat 43, then a second repeat record of 1 (shifted: 256) = 300.
    auto f = header(300, 1);
    append(f, {10, 20, 30, 128});
    append(f, {1, 1, 1, 43});
    append(f, {1, 1, 1, 1});
    ImageF img = decode_image_float(f, "t.hdr");
    for (int x = 0; x < 300; ++x) ASSERT_FLOAT_EQ(img.at(x, 0)[1], 20.0f / 256.0f) << x;
    // A repeat record with no pixel before it has nothing to repeat.
    auto g = header(4, 1);
    append(g, {1, 1, 1, 4});
    EXPECT_NE(decode_error(g).reason().find("no pixel before"), std::string::npos);
}

TEST(Radiance, AdaptiveRunLengthScanlines) {
    // Width 10: per channel a run of 6 (134) then 4 literals.
    auto f = header(10, 1);
    append(f, {2, 2, 0, 10});
    for (int ch = 0; ch < 4; ++ch) {
        int v = ch == 3 ? 128 : 100 + ch;
        append(f, {128 + 6, v, 4, v, v, v, ch == 3 ? 129 : 7});
    }
    ImageF img = decode_image_float(f, "t.hdr");
    for (int x = 0; x < 6; ++x) EXPECT_FLOAT_EQ(img.at(x, 0)[0], 100.0f / 256.0f);
    EXPECT_FLOAT_EQ(img.at(9, 0)[0], 7.0f / 128.0f);  // exponent 129 on the last pixel
}

TEST(Radiance, OrientationsFlipRowsAndColumns) {
    // 2x2 flat with distinct red values 1..4 in file order.
    auto body = [](std::vector<std::uint8_t> f) {
        for (int v = 1; v <= 4; ++v) append(f, {v, 0, 0, 136});
        return f;
    };
    ImageF a = decode_image_float(body(header(2, 2, "-Y %H +X %W")), "a.hdr");
    ImageF b = decode_image_float(body(header(2, 2, "+Y %H +X %W")), "b.hdr");
    ImageF c = decode_image_float(body(header(2, 2, "-Y %H -X %W")), "c.hdr");
    EXPECT_EQ(a.at(0, 0)[0], 1.0f);
    EXPECT_EQ(a.at(1, 1)[0], 4.0f);
    EXPECT_EQ(b.at(0, 0)[0], 3.0f);  // +Y: the first scanline is the bottom row
    EXPECT_EQ(b.at(0, 1)[0], 1.0f);
    EXPECT_EQ(c.at(0, 0)[0], 2.0f);  // -X: scanlines run right to left
    EXPECT_EQ(c.at(1, 0)[0], 1.0f);
    auto xmajor = body(header(2, 2, "+X %W -Y %H"));
    EXPECT_NE(decode_error(xmajor).reason().find("column-major"), std::string::npos);
}

TEST(Radiance, HostileRecordsFailWithTheByteOffset) {
    // The input fuzz_hdr found: a run-length count of 0, which never advances
    // (stb_image loops forever on it).
    auto zero = header(16, 1);
    const std::size_t record = zero.size() + 4;
    append(zero, {2, 2, 0, 16, 0});
    Error e = decode_error(zero);
    EXPECT_NE(e.reason().find("length 0"), std::string::npos) << e.what();
    EXPECT_EQ(e.where(), "byte " + std::to_string(record));

    auto overflow = header(16, 1);
    append(overflow, {2, 2, 0, 16, 128 + 17, 5});
    EXPECT_NE(decode_error(overflow).reason().find("overflows"), std::string::npos);

    auto wrong_len = header(16, 1);
    append(wrong_len, {2, 2, 0, 17});
    EXPECT_NE(decode_error(wrong_len).reason().find("17 pixels"), std::string::npos);

    auto xyze = header(1, 1, "-Y %H +X %W", "32-bit_rle_xyze");
    append(xyze, {1, 1, 1, 128});
    EXPECT_NE(decode_error(xyze).reason().find("XYZE"), std::string::npos);

    auto huge = header(100000, 100000);
    append(huge, {1, 2, 3, 4});
    EXPECT_NE(decode_error(huge).reason().find("limit"), std::string::npos);

    auto too_short = header(64, 4096);  // 4096 rows need at least 16 KiB of data
    append(too_short, {2, 2, 0, 64});
    EXPECT_NE(decode_error(too_short).reason().find("ends before"), std::string::npos);
}

TEST(Radiance, EveryTruncationFailsCleanlyAndFast) {
    // A 40x3 image in adaptive RLE with runs and literals, cut at every length.
    auto f = header(40, 3);
    for (int row = 0; row < 3; ++row) {
        append(f, {2, 2, 0, 40});
        for (int ch = 0; ch < 4; ++ch) {
            append(f, {128 + 20, 60 + row});
            append(f, {20});
            for (int k = 0; k < 20; ++k) append(f, {ch == 3 ? 130 : k * 10});
        }
    }
    ASSERT_NO_THROW(decode_image_float(f, "t.hdr"));
    const auto start = std::chrono::steady_clock::now();
    for (std::size_t n = 0; n < f.size(); ++n) {
        std::vector<std::uint8_t> cut(f.begin(), f.begin() + std::ptrdiff_t(n));
        EXPECT_THROW(decode_image_float(cut, "cut.hdr"), Error) << "length " << n;
    }
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

TEST(Radiance, MatchesStbImageOnTheSharedPanoramas) {
    const fs::path env = fs::path(FRESNEL_SHARED_DIR) / "assets" / "env";
    if (!fs::is_directory(env)) GTEST_SKIP() << env << " is absent";
    int checked = 0;
    for (const auto& entry : fs::directory_iterator(env)) {
        if (entry.path().extension() != ".hdr") continue;
        auto bytes = read_file_bytes(entry.path(), std::size_t(1) << 30);
        ImageF ours = decode_image_float(bytes, entry.path().string());
        int w = 0, h = 0, comp = 0;
        float* ref = stbi_loadf_from_memory(bytes.data(), int(bytes.size()), &w, &h, &comp, 4);
        ASSERT_NE(ref, nullptr) << entry.path();
        ASSERT_EQ(ours.width, w);
        ASSERT_EQ(ours.height, h);
        std::size_t mismatches = 0;
        for (std::size_t i = 0; i < ours.pixels.size(); ++i) mismatches += ours.pixels[i] != ref[i];
        stbi_image_free(ref);
        EXPECT_EQ(mismatches, 0u) << entry.path();
        ++checked;
    }
    EXPECT_GT(checked, 0);
}
