// UASTC LDR 4x4 to RGBA8, written from the Basis Universal "UASTC LDR 4x4 Texture Specification"
// and the ASTC section of the Khronos Data Format Specification (KDFS).
//
// A UASTC block is 128 bits, read from the least significant bit of its first byte on: a mode
// index (a prefix code), hint bits for transcoders into other formats (not needed for pixels), a
// dual-plane component selector or a partition pattern index, the endpoints as one integer
// sequence (all trits or quints first, then all low bits), and last the weights as plain bits.
// Mode 8 is a solid colour. Every other mode is a subset of ASTC LDR 4x4, and its pixels are
// what an ASTC decoder gives for the equivalent ASTC block: endpoints unquantised to 0..255,
// weights to 0..64, each 8-bit endpoint widened to 16 bits and interpolated.
#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <string>

#include "fresnel/core/basisu.h"
#include "fresnel/core/error.h"
#include "astc_partition.h"

namespace fresnel::basisu {
namespace {

// ---- UASTC partition patterns (ASTC seeds: astc_partition.h) ------------------------------------

// A UASTC partition pattern: each texel's subset, and each subset's anchor texel (the first
// texel of the subset in raster order), whose weight is stored with one bit less.
struct Pattern {
    std::array<std::uint8_t, 16> subset{};
    std::array<std::uint8_t, 3> anchor{};
};

template <std::size_t N>
constexpr std::array<Pattern, N> make_patterns(const std::array<std::uint16_t, N>& seeds, int count) {
    std::array<Pattern, N> out{};
    for (std::size_t p = 0; p < N; ++p) {
        bool seen[3] = {};
        for (int t = 0; t < 16; ++t) {
            const int s = astc_select_partition(seeds[p], t % 4, t / 4, count, /*small_block=*/true);
            out[p].subset[std::size_t(t)] = std::uint8_t(s);
            if (!seen[s]) out[p].anchor[std::size_t(s)] = std::uint8_t(t);
            seen[s] = true;
        }
    }
    return out;
}

// The ASTC partition seeds of the patterns UASTC allows (UASTC spec, the partition pattern
// tables): the 30 two-subset patterns ASTC and BC7 share, the 11 shared three-subset patterns,
// and the 19 two-subset ASTC patterns that are BC7 three-subset patterns merged (mode 7).
constexpr std::array<std::uint16_t, 30> kSeeds2 = {28,  20,  16,  29,  91,  9,   107, 72,  149, 204,
                                                   50,  114, 496, 17,  78,  39,  252, 828, 43,  156,
                                                   116, 210, 476, 273, 684, 359, 246, 195, 694, 524};
constexpr std::array<std::uint16_t, 11> kSeeds3 = {260, 74, 32, 156, 183, 15, 745, 0, 335, 902, 254};
constexpr std::array<std::uint16_t, 19> kSeeds7 = {36,  48,  61,  137, 161, 183, 226, 281, 302, 307,
                                                   479, 495, 593, 594, 605, 799, 812, 988, 993};

constexpr auto kPatterns2 = make_patterns(kSeeds2, 2);
constexpr auto kPatterns3 = make_patterns(kSeeds3, 3);
constexpr auto kPatterns7 = make_patterns(kSeeds7, 2);

// ---- Modes (UASTC spec, "UASTC modes" and the per-mode block layouts) ---------------------------

// An ASTC quantisation range (KDFS "Integer Sequence Encoding"): trits or quints, plus low bits.
struct Range {
    std::uint8_t trits, quints, bits;
};
constexpr Range kRange7{1, 0, 2};   // 12 levels
constexpr Range kRange8{0, 0, 4};   // 16
constexpr Range kRange11{0, 0, 5};  // 32
constexpr Range kRange12{0, 1, 3};  // 40
constexpr Range kRange13{1, 0, 4};  // 48
constexpr Range kRange18{0, 1, 5};  // 160
constexpr Range kRange19{1, 0, 6};  // 192
constexpr Range kRange20{0, 0, 8};  // 256

enum class Channels : std::uint8_t { rgb, rgba, la };          // ASTC CEM 8, 12, 4
enum class Patterns : std::uint8_t { none, two, three, mode7 };  // which table the pattern index reads

struct Mode {
    std::uint8_t code, code_bits;  // the mode's prefix code, first bit in the least significant bit
    Channels channels;
    std::uint8_t hint_bits;  // BC1, ETC1 and ETC2 hints, skipped
    Patterns patterns;
    std::uint8_t planes;
    Range endpoints;
    std::uint8_t weight_bits;
};

constexpr int kSolidMode = 8;
constexpr std::array<Mode, 19> kModes = {{
    {0b0001, 4, Channels::rgb, 15, Patterns::none, 1, kRange19, 4},     // 0
    {0b110101, 6, Channels::rgb, 15, Patterns::none, 1, kRange20, 2},   // 1
    {0b11101, 5, Channels::rgb, 15, Patterns::two, 1, kRange8, 3},      // 2
    {0b00011, 5, Channels::rgb, 15, Patterns::three, 1, kRange7, 2},    // 3
    {0b10011, 5, Channels::rgb, 15, Patterns::two, 1, kRange12, 2},     // 4
    {0b01011, 5, Channels::rgb, 15, Patterns::none, 1, kRange20, 3},    // 5
    {0b11011, 5, Channels::rgb, 15, Patterns::none, 2, kRange18, 2},    // 6
    {0b00111, 5, Channels::rgb, 15, Patterns::mode7, 1, kRange12, 2},   // 7
    {0b10111, 5, Channels::rgba, 0, Patterns::none, 0, kRange20, 0},    // 8: solid colour
    {0b01111, 5, Channels::rgba, 23, Patterns::two, 1, kRange8, 2},     // 9
    {0b010, 3, Channels::rgba, 17, Patterns::none, 1, kRange13, 4},     // 10
    {0b00, 2, Channels::rgba, 17, Patterns::none, 2, kRange13, 2},      // 11
    {0b110, 3, Channels::rgba, 17, Patterns::none, 1, kRange19, 3},     // 12
    {0b11111, 5, Channels::rgba, 23, Patterns::none, 2, kRange20, 1},   // 13
    {0b01101, 5, Channels::rgba, 23, Patterns::none, 1, kRange20, 2},   // 14
    {0b0000101, 7, Channels::la, 23, Patterns::none, 1, kRange20, 4},   // 15
    {0b010101, 6, Channels::la, 23, Patterns::two, 1, kRange20, 2},     // 16
    {0b100101, 6, Channels::la, 23, Patterns::none, 2, kRange20, 2},    // 17
    {0b1001, 4, Channels::rgb, 15, Patterns::none, 1, kRange11, 5},     // 18
}};

constexpr int subsets(const Mode& m) {
    return m.patterns == Patterns::none ? 1 : m.patterns == Patterns::three ? 3 : 2;
}
constexpr int channels(const Mode& m) {
    return m.channels == Channels::la ? 2 : m.channels == Channels::rgb ? 3 : 4;
}

// The mode of each value of a block's first 7 bits; 0xFF where no mode's code matches (the
// one reserved code, 1000101).
constexpr std::array<std::uint8_t, 128> kModeOfCode = [] {
    std::array<std::uint8_t, 128> lut{};
    lut.fill(0xFF);
    for (std::size_t m = 0; m < kModes.size(); ++m)
        for (unsigned v = 0; v < 128; ++v)
            if ((v & ((1u << kModes[m].code_bits) - 1)) == kModes[m].code) lut[v] = std::uint8_t(m);
    return lut;
}();

// Bits in a trit (quint) group of k values: the fewest that hold 3^k - 1 (5^k - 1).
constexpr int group_bits(int base, int k) {
    int n = 1;
    for (int i = 0; i < k; ++i) n *= base;
    return std::bit_width(unsigned(n - 1));
}

constexpr int block_bits(const Mode& m) {
    const int values = channels(m) * 2 * subsets(m);
    const int base = m.endpoints.trits ? 3 : m.endpoints.quints ? 5 : 0, per = base == 3 ? 5 : 3;
    int bits = m.code_bits + m.hint_bits + values * m.endpoints.bits;
    if (base) bits += values / per * group_bits(base, per) + group_bits(base, values % per);
    if (m.planes == 2 && m.channels != Channels::la) bits += 2;                // component selector
    if (m.patterns != Patterns::none) bits += m.patterns == Patterns::three ? 4 : 5;  // pattern index
    return bits + m.planes * (16 * m.weight_bits - subsets(m));  // anchors carry one bit less
}

constexpr bool layout_checks() {
    for (std::size_t m = 0; m < kModes.size(); ++m)
        if (m != kSolidMode && block_bits(kModes[m]) > 128) return false;
    for (unsigned v = 0; v < 128; ++v) {  // each 7-bit value matches one mode, or none if reserved
        int matches = 0;
        for (const Mode& m : kModes) matches += (v & ((1u << m.code_bits) - 1)) == m.code;
        if (matches != (v == 0b1000101 ? 0 : 1)) return false;
    }
    return true;
}
static_assert(layout_checks(), "every mode's fields fit in 128 bits and the mode codes are prefix-free");

// ---- Unquantisation (KDFS "Endpoint unquantization", "Weight unquantization") ------------------

// An endpoint of range `r` from its trit or quint `d` (0 if the range has none) and low bits `v`.
constexpr int unquantise_endpoint(const Range& r, int d, int v) {
    if (!r.trits && !r.quints) {  // replicate the bits to 8
        int out = 0;
        for (int shift = 8 - r.bits; shift > -int(r.bits); shift -= r.bits)
            out |= shift >= 0 ? v << shift : v >> -shift;
        return out & 0xFF;
    }
    const int a = (v & 1) ? 0x1FF : 0;
    const int x = v >> 1;  // the low bits above bit 0 ("b", "cb", "dcb", ...)
    int b = 0, c = 0;
    if (r.trits) {
        switch (r.bits) {
            case 1: c = 204; break;
            case 2: b = x ? 0b100010110 : 0, c = 93; break;       // b000b0bb0
            case 3: b = (x << 7) | (x << 2) | x, c = 44; break;   // cb000cbcb
            case 4: b = (x << 6) | x, c = 22; break;              // dcb000dcb
            case 5: b = (x << 5) | (x >> 2), c = 11; break;       // edcb000ed
            case 6: b = (x << 4) | (x >> 4), c = 5; break;        // fedcb000f
        }
    } else {
        switch (r.bits) {
            case 1: c = 113; break;
            case 2: b = x ? 0b100001100 : 0, c = 54; break;              // b0000bb00
            case 3: b = (x << 7) | (x << 1) | (x >> 1), c = 26; break;  // cb0000cbc
            case 4: b = (x << 6) | (x >> 1), c = 13; break;             // dcb0000dc
            case 5: b = (x << 5) | (x >> 3), c = 6; break;              // edcb0000e
        }
    }
    const int t = (d * c + b) ^ a;
    return (a & 0x80) | (t >> 2);
}

// A weight of `bits` plain bits to 0..64: replicated to 6 bits, then values above 32 gain one.
constexpr int unquantise_weight(int bits, int v) {
    int out = 0;
    for (int shift = 6 - bits; shift > -bits; shift -= bits) out |= shift >= 0 ? v << shift : v >> -shift;
    out &= 0x3F;
    return out > 32 ? out + 1 : out;
}

// ---- Block decoding ----------------------------------------------------------------------------

class BitReader {
public:
    explicit BitReader(const std::uint8_t* b) {
        for (int i = 7; i >= 0; --i) {
            lo_ = (lo_ << 8) | b[i];
            hi_ = (hi_ << 8) | b[8 + i];
        }
    }
    // The next `n` (0..8) bits; past the block's end they read as zero (block_bits() keeps
    // every mode inside it).
    int read(int n) {
        std::uint64_t v = 0;
        if (pos_ < 64)
            v = (lo_ >> pos_) | (pos_ ? hi_ << (64 - pos_) : 0);
        else if (pos_ < 128)
            v = hi_ >> (pos_ - 64);
        pos_ += n;
        return int(v & ((1u << n) - 1));
    }
    void skip(int n) { pos_ += n; }

private:
    std::uint64_t lo_ = 0, hi_ = 0;
    int pos_ = 0;
};

using Texels = std::array<std::array<std::uint8_t, 4>, 16>;

// Decodes one 16-byte block; returns nullptr, or why the block is invalid.
const char* decode_block(const std::uint8_t* block, Texels& out) {
    const int mode_index = kModeOfCode[block[0] & 0x7F];
    if (mode_index == 0xFF) return "reserved UASTC mode code";
    const Mode& mode = kModes[std::size_t(mode_index)];
    BitReader bits(block);
    bits.skip(mode.code_bits);

    if (mode_index == kSolidMode) {  // R, G, B, A as 8 bits each, then ETC1 hints
        std::array<std::uint8_t, 4> c{};
        for (auto& v : c) v = std::uint8_t(bits.read(8));
        out.fill(c);
        return nullptr;
    }
    bits.skip(mode.hint_bits);

    // Dual plane: which channel the second weight plane drives (LA modes: always alpha).
    int ccs = -1;
    if (mode.planes == 2) ccs = mode.channels == Channels::la ? 3 : bits.read(2);

    const Pattern* pattern = nullptr;
    if (mode.patterns != Patterns::none) {
        const int index = bits.read(mode.patterns == Patterns::three ? 4 : 5);
        switch (mode.patterns) {
            case Patterns::two:
                if (index >= int(kPatterns2.size())) return "two-subset pattern index out of range";
                pattern = &kPatterns2[std::size_t(index)];
                break;
            case Patterns::three:
                if (index >= int(kPatterns3.size())) return "three-subset pattern index out of range";
                pattern = &kPatterns3[std::size_t(index)];
                break;
            case Patterns::mode7:
                if (index >= int(kPatterns7.size())) return "mode 7 pattern index out of range";
                pattern = &kPatterns7[std::size_t(index)];
                break;
            case Patterns::none: break;
        }
    }

    // Endpoints: v0 v1 of each channel in turn (ASTC order), subset after subset. UASTC packs
    // each group of 5 trits (3 quints) as one base-3 (base-5) number, first value in the lowest
    // digit, all groups before the low bits.
    const Range& range = mode.endpoints;
    const int values = channels(mode) * 2 * subsets(mode);
    std::array<int, 18> digit{}, endpoint{};
    if (range.trits || range.quints) {
        const int base = range.trits ? 3 : 5, per = range.trits ? 5 : 3;
        for (int first = 0; first < values; first += per) {
            const int k = values - first < per ? values - first : per;
            int packed = bits.read(group_bits(base, k)), limit = 1;
            for (int i = 0; i < k; ++i) limit *= base;
            // No encoder writes a group past 3^k - 1 (5^k - 1); such a block is corrupt.
            if (packed >= limit) return range.trits ? "invalid trit group" : "invalid quint group";
            for (int i = 0; i < k; ++i, packed /= base) digit[std::size_t(first + i)] = packed % base;
        }
    }
    for (int i = 0; i < values; ++i)
        endpoint[std::size_t(i)] = unquantise_endpoint(range, digit[std::size_t(i)], bits.read(range.bits));

    // Weights, texel by texel (both planes of a texel together); each subset's anchor texel
    // has one bit less (its top bit is 0).
    std::array<std::array<int, 2>, 16> weight{};
    for (int t = 0; t < 16; ++t) {
        const int s = pattern ? pattern->subset[std::size_t(t)] : 0;
        const bool anchor = pattern ? pattern->anchor[std::size_t(s)] == t : t == 0;
        for (int p = 0; p < mode.planes; ++p)
            weight[std::size_t(t)][std::size_t(p)] =
                unquantise_weight(mode.weight_bits, bits.read(mode.weight_bits - (anchor ? 1 : 0)));
    }

    // Interpolation (KDFS "Weight application"): 8-bit endpoints widened to 16 bits by
    // replication, blended with 6-bit weights, and the top 8 bits kept.
    for (int t = 0; t < 16; ++t) {
        const int s = pattern ? pattern->subset[std::size_t(t)] : 0;
        const int* e = &endpoint[std::size_t(s * channels(mode) * 2)];
        int e0[4] = {}, e1[4] = {};
        switch (mode.channels) {
            case Channels::rgb:
                for (int c = 0; c < 3; ++c) e0[c] = e[2 * c], e1[c] = e[2 * c + 1];
                e0[3] = e1[3] = 255;
                break;
            case Channels::rgba:
                for (int c = 0; c < 4; ++c) e0[c] = e[2 * c], e1[c] = e[2 * c + 1];
                break;
            case Channels::la:
                e0[0] = e0[1] = e0[2] = e[0], e1[0] = e1[1] = e1[2] = e[1];
                e0[3] = e[2], e1[3] = e[3];
                break;
        }
        for (int c = 0; c < 4; ++c) {
            const int w = weight[std::size_t(t)][c == ccs ? 1 : 0];
            const int lo = e0[c] * 257, hi = e1[c] * 257;
            out[std::size_t(t)][std::size_t(c)] = std::uint8_t(((lo * (64 - w) + hi * w + 32) >> 6) >> 8);
        }
    }
    return nullptr;
}

}  // namespace

void transcode_uastc(std::span<const std::uint8_t> blocks, int width, int height, std::uint8_t* rgba,
                     const std::string& name) {
    if (width <= 0 || height <= 0)
        throw Error(name, "", "UASTC image size " + std::to_string(width) + "x" + std::to_string(height) + " is empty");
    const std::size_t bw = (std::size_t(width) + 3) / 4, bh = (std::size_t(height) + 3) / 4;
    if (blocks.size() != bw * bh * 16)  // no overflow: bw * bh * 16 < 2^62
        throw Error(name, "", "UASTC data holds " + std::to_string(blocks.size()) + " bytes; a " +
                                  std::to_string(width) + "x" + std::to_string(height) + " image needs " +
                                  std::to_string(bw * bh * 16) + " (16 per block of 4x4 texels)");
    Texels texels;
    for (std::size_t by = 0; by < bh; ++by) {
        for (std::size_t bx = 0; bx < bw; ++bx) {
            if (const char* why = decode_block(blocks.data() + (by * bw + bx) * 16, texels))
                throw Error(name, "block (" + std::to_string(bx) + ", " + std::to_string(by) + ")", why);
            const std::size_t w = std::min<std::size_t>(4, std::size_t(width) - bx * 4);
            const std::size_t h = std::min<std::size_t>(4, std::size_t(height) - by * 4);
            for (std::size_t y = 0; y < h; ++y)
                for (std::size_t x = 0; x < w; ++x)
                    for (std::size_t c = 0; c < 4; ++c)
                        rgba[((by * 4 + y) * std::size_t(width) + bx * 4 + x) * 4 + c] = texels[y * 4 + x][c];
        }
    }
}

}  // namespace fresnel::basisu
