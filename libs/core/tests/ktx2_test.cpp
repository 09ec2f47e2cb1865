// KTX2 textures: the container (fresnel/core/ktx2.h) and the Basis Universal transcoders
// (fresnel/core/basisu.h) on the real files of ../shared/assets/ktx2 (skipped without them),
// held value for value to the transcoder npm's `three` ships (skipped without Node and
// build/node-tools), against their source image, and fed truncated and corrupted copies.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "fresnel/core/error.h"
#include "fresnel/core/image.h"
#include "fresnel/core/ktx2.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace fresnel;

namespace {

const fs::path kAssets = fs::path(FRESNEL_SHARED_DIR) / "assets" / "ktx2";

std::vector<std::uint8_t> read_bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), {});
}

std::vector<std::uint8_t> asset(const char* name) {
    auto bytes = read_bytes(kAssets / name);
    return bytes;
}

#define SKIP_WITHOUT(bytes) \
    if ((bytes).empty()) GTEST_SKIP() << "no " << kAssets.string()

float half_to_float(std::uint16_t h) {
    const int e = (h >> 10) & 0x1F, m = h & 0x3FF;
    const float s = (h & 0x8000) ? -1.0f : 1.0f;
    if (e == 0) return s * std::ldexp(float(m), -24);
    if (e == 31) return m ? NAN : s * INFINITY;
    return s * std::ldexp(float(m | 0x400), e - 25);
}

double psnr8(const Image8& a, const Image8& b) {
    double se = 0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.pixels.size(); i += 4)
        for (int c = 0; c < 3; ++c, ++n) {
            const double d = double(a.pixels[i + std::size_t(c)]) - double(b.pixels[i + std::size_t(c)]);
            se += d * d;
        }
    return 10.0 * std::log10(255.0 * 255.0 / (se / double(n)));
}

// ---- the container ---------------------------------------------------------------------

TEST(Ktx2Header, ReadsTheBasisUniversalFiles) {
    auto etc1s = asset("kodim23_etc1s.ktx2");
    SKIP_WITHOUT(etc1s);
    ktx2::Header h = ktx2::read_header(etc1s, "etc1s");
    EXPECT_EQ(h.encoding, ktx2::Encoding::Etc1s);
    EXPECT_EQ(h.supercompression, ktx2::Supercompression::BasisLZ);
    EXPECT_EQ(h.width, 768);
    EXPECT_EQ(h.height, 512);
    EXPECT_EQ(h.levels, 1);
    EXPECT_FALSE(h.global_data.empty());
    EXPECT_FALSE(h.hdr());

    h = ktx2::read_header(asset("kodim23_uastc_zstd_mips.ktx2"), "uastc");
    EXPECT_EQ(h.encoding, ktx2::Encoding::Uastc);
    EXPECT_EQ(h.supercompression, ktx2::Supercompression::Zstandard);
    EXPECT_EQ(h.levels, 10);
    EXPECT_EQ(h.level_index[0].uncompressed_length, 192u * 128u * 16u);

    h = ktx2::read_header(asset("desk_uastc_hdr_zstd.ktx2"), "hdr");
    EXPECT_EQ(h.encoding, ktx2::Encoding::UastcHdr);
    EXPECT_EQ(h.width, 644);
    EXPECT_EQ(h.height, 874);
    EXPECT_TRUE(h.hdr());
}

TEST(Ktx2Header, FresnelInfoNamesTheFormat) {
    auto uastc = asset("kodim23_uastc_zstd_mips.ktx2");
    SKIP_WITHOUT(uastc);
    ImageHeader h = peek_image_header(uastc);
    EXPECT_EQ(h.format, "KTX2 UASTC (Zstandard), 10 levels");
    EXPECT_EQ(h.width, 768);
    EXPECT_EQ(h.height, 512);
    EXPECT_EQ(peek_image_header(asset("kodim23_etc1s.ktx2")).format, "KTX2 ETC1S");
    EXPECT_EQ(peek_image_header(asset("desk_uastc_hdr_zstd.ktx2")).format, "KTX2 UASTC HDR (Zstandard)");
    h = peek_image_header(read_bytes(kAssets / "kodim23.png"));
    EXPECT_EQ(h.format, "PNG");
    EXPECT_EQ(h.width, 768);
    uastc.resize(60);  // the identifier, then a cut header
    EXPECT_EQ(peek_image_header(uastc).format, "KTX2 (damaged header)");
    EXPECT_EQ(peek_image_header(std::vector<std::uint8_t>{1, 2, 3}).format, "unknown");
}

