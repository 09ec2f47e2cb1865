// Our Zstandard decoder (libs/core/src/zstd_decoder.h, the web build's) held byte for byte to
// libzstd: varied data compressed by libzstd at levels -5..22, with and without checksums and
// content sizes, long windows, small target blocks, several frames with skippable ones between;
// every level of the real Zstandard KTX2 files (skipped without ../shared/assets/ktx2);
// hand-built frames for what libzstd never writes; and hostile input (every truncation,
// random bit flips, lying headers, wrong output sizes) that must fail with fresnel::Error.
#include <gtest/gtest.h>
#define ZSTD_STATIC_LINKING_ONLY  // ZSTD_c_targetCBlockSize, ZSTD_c_literalCompressionMode
#include <zstd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "../src/zstd_decoder.h"
#include "fresnel/core/error.h"

#ifndef FRESNEL_SHARED_DIR
#define FRESNEL_SHARED_DIR "../shared"
#endif

namespace fs = std::filesystem;
using fresnel::Error;
using fresnel::detail::zstd_decompress;
using Bytes = std::vector<std::uint8_t>;

namespace {

// ------------------------------------------------------------------ libzstd side

struct Options {
    int level = 3;
    bool checksum = false;
    bool content_size = true;
    int window_log = 0;         // 0: libzstd's choice
    bool long_distance = false;
    int target_block = 0;       // ZSTD_c_targetCBlockSize: many small compressed blocks
    int literals = 0;           // ZSTD_c_literalCompressionMode: 0 auto, 1 Huffman, 2 raw
};

Bytes compress(const Bytes& data, const Options& o) {
    ZSTD_CCtx* c = ZSTD_createCCtx();
    ZSTD_CCtx_setParameter(c, ZSTD_c_compressionLevel, o.level);
    ZSTD_CCtx_setParameter(c, ZSTD_c_checksumFlag, o.checksum ? 1 : 0);
    ZSTD_CCtx_setParameter(c, ZSTD_c_contentSizeFlag, o.content_size ? 1 : 0);
    if (o.window_log) ZSTD_CCtx_setParameter(c, ZSTD_c_windowLog, o.window_log);
    if (o.long_distance) ZSTD_CCtx_setParameter(c, ZSTD_c_enableLongDistanceMatching, 1);
    if (o.target_block) ZSTD_CCtx_setParameter(c, ZSTD_c_targetCBlockSize, o.target_block);
    if (o.literals)
        ZSTD_CCtx_setParameter(c, ZSTD_c_literalCompressionMode, o.literals == 1 ? ZSTD_ps_enable : ZSTD_ps_disable);
    Bytes out(ZSTD_compressBound(data.size()));
    const std::size_t n = ZSTD_compress2(c, out.data(), out.size(), data.data(), data.size());
    ZSTD_freeCCtx(c);
    if (ZSTD_isError(n)) ADD_FAILURE() << "libzstd: " << ZSTD_getErrorName(n);
    out.resize(ZSTD_isError(n) ? 0 : n);
    return out;
}

// libzstd's verdict: true and `out` when `z` decodes to exactly `size` bytes.
bool libzstd_decode(const Bytes& z, std::size_t size, Bytes& out) {
    out.assign(size + 1, 0);  // one spare byte: inflating to more than `size` is a failure too
    const std::size_t n = ZSTD_decompress(out.data(), out.size(), z.data(), z.size());
    if (ZSTD_isError(n) || n != size) return false;
    out.resize(size);
    return true;
}

// ------------------------------------------------------------------ our side

Bytes decode(const Bytes& z, std::size_t size) {
    Bytes out(size, 0xCD);
    zstd_decompress(z, out, "test.zst");
    return out;
}

// Ours on hostile input: true when it decoded, false on fresnel::Error; anything else fails.
bool try_decode(const Bytes& z, std::size_t size, Bytes& out, std::string* reason = nullptr) {
    out.assign(size, 0xCD);
    try {
        zstd_decompress(z, out, "hostile.zst");
        return true;
    } catch (const Error& e) {
        if (reason) *reason = e.what();
        return false;
    } catch (const std::exception& e) {
        ADD_FAILURE() << "not a fresnel::Error: " << e.what();
        return false;
    }
}

// ------------------------------------------------------------------ data

Bytes text(std::size_t n, std::uint64_t seed) {
    static const char* const words[] = {"the",     "quick",  "brown",    "fox",   "jumps", "over",      "lazy",
                                        "dog",     "photon", "radiance", "BRDF",  "mip",   "texture",   "normal",
                                        "specular", "fresnel", "roughness", "glTF", "KTX2",  "supercompression",
                                        "Zstandard", "entropy", "Huffman", "FSE", "\n", ", ", ". ", "0.5", "1024"};
    std::mt19937_64 rng(seed);
    Bytes out;
    out.reserve(n + 32);
    while (out.size() < n) {
        const std::string w = words[rng() % std::size(words)];
        out.insert(out.end(), w.begin(), w.end());
        out.push_back(rng() % 7 == 0 ? '\t' : ' ');
    }
    out.resize(n);
    return out;
}

Bytes random_bytes(std::size_t n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    Bytes out(n);
    for (auto& b : out) b = std::uint8_t(rng());
    return out;
}

Bytes pattern(std::size_t n, std::size_t period, std::uint64_t seed) {
    const Bytes unit = random_bytes(period, seed);
    Bytes out(n);
    for (std::size_t i = 0; i < n; ++i) out[i] = unit[i % period];
    return out;
}

// Geometric symbol frequencies: long Huffman codes (up to the 11-bit limit).
Bytes skewed(std::size_t n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::geometric_distribution<int> g(0.35);
    Bytes out(n);
    for (auto& b : out) b = std::uint8_t(std::min(g(rng), 255) * 13);
    return out;
}

// Every byte value, unevenly: more than 128 symbols, so the Huffman weights are FSE-coded.
Bytes wide(std::size_t n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> d(128.0, 40.0);
    Bytes out(n);
    for (auto& b : out) b = std::uint8_t(std::clamp(d(rng), 0.0, 255.0));
    return out;
}

// Four symbols: a small Huffman tree (weights written directly).
Bytes small_alphabet(std::size_t n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    Bytes out(n);
    for (auto& b : out) b = "ACGT"[rng() % 4];
    return out;
}

// Values 0..15, geometric: few symbols, so the Huffman weights are written directly.
Bytes nibbles(std::size_t n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    Bytes out(n);
    for (auto& b : out) {
        int v = 0;
        while (rng() % 3 == 0 && v < 15) ++v;
        b = std::uint8_t(v);
    }
    return out;
}

// 120 KB of noise, then copies of pieces of it each after one 'Z': past the first block every
// literal is 'Z' (libzstd at level 19 codes such a block's literals as RLE).
Bytes one_literal(std::size_t n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    Bytes out = random_bytes(std::min<std::size_t>(n, 120000), seed);
    while (out.size() < n) {
        out.push_back('Z');
        const std::size_t from = rng() % 100000, len = 16 + rng() % 48;
        out.insert(out.end(), out.begin() + std::ptrdiff_t(from), out.begin() + std::ptrdiff_t(from + len));
    }
    out.resize(n);
    return out;
}

// Texture-like: 16-bit ramps with noise, like the half floats of an HDR level.
Bytes ramps(std::size_t n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    Bytes out(n);
    for (std::size_t i = 0; i + 1 < n; i += 2) {
        const std::uint16_t v = std::uint16_t(0x3C00 + (i / 2 % 512) * 3 + rng() % 4);
        out[i] = std::uint8_t(v), out[i + 1] = std::uint8_t(v >> 8);
    }
    return out;
}

// Runs of the above, zeros and repeats of earlier parts far back.
Bytes mixed(std::size_t n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    Bytes out;
    while (out.size() < n) {
        const std::size_t len = 1 + rng() % 20000;
        Bytes part;
        switch (rng() % 6) {
            case 0: part = text(len, rng()); break;
            case 1: part = random_bytes(len, rng()); break;
            case 2: part.assign(len, std::uint8_t(rng())); break;
            case 3: part = skewed(len, rng()); break;
            case 4: part = ramps(len, rng()); break;
            default:
                if (!out.empty()) {
                    const std::size_t from = rng() % out.size();
                    part.assign(out.begin() + std::ptrdiff_t(from),
                                out.begin() + std::ptrdiff_t(std::min(out.size(), from + len)));
                }
        }
        out.insert(out.end(), part.begin(), part.end());
    }
    out.resize(n);
    return out;
}

struct Kind {
    const char* name;
    Bytes (*make)(std::size_t, std::uint64_t);
};

const Kind kKinds[] = {
    {"text", text},
    {"random", random_bytes},
    {"zeros", [](std::size_t n, std::uint64_t) { return Bytes(n, 0); }},
    {"period3", [](std::size_t n, std::uint64_t s) { return pattern(n, 3, s); }},
    {"period1000", [](std::size_t n, std::uint64_t s) { return pattern(n, 1000, s); }},
    {"skewed", skewed},
    {"wide", wide},
    {"acgt", small_alphabet},
    {"nibbles", nibbles},
    {"ramps", ramps},
    {"mixed", mixed},
};

// ------------------------------------------------------------------ stream census

// Walks a Zstandard stream (trusted: libzstd's) and counts the format features it uses, so the
// tests can show every block, literals and table kind went through the decoder.
void census(const Bytes& z, std::map<std::string, int>& seen) {
    std::size_t p = 0;
    while (p + 4 <= z.size()) {
        const std::uint32_t magic = std::uint32_t(z[p]) | std::uint32_t(z[p + 1]) << 8 | std::uint32_t(z[p + 2]) << 16 |
                                    std::uint32_t(z[p + 3]) << 24;
        if ((magic & 0xFFFFFFF0u) == 0x184D2A50u) {
            ++seen["skippable frame"];
            p += 8 + (std::size_t(z[p + 4]) | std::size_t(z[p + 5]) << 8 | std::size_t(z[p + 6]) << 16 |
                      std::size_t(z[p + 7]) << 24);
            continue;
        }
        const unsigned d = z[p + 4];
        const bool single = d & 0x20;
        ++seen[single ? "single-segment frame" : "windowed frame"];
        if (d & 4) ++seen["checksum"];
        if ((d >> 6) == 0 && !single) ++seen["unknown content size"];
        const std::size_t fcs = (d >> 6) == 0 ? (single ? 1 : 0) : std::size_t(1) << (d >> 6);
        p += 5 + (single ? 0 : 1) + std::size_t(std::array<int, 4>{0, 1, 2, 4}[d & 3]) + fcs;
        for (bool last = false; !last;) {
            const std::uint32_t h = std::uint32_t(z[p]) | std::uint32_t(z[p + 1]) << 8 | std::uint32_t(z[p + 2]) << 16;
            last = h & 1;
            const unsigned type = (h >> 1) & 3;
            const std::size_t size = h >> 3;
            p += 3;
            if (type == 0) ++seen["raw block"];
            if (type == 1) ++seen["RLE block"];
            if (type == 2) {
                ++seen["compressed block"];
                std::size_t q = p;
                const unsigned lt = z[q] & 3, sf = (z[q] >> 2) & 3;
                if (lt < 2) {
                    ++seen[lt == 0 ? "raw literals" : "RLE literals"];
                    const std::size_t hdr = sf == 1 ? 2 : sf == 3 ? 3 : 1;
                    std::size_t n = z[q] >> 3;
                    if (sf == 1) n = (z[q] >> 4) | std::size_t(z[q + 1]) << 4;
                    if (sf == 3) n = (z[q] >> 4) | std::size_t(z[q + 1]) << 4 | std::size_t(z[q + 2]) << 12;
                    q += hdr + (lt == 0 ? n : 1);
                } else {
                    ++seen[std::string(lt == 2 ? "Huffman" : "treeless") + (sf == 0 ? " literals, 1 stream"
                                                                                    : " literals, 4 streams")];
                    const unsigned hdr = sf < 2 ? 3 : sf + 2, field = sf < 2 ? 10 : 4 * sf + 6;
                    std::uint64_t v = 0;
                    for (unsigned i = 0; i < hdr; ++i) v |= std::uint64_t(z[q + i]) << (8 * i);
                    if (lt == 2) ++seen[z[q + hdr] < 128 ? "FSE-coded Huffman weights" : "direct Huffman weights"];
                    q += hdr + std::size_t((v >> (4 + field)) & ((1u << field) - 1));
                }
                if (z[q] == 0) {
                    ++seen["no sequences"];
                } else {
                    q += z[q] < 128 ? 1 : z[q] < 255 ? 2 : 3;
                    static const char* const modes[] = {"predefined", "RLE", "FSE", "repeat"};
                    ++seen[std::string("LL ") + modes[z[q] >> 6]];
                    ++seen[std::string("OF ") + modes[(z[q] >> 4) & 3]];
                    ++seen[std::string("ML ") + modes[(z[q] >> 2) & 3]];
                }
            }
            p += type == 1 ? 1 : size;
        }
        if (d & 4) p += 4;
    }
}

// ------------------------------------------------------------------ hand-built frames

void put32(Bytes& b, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) b.push_back(std::uint8_t(v >> (8 * i)));
}

