// UASTC HDR 4x4: every 16-byte block is an ordinary ASTC 4x4 block, so this is an ASTC decoder for
// the HDR profile with a 4x4 footprint. Written from the Khronos Data Format Specification, chapter
// "ASTC Compressed Texture Image Formats"; the comments name its sections. Basis Universal's
// encoder emits only part of ASTC (endpoint modes 7 and 11, few grids), but any valid ASTC 4x4
// block decodes here, so hand-made or re-encoded files work too.
//
// Output is FP16 per channel, as the HDR profile returns it, widened to float exactly. Blocks are
// decoded independently; an illegal encoding ("Illegal Encodings") gives that block opaque magenta,
// one of the error results the spec allows (its HDR-profile NaN would spread through filtering and
// mipmaps), and decoding goes on.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>

#include "fresnel/core/basisu.h"
#include "fresnel/core/error.h"
#include "astc_partition.h"
#include "float16.h"

namespace fresnel::basisu {
namespace {

constexpr int kDim = 4;  // the block footprint, 4x4 texels

// The 128 bits of a block; bit 0 is the lowest bit of byte 0 ("Block Layout").
struct Bits {
    std::uint64_t lo = 0, hi = 0;

    static Bits of(const std::uint8_t* p) {
        Bits b;
        for (int i = 7; i >= 0; --i) b.lo = (b.lo << 8) | p[i], b.hi = (b.hi << 8) | p[8 + i];
        return b;
    }
    // `count` (0..32) bits starting at bit `pos`, lowest first; bits past 127 read as zero.
    std::uint32_t get(int pos, int count) const {
        if (pos >= 128 || count <= 0) return 0;
        std::uint64_t v = pos >= 64 ? hi >> (pos - 64) : pos == 0 ? lo : (lo >> pos) | (hi << (64 - pos));
        return count >= 32 ? std::uint32_t(v) : std::uint32_t(v) & ((1u << count) - 1);
    }
    // Bit i moves to bit 127 - i: the weight stream grows down from bit 127 ("Weight Decoding").
    Bits reversed() const {
        auto rev = [](std::uint64_t x) {
            std::uint64_t r = 0;
            for (int i = 0; i < 64; ++i, x >>= 1) r = (r << 1) | (x & 1);
            return r;
        };
        return Bits{rev(hi), rev(lo)};
    }
};

// --- Integer Sequence Encoding -------------------------------------------------------------

// A value range: 2^bits times 1, 3 (one trit) or 5 (one quint).
struct Range {
    int bits, trits, quints;
};
// Every range ASTC uses, in increasing size. Weights use the first 12 ("Block Mode"),
// colour endpoints the ones from 0..5 up ("Data Size Determination").
constexpr Range kRanges[21] = {{1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {0, 0, 1}, {1, 1, 0}, {3, 0, 0}, {1, 0, 1},
                               {2, 1, 0}, {4, 0, 0}, {2, 0, 1}, {3, 1, 0}, {5, 0, 0}, {3, 0, 1}, {4, 1, 0},
                               {6, 0, 0}, {4, 0, 1}, {5, 1, 0}, {7, 0, 0}, {5, 0, 1}, {6, 1, 0}, {8, 0, 0}};
constexpr int kFirstEndpointRange = 4;

// Bits that `count` values of range `r` occupy ("Data Size Determination").
int sequence_bits(int count, Range r) {
    return count * r.bits + (count * 8 * r.trits + 4) / 5 + (count * 7 * r.quints + 2) / 3;
}

// The five trits packed in 8 bits T ("Integer Sequence Encoding").
void unpack_trits(std::uint32_t T, int t[5]) {
    auto bit = [&](int i) { return int(T >> i) & 1; };
    int C;
    if (((T >> 2) & 7) == 7) {
        C = int(((T >> 5) & 7) << 2 | (T & 3));
        t[4] = t[3] = 2;
    } else {
        C = int(T & 0x1F);
        if (((T >> 5) & 3) == 3) t[4] = 2, t[3] = bit(7);
        else t[4] = bit(7), t[3] = int(T >> 5) & 3;
    }
    auto cbit = [&](int i) { return (C >> i) & 1; };
    if ((C & 3) == 3) t[2] = 2, t[1] = cbit(4), t[0] = cbit(3) << 1 | (cbit(2) & ~cbit(3) & 1);
    else if (((C >> 2) & 3) == 3) t[2] = 2, t[1] = 2, t[0] = C & 3;
    else t[2] = cbit(4), t[1] = (C >> 2) & 3, t[0] = cbit(1) << 1 | (cbit(0) & ~cbit(1) & 1);
}

// The three quints packed in 7 bits Q ("Integer Sequence Encoding"; the spec's "T[6:5]" in the
// q2 line means Q[6:5]).
void unpack_quints(std::uint32_t Q, int q[3]) {
    auto bit = [&](int i) { return int(Q >> i) & 1; };
    if (((Q >> 1) & 3) == 3 && ((Q >> 5) & 3) == 0) {
        q[2] = bit(0) << 2 | (bit(4) & ~bit(0) & 1) << 1 | (bit(3) & ~bit(0) & 1);
        q[1] = q[0] = 4;
        return;
    }
    int C;
    if (((Q >> 1) & 3) == 3) q[2] = 4, C = int(((Q >> 3) & 3) << 3 | (~(Q >> 5) & 3) << 1 | (Q & 1));
    else q[2] = int(Q >> 5) & 3, C = int(Q & 0x1F);
    if ((C & 7) == 5) q[1] = 4, q[0] = (C >> 3) & 3;
    else q[1] = (C >> 3) & 3, q[0] = C & 7;
}

// Decodes `count` values of range `r` from bit `pos` upward. Each value brings its own low bits
// and its share of its block's trit/quint bits; the shares of values past the end are never read,
// so they stay zero as the spec requires.
void decode_sequence(const Bits& b, int pos, int count, Range r, int* out) {
    static constexpr int kTritBits[5] = {2, 2, 1, 2, 1}, kTritShift[5] = {0, 2, 4, 5, 7};
    static constexpr int kQuintBits[3] = {3, 2, 2}, kQuintShift[3] = {0, 3, 5};
    const int group = r.trits ? 5 : r.quints ? 3 : 1;
    for (int first = 0; first < count; first += group) {
        int low[5] = {}, high[5] = {};
        std::uint32_t packed = 0;
        const int n = std::min(group, count - first);
        for (int k = 0; k < n; ++k) {
            low[k] = int(b.get(pos, r.bits));
            pos += r.bits;
            if (r.trits) packed |= b.get(pos, kTritBits[k]) << kTritShift[k], pos += kTritBits[k];
            if (r.quints) packed |= b.get(pos, kQuintBits[k]) << kQuintShift[k], pos += kQuintBits[k];
        }
        if (r.trits) unpack_trits(packed, high);
        if (r.quints) unpack_quints(packed, high);
        for (int k = 0; k < n; ++k) out[first + k] = high[k] << r.bits | low[k];
    }
}

// `v` (n bits) repeated from the top down to fill `to` bits.
int replicate(int v, int n, int to) {
    int r = 0, filled = 0;
    for (; filled < to; filled += n) r = r << n | v;
    return r >> (filled - to);
}

// "Endpoint Unquantization": a value of range `r` to 0..255.
int unquantize_endpoint(int v, Range r) {
    const int n = r.bits;
    if (!r.trits && !r.quints) return replicate(v, n, 8);
    const int D = v >> n, m = v & ((1 << n) - 1), x = m >> 1;
    const int A = (m & 1) ? 0x1FF : 0;
    int B = 0, C = 0;  // the table "ASTC color unquantization parameters"
    if (r.trits) {
        switch (n) {
            case 1: C = 204; break;
            case 2: B = x << 8 | x << 4 | x << 2 | x << 1, C = 93; break;   // b000b0bb0
            case 3: B = x << 7 | x << 2 | x, C = 44; break;                 // cb000cbcb
            case 4: B = x << 6 | x, C = 22; break;                          // dcb000dcb
            case 5: B = x << 5 | x >> 2, C = 11; break;                     // edcb000ed
            default: B = x << 4 | x >> 4, C = 5; break;                     // fedcb000f
        }
    } else {
        switch (n) {
            case 1: C = 113; break;
            case 2: B = x << 8 | x << 3 | x << 2, C = 54; break;            // b0000bb00
            case 3: B = x << 7 | x << 1 | x >> 1, C = 26; break;            // cb0000cbc
            case 4: B = x << 6 | x >> 1, C = 13; break;                     // dcb0000dc
            default: B = x << 5 | x >> 3, C = 6; break;                     // edcb0000e
        }
    }
    int T = (D * C + B) ^ A;
    return ((A & 0x80) | (T >> 2)) & 0xFF;
}

// "Weight Unquantization": a value of range `r` to 0..64.
int unquantize_weight(int v, Range r) {
    const int n = r.bits;
    int T;
    if (!r.trits && !r.quints) {
        T = replicate(v, n, 6);
    } else if (n == 0) {
        static constexpr int kTrit[3] = {0, 32, 63}, kQuint[5] = {0, 16, 32, 47, 63};
        T = r.trits ? kTrit[std::min(v, 2)] : kQuint[std::min(v, 4)];
    } else {
        const int D = v >> n, m = v & ((1 << n) - 1), x = m >> 1;
        const int A = (m & 1) ? 0x7F : 0;
        int B = 0, C;  // the table "ASTC weight unquantization parameters"
        if (r.trits) {
            if (n == 1) C = 50;
            else if (n == 2) B = x << 6 | x << 2 | x, C = 23;  // b000b0b
            else B = x << 5 | x, C = 11;                       // cb000cb
        } else {
            if (n == 1) C = 28;
            else B = x << 6 | x << 1, C = 13;  // b0000b0
        }
        T = (A & 0x20) | (((D * C + B) ^ A) >> 2);
    }
    return T > 32 ? T + 1 : T;
}

// --- Colour endpoints ----------------------------------------------------------------------

// Two RGBA endpoints. An LDR component holds 0..255, an HDR one a 12-bit value of the
// pseudo-logarithmic representation ("HDR Endpoint Decoding").
struct EndpointPair {
    int e0[4], e1[4];
    bool hdr[4];
};

void set_ldr(EndpointPair& p, int r0, int g0, int b0, int a0, int r1, int g1, int b1, int a1) {
    auto c = [](int v) { return std::clamp(v, 0, 255); };  // clamp_unorm8
    p = {{c(r0), c(g0), c(b0), c(a0)}, {c(r1), c(g1), c(b1), c(a1)}, {false, false, false, false}};
}

void set_hdr_rgb(EndpointPair& p, int r0, int g0, int b0, int r1, int g1, int b1) {
    auto c = [](int v) { return std::clamp(v, 0, 0xFFF); };
    p = {{c(r0), c(g0), c(b0), 0x780}, {c(r1), c(g1), c(b1), 0x780}, {true, true, true, true}};  // 0x780: 1.0
}

void bit_transfer_signed(int& a, int& b) {
    b >>= 1;
    b |= a & 0x80;
    a >>= 1;
    a &= 0x3F;
    if (a & 0x20) a -= 0x40;
}

// "LDR Endpoint Decoding", modes 8/9/12/13: stores the pair, blue-contracted and swapped when
// the direct pair's sum says so.
void set_ldr_rgba(EndpointPair& p, const int lo[4], const int hi[4], bool contract) {
    if (!contract) {
        set_ldr(p, lo[0], lo[1], lo[2], lo[3], hi[0], hi[1], hi[2], hi[3]);
        return;
    }
    // blue_contract on each endpoint, the endpoints swapped
    set_ldr(p, (hi[0] + hi[2]) >> 1, (hi[1] + hi[2]) >> 1, hi[2], hi[3], (lo[0] + lo[2]) >> 1, (lo[1] + lo[2]) >> 1,
            lo[2], lo[3]);
}

// "HDR Endpoint Mode 11": two RGB endpoints from six values.
void decode_hdr_rgb(EndpointPair& p, const int* v) {
    const int majcomp = (v[4] & 0x80) >> 7 | (v[5] & 0x80) >> 6;
    if (majcomp == 3) {
        set_hdr_rgb(p, v[0] << 4, v[2] << 4, (v[4] & 0x7F) << 5, v[1] << 4, v[3] << 4, (v[5] & 0x7F) << 5);
        return;
    }
    const int mode = (v[1] & 0x80) >> 7 | (v[2] & 0x80) >> 6 | (v[3] & 0x80) >> 5;
    int va = v[0] | (v[1] & 0x40) << 2, vb0 = v[2] & 0x3F, vb1 = v[3] & 0x3F, vc = v[1] & 0x3F;
    static constexpr int kDBits[8] = {7, 6, 7, 6, 5, 6, 5, 6};
    auto sign_extend = [](int x, int bits) {
        const int s = 1 << (bits - 1);
        return ((x & ((1 << bits) - 1)) ^ s) - s;
    };
    int vd0 = sign_extend(v[4] & 0x7F, kDBits[mode]), vd1 = sign_extend(v[5] & 0x7F, kDBits[mode]);
    const int x0 = (v[2] >> 6) & 1, x1 = (v[3] >> 6) & 1, x2 = (v[4] >> 6) & 1, x3 = (v[5] >> 6) & 1,
              x4 = (v[4] >> 5) & 1, x5 = (v[5] >> 5) & 1;
    const int ohm = 1 << mode;  // the table "ASTC HDR mode 11 endpoint bit mode"
    if (ohm & 0xA4) va |= x0 << 9;
    if (ohm & 0x08) va |= x2 << 9;
    if (ohm & 0x50) va |= x4 << 9;
    if (ohm & 0x50) va |= x5 << 10;
    if (ohm & 0xA0) va |= x1 << 10;
    if (ohm & 0xC0) va |= x2 << 11;
    if (ohm & 0x04) vc |= x1 << 6;
    if (ohm & 0xE8) vc |= x3 << 6;
    if (ohm & 0x20) vc |= x2 << 7;
    if (ohm & 0x5B) vb0 |= x0 << 6;
    if (ohm & 0x5B) vb1 |= x1 << 6;
    if (ohm & 0x12) vb0 |= x2 << 7;
    if (ohm & 0x12) vb1 |= x3 << 7;
    // Shift so the major component fills 12 bits (the spec's "modeval" here is `mode`).
    const int scale = 1 << ((mode >> 1) ^ 3);
    va *= scale, vb0 *= scale, vb1 *= scale, vc *= scale, vd0 *= scale, vd1 *= scale;
    int c1[3] = {va, va - vb0, va - vb1};
    int c0[3] = {va - vc, va - vb0 - vc - vd0, va - vb1 - vc - vd1};
    if (majcomp != 0) std::swap(c0[0], c0[majcomp]), std::swap(c1[0], c1[majcomp]);
    set_hdr_rgb(p, c0[0], c0[1], c0[2], c1[0], c1[1], c1[2]);
}

// "HDR Endpoint Mode 7": base RGB and a scale from four values.
void decode_hdr_rgb_scale(EndpointPair& p, const int* v) {
    const int modeval = (v[0] & 0xC0) >> 6 | (v[1] & 0x80) >> 5 | (v[2] & 0x80) >> 4;
    int majcomp, mode;
    if ((modeval & 0xC) != 0xC) majcomp = modeval >> 2, mode = modeval & 3;
    else if (modeval != 0xF) majcomp = modeval & 3, mode = 4;
    else majcomp = 0, mode = 5;
    int red = v[0] & 0x3F, green = v[1] & 0x1F, blue = v[2] & 0x1F, scale = v[3] & 0x1F;
    const int x0 = (v[1] >> 6) & 1, x1 = (v[1] >> 5) & 1, x2 = (v[2] >> 6) & 1, x3 = (v[2] >> 5) & 1,
              x4 = (v[3] >> 7) & 1, x5 = (v[3] >> 6) & 1, x6 = (v[3] >> 5) & 1;
    const int ohm = 1 << mode;  // the table "ASTC HDR mode 7 endpoint bit mode"
    if (ohm & 0x30) green |= x0 << 6;
    if (ohm & 0x3A) green |= x1 << 5;
    if (ohm & 0x30) blue |= x2 << 6;
    if (ohm & 0x3A) blue |= x3 << 5;
    if (ohm & 0x3D) scale |= x6 << 5;
    if (ohm & 0x2D) scale |= x5 << 6;
    if (ohm & 0x04) scale |= x4 << 7;
    if (ohm & 0x3B) red |= x4 << 6;
    if (ohm & 0x04) red |= x3 << 6;
    if (ohm & 0x10) red |= x5 << 7;
    if (ohm & 0x0F) red |= x2 << 7;
    if (ohm & 0x05) red |= x1 << 8;
    if (ohm & 0x0A) red |= x0 << 8;
    if (ohm & 0x05) red |= x0 << 9;
    if (ohm & 0x02) red |= x6 << 9;
    if (ohm & 0x01) red |= x3 << 10;
    if (ohm & 0x02) red |= x5 << 10;
    static constexpr int kShift[6] = {1, 1, 2, 3, 4, 5};
    red <<= kShift[mode], green <<= kShift[mode], blue <<= kShift[mode], scale <<= kShift[mode];
    if (mode != 5) green = red - green, blue = red - blue;  // minor components are differences
    if (majcomp == 1) std::swap(red, green);
    if (majcomp == 2) std::swap(red, blue);
    set_hdr_rgb(p, red - scale, green - scale, blue - scale, red, green, blue);
}

// "LDR Endpoint Decoding" and "HDR Endpoint Decoding": the pair of colour endpoint mode `cem`
// from its unquantized values v (2 to 8 of them, each 0..255).
EndpointPair decode_endpoints(int cem, const int* in) {
    int v[8];
    std::copy(in, in + 2 + 2 * (cem >> 2), v);
    EndpointPair p{};
    switch (cem) {
        case 0: set_ldr(p, v[0], v[0], v[0], 255, v[1], v[1], v[1], 255); break;
        case 1: {
            const int l0 = (v[0] >> 2) | (v[1] & 0xC0), l1 = std::min(l0 + (v[1] & 0x3F), 255);
            set_ldr(p, l0, l0, l0, 255, l1, l1, l1, 255);
            break;
        }
        case 2: {
            const int y0 = v[1] >= v[0] ? v[0] << 4 : (v[1] << 4) + 8;
            const int y1 = v[1] >= v[0] ? v[1] << 4 : (v[0] << 4) - 8;
            set_hdr_rgb(p, y0, y0, y0, y1, y1, y1);
            break;
        }
        case 3: {
            int y0, d;
            if (v[0] & 0x80) y0 = (v[1] & 0xE0) << 4 | (v[0] & 0x7F) << 2, d = (v[1] & 0x1F) << 2;
            else y0 = (v[1] & 0xF0) << 4 | (v[0] & 0x7F) << 1, d = (v[1] & 0x0F) << 1;
            const int y1 = std::min(y0 + d, 0xFFF);
            set_hdr_rgb(p, y0, y0, y0, y1, y1, y1);
            break;
        }
        case 4: set_ldr(p, v[0], v[0], v[0], v[2], v[1], v[1], v[1], v[3]); break;
        case 5:
            bit_transfer_signed(v[1], v[0]);
            bit_transfer_signed(v[3], v[2]);
            set_ldr(p, v[0], v[0], v[0], v[2], v[0] + v[1], v[0] + v[1], v[0] + v[1], v[2] + v[3]);
            break;
        case 6:
            set_ldr(p, v[0] * v[3] >> 8, v[1] * v[3] >> 8, v[2] * v[3] >> 8, 255, v[0], v[1], v[2], 255);
            break;
        case 7: decode_hdr_rgb_scale(p, v); break;
        case 8:
        case 12: {
            const int a0 = cem == 12 ? v[6] : 255, a1 = cem == 12 ? v[7] : 255;
            const int lo[4] = {v[0], v[2], v[4], a0}, hi[4] = {v[1], v[3], v[5], a1};
            set_ldr_rgba(p, lo, hi, v[1] + v[3] + v[5] < v[0] + v[2] + v[4]);
            break;
        }
        case 9:
        case 13: {
            for (int i = 0; i < (cem == 13 ? 8 : 6); i += 2) bit_transfer_signed(v[i + 1], v[i]);
            const int a0 = cem == 13 ? v[6] : 255, a1 = cem == 13 ? v[6] + v[7] : 255;
            const int lo[4] = {v[0], v[2], v[4], a0}, hi[4] = {v[0] + v[1], v[2] + v[3], v[4] + v[5], a1};
            set_ldr_rgba(p, lo, hi, v[1] + v[3] + v[5] < 0);
            break;
        }
        case 10:
            set_ldr(p, v[0] * v[3] >> 8, v[1] * v[3] >> 8, v[2] * v[3] >> 8, v[4], v[0], v[1], v[2], v[5]);
            break;
        case 11: decode_hdr_rgb(p, v); break;
        case 14:  // HDR RGB, LDR alpha (interpolated as LDR)
            decode_hdr_rgb(p, v);
            p.e0[3] = v[6], p.e1[3] = v[7], p.hdr[3] = false;
            break;
        default: {  // 15: HDR RGB, HDR alpha
            decode_hdr_rgb(p, v);
            const int mode = (v[6] >> 7 & 1) | (v[7] >> 6 & 2);
            int a0 = v[6] & 0x7F, a1 = v[7] & 0x7F;
            if (mode == 3) {
                a0 <<= 5, a1 <<= 5;
            } else {  // a0 takes bits from a1; a1 becomes a signed delta
                a0 |= (a1 << (mode + 1)) & 0x780;
                a1 &= 0x3F >> mode;
                a1 ^= 0x20 >> mode;
                a1 -= 0x20 >> mode;
                a0 <<= 4 - mode;
                a1 = std::clamp(a0 + a1 * (1 << (4 - mode)), 0, 0xFFF);
            }
            p.e0[3] = a0, p.e1[3] = a1;
            break;
        }
    }
    return p;
}

// --- Texel values --------------------------------------------------------------------------

// A UNORM16 value to FP16, 65535 to 1.0 and otherwise C / 65536 rounded toward zero
// ("Weight Application", LDR endpoint modes).
std::uint16_t unorm16_to_half(int c) {
    if (c >= 0xFFFF) return 0x3C00;
    if (c < 4) return std::uint16_t(c << 8);  // subnormal: c * 2^-16 = (c << 8) * 2^-24
    int top = 15;
    while (!(c >> top)) --top;  // 2..15
    return std::uint16_t((top - 1) << 10 | ((c << 10 >> top) & 0x3FF));
}

// "Weight Application": one component of an endpoint pair at weight w (0..64), as FP16.
std::uint16_t interpolate(int e0, int e1, bool hdr, int w) {
    if (!hdr) {
        const int c = ((e0 * 257) * (64 - w) + (e1 * 257) * w + 32) >> 6;
        return unorm16_to_half(c);
    }
    // Pseudo-logarithmic interpolation, then the piecewise conversion to FP16.
    const int c = ((e0 << 4) * (64 - w) + (e1 << 4) * w + 32) >> 6;
    const int E = (c & 0xF800) >> 11, M = c & 0x7FF;
    const int Mt = M < 512 ? 3 * M : M >= 1536 ? 5 * M - 2048 : 4 * M - 512;
    const int f = (E << 10) + (Mt >> 3);
    return f >= 0x7C00 ? 0x7BFF : std::uint16_t(f);  // +Inf or NaN becomes the largest finite value
}

// --- One block -----------------------------------------------------------------------------

using BlockTexels = std::uint16_t[kDim * kDim][4];  // FP16 RGBA, rows top to bottom

void fill(BlockTexels& out, const std::uint16_t c[4]) {
    for (auto& t : out) std::copy(c, c + 4, t);
}

// "Void-Extent Blocks" (2D layout): one colour for the whole block. Returns false for an illegal
// block: bits 10 and 11 not both 1 (the layout fixes them), an extent whose minimum is not below
// its maximum, or an FP16 colour that is Inf or NaN (undefined in the spec; the reference
// transcoder rejects it too).
bool decode_void_extent(const Bits& b, BlockTexels& out) {
    if (b.get(10, 2) != 3) return false;
    const std::uint32_t s0 = b.get(12, 13), s1 = b.get(25, 13), t0 = b.get(38, 13), t1 = b.get(51, 13);
    const bool all_ones = (s0 & s1 & t0 & t1) == 0x1FFF;  // no extent: just a constant-colour block
    if (!all_ones && (s0 >= s1 || t0 >= t1)) return false;
    const bool hdr = b.get(9, 1);  // FP16 components, else UNORM16
    std::uint16_t c[4];
    for (int i = 0; i < 4; ++i) {
        const std::uint32_t v = b.get(64 + 16 * i, 16);
        if (hdr && (v & 0x7C00) == 0x7C00) return false;
        c[i] = hdr ? std::uint16_t(v) : unorm16_to_half(int(v));
    }
    fill(out, c);
    return true;
}

// Decodes one block into FP16 texels. Returns false for an illegal encoding.
bool decode_block(const std::uint8_t* src, BlockTexels& out) {
    const Bits b = Bits::of(src);
    const int mode = int(b.get(0, 11));
    if ((mode & 0x1FF) == 0x1FC) return decode_void_extent(b, out);

    // "Block Mode", 2D layout: weight grid size, weight range, dual plane.
    const int A = (mode >> 5) & 3, B = (mode >> 7) & 3;
    int gw, gh, range_bits;
    bool dual = (mode >> 10) & 1, high = (mode >> 9) & 1;
    if (mode & 3) {
        range_bits = (mode & 3) << 1 | (mode >> 4 & 1);
        switch ((mode >> 2) & 3) {
            case 0: gw = B + 4, gh = A + 2; break;
            case 1: gw = B + 8, gh = A + 2; break;
            case 2: gw = A + 2, gh = B + 8; break;
            default:
                if (B & 2) gw = (B & 1) + 2, gh = A + 2;
                else gw = A + 2, gh = (B & 1) + 6;
                break;
        }
    } else {
        range_bits = (mode >> 1 & 6) | (mode >> 4 & 1);
        if ((mode & 0xF) == 0) return false;  // reserved
        switch (B) {
            case 0: gw = 12, gh = A + 2; break;
            case 1: gw = A + 2, gh = 12; break;
            case 2: gw = A + 6, gh = ((mode >> 9) & 3) + 6, dual = high = false; break;
            default:
                if (A == 0) gw = 6, gh = 10;
                else if (A == 1) gw = 10, gh = 6;
                else return false;  // reserved (bits 8:6 all set)
                break;
        }
    }
    if (gw > kDim || gh > kDim) return false;  // the grid exceeds the footprint
    const Range weight_range = kRanges[range_bits - 2 + (high ? 6 : 0)];
    const int planes = dual ? 2 : 1, weight_count = gw * gh * planes;
    const int weight_bits = sequence_bits(weight_count, weight_range);
    if (weight_bits < 24 || weight_bits > 96) return false;

    // "Color Endpoint Mode": partitions and each one's CEM.
    const int partitions = int(b.get(11, 2)) + 1;
    if (dual && partitions == 4) return false;
    int cems[4] = {}, config_bits = 17, extra_bits = 0, seed = 0;
    if (partitions == 1) {
        cems[0] = int(b.get(13, 4));
    } else {
        seed = int(b.get(13, 10));
        const int selector = int(b.get(23, 2));
        if (selector == 0) {
            for (int i = 0; i < partitions; ++i) cems[i] = int(b.get(25, 4));
            config_bits = 29;
        } else {
            // Bits 28:23, then 3 * partitions - 4 more right below the weights: per partition a
            // class bit C_i, then per partition two mode bits M_i.
            extra_bits = 3 * partitions - 4;
            const std::uint32_t field = b.get(23, 6) | b.get(128 - weight_bits - extra_bits, extra_bits) << 6;
            for (int i = 0; i < partitions; ++i) {
                const int cls = selector - 1 + int((field >> (2 + i)) & 1);
                cems[i] = cls << 2 | int((field >> (2 + partitions + 2 * i)) & 3);
            }
            config_bits = 25 + 3 * partitions;
        }
    }
    const int ccs_pos = 128 - weight_bits - extra_bits - 2;  // "Dual-Plane Decoding"
    if (dual) config_bits += 2;

    // "Data Size Determination": the largest endpoint range that fits the remaining bits.
    int value_count = 0;
    for (int i = 0; i < partitions; ++i) value_count += 2 + 2 * (cems[i] >> 2);
    if (value_count > 18) return false;
    const int remaining = 128 - config_bits - weight_bits;
    int er = -1;
    for (int r = 20; r >= kFirstEndpointRange && er < 0; --r)
        if (sequence_bits(value_count, kRanges[r]) <= remaining) er = r;
    if (er < 0) return false;  // not even 0..5 fits

    int values[18], weights[2 * kDim * kDim];
    decode_sequence(b, partitions == 1 ? 17 : 29, value_count, kRanges[er], values);
    for (int i = 0; i < value_count; ++i) values[i] = unquantize_endpoint(values[i], kRanges[er]);
    decode_sequence(b.reversed(), 0, weight_count, weight_range, weights);
    for (int i = 0; i < weight_count; ++i) weights[i] = unquantize_weight(weights[i], weight_range);

    EndpointPair pairs[4];
    for (int i = 0, at = 0; i < partitions; at += 2 + 2 * (cems[i] >> 2), ++i)
        pairs[i] = decode_endpoints(cems[i], values + at);  // each partition's values follow the last's
    const int plane1_component = dual ? int(b.get(ccs_pos, 2)) : -1;

    // "Weight Infill": bilinear from the grid to the 4x4 texels, then per texel its partition's
    // endpoints interpolated ("Weight Application").
    constexpr int kScale = (1024 + kDim / 2) / (kDim - 1);
    for (int y = 0; y < kDim; ++y) {
        const int gt = (kScale * y * (gh - 1) + 32) >> 6, jt = gt >> 4, ft = gt & 0xF;
        for (int x = 0; x < kDim; ++x) {
            const int gs = (kScale * x * (gw - 1) + 32) >> 6, js = gs >> 4, fs = gs & 0xF;
            // At the far edge the fraction is 0, so the clamped neighbour carries no weight.
            const int js1 = std::min(js + 1, gw - 1), jt1 = std::min(jt + 1, gh - 1);
            const int w11 = (fs * ft + 8) >> 4, w10 = ft - w11, w01 = fs - w11, w00 = 16 - fs - ft + w11;
            int w[2];
            for (int pl = 0; pl < planes; ++pl) {
                auto at = [&](int gx, int gy) { return weights[(gy * gw + gx) * planes + pl]; };
                w[pl] = (at(js, jt) * w00 + at(js1, jt) * w01 + at(js, jt1) * w10 + at(js1, jt1) * w11 + 8) >> 4;
            }
            const EndpointPair& p = pairs[partitions > 1 ? astc_select_partition(seed, x, y, partitions, true) : 0];
            auto& texel = out[y * kDim + x];
            for (int c = 0; c < 4; ++c)
                texel[c] = interpolate(p.e0[c], p.e1[c], p.hdr[c], w[c == plane1_component ? 1 : 0]);
        }
    }
    return true;
}

}  // namespace

void transcode_uastc_hdr(std::span<const std::uint8_t> blocks, int width, int height, float* rgba,
                         const std::string& name) {
    if (width <= 0 || height <= 0)
        throw Error(name, "", "UASTC HDR image is " + std::to_string(width) + " x " + std::to_string(height) +
                                  " pixels");
    const std::size_t bw = (std::size_t(width) + kDim - 1) / kDim, bh = (std::size_t(height) + kDim - 1) / kDim;
    const std::uint64_t expected = std::uint64_t(bw) * bh * 16;  // at most 2^62 for int sizes
    if (blocks.size() != expected)
        throw Error(name, "byte " + std::to_string(blocks.size()),
                    "UASTC HDR level ends here; " + std::to_string(width) + " x " + std::to_string(height) +
                        " pixels need " + std::to_string(expected) + " bytes (16 per 4x4 block)");
    // A reserved or illegal block: the spec's HDR error colour is NaN, which filtering and mipmaps
    // would spread; opaque magenta (the other colour the spec allows) shows the block instead.
    static constexpr std::uint16_t kError[4] = {0x3C00, 0x0000, 0x3C00, 0x3C00};
    BlockTexels texels;
    for (std::size_t by = 0; by < bh; ++by) {
        for (std::size_t bx = 0; bx < bw; ++bx) {
            if (!decode_block(blocks.data() + 16 * (by * bw + bx), texels)) fill(texels, kError);
            const std::size_t x0 = bx * kDim, y0 = by * kDim;
            for (std::size_t y = 0; y < kDim && y0 + y < std::size_t(height); ++y)
                for (std::size_t x = 0; x < kDim && x0 + x < std::size_t(width); ++x) {
                    float* px = rgba + ((y0 + y) * std::size_t(width) + x0 + x) * 4;
                    for (int c = 0; c < 4; ++c) px[c] = detail::half_to_float(texels[y * kDim + x][c]);
                }
        }
    }
}

}  // namespace fresnel::basisu
