// The UASTC transcoders (fresnel/core/basisu.h) held to the Basis Universal transcoder npm's
// `three` ships, run under Node (skipped without Node or build/node-tools), on synthetic blocks
// of every mode: the real files ktx2_test.cpp decodes use only the few modes their encoder
// chose. UASTC LDR: random valid blocks of all 19 modes, every partition pattern and dual-plane
// component; UASTC HDR (any ASTC 4x4 block of the HDR profile): structured random blocks over
// every legal weight grid, plane count, partition count, endpoint mode, weight and endpoint
// range, void-extent blocks, and illegal ones, decoded by the reference one block at a time.
// The generators are deterministic and written here from the formats' specifications.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "fresnel/core/basisu.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace fresnel;

namespace {

const fs::path kModules = fs::path(FRESNEL_NODE_TOOLS_DIR) / "node_modules";
const fs::path kScripts = fs::path(FRESNEL_SOURCE_DIR) / "tests" / "ktx";

bool have_reference() {
    return fs::exists(kModules / "three" / "examples" / "jsm" / "libs" / "basis" / "basis_transcoder.wasm") &&
           std::system("node --version > /dev/null 2>&1") == 0;
}

#define SKIP_WITHOUT_REFERENCE()                                                                     \
    if (!have_reference())                                                                           \
    GTEST_SKIP() << "no Node.js or no npm 'three' in " << kModules << " (scripts/install-test-tools.sh)"

std::vector<std::uint8_t> read_bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), {});
}