// A block header and its content (for RLE, `content` is the byte and `size` the run).
void add_block(Bytes& b, unsigned type, bool last, const Bytes& content, std::size_t size = SIZE_MAX) {
    if (size == SIZE_MAX) size = content.size();
    const std::uint32_t h = (last ? 1u : 0u) | type << 1 | std::uint32_t(size) << 3;
    b.push_back(std::uint8_t(h)), b.push_back(std::uint8_t(h >> 8)), b.push_back(std::uint8_t(h >> 16));
    b.insert(b.end(), content.begin(), content.end());
}

// A single-segment frame holding `size` (< 256) bytes, made of `blocks` (headers included).
Bytes single_frame(std::uint8_t size, const Bytes& blocks) {
    Bytes f;
    put32(f, 0xFD2FB528u);
    f.push_back(0x20);  // Single_Segment, 1-byte content size
    f.push_back(size);
    f.insert(f.end(), blocks.begin(), blocks.end());
    return f;
}

// A frame holding `size` bytes in a 1 KiB window, made of `blocks` (headers included).
Bytes small_frame(std::uint32_t size, const Bytes& blocks) {
    Bytes f;
    put32(f, 0xFD2FB528u);
    f.push_back(0x80);  // 4-byte content size, a window descriptor
    f.push_back(0x00);  // 1 KiB
    put32(f, size);
    f.insert(f.end(), blocks.begin(), blocks.end());
    return f;
}