TEST(Ktx2Decode, LdrFilesLookLikeTheirSourceImage) {
    auto etc1s = asset("kodim23_etc1s.ktx2");
    SKIP_WITHOUT(etc1s);
    const Image8 source = read_image8(kAssets / "kodim23.png");
    // Through decode_image8, as every loader reads an image.
    const Image8 a = decode_image8(etc1s, "etc1s");
    const Image8 b = decode_image8(asset("kodim23_uastc_zstd_mips.ktx2"), "uastc");
    ASSERT_EQ(a.width, source.width);
    ASSERT_EQ(b.height, source.height);
    EXPECT_GT(psnr8(a, source), 30.0);  // ETC1S: the smaller, lossier format
    EXPECT_GT(psnr8(b, source), 40.0);  // UASTC: near BC7 quality
    int w = 0, h = 0;
    EXPECT_TRUE(peek_image_size(etc1s, w, h));
    EXPECT_EQ(w, 768);
    EXPECT_FALSE(is_linear_image(etc1s));
}

TEST(Ktx2Decode, HdrFilesAreLinearFloatsAndNotEightBit) {
    auto hdr = asset("desk_uastc_hdr_zstd.ktx2");
    SKIP_WITHOUT(hdr);
    EXPECT_TRUE(is_linear_image(hdr));
    const ImageF img = decode_image_float(hdr, "desk");
    ASSERT_EQ(img.width, 644);
    float brightest = 0;
    for (std::size_t i = 0; i < img.pixels.size(); i += 4) brightest = std::max(brightest, img.pixels[i]);
    EXPECT_GT(brightest, 1.0f) << "an HDR image holds values above 1";
    try {
        decode_image8(hdr, "desk.ktx2");
        ADD_FAILURE() << "an HDR texture decoded as 8-bit";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("HDR"), std::string::npos) << e.what();
    }
}

// The decoders against the reference transcoder, every level of every file, value for value.
TEST(Ktx2Decode, EqualsThreesBasisTranscoder) {
    auto etc1s = asset("kodim23_etc1s.ktx2");
    SKIP_WITHOUT(etc1s);
    const fs::path modules = fs::path(FRESNEL_NODE_TOOLS_DIR) / "node_modules";
    if (!fs::exists(modules / "three" / "examples" / "jsm" / "libs" / "basis" / "basis_transcoder.wasm") ||
        std::system("node --version > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "no Node.js or no npm 'three' in " << modules << " (scripts/install-test-tools.sh)";
    const fs::path script = fs::path(FRESNEL_SOURCE_DIR) / "tests" / "ktx" / "basis_reference.cjs";
    test::TempDir tmp("fresnel_ktx2_ref");
    for (const char* file : {"kodim23_etc1s.ktx2", "kodim23_uastc_zstd_mips.ktx2", "desk_uastc_hdr_zstd.ktx2"}) {
        const fs::path prefix = tmp.path() / fs::path(file).stem();
        const std::string cmd = "node '" + script.string() + "' '" + modules.string() + "' '" + (kAssets / file).string() +
                                "' '" + prefix.string() + "' > /dev/null";
        ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
        const auto bytes = asset(file);
        const ktx2::Header h = ktx2::read_header(bytes, file);
        for (int level = 0; level < h.levels; ++level) {
            const ImageF ours = ktx2::decode_level_float(bytes, level, file)[0];
            const auto ref = read_bytes(prefix.string() + "_L" + std::to_string(level) + (h.hdr() ? ".rgbah" : ".rgba"));
            ASSERT_EQ(ref.size(), ours.pixels.size() * (h.hdr() ? 2 : 1)) << file << " level " << level;
            std::size_t differ = 0;
            for (std::size_t i = 0; i < ours.pixels.size(); ++i) {
                const float want = h.hdr() ? half_to_float(std::uint16_t(ref[2 * i] | (ref[2 * i + 1] << 8)))
                                           : float(ref[i]) / 255.0f;
                if (!(std::bit_cast<std::uint32_t>(ours.pixels[i]) == std::bit_cast<std::uint32_t>(want))) ++differ;
            }
            EXPECT_EQ(differ, 0u) << file << " level " << level << ": values that differ from the reference";
        }
    }
}

// ---- hostile files -----------------------------------------------------------------------

TEST(Ktx2Hostile, TruncatedFilesAreErrors) {
    for (const char* file : {"kodim23_etc1s.ktx2", "kodim23_uastc_zstd_mips.ktx2", "desk_uastc_hdr_zstd.ktx2"}) {
        auto bytes = asset(file);
        SKIP_WITHOUT(bytes);
        for (std::size_t n = 0; n < bytes.size(); n += (n < 400 ? 1 : 997)) {
            std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + std::ptrdiff_t(n));
            EXPECT_THROW(decode_image_float(cut, file), Error) << file << " cut at " << n;
        }
    }
}

// Corrupted copies decode or throw fresnel::Error; never crash (the sanitizer build runs this).
TEST(Ktx2Hostile, CorruptedFilesDecodeOrThrow) {
    std::mt19937 rng(7);
    for (const char* file : {"kodim23_etc1s.ktx2", "kodim23_uastc_zstd_mips.ktx2", "desk_uastc_hdr_zstd.ktx2"}) {
        auto bytes = asset(file);
        SKIP_WITHOUT(bytes);
        for (int trial = 0; trial < 60; ++trial) {
            auto bad = bytes;
            // The header and descriptors half the time, anywhere the other half.
            const std::size_t span = trial % 2 ? bad.size() : std::min<std::size_t>(bad.size(), 400);
            for (int k = 0; k < 1 + trial % 8; ++k) bad[rng() % span] ^= std::uint8_t(1u << (rng() % 8));
            try {
                decode_image_float(bad, file);
            } catch (const Error&) {
            }
        }
    }
}

TEST(Ktx2Hostile, LimitsAreCheckedBeforeDecoding) {
    auto bytes = asset("kodim23_uastc_zstd_mips.ktx2");
    SKIP_WITHOUT(bytes);
    ImageLimits small;
    small.max_dimension = 512;
    try {
        decode_image8(bytes, "big.ktx2", small);
        ADD_FAILURE();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("over the size limit of 512"), std::string::npos) << e.what();
    }
    // A level index that promises more bytes than the Zstandard stream holds.
    auto lie = bytes;
    lie[80 + 16] ^= 0x10;
    EXPECT_THROW(decode_image8(lie, "lie.ktx2"), Error);
}

