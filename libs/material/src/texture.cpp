#include "fresnel/material/texture.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "fresnel/core/color.h"
#include "fresnel/core/error.h"
#include "fresnel/core/mipmap.h"

namespace fresnel {

namespace {
Image8 to_rgba(const Image8& in) {
    if (in.channels == 4) return in;
    Image8 out(in.width, in.height, 4);
    for (int y = 0; y < in.height; ++y)
        for (int x = 0; x < in.width; ++x) {
            const std::uint8_t* s = in.at(x, y);
            std::uint8_t* d = out.at(x, y);
            switch (in.channels) {
                case 1: d[0] = d[1] = d[2] = s[0]; d[3] = 255; break;
                case 2: d[0] = d[1] = d[2] = s[0]; d[3] = s[1]; break;
                default: d[0] = s[0]; d[1] = s[1]; d[2] = s[2]; d[3] = 255; break;
            }
        }
    return out;
}

// The GL spec's wrap of an integer texel index (ES 3.0 table 3.20).
int wrap_index(int i, int size, TextureWrap w) {
    switch (w) {
        case TextureWrap::ClampToEdge: return std::clamp(i, 0, size - 1);
        case TextureWrap::Repeat: {
            int m = i % size;
            return m < 0 ? m + size : m;
        }
        case TextureWrap::MirroredRepeat: {
            int period = 2 * size;
            int m = i % period;
            if (m < 0) m += period;
            int a = m - size;
            int mirror = a >= 0 ? a : -(1 + a);
            return (size - 1) - mirror;
        }
    }
    return 0;
}
}  // namespace

SampledTexture::SampledTexture(const Image8& image, const TextureSampler& sampler, bool srgb, const TexelDecode* decode)
    : sampler_(sampler), srgb_(srgb) {
    if (image.width <= 0 || image.height <= 0) throw Error("texture", "", "empty image");
    for (int i = 0; i < 256; ++i) {
        float unorm = float(i) / 255.0f;
        decode_[i] = decode ? decode->rgb[i] : srgb ? srgb_to_linear(unorm) : unorm;
        alpha_[i] = decode ? decode->alpha[i] : unorm;
    }
    levels_.push_back(to_rgba(image));
    if (sampler.mip_filter == MipFilter::None) return;
    // The chain the renderer uploads (fresnel/core/mipmap.h): the GPU samples these very levels.
    for (Image8& level : build_mip_chain(levels_.front(), srgb)) levels_.push_back(std::move(level));
}

glm::vec4 SampledTexture::texel(int level, int x, int y) const {
    const Image8& img = levels_[std::size_t(level)];
    x = wrap_index(x, img.width, sampler_.wrap_s);
    y = wrap_index(y, img.height, sampler_.wrap_t);
    const std::uint8_t* p = img.at(x, y);
    return glm::vec4(decode_[p[0]], decode_[p[1]], decode_[p[2]], alpha_[p[3]]);
}

glm::vec4 SampledTexture::filter(int level, glm::vec2 uv, TextureFilter f) const {
    const Image8& img = levels_[std::size_t(level)];
    // Row 0 of the image is v = 0 (glTF and the renderer's upload agree: top row first).
    float u = uv.x * float(img.width), v = uv.y * float(img.height);
    if (f == TextureFilter::Nearest) return texel(level, int(std::floor(u)), int(std::floor(v)));
    float fu = u - 0.5f, fv = v - 0.5f;
    int i0 = int(std::floor(fu)), j0 = int(std::floor(fv));
    float a = fu - std::floor(fu), b = fv - std::floor(fv);
    // The four texels of texel(), with each index wrapped once.
    const int xa = wrap_index(i0, img.width, sampler_.wrap_s), xb = wrap_index(i0 + 1, img.width, sampler_.wrap_s);
    const int ya = wrap_index(j0, img.height, sampler_.wrap_t), yb = wrap_index(j0 + 1, img.height, sampler_.wrap_t);
    const std::uint8_t* row_a = img.pixels.data() + std::size_t(ya) * std::size_t(img.width) * 4;
    const std::uint8_t* row_b = img.pixels.data() + std::size_t(yb) * std::size_t(img.width) * 4;
    auto fetch = [this](const std::uint8_t* p) { return glm::vec4(decode_[p[0]], decode_[p[1]], decode_[p[2]], alpha_[p[3]]); };
    glm::vec4 t00 = fetch(row_a + std::size_t(xa) * 4), t10 = fetch(row_a + std::size_t(xb) * 4);
    glm::vec4 t01 = fetch(row_b + std::size_t(xa) * 4), t11 = fetch(row_b + std::size_t(xb) * 4);
    return (1 - a) * (1 - b) * t00 + a * (1 - b) * t10 + (1 - a) * b * t01 + a * b * t11;
}

glm::vec4 SampledTexture::sample(glm::vec2 uv, float lod) const { return sample_with(uv, lod, sampler_.min_filter); }

glm::vec4 SampledTexture::sample_with(glm::vec2 uv, float lod, TextureFilter min_filter) const {
    if (!(lod > 0.0f)) return filter(0, uv, sampler_.mag_filter);  // magnification (also NaN / -inf)
    int q = level_count() - 1;
    switch (sampler_.mip_filter) {
        case MipFilter::None: return filter(0, uv, min_filter);
        case MipFilter::Nearest: {
            int d = lod <= 0.5f ? 0 : int(std::ceil(lod + 0.5f)) - 1;
            return filter(std::min(d, q), uv, min_filter);
        }
        case MipFilter::Linear: {
            if (lod >= float(q)) return filter(q, uv, min_filter);
            int d1 = int(std::floor(lod));
            float frac = lod - float(d1);
            glm::vec4 t1 = filter(d1, uv, min_filter);
            if (frac == 0.0f) return t1;
            return (1.0f - frac) * t1 + frac * filter(d1 + 1, uv, min_filter);
        }
    }
    return glm::vec4(1.0f);
}

glm::vec4 SampledTexture::sample_footprint(const DetailFootprint& f, bool linear_min) const {
    const TextureFilter min_filter = linear_min ? TextureFilter::Linear : sampler_.min_filter;
    glm::vec4 sum(0.0f);
    glm::vec2 p = f.p;
    for (int i = 0; i < f.n; ++i, p += f.delta) sum += sample_with(p, f.lod, min_filter);
    return sum / float(f.n);
}

// The shader's detail_footprint (material_inputs.glsl), operation for operation.
DetailFootprint detail_footprint(glm::vec2 uv, glm::vec2 dx, glm::vec2 dy, glm::vec2 size, float max_anisotropy) {
    const glm::vec2 tx = dx * size, ty = dy * size;
    const float lx = glm::dot(tx, tx), ly = glm::dot(ty, ty);
    const float major2 = std::max(lx, ly);
    const float area = std::abs(tx.x * ty.y - tx.y * ty.x);
    const float anisotropy = std::clamp(major2 / std::max(area, 1e-30f), 1.0f, std::max(max_anisotropy, 1.0f));
    const glm::vec2 axis = lx >= ly ? dx : dy;
    DetailFootprint f;
    f.anisotropy = anisotropy;
    f.lod = 0.5f * std::log2(std::max(major2, 1e-30f) / (anisotropy * anisotropy));
    const float probes = anisotropy + 0.5f;
    f.n = int(probes < 17.0f ? probes : 1.0f);  // a NaN footprint takes one probe
    f.delta = axis / float(f.n);
    f.p = uv - axis * (float(f.n - 1) / float(2 * f.n));
    return f;
}

float detail_anisotropy(Filter mag_filter, MipmapMode mip_filter, float requested) {
    return mip_filter == MipmapMode::Linear && mag_filter != Filter::Nearest ? std::max(1.0f, requested) : 1.0f;
}

}  // namespace fresnel