// One compressed block: raw literals "abc", then one sequence with RLE tables for literal length
// code `ll`, offset code `of`, match length code `ml`, and `bits` (its top set bit the end marker)
// as the sequence bitstream.
Bytes one_sequence(std::uint8_t ll, std::uint8_t of, std::uint8_t ml, std::uint8_t bits, std::uint8_t modes = 0x54) {
    Bytes block;
    add_block(block, 2, true, {0x18, 'a', 'b', 'c', 0x01, modes, ll, of, ml, bits});
    return block;
}

std::string reason_of(const Bytes& z, std::size_t size) {
    Bytes out;
    std::string reason;
    if (try_decode(z, size, out, &reason)) return "(decoded)";
    return reason;
}

Bytes read_file(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(in), {});
}

double ms_since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

// ================================================================== round trips

TEST(ZstdDecoder, Xxh64MatchesLibzstdChecksums) {
    EXPECT_EQ(fresnel::detail::zstd_xxh64({}), 0xEF46DB3751D8E999ull);  // XXH64 of nothing, seed 0
    // Every tail length and both sides of the 32-byte stripe: the frame's checksum is XXH64's low half.
    for (std::size_t n = 0; n < 200; ++n) {
        const Bytes data = random_bytes(n, n);
        const Bytes z = compress(data, {.level = 1, .checksum = true});
        ASSERT_GE(z.size(), 4u);
        const std::uint32_t stored = std::uint32_t(z[z.size() - 4]) | std::uint32_t(z[z.size() - 3]) << 8 |
                                     std::uint32_t(z[z.size() - 2]) << 16 | std::uint32_t(z[z.size() - 1]) << 24;
        EXPECT_EQ(std::uint32_t(fresnel::detail::zstd_xxh64(data)), stored) << n << " bytes";
    }
}