// ---- the plain formats, written by hand --------------------------------------------------

std::vector<std::uint8_t> plain_ktx2(std::uint32_t vk_format, int w, int h, const std::vector<std::uint8_t>& pixels) {
    const std::size_t header = 80 + 24 + 28;
    std::vector<std::uint8_t> f(header + pixels.size(), 0);
    auto put = [&](std::size_t at, std::uint64_t v, int n) {
        for (int i = 0; i < n; ++i) f[at + std::size_t(i)] = std::uint8_t(v >> (8 * i));
    };
    const std::uint8_t id[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
    std::memcpy(f.data(), id, 12);
    put(12, vk_format, 4);
    put(20, std::uint32_t(w), 4);
    put(24, std::uint32_t(h), 4);
    put(36, 1, 4);   // faces
    put(40, 1, 4);   // levels
    put(48, 104, 4);  // DFD
    put(52, 28, 4);
    put(104, 28, 4);         // dfdTotalSize
    put(112, 24u << 16, 4);  // descriptor block size 24: no samples
    f[104 + 12] = 1;          // colour model RGBSDA
    put(80, header, 8);
    put(88, pixels.size(), 8);
    put(96, pixels.size(), 8);
    std::copy(pixels.begin(), pixels.end(), f.begin() + std::ptrdiff_t(header));
    return f;
}

TEST(Ktx2Plain, EightBitAndHalfFloatPixels) {
    const std::vector<std::uint8_t> rgb = {255, 0, 0, 0, 255, 0, 0, 0, 255, 10, 20, 30};
    Image8 img = decode_image8(plain_ktx2(29, 2, 2, rgb), "rgb.ktx2");  // R8G8B8_SRGB
    ASSERT_EQ(img.width, 2);
    EXPECT_EQ(img.at(1, 1)[0], 10);
    EXPECT_EQ(img.at(1, 1)[3], 255);
    // R16G16B16A16_SFLOAT: 2.5, -1, 65504 (the largest half), 1.
    const std::vector<std::uint8_t> half = {0x00, 0x41, 0x00, 0xBC, 0xFF, 0x7B, 0x00, 0x3C};
    ImageF f = decode_image_float(plain_ktx2(97, 1, 1, half), "half.ktx2");
    EXPECT_EQ(f.pixels[0], 2.5f);
    EXPECT_EQ(f.pixels[1], -1.0f);
    EXPECT_EQ(f.pixels[2], 65504.0f);
    EXPECT_EQ(f.pixels[3], 1.0f);
    EXPECT_TRUE(is_linear_image(plain_ktx2(97, 1, 1, half)));
    // A level of the wrong size, and a format fresnel does not read, name the byte.
    try {
        decode_image8(plain_ktx2(37, 2, 2, rgb), "short.ktx2");  // RGBA8 needs 16 bytes
        ADD_FAILURE();
    } catch (const Error& e) {
        EXPECT_EQ(e.where(), "byte 80");
        EXPECT_NE(e.reason().find("level 0 holds 12 bytes"), std::string::npos) << e.what();
    }
    try {
        decode_image8(plain_ktx2(131, 4, 4, std::vector<std::uint8_t>(8)), "bc1.ktx2");
        ADD_FAILURE();
    } catch (const Error& e) {
        EXPECT_EQ(e.where(), "byte 12");
        EXPECT_NE(e.reason().find("unsupported vkFormat 131"), std::string::npos) << e.what();
    }
}

}  // namespace
