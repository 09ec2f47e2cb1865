#include "fresnel/core/mipmap.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "fresnel/core/color.h"
#include "fresnel/core/error.h"

namespace fresnel {
namespace {

// sRGB byte -> linear float, for all 256 values.
const std::array<float, 256>& srgb_decode_table() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) t[std::size_t(i)] = srgb_to_linear(float(i) / 255.0f);
        return t;
    }();
    return table;
}

// Linear float -> sRGB byte rounded to nearest in the encoded space: the byte i + 1 begins
// where the encoded value reaches i + 0.5, i.e. at linear srgb_to_linear((i + 0.5) / 255).
const std::array<float, 255>& srgb_encode_thresholds() {
    static const std::array<float, 255> table = [] {
        std::array<float, 255> t{};
        for (int i = 0; i < 255; ++i) t[std::size_t(i)] = srgb_to_linear((float(i) + 0.5f) / 255.0f);
        return t;
    }();
    return table;
}
// The encoder: a first guess from 2^16 equal buckets of [0, 1] (narrower than the gap
// between any two thresholds, so at most one threshold falls in a bucket), then one
// comparison; exact, and ~10x faster than a binary search over the thresholds.
struct SrgbEncoder {
    static constexpr int kBuckets = 1 << 16;
    std::vector<std::uint8_t> guess;  // the code of the bucket's lower end
    const std::array<float, 255>& t;
    SrgbEncoder() : guess(kBuckets + 1), t(srgb_encode_thresholds()) {
        for (int i = 0; i <= kBuckets; ++i) {
            float v = float(i) / float(kBuckets);
            guess[std::size_t(i)] = std::uint8_t(std::upper_bound(t.begin(), t.end(), v) - t.begin());
        }
    }
    std::uint8_t operator()(float v) const {
        v = std::clamp(v, 0.0f, 1.0f);
        std::uint8_t c = guess[std::size_t(v * float(kBuckets))];
        return c < 255 && v >= t[c] ? std::uint8_t(c + 1) : c;
    }
};
const SrgbEncoder& srgb_encoder() {
    static const SrgbEncoder encoder;
    return encoder;
}

std::uint8_t to_unorm8(float v) { return std::uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }

// Source coordinate and weight of a destination texel along one axis (linear blit).
struct Tap {
    int i0, i1;
    float w1;  // weight of i1
};
std::vector<Tap> taps(int src, int dst) {
    std::vector<Tap> out(static_cast<std::size_t>(dst));
    float scale = float(src) / float(dst);
    for (int x = 0; x < dst; ++x) {
        float s = (float(x) + 0.5f) * scale - 0.5f;
        float f = std::floor(s);
        int i0 = int(f);
        float w1 = s - f;
        out[std::size_t(x)] = {std::clamp(i0, 0, src - 1), std::clamp(i0 + 1, 0, src - 1), w1};
    }
    return out;
}

}  // namespace

int mip_level_count(int width, int height) {
    int levels = 1;
    for (int s = std::max(width, height); s > 1; s >>= 1) ++levels;
    return levels;
}

Image8 downsample_half(const Image8& src, bool srgb) {
    if (src.channels != 4) throw Error("mipmap", "", "downsample_half needs an RGBA image");
    int w = std::max(1, src.width / 2), h = std::max(1, src.height / 2);
    Image8 dst(w, h, 4);
    const auto& lut = srgb_decode_table();
    const SrgbEncoder& enc = srgb_encoder();
    if (src.width % 2 == 0 && src.height % 2 == 0) {
        // Even sizes: the bilinear tap falls between four texels, the 2x2 box average.
        for (int y = 0; y < h; ++y) {
            const std::uint8_t* r0 = src.at(0, 2 * y);
            const std::uint8_t* r1 = src.at(0, 2 * y + 1);
            std::uint8_t* out = dst.at(0, y);
            for (int x = 0; x < w; ++x, r0 += 8, r1 += 8, out += 4) {
                for (int c = 0; c < 4; ++c) {
                    if (srgb && c < 3) {
                        float v = 0.25f * (lut[r0[c]] + lut[r0[c + 4]] + lut[r1[c]] + lut[r1[c + 4]]);
                        out[c] = enc(v);
                    } else {
                        out[c] = std::uint8_t((unsigned(r0[c]) + r0[c + 4] + r1[c] + r1[c + 4] + 2u) >> 2);
                    }
                }
            }
        }
        return dst;
    }
    std::vector<Tap> tx = taps(src.width, w), ty = taps(src.height, h);
    for (int y = 0; y < h; ++y) {
        const Tap& b = ty[std::size_t(y)];
        const std::uint8_t* r0 = src.at(0, b.i0);
        const std::uint8_t* r1 = src.at(0, b.i1);
        std::uint8_t* out = dst.at(0, y);
        for (int x = 0; x < w; ++x) {
            const Tap& a = tx[std::size_t(x)];
            const std::uint8_t* p[4] = {r0 + a.i0 * 4, r0 + a.i1 * 4, r1 + a.i0 * 4, r1 + a.i1 * 4};
            float wt[4] = {(1 - a.w1) * (1 - b.w1), a.w1 * (1 - b.w1), (1 - a.w1) * b.w1, a.w1 * b.w1};
            for (int c = 0; c < 4; ++c) {
                float v = 0.0f;
                if (srgb && c < 3) {
                    for (int k = 0; k < 4; ++k) v += wt[k] * lut[p[k][c]];
                    out[x * 4 + c] = enc(v);
                } else {
                    for (int k = 0; k < 4; ++k) v += wt[k] * float(p[k][c]);
                    out[x * 4 + c] = to_unorm8(v / 255.0f);
                }
            }
        }
    }
    return dst;
}

std::vector<Image8> build_mip_chain(const Image8& level0, bool srgb) {
    std::vector<Image8> out;
    int levels = mip_level_count(level0.width, level0.height);
    const Image8* prev = &level0;
    out.reserve(std::size_t(std::max(0, levels - 1)));
    for (int l = 1; l < levels; ++l) {
        out.push_back(downsample_half(*prev, srgb));
        prev = &out.back();
    }
    return out;
}

}  // namespace fresnel