TEST(ZstdDecoder, MatchesLibzstdAcrossDataLevelsAndSizes) {
    const std::size_t sizes[] = {0, 1, 2, 5, 31, 32, 33, 100, 1000, 4095, 65536, 131071, 131072, 131073, 400000, 1100000};
    const int levels[] = {-5, 1, 3, 9, 19, 22};
    std::map<std::string, int> seen;
    std::size_t streams = 0, in_bytes = 0, out_bytes = 0;
    std::uint64_t seed = 1;
    for (const Kind& kind : kKinds)
        for (const std::size_t size : sizes) {
            const Bytes data = kind.make(size, seed++);
            for (const int level : levels) {
                // The slow levels on the big sizes cost seconds for nothing new.
                const std::string name = kind.name;
                if (level >= 19 && size > 65536 && !(size <= 400000 && (name == "mixed" || name == "text"))) continue;
                if (level >= 9 && size > 400000) continue;
                const bool checksum = (seed + std::uint64_t(level)) % 2 == 0;
                const bool content_size = (seed + std::uint64_t(level)) % 3 != 0;
                const Bytes z = compress(data, {.level = level, .checksum = checksum, .content_size = content_size});
                census(z, seen);
                ++streams, in_bytes += z.size(), out_bytes += data.size();
                Bytes out;
                ASSERT_NO_THROW(out = decode(z, data.size())) << kind.name << " " << size << " bytes, level " << level;
                ASSERT_TRUE(out == data) << kind.name << " " << size << " bytes, level " << level;
            }
        }
    std::printf("%zu streams, %zu compressed bytes -> %zu bytes\n", streams, in_bytes, out_bytes);
    for (const auto& [feature, count] : seen) std::printf("  %-36s %d\n", feature.c_str(), count);
    // What libzstd writes for such data: every kind of block, literals and table.
    for (const char* feature :
         {"raw block", "RLE block", "compressed block", "raw literals", "Huffman literals, 1 stream",
          "Huffman literals, 4 streams", "treeless literals, 4 streams", "FSE-coded Huffman weights",
          "direct Huffman weights", "no sequences", "LL predefined", "LL RLE", "LL FSE", "LL repeat", "OF predefined",
          "OF FSE", "OF repeat", "ML predefined", "ML RLE", "ML FSE", "ML repeat", "checksum", "single-segment frame",
          "windowed frame", "unknown content size"})
        EXPECT_GT(seen[feature], 0) << feature;
}

TEST(ZstdDecoder, SmallBlocksReuseTablesAndTrees) {
    // A small target block size splits the data into many compressed blocks that repeat the
    // previous block's FSE tables and Huffman tree (Repeat_Mode, treeless literals).
    std::map<std::string, int> seen;
    std::uint64_t seed = 100;
    for (const Kind& kind : kKinds)
        for (const int level : {1, 3, 19}) {
            const Bytes data = kind.make(200000, seed++);
            const Bytes z = compress(data, {.level = level, .checksum = true, .target_block = 1340});
            census(z, seen);
            Bytes out;
            ASSERT_NO_THROW(out = decode(z, data.size())) << kind.name << " level " << level;
            ASSERT_TRUE(out == data) << kind.name << " level " << level;
        }
    EXPECT_GT(seen["treeless literals, 1 stream"] + seen["treeless literals, 4 streams"], 0);
    EXPECT_GT(seen["LL repeat"] + seen["OF repeat"] + seen["ML repeat"], 0);
}

TEST(ZstdDecoder, RleLiterals) {
    const Bytes data = one_literal(400000, 1);
    const Bytes z = compress(data, {.level = 19, .checksum = true});
    std::map<std::string, int> seen;
    census(z, seen);
    EXPECT_GT(seen["RLE literals"], 0);
    Bytes out;
    ASSERT_NO_THROW(out = decode(z, data.size()));
    EXPECT_TRUE(out == data);
}

