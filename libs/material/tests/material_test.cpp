// The material rules of fresnel::evaluate, texture sampling conventions and the
// specular-glossiness -> metallic-roughness conversion.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>
#include <random>

#include "fresnel/core/color.h"
#include "fresnel/material/evaluate.h"
#include "gltf_sampler.h"

namespace {
using namespace fresnel;

constexpr float kTol = 1e-6f;

// Textures by index, each built once per colour space.
class Textures final : public TextureSource {
public:
    int add(Image8 image, TextureSampler sampler = {}) {
        images_.push_back({std::move(image), sampler});
        return int(images_.size()) - 1;
    }
    const SampledTexture* get(int texture, bool srgb) const override {
        if (texture < 0 || texture >= int(images_.size())) return nullptr;
        auto key = std::make_pair(texture, srgb);
        auto it = cache_.find(key);
        if (it == cache_.end())
            it = cache_.emplace(key, std::make_unique<SampledTexture>(images_[std::size_t(texture)].first,
                                                                      images_[std::size_t(texture)].second, srgb)).first;
        return it->second.get();
    }

private:
    std::vector<std::pair<Image8, TextureSampler>> images_;
    mutable std::map<std::pair<int, bool>, std::unique_ptr<SampledTexture>> cache_;
};

Image8 solid(int w, int h, std::array<std::uint8_t, 4> c) {
    Image8 img(w, h, 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int k = 0; k < 4; ++k) img.at(x, y)[k] = c[std::size_t(k)];
    return img;
}

TextureSlot slot(int texture, int tex_coord = 0) {
    TextureSlot s;
    s.texture = texture;
    s.tex_coord = tex_coord;
    return s;
}

void expect_near(glm::vec3 a, glm::vec3 b, float tol = kTol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

TEST(MaterialEvaluate, DefaultsAreTheSpecificationsDefaults) {
    EvaluatedMaterial e = evaluate(Material{}, NoTextures{}, SurfacePoint{});
    expect_near(e.surface.base_color, glm::vec3(1.0f));
    EXPECT_EQ(e.surface.metallic, 1.0f);
    EXPECT_EQ(e.surface.perceptual_roughness, 1.0f);
    expect_near(e.surface.dielectric_f0(), glm::vec3(0.04f));
    EXPECT_EQ(e.surface.specular_weight, 1.0f);
    EXPECT_EQ(e.alpha, 1.0f);
    EXPECT_FALSE(e.discard);
    EXPECT_EQ(e.occlusion, 1.0f);
    expect_near(e.emissive, glm::vec3(0.0f));
    EXPECT_EQ(e.clearcoat, 0.0f);
    expect_near(e.normal, glm::vec3(0, 0, 1));
    EXPECT_FALSE(e.unlit);
}

TEST(MaterialEvaluate, F0FromIorAndSpecular) {
    Textures tex;
    int spec = tex.add(solid(2, 2, {255, 128, 0, 64}));   // A = 64/255 (linear)
    int color = tex.add(solid(2, 2, {188, 128, 64, 255}));  // RGB sRGB
    Material m;
    m.metallic_factor = 0.0f;
    m.ior = IorExt{1.33f};
    SpecularExt s;
    s.specular_factor = 0.5f;
    s.specular_color_factor = glm::vec3(2.0f, 1.0f, 30.0f);
    s.specular_texture = slot(spec);
    s.specular_color_texture = slot(color);
    m.specular = s;
    EvaluatedMaterial e = evaluate(m, tex, SurfacePoint{});
    float f0 = std::pow((1.33f - 1.0f) / (1.33f + 1.0f), 2.0f);
    glm::vec3 c(srgb_to_linear(188.0f / 255.0f), srgb_to_linear(128.0f / 255.0f), srgb_to_linear(64.0f / 255.0f));
    glm::vec3 expected = glm::min(f0 * glm::vec3(2.0f, 1.0f, 30.0f) * c, glm::vec3(1.0f));
    expect_near(e.surface.dielectric_f0(), expected);
    EXPECT_LE(e.surface.dielectric_f0().z, 1.0f);  // clamped
    EXPECT_NEAR(e.surface.specular_weight, 0.5f * 64.0f / 255.0f, kTol);
    // ior 0 is allowed: F0 = 1.
    m.specular.reset();
    m.ior = IorExt{0.0f};
    expect_near(evaluate(m, tex, SurfacePoint{}).surface.dielectric_f0(), glm::vec3(1.0f));
}

TEST(MaterialEvaluate, BaseColourMetallicRoughnessVertexColour) {
    Textures tex;
    int base = tex.add(solid(1, 1, {255, 128, 0, 128}));
    int mr = tex.add(solid(1, 1, {0, 51, 204, 255}));  // G roughness 0.2, B metallic 0.8
    Material m;
    m.base_color_factor = glm::vec4(0.5f, 1.0f, 1.0f, 0.8f);
    m.base_color = slot(base);
    m.metallic_factor = 0.5f;
    m.roughness_factor = 0.5f;
    m.metallic_roughness = slot(mr);
    m.alpha_mode = AlphaMode::Blend;
    SurfacePoint p;
    p.color = glm::vec4(1.0f, 0.5f, 1.0f, 0.5f);
    EvaluatedMaterial e = evaluate(m, tex, p);
    expect_near(e.surface.base_color, glm::vec3(0.5f, 0.5f * srgb_to_linear(128.0f / 255.0f), 0.0f));
    EXPECT_NEAR(e.alpha, 0.8f * 0.5f * 128.0f / 255.0f, kTol);  // alpha is linear
    EXPECT_NEAR(e.surface.metallic, 0.5f * 0.8f, kTol);
    EXPECT_NEAR(e.surface.perceptual_roughness, 0.5f * 0.2f, kTol);
    // A map on TEXCOORD_1 is not read without TEXCOORD_1; no map without TEXCOORD_0.
    m.metallic_roughness.tex_coord = 1;
    p.inputs.has_uv1 = false;
    EXPECT_NEAR(evaluate(m, tex, p).surface.metallic, 0.5f, kTol);
    p.inputs.has_uv0 = false;
    expect_near(evaluate(m, tex, p).surface.base_color, glm::vec3(0.5f, 0.5f, 1.0f));
}

TEST(MaterialEvaluate, AlphaModes) {
    Material m;
    m.base_color_factor.w = 0.4f;
    EXPECT_EQ(evaluate(m, NoTextures{}, {}).alpha, 1.0f);  // OPAQUE
    m.alpha_mode = AlphaMode::Blend;
    EXPECT_FLOAT_EQ(evaluate(m, NoTextures{}, {}).alpha, 0.4f);
    m.alpha_mode = AlphaMode::Mask;
    m.alpha_cutoff = 0.5f;
    EvaluatedMaterial e = evaluate(m, NoTextures{}, {});
    EXPECT_TRUE(e.discard);
    EXPECT_EQ(e.alpha, 1.0f);
    m.alpha_cutoff = 0.3f;
    e = evaluate(m, NoTextures{}, {});
    EXPECT_FALSE(e.discard);
    EXPECT_EQ(e.alpha, 1.0f);
}

TEST(MaterialEvaluate, OcclusionEmissiveAndStrength) {
    Textures tex;
    int occ = tex.add(solid(1, 1, {51, 0, 0, 255}));
    int em = tex.add(solid(1, 1, {255, 128, 0, 255}));
    Material m;
    m.occlusion = slot(occ);
    m.occlusion_strength = 0.5f;
    m.emissive = slot(em);
    m.emissive_factor = glm::vec3(1.0f, 0.5f, 1.0f);
    m.emissive_strength = EmissiveStrengthExt{4.0f};
    EvaluatedMaterial e = evaluate(m, tex, {});
    EXPECT_NEAR(e.occlusion, 1.0f + 0.5f * (0.2f - 1.0f), kTol);
    expect_near(e.emissive, glm::vec3(4.0f, 2.0f * srgb_to_linear(128.0f / 255.0f), 0.0f), 1e-5f);
}

TEST(MaterialEvaluate, ClearcoatOnlyWithAPositiveFactor) {
    Textures tex;
    int t = tex.add(solid(1, 1, {128, 102, 0, 255}));
    Material m;
    m.ior = IorExt{2.0f};
    ClearcoatExt cc;
    cc.clearcoat_factor = 0.0f;
    cc.clearcoat_texture = slot(t);
    m.clearcoat = cc;
    EXPECT_EQ(evaluate(m, tex, {}).clearcoat, 0.0f);
    m.clearcoat->clearcoat_factor = 0.8f;
    m.clearcoat->clearcoat_roughness_factor = 0.5f;
    m.clearcoat->clearcoat_roughness_texture = slot(t);
    EvaluatedMaterial e = evaluate(m, tex, {});
    EXPECT_NEAR(e.clearcoat, 0.8f * 128.0f / 255.0f, kTol);  // R, linear
    EXPECT_NEAR(e.clearcoat_roughness, 0.5f * 102.0f / 255.0f, kTol);  // G
    EXPECT_NEAR(e.clearcoat_f0, 1.0f / 9.0f, kTol);  // the material's ior
    expect_near(e.clearcoat_normal, glm::vec3(0, 0, 1));
}

TEST(MaterialEvaluate, IridescenceFactorAndThickness) {
    Textures tex;
    int t = tex.add(solid(1, 1, {153, 51, 0, 255}));
    Material m;
    IridescenceExt ir;
    ir.iridescence_factor = 0.0f;
    ir.iridescence_texture = slot(t);
    m.iridescence = ir;
    EXPECT_EQ(evaluate(m, tex, {}).iridescence, 0.0f);  // factor 0: no film
    m.iridescence->iridescence_factor = 0.5f;
    m.iridescence->iridescence_ior = 1.8f;
    m.iridescence->iridescence_thickness_minimum = 200.0f;
    m.iridescence->iridescence_thickness_maximum = 700.0f;
    EvaluatedMaterial e = evaluate(m, tex, {});
    EXPECT_NEAR(e.iridescence, 0.5f * 0.6f, kTol);  // factor * R (linear)
    EXPECT_EQ(e.iridescence_ior, 1.8f);
    EXPECT_EQ(e.iridescence_thickness, 700.0f);      // no thickness map: the maximum
    m.iridescence->iridescence_thickness_texture = slot(t);
    e = evaluate(m, tex, {});
    EXPECT_NEAR(e.iridescence_thickness, 200.0f + 500.0f * 0.2f, 1e-3f);  // mix(min, max, G)
}

TEST(MaterialEvaluate, DiffuseTransmissionFactorAndColour) {
    // The specification's defaults: factor 0 (none), colour white.
    DiffuseTransmissionExt defaults;
    EXPECT_EQ(defaults.diffuse_transmission_factor, 0.0f);
    EXPECT_EQ(defaults.diffuse_transmission_color_factor, glm::vec3(1.0f));
    Textures tex;
    // A (the factor texture's channel) 0.6 linear; RGB (the colour texture's) sRGB.
    int t = tex.add(solid(1, 1, {153, 51, 255, 153}));
    Material m;
    DiffuseTransmissionExt dt;
    dt.diffuse_transmission_texture = slot(t);
    dt.diffuse_transmission_color_texture = slot(t);
    m.diffuse_transmission = dt;
    EvaluatedMaterial e = evaluate(m, tex, {});
    EXPECT_FALSE(m.has_diffuse_transmission());
    EXPECT_EQ(e.diffuse_transmission, 0.0f);  // factor 0: none, and its maps are not read
    EXPECT_EQ(material_map(m, MaterialMap::DiffuseTransmission), nullptr);
    m.diffuse_transmission->diffuse_transmission_factor = 0.5f;
    m.diffuse_transmission->diffuse_transmission_color_factor = glm::vec3(0.4f, 0.9f, 0.2f);
    e = evaluate(m, tex, {});
    EXPECT_NEAR(e.diffuse_transmission, 0.5f * 0.6f, kTol);  // factor * A (linear)
    expect_near(e.diffuse_transmission_color,
                glm::vec3(0.4f * srgb_to_linear(0.6f), 0.9f * srgb_to_linear(0.2f), 0.2f), 1e-5f);  // RGB, sRGB
    EXPECT_TRUE(material_map_info(MaterialMap::DiffuseTransmissionColor).srgb);
    EXPECT_FALSE(material_map_info(MaterialMap::DiffuseTransmission).srgb);
}

TEST(MaterialEvaluate, NormalMapWithScaleInTheGivenFrame) {
    Textures tex;
    // (1, 0.5, 1) in [0,1]^3 -> tangent-space (1, 0, 1) (+1/255 rounding of 128).
    int n = tex.add(solid(1, 1, {255, 128, 255, 255}));
    Material m;
    m.normal = slot(n);
    m.normal_scale = 0.5f;
    SurfacePoint p;
    p.tangent = glm::vec3(0, 1, 0);
    p.bitangent = glm::vec3(0, 0, 1);
    p.normal = glm::vec3(1, 0, 0);
    glm::vec3 tn(1.0f * 0.5f, (128.0f / 255.0f * 2.0f - 1.0f) * 0.5f, 1.0f);
    glm::vec3 expected = glm::normalize(tn.x * p.tangent + tn.y * p.bitangent + tn.z * p.normal);
    expect_near(evaluate(m, tex, p).normal, expected);
    // Normal maps need tangents.
    p.inputs.has_tangent = false;
    expect_near(evaluate(m, tex, p).normal, p.normal);
}

TEST(MaterialEvaluate, UnlitIsCarried) {
    Material m;
    m.unlit = UnlitExt{};
    EXPECT_TRUE(evaluate(m, NoTextures{}, {}).unlit);
}

TEST(MaterialEvaluate, SpecularGlossinessReplacesMetallicRoughness) {
    Textures tex;
    int diffuse = tex.add(solid(1, 1, {128, 255, 64, 200}));
    int sgt = tex.add(solid(1, 1, {255, 128, 64, 102}));  // RGB sRGB, A glossiness linear
    Material m;
    m.metallic_factor = 1.0f;  // ignored with the block
    m.base_color_factor = glm::vec4(0.1f);
    SpecularGlossinessExt sg;
    sg.diffuse_factor = glm::vec4(0.5f, 1.0f, 1.0f, 1.0f);
    sg.diffuse_texture = slot(diffuse);
    sg.specular_factor = glm::vec3(0.2f, 0.4f, 0.6f);
    sg.glossiness_factor = 0.5f;
    sg.specular_glossiness_texture = slot(sgt);
    m.specular_glossiness = sg;
    m.specular = SpecularExt{0.1f, {}, glm::vec3(5.0f), {}};  // ignored with the block
    EvaluatedMaterial e = evaluate(m, tex, {});
    expect_near(e.surface.base_color, glm::vec3(0.5f * srgb_to_linear(128.0f / 255.0f), 1.0f, srgb_to_linear(64.0f / 255.0f)));
    EXPECT_EQ(e.surface.metallic, 0.0f);
    EXPECT_NEAR(e.surface.perceptual_roughness, 1.0f - 0.5f * 102.0f / 255.0f, kTol);
    expect_near(e.surface.dielectric_f0(),
                glm::vec3(0.2f, 0.4f * srgb_to_linear(128.0f / 255.0f), 0.6f * srgb_to_linear(64.0f / 255.0f)));
    EXPECT_EQ(e.surface.specular_weight, 1.0f);
}

TEST(SpecularGlossiness, PointConversion) {
    MetallicRoughnessPoint p = specular_glossiness_to_metallic_roughness(glm::vec4(0.1f, 0.2f, 0.3f, 0.4f),
                                                                         glm::vec3(0.5f, 0.6f, 0.7f), 0.25f);
    EXPECT_EQ(p.base_color, glm::vec4(0.1f, 0.2f, 0.3f, 0.4f));
    EXPECT_EQ(p.metallic, 0.0f);
    EXPECT_EQ(p.roughness, 0.75f);
    EXPECT_EQ(p.f0, glm::vec3(0.5f, 0.6f, 0.7f));
    EXPECT_EQ(p.specular_weight, 1.0f);
}

// The material-level conversion gives the same shading inputs as the block, everywhere,
// when the glossiness comes from the factor alone; with a glossiness map it says it lost it.
TEST(SpecularGlossiness, MaterialConversionShadesTheSame) {
    Textures tex;
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> byte(0, 255);
    Image8 img(4, 4, 4);
    for (auto& v : img.pixels) v = std::uint8_t(byte(rng));
    int t = tex.add(img, test::sampler_from_gltf(9728, 9728, 10497, 10497));
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int trial = 0; trial < 50; ++trial) {
        Material m;
        m.alpha_mode = AlphaMode::Blend;
        if (trial % 3 == 0) m.ior = IorExt{1.0f + 2.0f * u(rng)};
        if (trial % 5 == 1) m.ior = IorExt{1.0f};  // F0 0: the conversion moves to ior 0
        SpecularGlossinessExt sg;
        sg.diffuse_factor = glm::vec4(u(rng), u(rng), u(rng), u(rng));
        sg.specular_factor = glm::vec3(u(rng), u(rng), u(rng));
        sg.glossiness_factor = u(rng);
        sg.diffuse_texture = slot(t);
        if (trial % 2) {
            sg.specular_glossiness_texture = slot(t);
            sg.glossiness_factor = 1.0f;  // the texture's A is lost by the conversion...
        }
        m.specular_glossiness = sg;
        bool lost = false;
        Material mr = to_metallic_roughness(m, &lost);
        EXPECT_EQ(lost, bool(trial % 2));
        EXPECT_FALSE(mr.specular_glossiness);
        for (int k = 0; k < 8; ++k) {
            SurfacePoint p;
            p.uv0 = glm::vec2((float(k % 4) + 0.5f) / 4.0f, (float(k / 4) + 0.5f) / 4.0f);
            EvaluatedMaterial a = evaluate(m, tex, p), b = evaluate(mr, tex, p);
            expect_near(a.surface.base_color, b.surface.base_color);
            EXPECT_NEAR(a.alpha, b.alpha, kTol);
            EXPECT_EQ(a.surface.metallic, b.surface.metallic);
            expect_near(a.surface.dielectric_f0(), b.surface.dielectric_f0(), 1e-5f);
            EXPECT_EQ(a.surface.specular_weight, b.surface.specular_weight);
            if (!lost) {
                EXPECT_NEAR(a.surface.perceptual_roughness, b.surface.perceptual_roughness, kTol);
            }
        }
    }
    Material plain;
    EXPECT_EQ(to_metallic_roughness(plain).metallic_factor, plain.metallic_factor);
}

TEST(TextureSampling, WrapModesAndFilters) {
    Image8 img(4, 1, 4);
    for (int x = 0; x < 4; ++x) img.at(x, 0)[0] = std::uint8_t(x * 80), img.at(x, 0)[3] = 255;
    auto red = [&](TextureSampler s, float u, float lod = 0.0f) {
        return SampledTexture(img, s, false).sample(glm::vec2(u, 0.5f), lod).x * 255.0f;
    };
    TextureSampler nearest = test::sampler_from_gltf(9728, 9728, 10497, 10497);
    EXPECT_NEAR(red(nearest, 0.125f), 0.0f, 1e-3f);
    EXPECT_NEAR(red(nearest, 1.375f), 80.0f, 1e-3f);   // repeat
    EXPECT_NEAR(red(nearest, -0.125f), 240.0f, 1e-3f);  // repeat below 0
    TextureSampler clamp = test::sampler_from_gltf(9728, 9728, 33071, 33071);
    EXPECT_NEAR(red(clamp, 1.375f), 240.0f, 1e-3f);
    EXPECT_NEAR(red(clamp, -3.0f), 0.0f, 1e-3f);
    TextureSampler mirror = test::sampler_from_gltf(9728, 9728, 33648, 33648);
    EXPECT_NEAR(red(mirror, 1.125f), 240.0f, 1e-3f);  // mirrored: texel 4 -> 3
    EXPECT_NEAR(red(mirror, 1.875f), 0.0f, 1e-3f);
    EXPECT_NEAR(red(mirror, -0.125f), 0.0f, 1e-3f);
    TextureSampler linear = test::sampler_from_gltf(9729, 9729, 10497, 10497);
    EXPECT_NEAR(red(linear, 0.25f), 40.0f, 1e-3f);   // halfway between texels 0 and 1
    EXPECT_NEAR(red(linear, 0.0f), 120.0f, 1e-3f);   // repeat: between texels 3 and 0
    TextureSampler clamp_linear = test::sampler_from_gltf(9729, 9729, 33071, 33071);
    EXPECT_NEAR(red(clamp_linear, 0.0f), 0.0f, 1e-3f);
}

TEST(TextureSampling, SrgbDecodedBeforeFiltering) {
    Image8 img(2, 1, 4);
    img.at(0, 0)[0] = 0;
    img.at(1, 0)[0] = 255;
    img.at(0, 0)[3] = 0;
    img.at(1, 0)[3] = 255;
    SampledTexture t(img, test::sampler_from_gltf(9729, 9729, 33071, 33071), true);
    glm::vec4 mid = t.sample(glm::vec2(0.5f, 0.5f), 0.0f);
    EXPECT_NEAR(mid.x, 0.5f, 1e-6f);  // the mean of linear 0 and 1, not the decode of the mean
    EXPECT_NEAR(mid.w, 0.5f, 1e-6f);  // alpha is linear
}

TEST(TextureSampling, MipLevelsAndLod) {
    Image8 img(4, 4, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            img.at(x, y)[0] = std::uint8_t((x + y) % 2 ? 200 : 0);
            img.at(x, y)[3] = 255;
        }
    SampledTexture t(img, test::sampler_from_gltf(9728, 9987, 10497, 10497), false);
    ASSERT_EQ(t.level_count(), 3);
    EXPECT_EQ(t.level(1).width, 2);
    EXPECT_EQ(t.level(1).at(0, 0)[0], 100);  // box average
    glm::vec2 uv(0.125f, 0.125f);
    EXPECT_NEAR(t.sample(uv, 0.0f).x, 0.0f, 1e-6f);               // magnification: NEAREST, level 0
    EXPECT_NEAR(t.sample(uv, 1.0f).x, 100.0f / 255.0f, 1e-6f);    // level 1
    EXPECT_NEAR(t.sample(uv, 0.5f).x, 50.0f / 255.0f, 1e-6f);     // halfway between levels 0 and 1
    EXPECT_NEAR(t.sample(uv, 9.0f).x, 100.0f / 255.0f, 1e-6f);    // clamped to the last level
    SampledTexture srgb(img, test::sampler_from_gltf(9728, 9987, 10497, 10497), true);
    // sRGB levels average in linear light and store sRGB bytes.
    EXPECT_EQ(srgb.level(1).at(0, 0)[0], std::uint8_t(std::lround(linear_to_srgb(0.5f * srgb_to_linear(200.0f / 255.0f)) * 255.0f)));
}

TEST(MaterialEvaluate, TextureTransformAndLodFromDerivatives) {
    Image8 img(4, 4, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            img.at(x, y)[0] = std::uint8_t(x * 60);
            img.at(x, y)[1] = std::uint8_t(y * 60);
            img.at(x, y)[3] = 255;
        }
    Textures tex;
    int t = tex.add(img, test::sampler_from_gltf(9728, 9984, 10497, 10497));
    Material m;
    m.metallic_factor = 0.0f;
    m.metallic_roughness = slot(t);
    TextureTransform tt;
    tt.offset = glm::vec2(0.25f, 0.5f);
    m.metallic_roughness.set_transform(tt);
    SurfacePoint p;
    p.uv0 = glm::vec2(0.125f, 0.125f);  // -> (0.375, 0.625): texel (1, 2)
    m.metallic_factor = 1.0f;
    m.roughness_factor = 1.0f;
    EvaluatedMaterial e = evaluate(m, tex, p);
    EXPECT_NEAR(e.surface.perceptual_roughness, 120.0f / 255.0f, 1e-6f);  // G of texel y = 2
    // A footprint of 2 texels per pixel: λ = 1, level 1 (2x2 box averages).
    p.duv0_dx = glm::vec2(0.5f, 0.0f);
    e = evaluate(m, tex, p);
    const SampledTexture* st = tex.get(t, false);
    EXPECT_NEAR(e.surface.perceptual_roughness, st->level(1).at(0, 1)[1] / 255.0f, 1e-6f);
}

TEST(ShadeLight, ClearcoatLayering) {
    Material m;
    m.metallic_factor = 0.0f;
    m.roughness_factor = 0.5f;
    EvaluatedMaterial e = evaluate(m, NoTextures{}, {});
    glm::vec3 v = glm::normalize(glm::vec3(0.3f, 0.0f, 1.0f)), l = glm::normalize(glm::vec3(-0.5f, 0.2f, 1.0f));
    glm::vec3 base = shade_light(e, v, l, glm::vec3(2.0f));
    expect_near(base, 2.0f * brdf::evaluate(e.surface, e.normal, v, l) * glm::dot(e.normal, l), 1e-5f);
    e.clearcoat = 1.0f;
    e.clearcoat_roughness = 0.1f;
    glm::vec3 coated = shade_light(e, v, l, glm::vec3(2.0f));
    float w = brdf::clearcoat_mix(1.0f, 0.04f, e.clearcoat_normal, v);
    glm::vec3 coat = 2.0f * glm::vec3(brdf::clearcoat_specular(e.clearcoat_normal, v, l, 0.01f));
    expect_near(coated, base * (1.0f - w) + coat * w, 1e-5f);
}

TEST(ShadeLight, IridescenceReplacesTheFresnelAndVanishesAtZeroThickness) {
    Material m;
    m.metallic_factor = 0.3f;
    m.roughness_factor = 0.4f;
    EvaluatedMaterial e = evaluate(m, NoTextures{}, {});
    glm::vec3 v = glm::normalize(glm::vec3(0.3f, 0.0f, 1.0f)), l = glm::normalize(glm::vec3(-0.5f, 0.2f, 1.0f));
    glm::vec3 plain = shade_light(e, v, l, glm::vec3(2.0f));
    e.iridescence = 1.0f;
    e.iridescence_ior = 1.3f;
    e.iridescence_thickness = 0.0f;
    EXPECT_EQ(shade_light(e, v, l, glm::vec3(2.0f)), plain);
    e.iridescence_thickness = 400.0f;
    brdf::IridescenceFresnel film = brdf::iridescence_at(1.0f, 1.3f, 400.0f, glm::dot(e.normal, v),
                                                         e.surface.dielectric_f0(), e.surface.base_color);
    glm::vec3 want = 2.0f * glm::dot(e.normal, l) *
                     [&] { brdf::Terms t = brdf::evaluate_terms(e.surface, e.normal, v, l, film); return t.diffuse + t.specular; }();
    glm::vec3 got = shade_light(e, v, l, glm::vec3(2.0f));
    expect_near(got, want, 1e-5f);
    EXPECT_GT(glm::length(got - plain), 1e-3f);  // the film changes the colour
}


TEST(ShadeLight, DiffuseTransmissionLightsTheBackAsTheKhronosViewer) {
    Material m;
    m.base_color_factor = glm::vec4(0.3f, 0.6f, 0.2f, 1.0f);
    m.metallic_factor = 0.2f;
    m.roughness_factor = 0.5f;
    EvaluatedMaterial e = evaluate(m, NoTextures{}, {});
    glm::vec3 v = glm::normalize(glm::vec3(0.3f, 0.0f, 1.0f)), l = glm::normalize(glm::vec3(-0.5f, 0.2f, 1.0f));
    const glm::vec3 plain = shade_light(e, v, l, glm::vec3(2.0f));
    EXPECT_EQ(shade_light(e, v, -l, glm::vec3(2.0f)), glm::vec3(0.0f));  // without it, nothing from behind
    e.diffuse_transmission = 0.0f;
    e.diffuse_transmission_color = glm::vec3(0.4f, 0.9f, 0.2f);
    EXPECT_EQ(shade_light(e, v, l, glm::vec3(2.0f)), plain);  // factor 0: unchanged
    e.diffuse_transmission = 0.8f;
    // In front: the reflected diffuse keeps 1 - factor, the specular stays.
    brdf::Terms t = brdf::evaluate_terms(e.surface, e.normal, v, l);
    float n_dot_l = glm::dot(e.normal, l);
    expect_near(shade_light(e, v, l, glm::vec3(2.0f)), 2.0f * n_dot_l * (0.2f * t.diffuse + t.specular), 1e-5f);
    // Behind: factor (1 - metallic) (1 - F) colour / pi n.(-l), F at h = normalize(l + v) as the viewer.
    glm::vec3 lb = glm::normalize(glm::vec3(0.2f, -0.3f, -1.0f));
    brdf::Terms tb = brdf::evaluate_terms(e.surface, e.normal, v, lb);
    glm::vec3 want = 2.0f * 0.8f * 0.8f * (1.0f - tb.f_dielectric) * e.diffuse_transmission_color / brdf::kPi *
                     -glm::dot(e.normal, lb);
    expect_near(shade_light(e, v, lb, glm::vec3(2.0f)), want, 1e-5f);
}

TEST(ShadeLight, DiffuseTransmissionConservesTheDiffuseEnergy) {
    // Reflected plus transmitted diffuse, over the whole sphere of light directions, is at most
    // the albedo: with a white transmission colour exactly the reflected diffuse alone.
    Material m;
    m.base_color_factor = glm::vec4(0.9f, 0.5f, 0.7f, 1.0f);
    m.metallic_factor = 0.0f;
    m.roughness_factor = 1.0f;
    m.specular = SpecularExt{};
    m.specular->specular_factor = 0.0f;  // no specular lobe, so the diffuse has weight 1
    EvaluatedMaterial e = evaluate(m, NoTextures{}, {});
    const glm::vec3 v = glm::normalize(glm::vec3(0.4f, 0.1f, 1.0f));
    auto integral = [&](float dt, glm::vec3 colour) {
        e.diffuse_transmission = dt;
        e.diffuse_transmission_color = colour;
        glm::dvec3 sum(0.0);
        const int n = 256;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < 2 * n; ++j) {  // midpoints in (cos theta, phi) over the sphere: d omega = dz dphi
                float z = -1.0f + 2.0f * (float(i) + 0.5f) / float(n);
                float phi = 2.0f * brdf::kPi * (float(j) + 0.5f) / float(2 * n);
                float r = std::sqrt(std::max(1.0f - z * z, 0.0f));
                glm::vec3 l(r * std::cos(phi), r * std::sin(phi), z);
                sum += glm::dvec3(shade_light(e, v, l, glm::vec3(1.0f)));
            }
        return glm::vec3(sum * (4.0 * double(brdf::kPi) / (double(n) * 2.0 * double(n))));
    };
    const glm::vec3 albedo(0.9f, 0.5f, 0.7f);
    expect_near(integral(0.0f, glm::vec3(1.0f)), albedo, 2e-3f);
    const glm::vec3 half = integral(0.5f, albedo);  // the same colour through: still the albedo
    expect_near(half, albedo, 2e-3f);
    const glm::vec3 leaf = integral(0.8f, glm::vec3(0.4f, 0.9f, 0.2f));
    const glm::vec3 want = 0.2f * albedo + 0.8f * glm::vec3(0.4f, 0.9f, 0.2f);
    expect_near(leaf, want, 2e-3f);
    EXPECT_LE(leaf.x, 1.0f);
    EXPECT_LE(leaf.y, 1.0f);
}

}  // namespace
