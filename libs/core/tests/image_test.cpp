// Tests of image I/O (PNG, Radiance HDR, OpenEXR), hostile-input handling of the
// decoders, read_file_bytes' size cap, and the comparison metrics.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "fresnel/core/error.h"
#include "fresnel/core/image.h"
#include "fresnel/core/metrics.h"
#include "file_size_limit.h"
#include "temp_dir.h"

using namespace fresnel;
namespace fs = std::filesystem;

namespace {

using fresnel::test::TempDir;  // tests/support/temp_dir.h
using fresnel::test::FileSizeLimit;  // tests/support/file_size_limit.h

void write_bytes(const fs::path& p, const std::vector<std::uint8_t>& bytes) {
    std::ofstream out(p, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// CRC-32 (ISO-HDLC, as PNG uses), bit by bit: independent of any library.
std::uint32_t crc32(const std::uint8_t* data, std::size_t n) {
    std::uint32_t crc = 0xFFFFFFFFu;
    for (std::size_t i = 0; i < n; ++i) {
        crc ^= data[i];
        for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return crc ^ 0xFFFFFFFFu;
}

void put_be32(std::vector<std::uint8_t>& out, std::uint32_t v) {
    out.push_back(std::uint8_t(v >> 24));
    out.push_back(std::uint8_t(v >> 16));
    out.push_back(std::uint8_t(v >> 8));
    out.push_back(std::uint8_t(v));
}

// PNG signature + one IHDR chunk (with a correct CRC) and nothing after it.
std::vector<std::uint8_t> png_header_only(std::uint32_t width, std::uint32_t height, std::uint8_t color_type) {
    std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    std::vector<std::uint8_t> chunk = {'I', 'H', 'D', 'R'};
    put_be32(chunk, width);
    put_be32(chunk, height);
    chunk.insert(chunk.end(), {8, color_type, 0, 0, 0});  // bit depth, colour type, compression, filter, interlace
    put_be32(png, 13);
    png.insert(png.end(), chunk.begin(), chunk.end());
    put_be32(png, crc32(chunk.data(), chunk.size()));
    return png;
}

Image8 pattern8(int w, int h, int channels) {
    Image8 img(w, h, channels);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < channels; ++c) img.at(x, y)[c] = std::uint8_t((x * 37 + y * 101 + c * 53 + x * y) & 0xFF);
    return img;
}

ImageF pattern_float(int w, int h) {
    ImageF img(w, h);
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> exp_dist(-6.0f, 8.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float* p = img.at(x, y);
            for (int c = 0; c < 3; ++c) p[c] = std::exp2(exp_dist(rng));
            p[3] = float(x + y) / float(w + h);
        }
    // A few exact values: black, white, and a bright pixel.
    img.at(0, 0)[0] = img.at(0, 0)[1] = img.at(0, 0)[2] = 0.0f;
    img.at(1, 0)[0] = img.at(1, 0)[1] = img.at(1, 0)[2] = 1.0f;
    img.at(2, 0)[0] = 1000.0f;
    return img;
}

template <class Fn>
Error capture_error(Fn&& fn) {
    try {
        fn();
    } catch (const Error& e) {
        return e;
    } catch (const std::exception& e) {
        ADD_FAILURE() << "threw a non-fresnel exception: " << e.what();
        return Error("", "", e.what());
    }
    ADD_FAILURE() << "no fresnel::Error was thrown";
    return Error("", "", "<none>");
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Round trips

TEST(ImageIo, PngRoundTripRgba) {
    TempDir dir;
    Image8 img = pattern8(37, 23, 4);
    fs::path p = dir / "rgba.png";
    write_png(p, img);
    ASSERT_TRUE(fs::exists(p));
    Image8 back = read_image8(p);
    ASSERT_EQ(back.width, img.width);
    ASSERT_EQ(back.height, img.height);
    ASSERT_EQ(back.channels, 4);
    EXPECT_EQ(back.pixels, img.pixels);
}

// A disk that fills mid-file: every image writer fails naming the file and the reason, and the
// old file is left as it was, with no temporary beside it (stb's writers ignore fwrite's result:
// the bytes are encoded in memory and written with every write checked).
TEST(ImageIo, WritersAreWholeOrAbsentOnAFullDisk) {
    TempDir dir;
    std::mt19937 rng(3);
    Image8 noise8(256, 256, 4);
    for (auto& v : noise8.pixels) v = std::uint8_t(rng());
    ImageF noise(256, 256);
    for (auto& v : noise.pixels) v = float(rng() % 1000) / 100.0f;
    const fs::path png = dir / "frame.png", hdr = dir / "frame.hdr", exr = dir / "frame.exr";
    write_png(png, pattern8(8, 8, 4));
    write_hdr(hdr, ImageF(8, 8));
    write_exr(exr, ImageF(8, 8));
    const auto before = [&](const fs::path& p) { return read_file_bytes(p, 1 << 20); };
    const auto png0 = before(png), hdr0 = before(hdr), exr0 = before(exr);
    auto expect_fails = [&](const fs::path& p, auto&& write, bool system_reason) {
        try {
            FileSizeLimit limit(4096);
            write();
            ADD_FAILURE() << p << ": a write past the disk's end passed";
        } catch (const Error& e) {
            EXPECT_EQ(e.file(), p.string());
            if (system_reason) {
                EXPECT_NE(e.reason().find(std::strerror(EFBIG)), std::string::npos) << e.reason();
            }
        }
    };
    expect_fails(png, [&] { write_png(png, noise8); }, true);
    expect_fails(hdr, [&] { write_hdr(hdr, noise); }, true);
    expect_fails(exr, [&] { write_exr(exr, noise); }, false);  // OpenEXR words its own reason
    EXPECT_EQ(before(png), png0);
    EXPECT_EQ(before(hdr), hdr0);
    EXPECT_EQ(before(exr), exr0);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 3);
}

// Large images are deflated in parts on several threads (stb_impl.cpp); the parts make one
// zlib stream that decodes to the same bytes. 700 x 500 RGB: 1 MB of filtered rows, 4 parts
// of 256 KiB or more (or fewer on fewer threads). Smooth and noisy rows alike, and a repeat
// across the part boundaries (what the 32 KiB dictionary lets the next part refer back to).
TEST(ImageIo, PngRoundTripOfALargeImageDeflatedInParts) {
    TempDir dir;
    Image8 img(700, 500, 3);
    std::uint32_t state = 12345u;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            for (int c = 0; c < 3; ++c) {
                state = state * 1664525u + 1013904223u;
                const bool noisy = (y / 50) % 2 == 1;
                img.at(x, y)[c] = std::uint8_t(noisy ? state >> 24 : (x * (c + 1) + y / 7 * 3) & 0xFF);
            }
    for (int y = 260; y < 270; ++y) std::copy_n(img.at(0, y - 130), 700 * 3, img.at(0, y));
    fs::path p = dir / "large.png";
    write_png(p, img);
    Image8 back = read_image8(p);
    ASSERT_EQ(back.width, img.width);
    ASSERT_EQ(back.height, img.height);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            for (int c = 0; c < 3; ++c) ASSERT_EQ(back.at(x, y)[c], img.at(x, y)[c]) << x << "," << y;
    // Still compressed: the smooth half deflates well.
    EXPECT_LT(fs::file_size(p), std::uintmax_t(img.pixels.size()) * 3 / 4);
}

TEST(ImageIo, PngRoundTripRgbGetsOpaqueAlpha) {
    TempDir dir;
    Image8 img = pattern8(16, 9, 3);
    fs::path p = dir / "rgb.png";
    write_png(p, img);
    Image8 back = read_image8(p);
    ASSERT_EQ(back.width, 16);
    ASSERT_EQ(back.height, 9);
    ASSERT_EQ(back.channels, 4);
    for (int y = 0; y < 9; ++y)
        for (int x = 0; x < 16; ++x) {
            for (int c = 0; c < 3; ++c) ASSERT_EQ(back.at(x, y)[c], img.at(x, y)[c]) << x << "," << y;
            ASSERT_EQ(back.at(x, y)[3], 255);
        }
}

TEST(ImageIo, PngDecodeFromMemoryAndPeek) {
    TempDir dir;
    Image8 img = pattern8(5, 7, 4);
    fs::path p = dir / "small.png";
    write_png(p, img);
    auto bytes = read_file_bytes(p, 1 << 20);
    int w = 0, h = 0;
    ASSERT_TRUE(peek_image_size(bytes, w, h));
    EXPECT_EQ(w, 5);
    EXPECT_EQ(h, 7);
    Image8 back = decode_image8(bytes, "small.png");
    EXPECT_EQ(back.pixels, img.pixels);
    // read_image_float of an 8-bit file is value / 255 (no colour conversion).
    ImageF f = read_image_float(p);
    ASSERT_EQ(f.width, 5);
    for (std::size_t i = 0; i < f.pixels.size(); ++i) ASSERT_FLOAT_EQ(f.pixels[i], img.pixels[i] / 255.0f);
}

TEST(ImageIo, HdrRoundTripWithinRgbePrecision) {
    TempDir dir;
    ImageF img = pattern_float(19, 11);
    fs::path p = dir / "img.hdr";
    write_hdr(p, img);
    ImageF back = read_image_float(p);
    ASSERT_EQ(back.width, img.width);
    ASSERT_EQ(back.height, img.height);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const float* a = img.at(x, y);
            const float* b = back.at(x, y);
            // RGBE: an 8-bit mantissa shared by the three channels, relative to the largest.
            float maxc = std::max(a[0], std::max(a[1], a[2]));
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(b[c], a[c], maxc / 128.0f + 1e-7f) << "pixel " << x << "," << y << " channel " << c;
            ASSERT_EQ(b[3], 1.0f) << "RGBE has no alpha; it reads back as 1";
        }
    EXPECT_EQ(back.at(0, 0)[0], 0.0f);
    EXPECT_EQ(back.at(1, 0)[1], 1.0f);  // powers of two are exact in RGBE
}

TEST(ImageIo, ExrRoundTripWithinHalfPrecision) {
    TempDir dir;
    ImageF img = pattern_float(21, 13);
    img.at(3, 0)[0] = 60000.0f;  // near the top of the half range
    fs::path p = dir / "img.exr";
    write_exr(p, img);
    ImageF back = read_image_float(p);
    ASSERT_EQ(back.width, img.width);
    ASSERT_EQ(back.height, img.height);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            for (int c = 0; c < 4; ++c) {
                float a = img.at(x, y)[c], b = back.at(x, y)[c];
                // Half floats: 11 significant bits, relative error <= 2^-11 (round to nearest).
                ASSERT_NEAR(b, a, std::fabs(a) * (1.0f / 2048.0f) + 1e-7f)
                    << "pixel " << x << "," << y << " channel " << c;
            }
    EXPECT_EQ(back.at(0, 0)[0], 0.0f);
    EXPECT_EQ(back.at(1, 0)[0], 1.0f);
}

TEST(ImageIo, ReadImageFloatRejectsMissingAndCorruptFiles) {
    TempDir dir;
    Error e1 = capture_error([&] { read_image_float(dir / "missing.exr"); });
    EXPECT_NE(std::string(e1.what()).find("missing.exr"), std::string::npos) << e1.what();
    write_bytes(dir / "bad.exr", {1, 2, 3, 4, 5, 6, 7, 8});
    Error e2 = capture_error([&] { read_image_float(dir / "bad.exr"); });
    EXPECT_NE(e2.file().find("bad.exr"), std::string::npos) << e2.what();
    write_bytes(dir / "bad.hdr", {'#', '?', 'R', 'A', 'D'});
    Error e3 = capture_error([&] { read_image_float(dir / "bad.hdr"); });
    EXPECT_NE(e3.file().find("bad.hdr"), std::string::npos) << e3.what();
}

// ---------------------------------------------------------------------------------------------
// Hostile input

TEST(ImageDecode, RejectsEmptyBuffer) {
    std::vector<std::uint8_t> empty;
    Error e = capture_error([&] { decode_image8(empty, "empty.png"); });
    EXPECT_EQ(e.file(), "empty.png");
    EXPECT_FALSE(e.reason().empty());
}

TEST(ImageDecode, RejectsGarbage) {
    std::mt19937 rng(7);
    for (int trial = 0; trial < 50; ++trial) {
        std::vector<std::uint8_t> junk(1 + rng() % 512);
        for (auto& b : junk) b = std::uint8_t(rng());
        // Make sure it does not accidentally start with a known signature.
        junk[0] = 0x00;
        Error e = capture_error([&] { decode_image8(junk, "junk.bin"); });
        EXPECT_EQ(e.file(), "junk.bin");
        int w = 0, h = 0;
        EXPECT_FALSE(peek_image_size(junk, w, h));
    }
    const std::string text = "this is not an image at all";
    std::vector<std::uint8_t> bytes(text.begin(), text.end());
    capture_error([&] { decode_image8(bytes, "text.png"); });
}

TEST(ImageDecode, RejectsTruncatedPng) {
    TempDir dir;
    write_png(dir / "t.png", pattern8(32, 32, 4));
    auto bytes = read_file_bytes(dir / "t.png", 1 << 20);
    for (std::size_t n = 1; n < bytes.size(); n += std::max<std::size_t>(1, n / 8)) {
        std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + std::ptrdiff_t(n));
        Error e = capture_error([&] { decode_image8(cut, "t.png"); });
        EXPECT_EQ(e.file(), "t.png") << "length " << n;
    }
}

// fuzz_webp: 19 bytes that stb_image takes for a greyscale TGA of 4212x3963 (it reads zeros
// past the end). Refused by size before decoding; a real TGA of that header still decodes.
TEST(ImageDecode, TgaHeaderClaimingMorePixelsThanItsBytesIsRefused) {
    const std::vector<std::uint8_t> tiny = {0xaa, 0x00, 0x03, 0x01, 0x00, 0x00, 0x00, 0x00, 0x61, 0x73,
                                            0x73, 0x65, 0x74, 0x10, 0x7b, 0x0f, 0x0f, 0xe5, 0x00};
    try {
        fresnel::decode_image8(tiny, "tiny.tga");
        FAIL() << "decoded";
    } catch (const fresnel::Error& e) {
        EXPECT_NE(std::string(e.what()).find("pixels in 19 bytes"), std::string::npos) << e.what();
    }
    // An uncompressed 3x2 greyscale TGA (18-byte header, 6 pixel bytes) is fine.
    std::vector<std::uint8_t> tga = {0, 0, 3, 0, 0, 0, 0, 0, 0, 0, 0, 0, 3, 0, 2, 0, 8, 0, 10, 20, 30, 40, 50, 60};
    fresnel::Image8 img = fresnel::decode_image8(tga, "small.tga");
    EXPECT_EQ(img.width, 3);
    EXPECT_EQ(img.height, 2);
}

// fuzz_webp: a truncated 16-bit PNM made Debian's stb_image write past its buffer; PNM is not read.
TEST(ImageDecode, PnmIsNotRead) {
    const std::string pnm = "P6 1 1 661 ";
    std::vector<std::uint8_t> bytes(pnm.begin(), pnm.end());
    bytes.push_back(0);
    Error e = capture_error([&] { decode_image8(bytes, "x.ppm"); });
    EXPECT_EQ(e.file(), "x.ppm");
}

TEST(ImageDecode, Crc32Reference) {
    // Sanity check of the test's own CRC: the standard check value.
    const char* s = "123456789";
    EXPECT_EQ(crc32(reinterpret_cast<const std::uint8_t*>(s), 9), 0xCBF43926u);
}

TEST(ImageDecode, HugeIhdrIsRejectedQuicklyWithTheLimit) {
    // 100000 x 100000 RGBA would be 40 GB: the header alone must be enough to refuse it.
    auto png = png_header_only(100000, 100000, 6);
    ASSERT_EQ(png.size(), 8u + 4 + 4 + 13 + 4);
    auto start = std::chrono::steady_clock::now();
    Error e = capture_error([&] { decode_image8(png, "huge.png"); });
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LT(seconds, 1.0);
    EXPECT_EQ(e.file(), "huge.png");
    std::string msg = e.what();
    // The message must say why: the size claimed and the limit (16384 pixels per side by default).
    EXPECT_NE(msg.find("16384"), std::string::npos) << msg;
    EXPECT_NE(msg.find("limit"), std::string::npos) << msg;
    EXPECT_NE(msg.find("100000"), std::string::npos) << msg;
    // Also as a file: read_image8 goes through the same check.
    TempDir dir;
    {
        std::ofstream out(dir / "huge.png", std::ios::binary);
        out.write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
    }
    Error f = capture_error([&] { read_image8(dir / "huge.png"); });
    EXPECT_NE(std::string(f.what()).find("limit"), std::string::npos) << f.what();
    int w = 0, h = 0;
    EXPECT_TRUE(peek_image_size(png, w, h));
    EXPECT_EQ(w, 100000);
    EXPECT_EQ(h, 100000);
}

TEST(ImageDecode, OverLimitHeaderNamesTheLimit) {
    // Within stb's own dimension cap but over ImageLimits::max_dimension: fresnel's check speaks.
    auto png = png_header_only(20000, 20000, 0);  // greyscale: 400 MB, under stb's 1 GB check
    auto start = std::chrono::steady_clock::now();
    Error e = capture_error([&] { decode_image8(png, "big.png"); });
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LT(seconds, 1.0);
    std::string msg = e.what();
    EXPECT_NE(msg.find("16384"), std::string::npos) << msg;
    EXPECT_NE(msg.find("limit"), std::string::npos) << msg;
    EXPECT_NE(msg.find("20000"), std::string::npos) << msg;
}

TEST(ImageDecode, ImageLimitsAreHonoured) {
    TempDir dir;
    write_png(dir / "8x8.png", pattern8(8, 8, 4));
    auto bytes = read_file_bytes(dir / "8x8.png", 1 << 20);
    ImageLimits dim;
    dim.max_dimension = 4;
    Error e1 = capture_error([&] { decode_image8(bytes, "8x8.png", dim); });
    EXPECT_NE(std::string(e1.what()).find("limit"), std::string::npos) << e1.what();
    ImageLimits mem;
    mem.max_decoded_bytes = 8 * 8 * 4 - 1;
    Error e2 = capture_error([&] { decode_image8(bytes, "8x8.png", mem); });
    EXPECT_NE(std::string(e2.what()).find("limit"), std::string::npos) << e2.what();
    // Exactly at the limits it decodes.
    ImageLimits exact;
    exact.max_dimension = 8;
    exact.max_decoded_bytes = 8 * 8 * 4;
    EXPECT_EQ(decode_image8(bytes, "8x8.png", exact).width, 8);
}

// ---------------------------------------------------------------------------------------------
// read_file_bytes

TEST(ReadFileBytes, EnforcesMaxBytes) {
    TempDir dir;
    std::vector<std::uint8_t> data(1000);
    for (std::size_t i = 0; i < data.size(); ++i) data[i] = std::uint8_t(i * 7);
    write_bytes(dir / "f.bin", data);
    EXPECT_EQ(read_file_bytes(dir / "f.bin", 1000), data);
    EXPECT_EQ(read_file_bytes(dir / "f.bin", 1 << 20), data);
    Error e = capture_error([&] { read_file_bytes(dir / "f.bin", 999); });
    EXPECT_NE(e.file().find("f.bin"), std::string::npos);
    EXPECT_NE(e.reason().find("1000"), std::string::npos) << e.what();
    EXPECT_NE(e.reason().find("999"), std::string::npos) << e.what();
    EXPECT_NE(e.reason().find("limit"), std::string::npos) << e.what();
}

TEST(ReadFileBytes, EmptyMissingAndDirectory) {
    TempDir dir;
    write_bytes(dir / "empty.bin", {});
    EXPECT_TRUE(read_file_bytes(dir / "empty.bin", 0).empty());
    Error e1 = capture_error([&] { read_file_bytes(dir / "nope.bin", 100); });
    EXPECT_NE(e1.file().find("nope.bin"), std::string::npos);
    Error e2 = capture_error([&] { read_file_bytes(dir.path(), 100); });
    EXPECT_FALSE(e2.reason().empty());
}

// ---------------------------------------------------------------------------------------------
// compare_images

namespace {
Image8 solid(int w, int h, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    Image8 img(w, h, 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            std::uint8_t* p = img.at(x, y);
            p[0] = r, p[1] = g, p[2] = b, p[3] = 255;
        }
    return img;
}
}  // namespace

TEST(Metrics, IdenticalImagesHaveInfinitePsnr) {
    Image8 a = pattern8(20, 10, 4);
    ImageMetrics m = compare_images(a, a, false);
    EXPECT_TRUE(std::isinf(m.psnr_db) && m.psnr_db > 0);
    EXPECT_EQ(m.mad, 0.0);
    EXPECT_EQ(m.max_abs, 0.0);
    EXPECT_EQ(m.p99, 0.0);
    EXPECT_EQ(m.pixels, 200u);
}

TEST(Metrics, SinglePixelDifferenceGivesExpectedPsnr) {
    const int w = 8, h = 4;  // 32 pixels, none background (grey)
    Image8 a = solid(w, h, 128, 128, 128);
    Image8 b = a;
    b.at(3, 2)[1] = 128 + 10;  // one channel of one pixel off by 10
    ImageMetrics m = compare_images(a, b);
    ASSERT_EQ(m.pixels, 32u);
    double mse = 100.0 / (3.0 * 32.0);
    EXPECT_NEAR(m.psnr_db, 10.0 * std::log10(255.0 * 255.0 / mse), 1e-9);
    EXPECT_NEAR(m.psnr_db, 10.0 * std::log10(255.0 * 255.0 * 96.0 / 100.0), 1e-9);
    EXPECT_NEAR(m.mad, 10.0 / 96.0, 1e-12);
    EXPECT_EQ(m.max_abs, 10.0);
    EXPECT_EQ(m.p99, 10.0);  // the 99th percentile of 32 per-pixel maxima is the largest
    // Symmetric.
    ImageMetrics r = compare_images(b, a);
    EXPECT_EQ(r.psnr_db, m.psnr_db);
    EXPECT_EQ(r.mad, m.mad);
}

TEST(Metrics, AlphaIsIgnored) {
    Image8 a = solid(4, 4, 10, 20, 30);
    Image8 b = a;
    b.at(1, 1)[3] = 0;
    ImageMetrics m = compare_images(a, b);
    EXPECT_TRUE(std::isinf(m.psnr_db));
    EXPECT_EQ(m.max_abs, 0.0);
}

TEST(Metrics, BackgroundMasking) {
    const int w = 10, h = 10;
    Image8 a = solid(w, h, 0, 0, 0), b = solid(w, h, 0, 0, 0);
    // Two object pixels equal in both, one that differs, one present only in b.
    a.at(1, 1)[0] = b.at(1, 1)[0] = 200;
    a.at(2, 2)[1] = b.at(2, 2)[1] = 50;
    a.at(5, 5)[2] = 100;
    b.at(5, 5)[2] = 90;
    b.at(7, 3)[0] = 20;  // a has background here
    ImageMetrics masked = compare_images(a, b);  // default: mask black
    EXPECT_EQ(masked.pixels, 4u);
    double sq = 10.0 * 10.0 + 20.0 * 20.0;
    EXPECT_NEAR(masked.psnr_db, 10.0 * std::log10(255.0 * 255.0 / (sq / (3.0 * 4.0))), 1e-9);
    EXPECT_NEAR(masked.mad, 30.0 / 12.0, 1e-12);
    EXPECT_EQ(masked.max_abs, 20.0);

    ImageMetrics full = compare_images(a, b, false);
    EXPECT_EQ(full.pixels, 100u);
    EXPECT_NEAR(full.psnr_db, 10.0 * std::log10(255.0 * 255.0 / (sq / 300.0)), 1e-9);
    EXPECT_GT(full.psnr_db, masked.psnr_db);  // the same error diluted over more pixels

    // A custom background: white. Now every black pixel counts as foreground.
    const std::uint8_t white[3] = {255, 255, 255};
    ImageMetrics wbg = compare_images(a, b, true, white);
    EXPECT_EQ(wbg.pixels, 100u);
    Image8 c = solid(w, h, 255, 255, 255), d = solid(w, h, 255, 255, 255);
    c.at(0, 0)[0] = 0;
    d.at(0, 0)[0] = 0;
    d.at(9, 9)[2] = 250;
    ImageMetrics wm = compare_images(c, d, true, white);
    EXPECT_EQ(wm.pixels, 2u);
    EXPECT_EQ(wm.max_abs, 5.0);
    EXPECT_NEAR(wm.psnr_db, 10.0 * std::log10(255.0 * 255.0 / (25.0 / 6.0)), 1e-9);
}

TEST(Metrics, AllBackgroundIsInfinite) {
    Image8 a = solid(6, 6, 0, 0, 0);
    ImageMetrics m = compare_images(a, a);
    EXPECT_EQ(m.pixels, 0u);
    EXPECT_TRUE(std::isinf(m.psnr_db));
}

TEST(Metrics, P99IgnoresRareOutliers) {
    // 1000 pixels, 5 with a large error: the 99th percentile is still small.
    Image8 a = solid(100, 10, 100, 100, 100), b = a;
    for (int x = 0; x < 100; ++x)
        for (int y = 0; y < 10; ++y) b.at(x, y)[0] = 101;
    for (int i = 0; i < 5; ++i) b.at(i * 10, 3)[1] = 200;
    ImageMetrics m = compare_images(a, b);
    EXPECT_EQ(m.pixels, 1000u);
    EXPECT_EQ(m.max_abs, 100.0);
    EXPECT_EQ(m.p99, 1.0);
}

TEST(Metrics, SizeMismatchThrows) {
    Image8 a = solid(4, 4, 1, 1, 1), b = solid(4, 5, 1, 1, 1);
    Error e = capture_error([&] { compare_images(a, b); });
    EXPECT_NE(e.reason().find("4x4"), std::string::npos) << e.what();
    EXPECT_NE(e.reason().find("4x5"), std::string::npos) << e.what();
}

TEST(ImageDecode, ExrAttributeClaimingMoreThanTheFileIsRefusedBeforeOpenExr) {
    // OpenEXR would resize a string to the declared attribute size (up to 2 GiB) before
    // reading it; the header walk refuses such a size first, naming the attribute.
    TempDir dir;
    write_exr(dir / "ok.exr", pattern_float(4, 4));
    auto bytes = read_file_bytes(dir / "ok.exr", 1 << 20);
    // The first attribute starts at byte 8: "channels\0chlist\0" then its int32 size.
    ASSERT_EQ(std::string(reinterpret_cast<const char*>(bytes.data()) + 8), "channels");
    const std::size_t size_at = 8 + 9 + 7;
    for (std::uint32_t claimed : {0x7FFFFFF0u, 0x80000000u, std::uint32_t(bytes.size())}) {
        auto bad = bytes;
        for (int k = 0; k < 4; ++k) bad[size_at + k] = std::uint8_t(claimed >> (8 * k));
        const auto start = std::chrono::steady_clock::now();
        Error e = capture_error([&] { decode_image_float(bad, "big-attr.exr"); });
        EXPECT_NE(e.reason().find("'channels' claims"), std::string::npos) << e.what();
        EXPECT_EQ(e.where(), "byte 8");
        EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
    }
    EXPECT_NO_THROW(decode_image_float(bytes, "ok.exr"));
}

TEST(ImageDecode, ExrHugeDataWindowIsRefusedBeforeOpenExrAllocates) {
    TempDir dir;
    write_exr(dir / "ok.exr", pattern_float(4, 4));
    auto bytes = read_file_bytes(dir / "ok.exr", 1 << 20);
    // Find the dataWindow attribute's value and make it 2^30 lines tall.
    const std::string key("dataWindow");
    auto it = std::search(bytes.begin(), bytes.end(), key.begin(), key.end());
    ASSERT_NE(it, bytes.end());
    std::size_t value = std::size_t(it - bytes.begin()) + key.size() + 1 + 6 + 4;  // name\0 "box2i\0" size
    const std::int32_t ymax = 1 << 30;
    for (int k = 0; k < 4; ++k) bytes[value + 12 + k] = std::uint8_t(std::uint32_t(ymax) >> (8 * k));
    Error e = capture_error([&] { decode_image_float(bytes, "tall.exr"); });
    EXPECT_NE(e.reason().find("limit"), std::string::npos) << e.what();
    EXPECT_NE(e.where().find("dataWindow"), std::string::npos) << "refused by the header walk: " << e.what();
}

TEST(ImageDecode, ExrAttributeWhoseStructureDoesNotFitItsSizeIsRefused) {
    // OpenEXR reads a channel list by its structure; if that disagrees with the declared
    // size, the rest of the header is read from the wrong place (fuzz_exr found a 1.7 GB
    // allocation that way). The header walk refuses such a file first.
    TempDir dir;
    write_exr(dir / "ok.exr", pattern_float(4, 4));
    auto bytes = read_file_bytes(dir / "ok.exr", 1 << 20);
    const std::size_t size_at = 8 + 9 + 7;  // "channels\0chlist\0" then the int32 size
    bytes[size_at] = std::uint8_t(bytes[size_at] - 1);  // one byte less than the list takes
    Error e = capture_error([&] { decode_image_float(bytes, "chlist.exr"); });
    EXPECT_NE(e.reason().find("does not fit"), std::string::npos) << e.what();
    EXPECT_EQ(e.where(), "byte 8");
}