TEST(ZstdDecoder, ForcedLiteralModes) {
    std::uint64_t seed = 200;
    for (const Kind& kind : kKinds)
        for (const int literals : {1, 2}) {
            const Bytes data = kind.make(150000, seed++);
            const Bytes z = compress(data, {.level = 3, .literals = literals});
            Bytes out;
            ASSERT_NO_THROW(out = decode(z, data.size())) << kind.name << " literals mode " << literals;
            ASSERT_TRUE(out == data) << kind.name << " literals mode " << literals;
        }
}

TEST(ZstdDecoder, LongWindowsAndUltra) {
    // 1.5 MiB of noise twice: the second copy is one match 1.5 MiB back (long-distance matching,
    // a 16 MiB window; offset codes of 20+ extra bits).
    Bytes data = random_bytes(1536 * 1024, 7);
    data.insert(data.end(), data.begin(), data.end());
    for (const int level : {1, 3}) {
        const Bytes z = compress(data, {.level = level, .checksum = true, .window_log = 24, .long_distance = true});
        EXPECT_LT(z.size(), data.size() * 6 / 10);  // the repeat was found
        Bytes out;
        ASSERT_NO_THROW(out = decode(z, data.size()));
        EXPECT_TRUE(out == data);
    }
    // --ultra -22 with a 128 MiB window on text with far repeats.
    const Bytes far = mixed(600000, 8);
    const Bytes z = compress(far, {.level = 22, .checksum = true, .content_size = false, .window_log = 27});
    Bytes out;
    ASSERT_NO_THROW(out = decode(z, far.size()));
    EXPECT_TRUE(out == far);
}

TEST(ZstdDecoder, FramesSkippableFramesAndEmptyContent) {
    const Bytes a = text(10000, 1), b(200000, 0), c = random_bytes(5000, 3), d = mixed(300000, 4);
    Bytes skippable;
    put32(skippable, 0x184D2A5Au);
    put32(skippable, 100);
    skippable.insert(skippable.end(), 100, 0xEE);
    Bytes empty_skippable;
    put32(empty_skippable, 0x184D2A50u);
    put32(empty_skippable, 0);

    Bytes z, expect;
    auto add = [&](const Bytes& data, const Options& o) {
        const Bytes f = compress(data, o);
        z.insert(z.end(), f.begin(), f.end());
        expect.insert(expect.end(), data.begin(), data.end());
    };
    z = empty_skippable;
    add(a, {.level = 1});
    z.insert(z.end(), skippable.begin(), skippable.end());
    add(b, {.level = 3, .checksum = true});
    add({}, {.level = 3});
    add(c, {.level = 19, .content_size = false});
    add({}, {.level = 1, .checksum = true, .content_size = false});
    add(d, {.level = 9, .checksum = true, .content_size = false});
    z.insert(z.end(), skippable.begin(), skippable.end());

    Bytes ref;
    ASSERT_TRUE(libzstd_decode(z, expect.size(), ref));
    ASSERT_TRUE(ref == expect);
    Bytes out;
    ASSERT_NO_THROW(out = decode(z, expect.size()));
    EXPECT_TRUE(out == expect);

    // Empty content, alone: a frame of no bytes; only skippable frames; but no data at all is not Zstandard.
    for (const bool checksum : {false, true})
        for (const bool content_size : {false, true})
            EXPECT_NO_THROW(decode(compress({}, {.level = 3, .checksum = checksum, .content_size = content_size}), 0));
    EXPECT_NO_THROW(decode(skippable, 0));
    EXPECT_THROW(decode({}, 0), Error);
}

