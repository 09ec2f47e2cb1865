#pragma once
// Texture sampling with the conventions of the GPU path (OpenGL ES 3.0, section 3.8), so
// that fresnel::evaluate reads a material's textures exactly as the shader does:
//   - wrap modes REPEAT, CLAMP_TO_EDGE, MIRRORED_REPEAT applied to texel indices;
//   - NEAREST / LINEAR filtering, mip-map selection NEAREST / LINEAR from a given LOD λ
//     (λ <= 0 magnifies; minification without mip-maps reads level 0);
//   - sRGB textures (SRGB8_ALPHA8) are decoded per texel before filtering; alpha is linear;
//   - the mip chain is fresnel::build_mip_chain's (core/mipmap.h), the one the renderer
//     builds and uploads: each level from the one above as a linear blit filters it (in
//     linear light for sRGB), rounded to 8 bits.
//   - the detail maps' anisotropic filter, which the renderer runs in the shader
//     (sample_detail_map in shaders/material_inputs.glsl): detail_footprint and
//     SampledTexture::sample_footprint below. The sampler's own anisotropic filtering
//     (GL's TEXTURE_MAX_ANISOTROPY, driver-defined) is not modelled.
#include <memory>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "fresnel/core/image.h"
#include "fresnel/core/sampler.h"

namespace fresnel {

// The sampler vocabulary is core's (fresnel/core/sampler.h), shared with the scene model
// and the GPU layer.
using TextureFilter = Filter;
using MipFilter = MipmapMode;
using TextureWrap = Wrap;

struct TextureSampler {
    TextureFilter mag_filter = TextureFilter::Linear;
    TextureFilter min_filter = TextureFilter::Linear;
    MipFilter mip_filter = MipFilter::Linear;
    TextureWrap wrap_s = TextureWrap::Repeat;
    TextureWrap wrap_t = TextureWrap::Repeat;
};

// The detail maps' anisotropic filter (the shader's detail_footprint): from a map's
// coordinates uv and their screen-space derivatives dx, dy (what dFdx/dFdy give, in the
// map's transformed coordinates) on a level-0 image of `size` texels, the anisotropy is the
// texel footprint's major axis over its parallelogram's height, at most max_anisotropy;
// round(it) probes spread evenly along the major axis, at the level of detail of the
// footprint's height, are averaged. With max_anisotropy 1 it is one probe at uv and the GL
// spec's level of detail, log2 of the longer derivative in texels.
struct DetailFootprint {
    glm::vec2 p{0.0f};      // the first probe
    glm::vec2 delta{0.0f};  // from one probe to the next
    float lod = 0.0f;
    int n = 1;              // probes, >= 1
    float anisotropy = 1.0f;  // before rounding to n (a point near a half is where float rounding may flip n)
};
DetailFootprint detail_footprint(glm::vec2 uv, glm::vec2 dx, glm::vec2 dy, glm::vec2 size, float max_anisotropy);

// The most probes the renderer's detail filter takes for a map read through a sampler with
// these filters when `requested` are asked for (RenderSettings::anisotropy): `requested` (at
// least 1) for trilinear samplers that magnify linearly, else 1. With more than one, the
// probes minify linearly whatever the sampler's minification filter (as SwiftShader does).
float detail_anisotropy(Filter mag_filter, MipmapMode mip_filter, float requested);

// How texel bytes become values: by default byte / 255, and the exact sRGB curve for the
// colour channels of sRGB textures. Tests that compare with a driver pass its measured
// response instead (llvmpipe decodes sRGB with a polynomial, 1.2e-3 off the curve), so
// that they compare the rules alone.
struct TexelDecode {
    float rgb[256];
    float alpha[256];
};

// A texture as the GPU holds it: RGBA8 levels, sRGB or linear, with its sampler.
class SampledTexture {
public:
    // `image` has 1..4 channels (expanded to RGBA as GL does: grey, grey+alpha, RGB, RGBA).
    SampledTexture(const Image8& image, const TextureSampler& sampler, bool srgb, const TexelDecode* decode = nullptr);
    // Filtered, decoded RGBA at uv for the level of detail `lod` (λ, any bias included).
    glm::vec4 sample(glm::vec2 uv, float lod) const;
    // The average of the footprint's probes, each sample(probe, f.lod) but with a linear
    // minification filter where `linear_min` (detail_anisotropy above 1).
    glm::vec4 sample_footprint(const DetailFootprint& f, bool linear_min) const;
    // One decoded texel of `level` (indices wrapped by the sampler).
    glm::vec4 texel(int level, int x, int y) const;
    int width() const { return levels_[0].width; }
    int height() const { return levels_[0].height; }
    int level_count() const { return int(levels_.size()); }
    const Image8& level(int i) const { return levels_[std::size_t(i)]; }
    const TextureSampler& sampler() const { return sampler_; }
    bool srgb() const { return srgb_; }

private:
    glm::vec4 filter(int level, glm::vec2 uv, TextureFilter f) const;
    glm::vec4 sample_with(glm::vec2 uv, float lod, TextureFilter min_filter) const;
    std::vector<Image8> levels_;  // RGBA8
    TextureSampler sampler_;
    bool srgb_ = false;
    float decode_[256];   // colour byte -> value
    float alpha_[256];    // alpha byte -> value
};

// Where evaluate finds textures: by the material's texture index and colour space (the
// same texture may be read as sRGB by one slot and as linear data by another).
class TextureSource {
public:
    virtual ~TextureSource() = default;
    // nullptr: no usable image (the slot then reads as white, like the renderer's fallback of leaving the map unbound).
    virtual const SampledTexture* get(int texture, bool srgb) const = 0;
};

// No textures at all (factors only).
class NoTextures final : public TextureSource {
public:
    const SampledTexture* get(int, bool) const override { return nullptr; }
};

}  // namespace fresnel