void write_bytes(const fs::path& p, const std::vector<std::uint8_t>& bytes) {
    std::ofstream(p, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

std::string hex(const std::uint8_t* block) {
    std::string s;
    char b[3];
    for (int i = 0; i < 16; ++i) std::snprintf(b, sizeof b, "%02x", block[i]), s += b;
    return s;
}

// A 128-bit block under construction; bit 0 is the lowest bit of byte 0 (both formats).
struct Block {
    std::uint8_t bytes[16] = {};
    void set(int pos, std::uint32_t value, int count) {
        for (int i = 0; i < count; ++i, ++pos) {
            const std::uint8_t bit = std::uint8_t(1u << (pos % 8));
            bytes[pos / 8] = std::uint8_t((value >> i) & 1 ? bytes[pos / 8] | bit : bytes[pos / 8] & ~bit);
        }
    }
};

// Deterministic across standard libraries: raw mt19937_64 output only (the distributions of
// <random> are not specified bit for bit).
struct Rng {
    std::mt19937_64 engine;
    explicit Rng(std::uint64_t seed) : engine(seed) {}
    std::uint32_t below(std::uint32_t n) { return std::uint32_t(engine() % n); }
    std::uint32_t bits(int count) { return count ? std::uint32_t(engine() & ((1ull << count) - 1)) : 0; }
    // 0 .. n-1, an end of the range a quarter of the time (extreme endpoints and weights).
    std::uint32_t value(std::uint32_t n) {
        const std::uint32_t r = below(8);
        return r == 0 ? 0 : r == 1 ? n - 1 : below(n);
    }
    void fill(Block& b) {
        for (auto& x : b.bytes) x = std::uint8_t(engine());
    }
};

// An uncompressed (supercompression 0) single-level KTX2 file (KTX 2.0 specification) of
// Basis Universal blocks: vkFormat 0 and a basic data format descriptor with `model`, BT.709
// primaries, `transfer`, a 4x4 block of 16 bytes and one 128-bit sample of `channel`.
std::vector<std::uint8_t> basis_ktx2(int width, int height, std::uint8_t model, std::uint8_t transfer,
                                     std::uint8_t channel, const std::vector<std::uint8_t>& blocks) {
    constexpr std::uint32_t kDfdOffset = 80 + 24, kDfdLength = 44, kDataOffset = 160;  // levels align to 16
    std::vector<std::uint8_t> f(kDataOffset + blocks.size());
    auto u32 = [&](std::size_t at, std::uint32_t v) {
        for (int i = 0; i < 4; ++i) f[at + std::size_t(i)] = std::uint8_t(v >> (8 * i));
    };
    auto u64 = [&](std::size_t at, std::uint64_t v) { u32(at, std::uint32_t(v)), u32(at + 4, std::uint32_t(v >> 32)); };
    const std::uint8_t id[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
    std::memcpy(f.data(), id, 12);
    // vkFormat, typeSize, width, height, depth, layers, faces, levels, supercompression
    const std::uint32_t fields[9] = {0, 1, std::uint32_t(width), std::uint32_t(height), 0, 0, 1, 1, 0};
    for (int i = 0; i < 9; ++i) u32(12 + 4 * std::size_t(i), fields[i]);
    u32(48, kDfdOffset);
    u32(52, kDfdLength);  // no key/value data, no global data
    u64(80, kDataOffset);
    u64(88, blocks.size());
    u64(96, blocks.size());
    const std::uint32_t dfd[11] = {kDfdLength, 0, 40u << 16 | 2,  // vendor and type 0; version 2, block size 40
                                   std::uint32_t(model) | 1u << 8 | std::uint32_t(transfer) << 16,
                                   3 | 3 << 8,                 // texel block 4x4 (dimensions minus one)
                                   16, 0,                      // bytesPlane0
                                   127u << 16 | std::uint32_t(channel) << 24,  // bits 0..127 of the channel
                                   0, 0, 0xFFFFFFFF};
    for (int i = 0; i < 11; ++i) u32(kDfdOffset + 4 * std::size_t(i), dfd[i]);
    std::memcpy(f.data() + kDataOffset, blocks.data(), blocks.size());
    return f;
}

// ---- UASTC LDR 4x4 ----------------------------------------------------------------------------

// The 19 UASTC modes (UASTC LDR 4x4 specification, its mode table and block layouts). A block is
// the mode's code, hint bits, a dual-plane component selector (2-plane RGB(A) modes) or a
// partition pattern index, the endpoints (all trit or quint groups as base-3 / base-5 numbers,
// then all low bits), then the weights, anchors with one bit less.
struct UastcMode {
    std::uint32_t code;
    int code_bits, components, hint_bits;
    int pattern_table;  // 0 none, 2 two-subset (30), 3 three-subset (11), 7 mode 7's (19)
    int planes, trits, quints, endpoint_bits, weight_bits;
};
constexpr UastcMode kUastcModes[19] = {
    {0b0001, 4, 3, 15, 0, 1, 1, 0, 6, 4},    {0b110101, 6, 3, 15, 0, 1, 0, 0, 8, 2},
    {0b11101, 5, 3, 15, 2, 1, 0, 0, 4, 3},   {0b00011, 5, 3, 15, 3, 1, 1, 0, 2, 2},
    {0b10011, 5, 3, 15, 2, 1, 0, 1, 3, 2},   {0b01011, 5, 3, 15, 0, 1, 0, 0, 8, 3},
    {0b11011, 5, 3, 15, 0, 2, 0, 1, 5, 2},   {0b00111, 5, 3, 15, 7, 1, 0, 1, 3, 2},
    {0b10111, 5, 4, 0, 0, 0, 0, 0, 8, 0},  // mode 8: solid colour, RGBA 8 bits each
    {0b01111, 5, 4, 23, 2, 1, 0, 0, 4, 2},   {0b010, 3, 4, 17, 0, 1, 1, 0, 4, 4},
    {0b00, 2, 4, 17, 0, 2, 1, 0, 4, 2},      {0b110, 3, 4, 17, 0, 1, 1, 0, 6, 3},
    {0b11111, 5, 4, 23, 0, 2, 0, 0, 8, 1},   {0b01101, 5, 4, 23, 0, 1, 0, 0, 8, 2},
    {0b0000101, 7, 2, 23, 0, 1, 0, 0, 8, 4}, {0b010101, 6, 2, 23, 2, 1, 0, 0, 8, 2},
    {0b100101, 6, 2, 23, 0, 2, 0, 0, 8, 2},  {0b1001, 4, 3, 15, 0, 1, 0, 0, 5, 5},
};

// The anchor texels (each subset's first texel in raster order) of the UASTC partition patterns,
// by pattern index: a format-defined table.
constexpr std::uint8_t kAnchors2[30][2] = {{0, 2}, {0, 3},  {1, 0},  {0, 3}, {7, 0}, {0, 2}, {3, 0}, {7, 0},
                                           {0, 11}, {2, 0}, {0, 7},  {11, 0}, {3, 0}, {8, 0}, {0, 4}, {12, 0},
                                           {1, 0}, {8, 0},  {0, 1},  {0, 2},  {0, 4}, {8, 0}, {1, 0}, {0, 2},
                                           {4, 0}, {0, 1},  {4, 0},  {1, 0},  {4, 0}, {1, 0}};
constexpr std::uint8_t kAnchors3[11][3] = {{0, 8, 10}, {8, 0, 12}, {4, 0, 12}, {8, 0, 4}, {3, 0, 2}, {0, 1, 3},
                                           {0, 2, 1},  {1, 9, 0},  {1, 2, 0},  {4, 0, 8}, {0, 6, 2}};
constexpr std::uint8_t kAnchors7[19][2] = {{0, 4}, {0, 2}, {2, 0}, {0, 7}, {8, 0},  {0, 1}, {0, 3},
                                           {0, 1}, {2, 0}, {0, 1}, {0, 8}, {2, 0},  {0, 1}, {0, 7},
                                           {12, 0}, {2, 0}, {9, 0}, {0, 2}, {4, 0}};

// The k-th block of `mode`: pattern k mod the table's size, dual-plane component k mod 4, the
// rest random (endpoints and weights at their ends a quarter of the time), and the bits past the
// layout random too (a decoder ignores them).
Block uastc_block(int mode, int k, Rng& rng) {
    const UastcMode& m = kUastcModes[mode];
    Block b;
    rng.fill(b);
    int pos = 0;
    auto put = [&](std::uint32_t v, int n) { b.set(pos, v, n), pos += n; };
    put(m.code, m.code_bits);
    if (mode == 8) {
        for (int c = 0; c < 4; ++c) put(rng.value(256), 8);
        return b;
    }
    put(rng.bits(m.hint_bits), m.hint_bits);
    if (m.planes == 2 && m.components != 2) put(std::uint32_t(k % 4), 2);
    std::vector<int> anchors = {0};
    if (m.pattern_table == 2) put(std::uint32_t(k % 30), 5), anchors = {kAnchors2[k % 30][0], kAnchors2[k % 30][1]};
    if (m.pattern_table == 3)
        put(std::uint32_t(k % 11), 4), anchors = {kAnchors3[k % 11][0], kAnchors3[k % 11][1], kAnchors3[k % 11][2]};
    if (m.pattern_table == 7) put(std::uint32_t(k % 19), 5), anchors = {kAnchors7[k % 19][0], kAnchors7[k % 19][1]};
    const int values = m.components * 2 * int(anchors.size());
    if (m.trits || m.quints) {
        const int base = m.trits ? 3 : 5, per = m.trits ? 5 : 3;
        for (int i = 0; i < values; i += per) {
            std::uint32_t limit = 1;
            for (int j = 0; j < std::min(per, values - i); ++j) limit *= std::uint32_t(base);
            int width = 0;
            while ((1u << width) < limit) ++width;  // bits for 0 .. limit - 1
            put(rng.value(limit), width);
        }
    }
    for (int i = 0; i < values; ++i) put(rng.value(1u << m.endpoint_bits), m.endpoint_bits);
    for (int t = 0; t < 16; ++t)
        for (int p = 0; p < m.planes; ++p) {
            const bool anchor = std::find(anchors.begin(), anchors.end(), t) != anchors.end();
            const int n = m.weight_bits - (anchor ? 1 : 0);
            put(n ? rng.value(1u << n) : 0, n);
        }
    if (pos > 128) ADD_FAILURE() << "mode " << mode << " takes " << pos << " bits";
    return b;
}

// Every UASTC mode, every partition pattern of the 2-subset, 3-subset and mode-7 tables and every
// dual-plane component selector, byte for byte as the reference decodes them.
TEST(UastcModes, EveryModeEqualsTheReference) {
    SKIP_WITHOUT_REFERENCE();
    constexpr int kPerMode = 330;  // 11 x each 2-subset pattern, 30 x each 3-subset one
    constexpr int kBlocksWide = 66, kBlocks = 19 * kPerMode, kBlocksHigh = kBlocks / kBlocksWide;
    static_assert(kBlocks % kBlocksWide == 0);
    const int width = kBlocksWide * 4, height = kBlocksHigh * 4;
    Rng rng(0x5A57C);
    std::vector<std::uint8_t> blocks;
    for (int i = 0; i < kBlocks; ++i) {  // the modes interleaved: block i is of mode i % 19
        const Block b = uastc_block(i % 19, i / 19, rng);
        blocks.insert(blocks.end(), b.bytes, b.bytes + 16);
    }
    test::TempDir tmp("fresnel_uastc_modes");
    write_bytes(tmp / "modes.ktx2", basis_ktx2(width, height, 166, 2, 3, blocks));  // UASTC, sRGB, RGBA
    const std::string cmd = "node '" + (kScripts / "basis_reference.cjs").string() + "' '" + kModules.string() + "' '" +
                            (tmp / "modes.ktx2").string() + "' '" + (tmp / "ref").string() + "' > /dev/null";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    const auto ref = read_bytes(tmp / "ref_L0.rgba");
    ASSERT_EQ(ref.size(), std::size_t(width) * std::size_t(height) * 4);

    std::vector<std::uint8_t> ours(ref.size());
    basisu::transcode_uastc(blocks, width, height, ours.data(), "modes");
    int compared[19] = {}, differ[19] = {}, reported = 0;
    for (int i = 0; i < kBlocks; ++i) {
        const std::size_t bx = std::size_t(i % kBlocksWide), by = std::size_t(i / kBlocksWide);
        bool same = true;
        for (std::size_t y = 0; y < 4; ++y) {
            const std::size_t at = ((by * 4 + y) * std::size_t(width) + bx * 4) * 4;
            same &= std::memcmp(ours.data() + at, ref.data() + at, 16) == 0;
        }
        ++compared[i % 19];
        if (!same) {
            ++differ[i % 19];
            if (reported++ < 5) ADD_FAILURE() << "mode " << i % 19 << " block " << hex(&blocks[16 * std::size_t(i)]);
        }
    }
    std::printf("UASTC LDR blocks compared with the reference (mode: blocks, differing)\n");
    for (int m = 0; m < 19; ++m) {
        std::printf("  mode %2d: %d, %d\n", m, compared[m], differ[m]);
        EXPECT_EQ(differ[m], 0) << "mode " << m << ": blocks that differ from the reference";
    }
}

// ---- UASTC HDR 4x4: ASTC 4x4 blocks of the HDR profile ---------------------------------------

// The ASTC integer-sequence ranges (Khronos Data Format spec, "Integer Sequence Encoding"), in
// increasing size: 2, 3, 4, 5, 6, 8, 10, 12, 16, 20, 24, 32, 40, 48, 64, 80, 96, 128, 160,
// 192, 256 levels. Weights use the first 12, colour endpoints range 4 (0..5) and up.
struct IseRange {
    int bits, trits, quints, levels;
};
constexpr IseRange kIse[21] = {{1, 0, 0, 2},   {0, 1, 0, 3},   {2, 0, 0, 4},   {0, 0, 1, 5},   {1, 1, 0, 6},
                               {3, 0, 0, 8},   {1, 0, 1, 10},  {2, 1, 0, 12},  {4, 0, 0, 16},  {2, 0, 1, 20},
                               {3, 1, 0, 24},  {5, 0, 0, 32},  {3, 0, 1, 40},  {4, 1, 0, 48},  {6, 0, 0, 64},
                               {4, 0, 1, 80},  {5, 1, 0, 96},  {7, 0, 0, 128}, {5, 0, 1, 160}, {6, 1, 0, 192},
                               {8, 0, 0, 256}};
constexpr int kFirstEndpointRange = 4;

// Bits `count` values of a range take: their low bits, 8 bits per 5 trits, 7 per 3 quints.
int ise_bits(int count, int range) {
    const IseRange& r = kIse[range];
    return count * r.bits + (r.trits ? (8 * count + 4) / 5 : 0) + (r.quints ? (7 * count + 2) / 3 : 0);
}

// The weight grids a 4x4 block allows (at most 4x4), as the block-mode table spells them: 4 x
// (2..4) in its first row, (2..3) x (2..4) in its fifth.
constexpr int kGrids[9][2] = {{4, 2}, {4, 3}, {4, 4}, {2, 2}, {2, 3}, {2, 4}, {3, 2}, {3, 3}, {3, 4}};

// The 11-bit block mode ("Block Mode", 2D) of a legal grid with weight range `range` (0..11:
// R = 2..7, then the same with the precision bit H) and one or two planes.
std::uint32_t block_mode(int grid, int range, bool dual) {
    const int gw = kGrids[grid][0], gh = kGrids[grid][1];
    const std::uint32_t R = std::uint32_t(range % 6 + 2), H = range >= 6;
    std::uint32_t m = (R >> 1) | (R & 1) << 4 | std::uint32_t(gh - 2) << 5;  // R2 R1 at bits 1:0, R0 at 4, A at 6:5
    if (gw != 4) m |= 3u << 2 | std::uint32_t(gw - 2) << 7 | 1u << 8;         // fifth row: B + 2 wide
    return m | H << 9 | std::uint32_t(dual) << 10;
}

// What a generated block is, for the counts and the coverage checks.
enum class Kind { Structured, VoidLdr, VoidHdr, IllegalMode, RandomBytes };
constexpr const char* kKindNames[5] = {"structured", "void-extent LDR", "void-extent HDR",
                                       "block mode illegal for 4x4", "random bytes"};
enum class CemEncoding { Single, Shared, PerPartition };  // 1 partition; selector 0; class + modes

struct AstcBlock {
    Block block;
    Kind kind = Kind::Structured;
    // Structured blocks: what the generator chose.
    int grid = 0, range = 0, partitions = 1, ccs = -1, endpoint_range = -1;
    bool extent = false;  // void-extent blocks: an extent given (not all ones)
    int cems[4] = {};
    CemEncoding encoding = CemEncoding::Single;
    bool legal = true;  // what the spec's rules say of it
};

// A void-extent block ("Void-Extent Blocks", 2D): LDR (UNORM16) or HDR (FP16) colour, no extent
// or an extent (an inverted one now and then), the two reserved bits usually 11.
AstcBlock void_extent(bool hdr, Rng& rng) {
    AstcBlock a;
    a.kind = hdr ? Kind::VoidHdr : Kind::VoidLdr;
    rng.fill(a.block);
    a.block.set(0, 0x1FC | std::uint32_t(hdr) << 9, 10);
    a.block.set(10, rng.below(8) ? 3 : rng.below(3), 2);
    if (rng.below(2)) {
        a.block.set(12, 0xFFFFFFFF, 26), a.block.set(38, 0xFFFFFFFF, 26);  // no extent: all ones
    } else {
        a.extent = true;
        for (int axis = 0; axis < 2; ++axis) {
            std::uint32_t lo = rng.below(8191), hi = lo + 1 + rng.below(8191 - lo);
            if (!rng.below(8)) std::swap(lo, hi);  // minimum above maximum: illegal
            a.block.set(12 + 26 * axis, lo, 13), a.block.set(25 + 26 * axis, hi, 13);
        }
    }
    for (int c = 0; c < 4; ++c) {
        std::uint32_t v = rng.value(0x10000);
        if (hdr) {  // a finite FP16 value, non-negative mostly; now and then infinity or NaN
            v = rng.below(4) ? rng.bits(15) % 0x7C00 : rng.bits(16) & 0xFBFF;
            if (!rng.below(24)) v = 0x7C00 | rng.bits(10) | rng.bits(1) << 15;
        }
        a.block.set(64 + 16 * c, v, 16);
    }
    return a;
}

// A block mode that no 4x4 block may use: a grid wider or taller than 4 from any row of the
// table, or one of the reserved encodings.
AstcBlock illegal_mode(Rng& rng) {
    AstcBlock a;
    a.kind = Kind::IllegalMode;
    a.legal = false;
    rng.fill(a.block);
    const std::uint32_t r = 1 + rng.below(3);  // R2 R1 (bits 1:0), not 00
    const std::uint32_t R0_H_D = rng.bits(1) << 4 | rng.bits(2) << 9;  // R0, H and D: any
    std::uint32_t m = 0;
    switch (rng.below(6)) {
        case 0: m = r | 3u << 5 | rng.bits(2) << 7 | R0_H_D; break;                  // row 1, A = 3: (B+4) x 5
        case 1: m = r | rng.bits(2) << 5 | (1 + rng.below(3)) << 7 | R0_H_D; break;  // row 1, B > 0: 5..7 wide
        case 2: m = r | 3u << 2 | 3u << 5 | rng.bits(1) << 7 | 1u << 8 | R0_H_D; break;  // row 5, A = 3: x 5
        case 3: m = r | (1 + rng.below(2)) << 2 | rng.bits(4) << 5 | R0_H_D; break;  // rows 2, 3: 8..11
        case 4: m = r | 3u << 2 | rng.bits(3) << 5 | R0_H_D; break;                  // row 4: 6 or 7 tall
        default:  // R2 R1 = 00: the rows of 6..12-texel grids, and the reserved encodings
            do m = rng.bits(9) << 2;
            while ((m & 0x1FF) == 0x1FC);  // not void-extent
    }
    a.block.set(0, m, 11);
    return a;
}

// A structured block: a legal grid, one or two planes (the second of each component), 1..4
// partitions, endpoint modes encoded singly, shared or per partition (class and mode), a weight
// range; the endpoint and weight bits and the partition seed random. Blocks the rules make
// illegal (weights outside 24..96 bits, over 18 endpoint values, no room for the 0..5 endpoint
// range, two planes with four partitions) are kept one time in ten.
AstcBlock structured(Rng& rng) {
    for (;;) {
        AstcBlock a;
        rng.fill(a.block);
        a.grid = int(rng.below(9));
        const bool dual = rng.below(3) == 0;
        a.range = int(rng.below(12));
        a.partitions = 1 + int(rng.below(4));
        if (dual) a.ccs = int(rng.below(4));
        std::uint32_t cem_field = 0;  // the class-and-mode field of the per-partition encoding
        if (a.partitions == 1) {
            a.cems[0] = int(rng.below(16));
        } else if (rng.below(3) == 0) {
            a.encoding = CemEncoding::Shared;
            a.cems[0] = a.cems[1] = a.cems[2] = a.cems[3] = int(rng.below(16));
        } else {
            a.encoding = CemEncoding::PerPartition;
            const std::uint32_t base = rng.below(3);  // classes base and base + 1
            cem_field = base + 1;
            for (int i = 0; i < a.partitions; ++i) {
                const std::uint32_t c = rng.bits(1), mode = rng.bits(2);
                a.cems[i] = int((base + c) * 4 + mode);
                cem_field |= c << (2 + i) | mode << (2 + a.partitions + 2 * i);
            }
        }
        a.encoding = a.partitions == 1 ? CemEncoding::Single : a.encoding;
        const int gw = kGrids[a.grid][0], gh = kGrids[a.grid][1];
        const int weight_bits = ise_bits(gw * gh * (dual ? 2 : 1), a.range);
        int values = 0;
        for (int i = 0; i < a.partitions; ++i) values += 2 * (a.cems[i] / 4 + 1);
        const int extra = a.encoding == CemEncoding::PerPartition ? 3 * a.partitions - 4 : 0;
        const int config = (a.partitions == 1 ? 17 : 29) + extra + (dual ? 2 : 0);
        for (int r = 20; r >= kFirstEndpointRange && a.endpoint_range < 0; --r)
            if (ise_bits(values, r) <= 128 - config - weight_bits) a.endpoint_range = r;
        a.legal = weight_bits >= 24 && weight_bits <= 96 && values <= 18 && a.endpoint_range >= 0 &&
                  !(dual && a.partitions == 4);
        if (!a.legal && rng.below(10)) continue;

        a.block.set(0, block_mode(a.grid, a.range, dual), 11);
        a.block.set(11, std::uint32_t(a.partitions - 1), 2);
        if (a.partitions == 1) {
            a.block.set(13, std::uint32_t(a.cems[0]), 4);
        } else if (a.encoding == CemEncoding::Shared) {  // bits 13..22: the partition seed, random
            a.block.set(23, 0, 2), a.block.set(25, std::uint32_t(a.cems[0]), 4);
        } else {
            a.block.set(23, cem_field, 6);  // the field's low 6 bits; the rest below the weights
        }
        // The fields below the weights, where they do not run into those above (when they
        // would, no endpoint range fits and the block is illegal anyway).
        const int below_weights = 128 - weight_bits - extra;
        if (128 - config - weight_bits >= 0) {
            if (extra) a.block.set(below_weights, cem_field >> 6, extra);
            if (dual) a.block.set(below_weights - 2, std::uint32_t(a.ccs), 2);  // the second plane's component
        }
        return a;
    }
}

std::uint32_t half_to_float_bits(std::uint16_t h) {  // exactly, NaN payloads kept
    const std::uint32_t sign = std::uint32_t(h & 0x8000) << 16, e = (h >> 10) & 0x1F;
    std::uint32_t m = h & 0x3FF;
    if (e == 0x1F) return sign | 0x7F800000u | m << 13;
    if (e != 0) return sign | (e + 112) << 23 | m << 13;
    if (m == 0) return sign;
    int shift = 0;
    for (; !(m & 0x400); ++shift) m <<= 1;  // subnormal: normalise
    return sign | std::uint32_t(113 - shift) << 23 | (m & 0x3FF) << 13;
}

// ~20,000 ASTC 4x4 blocks: where the reference decodes a block, ours equals it bit for bit; where
// the reference refuses it, ours gives the block opaque magenta. Each grid, plane count and
// second-plane component, partition count, endpoint mode, endpoint-mode encoding, weight range
// and endpoint range is compared on blocks the reference decodes, and so are void-extent blocks
// of both kinds.
TEST(AstcHdrBlocks, EqualTheReference) {
    SKIP_WITHOUT_REFERENCE();
    constexpr int kBlocksWide = 200, kBlocksHigh = 100, kBlocks = kBlocksWide * kBlocksHigh;
    Rng rng(0xA57C4D2);
    std::vector<AstcBlock> gen;
    std::vector<std::uint8_t> blocks;
    for (int i = 0; i < kBlocks; ++i) {
        const int slot = i % 50;  // of every 50: 5 void-extent, 2 illegal modes, 1 random, 42 structured
        AstcBlock a;
        if (slot < 5) a = void_extent(slot % 2 != 0, rng);
        else if (slot < 7) a = illegal_mode(rng);
        else if (slot < 8) a.kind = Kind::RandomBytes, a.legal = false, rng.fill(a.block);
        else a = structured(rng);
        blocks.insert(blocks.end(), a.block.bytes, a.block.bytes + 16);
        gen.push_back(a);
    }
    test::TempDir tmp("fresnel_astc_blocks");
    write_bytes(tmp / "blocks.bin", blocks);
    const std::string cmd = "node '" + (kScripts / "astc_blocks_reference.cjs").string() + "' '" + kModules.string() +
                            "' '" + (tmp / "blocks.bin").string() + "' '" + (tmp / "ref").string() + "' > /dev/null";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    const auto ref = read_bytes(tmp / "ref.rgbah"), valid = read_bytes(tmp / "ref.valid");
    ASSERT_EQ(ref.size(), std::size_t(kBlocks) * 128);
    ASSERT_EQ(valid.size(), std::size_t(kBlocks));

    // Ours, all blocks as one image: a refused block must not disturb its neighbours either.
    const int width = kBlocksWide * 4, height = kBlocksHigh * 4;
    std::vector<float> ours(std::size_t(width) * std::size_t(height) * 4);
    basisu::transcode_uastc_hdr(blocks, width, height, ours.data(), "blocks");

    const std::uint32_t kMagenta[4] = {0x3F800000, 0, 0x3F800000, 0x3F800000};
    struct Tally {
        int compared = 0, refused = 0;
    };
    Tally by_kind[5], void_extent[2][2], by_grid[9], by_ccs[4], single_plane, by_partitions[5], by_cem[16],
        by_encoding[3], by_range[12], by_endpoint_range[21], expected_legal, expected_illegal;
    int differ = 0, not_magenta = 0, reported = 0;
    for (int i = 0; i < kBlocks; ++i) {
        const AstcBlock& a = gen[std::size_t(i)];
        const bool ok = valid[std::size_t(i)] != 0;
        bool same = true;
        for (int t = 0; t < 16; ++t) {
            const std::size_t px = (std::size_t(i / kBlocksWide) * 4 + std::size_t(t / 4)) * std::size_t(width) +
                                   std::size_t(i % kBlocksWide) * 4 + std::size_t(t % 4);
            for (int c = 0; c < 4; ++c) {
                const std::size_t h = (std::size_t(i) * 16 + std::size_t(t)) * 4 + std::size_t(c);
                const std::uint16_t half = std::uint16_t(ref[2 * h] | ref[2 * h + 1] << 8);
                const std::uint32_t want = ok ? half_to_float_bits(half) : kMagenta[c];
                same &= std::bit_cast<std::uint32_t>(ours[px * 4 + std::size_t(c)]) == want;
            }
        }
        if (!same) {
            ++(ok ? differ : not_magenta);
            if (reported++ < 8)
                ADD_FAILURE() << kKindNames[int(a.kind)] << " block " << i << " " << hex(a.block.bytes)
                              << (ok ? ": differs from the reference's decode"
                                     : ": refused by the reference, not magenta");
        }
        auto count = [&](Tally& t) { ++(ok ? t.compared : t.refused); };
        count(by_kind[int(a.kind)]);
        if (a.kind == Kind::VoidLdr || a.kind == Kind::VoidHdr)
            count(void_extent[a.kind == Kind::VoidHdr][a.extent]);
        if (a.kind != Kind::Structured) continue;
        count(a.legal ? expected_legal : expected_illegal);
        count(by_grid[a.grid]);
        count(a.ccs < 0 ? single_plane : by_ccs[a.ccs]);
        count(by_partitions[a.partitions]);
        for (int p = 0; p < a.partitions; ++p)
            if (std::find(a.cems, a.cems + p, a.cems[p]) == a.cems + p) count(by_cem[a.cems[p]]);  // once per mode
        count(by_encoding[int(a.encoding)]);
        count(by_range[a.range]);
        if (a.endpoint_range >= 0) count(by_endpoint_range[a.endpoint_range]);
    }
    EXPECT_EQ(differ, 0) << "blocks the reference decodes that ours decodes otherwise";
    EXPECT_EQ(not_magenta, 0) << "blocks the reference refuses that ours does not give magenta";

    // The counts, and that every kind was compared on decoded blocks (and illegal ones refused).
    auto row = [](const std::string& what, const Tally& t) {
        std::printf("  %-34s %6d compared, %5d refused\n", what.c_str(), t.compared, t.refused);
        EXPECT_GT(t.compared, 0) << what << ": no block the reference decodes";
    };
    std::printf("ASTC 4x4 (UASTC HDR) blocks against the reference, one at a time\n");
    row(kKindNames[int(Kind::Structured)], by_kind[int(Kind::Structured)]);
    for (const bool hdr : {false, true})
        for (const bool extent : {false, true})
            row(std::string(kKindNames[int(hdr ? Kind::VoidHdr : Kind::VoidLdr)]) +
                    (extent ? ", an extent" : ", no extent"),
                void_extent[hdr][extent]);
    for (const Kind k : {Kind::IllegalMode, Kind::RandomBytes})
        std::printf("  %-34s %6d compared, %5d refused\n", kKindNames[int(k)], by_kind[int(k)].compared,
                    by_kind[int(k)].refused);
    EXPECT_EQ(by_kind[int(Kind::IllegalMode)].compared, 0) << "the reference decoded a block mode illegal for 4x4";
    EXPECT_GT(by_kind[int(Kind::Structured)].refused, 0) << "no structured block the reference refuses";
    std::printf("  structured, legal by the spec's rules: %d compared, %d refused; illegal: %d compared, %d refused\n",
                expected_legal.compared, expected_legal.refused, expected_illegal.compared, expected_illegal.refused);
    // The generator's own account of its blocks (what the counts below rest on): the reference
    // refuses exactly the structured blocks the spec's rules make illegal.
    EXPECT_EQ(expected_legal.refused, 0) << "structured blocks legal by the spec's rules that the reference refuses";
    EXPECT_EQ(expected_illegal.compared, 0)
        << "structured blocks illegal by the spec's rules that the reference decodes";
    for (int g = 0; g < 9; ++g)
        row("grid " + std::to_string(kGrids[g][0]) + "x" + std::to_string(kGrids[g][1]), by_grid[g]);
    row("one plane", single_plane);
    for (int c = 0; c < 4; ++c) row("two planes, second of component " + std::to_string(c), by_ccs[c]);
    for (int p = 1; p <= 4; ++p) row(std::to_string(p) + " partition(s)", by_partitions[p]);
    for (int c = 0; c < 16; ++c) row("endpoint mode " + std::to_string(c), by_cem[c]);
    const char* encodings[3] = {"endpoint mode: one partition's", "endpoint mode: shared",
                                "endpoint mode: per partition"};
    for (int e = 0; e < 3; ++e) row(encodings[e], by_encoding[e]);
    for (int r = 0; r < 12; ++r) row("weight range 0.." + std::to_string(kIse[r].levels - 1), by_range[r]);
    for (int r = kFirstEndpointRange; r < 21; ++r)
        row("endpoint range 0.." + std::to_string(kIse[r].levels - 1), by_endpoint_range[r]);
}

}  // namespace