TEST(ZstdDecoder, HandBuiltFramesAgreeWithLibzstd) {
    // What libzstd does not write on its own, built by hand and checked against libzstd too.
    struct Case {
        const char* what;
        std::uint32_t size;
        Bytes blocks;
        bool valid;
        Bytes expect;
        bool libzstd_lenient = false;  // libzstd (1.5.4) takes it although RFC 8878 says no
    };
    auto bytes = [](const char* s) { return Bytes(s, s + std::strlen(s)); };
    Bytes rle_literals;  // RLE literals "zzzzz", no sequences
    add_block(rle_literals, 2, true, {(5 << 3) | 1, 'z', 0x00});
    Bytes blocks_of_every_type;
    add_block(blocks_of_every_type, 0, false, {'x', 'y'});
    add_block(blocks_of_every_type, 1, false, {'-'}, 3);
    add_block(blocks_of_every_type, 2, true, {0x18, 'a', 'b', 'c', 0x00});
    Bytes empty_raw_blocks;
    add_block(empty_raw_blocks, 0, false, {});
    add_block(empty_raw_blocks, 1, false, {'q'}, 0);
    add_block(empty_raw_blocks, 0, true, {'k'});
    // Huffman literals {0, 1}, 1 stream, 3 bytes: the tree (128: one weight written, 0x10: weight 1
    // for symbol 0, symbol 1's weight 1 implied; codes 0 and 1) and one stream byte 0b101 (read from
    // below the end marker: 0, then 1).
    Bytes direct_weights;
    add_block(direct_weights, 2, true, {0x02 | (2 << 4), 3 << 6, 0x00, 0x80, 0x10, 0b101, 0x00});
    const Case cases[] = {
        {"raw, RLE and compressed blocks", 8, blocks_of_every_type, true, bytes("xy---abc")},
        {"empty blocks", 1, empty_raw_blocks, true, bytes("k")},
        {"RLE literals", 5, rle_literals, true, bytes("zzzzz")},
        {"RLE tables, one match of offset 3", 6, one_sequence(3, 2, 0, 0b110), true, bytes("abcabc")},
        {"overlapping match, offset 1", 9, one_sequence(3, 2, 3, 0b100), true, bytes("abccccccc")},
        {"Huffman literals with directly written weights", 2, direct_weights, true, Bytes{0, 1}},
        {"repeat offset 3 (initially 8) reaches before the frame", 6, one_sequence(3, 1, 0, 0b11), false, {}},
        {"offset 29 reaches before the frame", 6, one_sequence(3, 5, 0, 0b100000), false, {}},
        {"4 literals taken of 3", 7, one_sequence(4, 2, 0, 0b110), false, {}},
        {"match past the content size", 6, one_sequence(3, 2, 5, 0b110), false, {}},
        {"bits left over in the sequence bitstream", 6, one_sequence(3, 2, 0, 0b11010), false, {}},
        {"repeated literal-length table with none before", 6, one_sequence(3, 2, 0, 0b110, 0xD4), false, {}},
        {"reserved bits in the sequence modes", 6, one_sequence(3, 2, 0, 0b110, 0x55), false, {}, true},
        {"RLE symbol past the literal-length codes", 6, one_sequence(36, 2, 0, 0b110), false, {}},
    };
    for (const Case& c : cases) {
        const Bytes frame = small_frame(c.size, c.blocks);
        const std::size_t size = c.size;
        Bytes ref, ours;
        const bool lib_ok = libzstd_decode(frame, size, ref);
        const bool our_ok = try_decode(frame, size, ours);
        EXPECT_EQ(our_ok, c.valid) << c.what << ": " << reason_of(frame, size);
        EXPECT_EQ(lib_ok, c.valid || c.libzstd_lenient) << c.what << " (libzstd)";
        if (our_ok && c.valid) {
            EXPECT_TRUE(ours == c.expect) << c.what;
        }
        if (lib_ok && c.valid) {
            EXPECT_TRUE(ref == c.expect) << c.what << " (libzstd)";
        }
    }
}

// ================================================================== the real KTX2 levels

TEST(ZstdDecoder, Ktx2LevelsMatchLibzstd) {
    const fs::path dir = fs::path(FRESNEL_SHARED_DIR) / "assets" / "ktx2";
    int levels = 0;
    for (const char* file : {"kodim23_uastc_zstd_mips.ktx2", "desk_uastc_hdr_zstd.ktx2"}) {
        const Bytes k = read_file(dir / file);
        if (k.empty()) continue;
        auto u32 = [&](std::size_t at) { return std::uint32_t(k[at]) | std::uint32_t(k[at + 1]) << 8 |
                                                std::uint32_t(k[at + 2]) << 16 | std::uint32_t(k[at + 3]) << 24; };
        auto u64 = [&](std::size_t at) { return std::uint64_t(u32(at)) | std::uint64_t(u32(at + 4)) << 32; };
        ASSERT_GE(k.size(), 80u);
        ASSERT_EQ(u32(44), 2u) << file << " is not Zstandard-supercompressed";
        const std::uint32_t count = std::max<std::uint32_t>(u32(40), 1);
        ASSERT_GE(k.size(), 80 + 24 * std::size_t(count));
        for (std::uint32_t i = 0; i < count; ++i) {
            const std::uint64_t offset = u64(80 + 24 * i), length = u64(88 + 24 * i), size = u64(96 + 24 * i);
            ASSERT_LE(offset + length, k.size());
            const Bytes z(k.begin() + std::ptrdiff_t(offset), k.begin() + std::ptrdiff_t(offset + length));
            Bytes ref;
            ASSERT_TRUE(libzstd_decode(z, std::size_t(size), ref)) << file << " level " << i;
            std::map<std::string, int> seen;
            census(z, seen);
            // Best of 5 each, ours then libzstd's.
            double ours_ms = 1e9, lib_ms = 1e9;
            Bytes out(ref.size());
            for (int run = 0; run < 5; ++run) {
                auto t = std::chrono::steady_clock::now();
                ASSERT_NO_THROW(zstd_decompress(z, out, file)) << file << " level " << i;
                ours_ms = std::min(ours_ms, ms_since(t));
                t = std::chrono::steady_clock::now();
                ZSTD_decompress(ref.data(), ref.size(), z.data(), z.size());
                lib_ms = std::min(lib_ms, ms_since(t));
            }
            EXPECT_TRUE(out == ref) << file << " level " << i;
            std::printf("%s level %u: %zu -> %zu bytes (%d blocks), ours %.3f ms, libzstd %.3f ms\n", file, i, z.size(),
                        ref.size(), seen["raw block"] + seen["RLE block"] + seen["compressed block"], ours_ms, lib_ms);
            ++levels;
        }
    }
    if (levels == 0) GTEST_SKIP() << "no " << dir.string();
}

// ================================================================== hostile input

TEST(ZstdDecoder, EveryTruncationFails) {
    // Streams that use compressed literals and FSE tables (text), 4 Huffman streams, raw and RLE
    // blocks, with and without checksums: each cut short at every length must be an Error.
    const Bytes t = text(3000, 11), m = mixed(12000, 12);
    Bytes multi = compress(t, {.level = 19});
    const Bytes second = compress(Bytes(600, 'r'), {.level = 1, .checksum = true});
    multi.insert(multi.end(), second.begin(), second.end());
    Bytes multi_data = t;
    multi_data.insert(multi_data.end(), 600, 'r');
    const std::pair<Bytes, Bytes> streams[] = {
        {compress(t, {.level = 3}), t},
        {compress(t, {.level = 19, .checksum = true, .content_size = false}), t},
        {compress(m, {.level = 1, .checksum = true}), m},
        {compress(m, {.level = 9, .content_size = false, .target_block = 500}), m},
        {multi, multi_data},
    };
    std::size_t cuts = 0;
    for (const auto& [z, data] : streams) {
        ASSERT_TRUE(decode(z, data.size()) == data);
        for (std::size_t n = 0; n < z.size(); ++n) {
            const Bytes cut(z.begin(), z.begin() + std::ptrdiff_t(n));
            Bytes out;
            EXPECT_FALSE(try_decode(cut, data.size(), out)) << "cut at " << n << " of " << z.size();
            ++cuts;
        }
    }
    std::printf("%zu truncations of %zu streams rejected\n", cuts, std::size(streams));
}

TEST(ZstdDecoder, BitFlipsNeverCrashAndAgreeWithLibzstd) {
    // Flip 1-4 random bits (or overwrite a byte) in valid streams: ours must decode or throw
    // fresnel::Error (the sanitizer build checks it never reads or writes out of bounds), and
    // where both decoders accept the stream, they must agree byte for byte.
    std::vector<std::pair<Bytes, Bytes>> streams;
    std::uint64_t seed = 300;
    for (const Kind& kind : kKinds) {
        const Bytes data = kind.make(12000, seed++);
        streams.push_back({compress(data, {.level = 3}), data});
        streams.push_back({compress(data, {.level = 19, .content_size = false}), data});
    }
    const Bytes big = mixed(150000, 9);
    streams.push_back({compress(big, {.level = 1}), big});
    std::mt19937_64 rng(42);
    int trials = 0, both_ok = 0, both_reject = 0, only_ours = 0, only_libzstd = 0;
    std::map<std::string, int> only_libzstd_reasons;
    for (const auto& [z, data] : streams)
        for (int t = 0; t < 600; ++t) {
            Bytes bad = z;
            if (rng() % 4 == 0) {
                bad[rng() % bad.size()] = std::uint8_t(rng());
            } else {
                for (int flips = 1 + int(rng() % 4); flips > 0; --flips) bad[rng() % bad.size()] ^= std::uint8_t(1u << (rng() % 8));
            }
            Bytes ours, ref;
            std::string reason;
            const bool our_ok = try_decode(bad, data.size(), ours, &reason);
            const bool lib_ok = libzstd_decode(bad, data.size(), ref);
            ++trials;
            if (our_ok && lib_ok) {
                ++both_ok;
                EXPECT_TRUE(ours == ref) << "trial " << trials;
            } else if (!our_ok && !lib_ok) {
                ++both_reject;
            } else if (our_ok) {
                ++only_ours;
            } else {
                ++only_libzstd;
                ++only_libzstd_reasons[reason.substr(reason.find("Zstandard:")) + (ref == data ? " [libzstd: original]" : " [libzstd: other]")];
            }
        }
    std::printf("%d corrupted streams: %d decoded by both (identical), %d rejected by both, %d only ours decoded, "
                "%d only libzstd decoded\n",
                trials, both_ok, both_reject, only_ours, only_libzstd);
    for (const auto& [r, n] : only_libzstd_reasons) std::printf("  ours rejected, libzstd not: %s (x%d)\n", r.c_str(), n);
    EXPECT_EQ(only_ours, 0);
}

TEST(ZstdDecoder, RandomBlocksAfterAValidHeader) {
    std::mt19937_64 rng(5);
    for (int t = 0; t < 3000; ++t) {
        Bytes z;
        put32(z, 0xFD2FB528u);
        z.push_back(std::uint8_t(0x20 | (rng() & 0x04)));  // single segment, 1-byte content size, maybe a checksum
        const std::uint8_t content = std::uint8_t(rng());
        z.push_back(content);
        // A compressed-block header of a plausible size, then noise.
        const std::uint32_t size = std::uint32_t(rng() % 400);
        const std::uint32_t h = 1u | 2u << 1 | size << 3;
        z.push_back(std::uint8_t(h)), z.push_back(std::uint8_t(h >> 8)), z.push_back(std::uint8_t(h >> 16));
        for (std::uint32_t i = 0; i < size + rng() % 8; ++i) z.push_back(std::uint8_t(rng()));
        Bytes out;
        try_decode(z, rng() % 4 ? content : std::size_t(rng() % 3000), out);  // must not crash; either verdict is fine
    }
}

TEST(ZstdDecoder, LyingHeadersAndWrongSizes) {
    const Bytes data = text(50000, 21);
    for (const bool content_size : {true, false}) {
        const Bytes z = compress(data, {.level = 3, .content_size = content_size});
        for (const std::size_t size : {std::size_t(0), data.size() - 1, data.size() + 1, data.size() * 2}) {
            const std::string r = reason_of(z, size);
            EXPECT_NE(r, "(decoded)") << size;
            EXPECT_NE(r.find("byte "), std::string::npos) << r;
        }
    }
    // A window of 2^41 bytes (the largest descriptor), or a content size of 2^62: refused before any work.
    Bytes huge_window;
    put32(huge_window, 0xFD2FB528u);
    huge_window.push_back(0x00);
    huge_window.push_back(0xFF);
    add_block(huge_window, 0, true, {'a'});
    EXPECT_NE(reason_of(huge_window, 1).find("window"), std::string::npos);
    // The largest window libzstd takes (2 GiB) is fine: it is never allocated.
    Bytes big_window;
    put32(big_window, 0xFD2FB528u);
    big_window.push_back(0x00);
    big_window.push_back(0xA8);
    add_block(big_window, 0, true, {'a'});
    EXPECT_EQ(reason_of(big_window, 1), "(decoded)");
    Bytes huge_content;
    put32(huge_content, 0xFD2FB528u);
    huge_content.push_back(0xE0);
    for (int i = 0; i < 8; ++i) huge_content.push_back(i == 7 ? 0x40 : 0);
    add_block(huge_content, 0, true, {'a'});
    EXPECT_NE(reason_of(huge_content, 1).find("more than the 1 left"), std::string::npos) << reason_of(huge_content, 1);

    // Dictionaries are not supported; reserved bits and block types are errors.
    Bytes with_dict;
    put32(with_dict, 0xFD2FB528u);
    with_dict.push_back(0x21);  // single segment, 1-byte dictionary ID
    with_dict.push_back(7);
    with_dict.push_back(1);
    add_block(with_dict, 0, true, {'a'});
    EXPECT_NE(reason_of(with_dict, 1).find("dictionar"), std::string::npos);
    Bytes zero_dict = with_dict;
    zero_dict[5] = 0;  // Dictionary_ID 0 means none
    EXPECT_EQ(reason_of(zero_dict, 1), "(decoded)");
    Bytes reserved = single_frame(1, {});
    reserved[4] |= 0x08;
    add_block(reserved, 0, true, {'a'});
    EXPECT_NE(reason_of(reserved, 1).find("reserved"), std::string::npos);
    Bytes reserved_block;
    add_block(reserved_block, 3, true, {'a'});
    EXPECT_NE(reason_of(single_frame(1, reserved_block), 1).find("reserved"), std::string::npos);
    Bytes raw_too_big;  // a 1-byte frame (so a 1-byte window) whose raw block says 2
    add_block(raw_too_big, 0, true, {'a', 'b'});
    EXPECT_NE(reason_of(single_frame(1, raw_too_big), 1), "(decoded)");

    // A corrupted checksum; bad magic; trailing garbage after a good frame.
    Bytes z = compress(data, {.level = 3, .checksum = true});
    z[z.size() - 2] ^= 0x10;
    EXPECT_NE(reason_of(z, data.size()).find("checksum"), std::string::npos);
    z = compress(data, {.level = 3});
    Bytes bad_magic = z;
    bad_magic[0] ^= 1;
    EXPECT_NE(reason_of(bad_magic, data.size()).find("magic"), std::string::npos);
    z.push_back(0x28);
    z.push_back(0xB5);
    EXPECT_NE(reason_of(z, data.size()), "(decoded)");

    // Huffman weights that do not form a tree (2^2 + 2^0 = 5: no power of two completes it),
    // treeless literals with no tree before, four streams for 5 literals.
    Bytes bad_tree;
    add_block(bad_tree, 2, true, {0x02 | (2 << 4), 3 << 6, 0x00, 0x81, 0x31, 0b110, 0x00});
    EXPECT_NE(reason_of(small_frame(2, bad_tree), 2).find("tree"), std::string::npos);
    Bytes treeless;
    add_block(treeless, 2, true, {0x03 | (2 << 4), 1 << 6, 0x00, 0b110, 0x00});
    EXPECT_NE(reason_of(small_frame(2, treeless), 2).find("treeless"), std::string::npos);
    Bytes four_for_five;
    add_block(four_for_five, 2, true,
              {0x06 | (5 << 4), 0x00, 12 >> 2, 0x80, 0x10, 1, 0, 1, 0, 1, 0, 1, 1, 1, 1, 0x00});
    EXPECT_NE(reason_of(small_frame(5, four_for_five), 5).find("four streams"), std::string::npos);

    // An error names the file and the byte, and src_offset shifts the byte.
    Bytes cut = compress(data, {.level = 3});
    cut.resize(cut.size() / 2);
    Bytes out(data.size());
    try {
        fresnel::detail::zstd_decompress(cut, out, "level.ktx2", 1000);
        ADD_FAILURE() << "decoded a cut stream";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), "level.ktx2");
        ASSERT_EQ(e.where().rfind("byte ", 0), 0u) << e.where();
        EXPECT_GE(std::stoull(e.where().substr(5)), 1000u);
        EXPECT_EQ(e.reason().rfind("Zstandard: ", 0), 0u) << e.reason();
    }
}
