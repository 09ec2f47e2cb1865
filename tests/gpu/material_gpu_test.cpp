// GPU (llvmpipe) checks of read_material and shade_light (shaders/material_inputs.glsl)
// against their C++ twins fresnel::evaluate and fresnel::shade_light (libs/material).
//
// Seeded random materials cover every input: factors (F0 clamping included), every map
// slot with small random textures on both UV sets, KHR_texture_transform, all wrap modes
// and filters, sRGB and linear slots, specular-glossiness and metallic-roughness,
// KHR_materials_ior / _specular / _clearcoat / _sheen / _anisotropy / _iridescence / _diffuse_transmission
// / _diffuse_roughness
// (with lights behind the surface) / _emissive_strength, alpha modes, vertex
// colour, missing second UV sets and tangents. Uniforms are packed by the renderer's own
// material_uniforms / set_material_uniforms (the material block); the probe binds map i to
// unit i, where the renderer packs units per draw (its images test that).
// shaders/material_probe.frag evaluates one surface point per pixel.
//
// Three regimes:
//  - exact sampling: every map is read at a texel centre of level 0 (uv at texel centres,
//    transforms that map centres to centres: offsets k/N, quarter-turn rotations, odd
//    integer scales; explicit LOD 0 with NEAREST magnification, see Gen::make). The GPU
//    must agree to 1e-4 relative (a 1e-6 floor; unit vectors per component to 1e-4
//    absolute); measured 3.5e-7. Texels are decoded with the driver's measured response
//    (MaterialProbe::decode: llvmpipe's sRGB decode is a polynomial, 1.2e-3 off the
//    curve). shade_light is held to kShadeRelTol, as gpu_brdf_test holds the BRDF.
//  - filtered sampling: uv anywhere, explicit LOD in [-1, 4] with fractions, mip-mapped
//    samplers. llvmpipe quantises filter weights (bilinear and between levels) to 1/256
//    steps, so texture-derived values agree to a few 8-bit steps: kFilteredAbsTol (0.025)
//    per texel value, scaled by what multiplies it (strengths, F0 tints, normal scales);
//    measured 0.0038. Normals are skipped where the filtered vector, scaled and in the
//    (random, not orthogonal) world frame, is shorter than 0.5, and the anisotropy
//    direction's tolerance is divided by its length (normalising a short vector amplifies
//    any difference).
//  - footprint sampling: the filters the renderer draws with. Each point covers a 2x2 quad
//    (MATERIAL_PROBE_QUADS) whose UVs step by the point's random derivatives (1/16 to 8
//    texels a pixel, footprints up to 20:1, skewed; square and oblong textures), so dFdx /
//    dFdy give them to sample_detail_map's anisotropic footprint with at most 1 to 16 probes,
//    against evaluate's detail_footprint with the same derivatives and limit. Only the detail
//    maps are read there (the others' texture() takes the driver's level of detail); the
//    filtered tolerance applies (measured 0.0061). Points where float rounding of the
//    derivatives could change the probe count or the major axis are skipped (11 of 3072).
// Not covered here: the transmission maps (gpu_transmission_test), and the renderer's own
// variants that pack textures (shared footprints, channels in alpha): render_target_test and
// the Khronos image tests hold those to the unpacked images.
// Points whose alpha lies within 1e-4 (filtered: kFilteredAbsTol) of the MASK cutoff are
// skipped: a rounding there may legitimately flip the discard.
#include <gtest/gtest.h>

#include "fresnel/core/mipmap.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include <glm/geometric.hpp>

#include "fresnel/core/color.h"
#include "fresnel/gpu/context.h"
#include "fresnel/gpu/device.h"
#include "fresnel/gpu/resources.h"
#include "fresnel/material/evaluate.h"
#include "details/material_uniforms.h"
#include "details/shader_library.h"
#include "probe_harness.h"
#include "gltf_sampler.h"

namespace {
using namespace fresnel;

constexpr int kSide = 8;                 // points per case: kSide x kSide pixels
constexpr int kTexels = 11;              // input texels per point (material_probe.frag)
constexpr int kOutputs = 12;             // u_output values (6 = shade_light)
constexpr float kRelTol = 1e-4f;         // exact sampling: relative ...
constexpr float kAbsFloor = 1e-6f;       // ... or absolute near zero
// shade_light: relative beyond the band that float rounding of its directions explains
// (shade_band: the GGX peak of a glossy lobe turns rounding of n.h, 1e-7, into up to 1e-3
// of D, in C++ as on the GPU) ...
constexpr float kShadeRelTol = 1e-4f;
constexpr float kShadeAbsFloor = 1e-5f;  // ... or absolute (radiance of order 1..1e3)
constexpr float kFilteredAbsTol = 2.5e-2f;  // filtered sampling: absolute, per texel value (measured 0.0038)

struct TextureDesc {
    Image8 image;
    int mag, min, wrap_s, wrap_t;  // GL enums
};

// How the driver turns texel bytes into values: [linear filter][sRGB] (see MaterialProbe::decode).
using DriverDecode = std::array<std::array<TexelDecode, 2>, 2>;

class CpuTextures final : public TextureSource {
public:
    CpuTextures(const std::vector<TextureDesc>& t, const DriverDecode* decode) : t_(t), decode_(decode) {}
    const SampledTexture* get(int texture, bool srgb) const override {
        if (texture < 0 || texture >= int(t_.size())) return nullptr;
        auto key = std::make_pair(texture, srgb);
        auto it = cache_.find(key);
        if (it == cache_.end()) {
            const TextureDesc& d = t_[std::size_t(texture)];
            auto s = test::sampler_from_gltf(d.mag, d.min, d.wrap_s, d.wrap_t);
            const TexelDecode* dec = decode_ ? &(*decode_)[d.mag == 9729 ? 1 : 0][srgb ? 1 : 0] : nullptr;
            it = cache_.emplace(key, std::make_unique<SampledTexture>(d.image, s, srgb, dec)).first;
        }
        return it->second.get();
    }

private:
    const std::vector<TextureDesc>& t_;
    const DriverDecode* decode_;
    mutable std::map<std::pair<int, bool>, std::unique_ptr<SampledTexture>> cache_;
};

struct Point {
    SurfacePoint p;
    glm::vec3 v, l, comp_d, comp_m;
};

struct Case {
    Material material;
    std::vector<TextureDesc> textures;
    VertexInputs inputs;
    float lod = 0.0f;
    // The footprint regime: no explicit LOD; each point has its UV derivatives and the
    // detail maps are read through the renderer's anisotropic filter, at most max_anisotropy
    // probes (RenderSettings::anisotropy).
    bool footprint = false;
    float max_anisotropy = 1.0f;
    std::vector<Point> points;  // kSide * kSide
};

// The regimes of the file comment.
enum class Regime { Exact, Filtered, Footprint };

class Gen {
public:
    explicit Gen(unsigned seed)
        : rng_(seed), side_(seed ^ 0x5eedu), aniso_(seed ^ 0xa2150u), film_(seed ^ 0xf11du), dt_(seed ^ 0xd1f7u),
          deriv_(seed ^ 0xd0d0u), dr_(seed ^ 0xd12au) {}
    float u() { return u01_(*cur_); }
    float range(float a, float b) { return a + (b - a) * u(); }
    int pick(int n) { return int(u() * float(n)) % n; }
    bool chance(float p) { return u() < p; }
    glm::vec3 unit() {
        for (;;) {
            glm::vec3 d(range(-1, 1), range(-1, 1), range(-1, 1));
            float l = glm::length(d);
            if (l > 0.1f && l <= 1.0f) return d / l;
        }
    }
    // A unit vector in the hemisphere around n (some slightly below, to test clamping).
    glm::vec3 around(glm::vec3 n) {
        glm::vec3 d = unit();
        if (glm::dot(d, n) < -0.1f) d = -d;
        return d;
    }

    Case make(Regime regime) {
        const bool exact = regime == Regime::Exact;
        Case c;
        int n = 1 << (1 + pick(3));  // 2, 4, 8 texels per side (power of two: mip chains agree)
        const int filters[] = {9728, 9729}, mins[] = {9728, 9729, 9984, 9985, 9986, 9987};
        const int wraps[] = {10497, 33071, 33648};
        int count = 1 + pick(3);
        for (int t = 0; t < count; ++t) {
            TextureDesc d;
            d.image = Image8(n, n, 4);
            for (auto& b : d.image.pixels) b = std::uint8_t(pick(256));
            // Exact regime: NEAREST magnification. At a texel centre LINEAR is the same in
            // exact arithmetic, but llvmpipe quantises filter weights to 1/256, so a centre
            // that float rounding of the transform puts 1e-6 below the texel's start mixes
            // in 1/256 of the neighbour (measured: up to 1e-4 relative). The filtered
            // regime covers LINEAR.
            d.mag = exact ? 9728 : filters[pick(2)];
            d.min = exact ? mins[pick(6)] : mins[2 + pick(4)];
            d.wrap_s = wraps[pick(3)];
            d.wrap_t = wraps[pick(3)];
            c.textures.push_back(std::move(d));
        }
        auto slot = [&](float p = 0.6f) {
            TextureSlot s;
            if (!chance(p)) return s;
            s.texture = pick(count);
            s.tex_coord = pick(2);
            if (chance(0.5f)) {
                TextureTransform tt;
                if (exact) {
                    tt.offset = glm::vec2(float(pick(2 * n + 1) - n), float(pick(2 * n + 1) - n)) / float(n);
                    tt.rotation = float(pick(4)) * 1.57079632679f;
                    const float scales[] = {1, -1, 3, -3};
                    tt.scale = glm::vec2(scales[pick(4)], scales[pick(4)]);
                } else {
                    tt.offset = glm::vec2(range(-1, 1), range(-1, 1));
                    tt.rotation = range(-3.2f, 3.2f);
                    tt.scale = glm::vec2(range(-2, 2), range(-2, 2));
                }
                s.set_transform(tt);
            }
            return s;
        };
        Material& m = c.material;
        m.base_color_factor = glm::vec4(u(), u(), u(), u());
        m.base_color = slot();
        m.metallic_factor = chance(0.2f) ? float(pick(2)) : u();
        m.roughness_factor = chance(0.2f) ? float(pick(2)) : u();
        m.metallic_roughness = slot();
        m.normal = slot();
        m.normal_scale = range(-2, 2);
        m.occlusion = slot();
        m.occlusion_strength = u();
        m.emissive = slot();
        m.emissive_factor = glm::vec3(u(), u(), u());
        if (chance(0.4f)) m.emissive_strength = EmissiveStrengthExt{range(0, 20)};
        m.alpha_mode = AlphaMode(pick(3));
        m.alpha_cutoff = u();
        if (chance(0.5f)) m.ior = IorExt{chance(0.1f) ? 0.0f : range(1, 3)};
        if (chance(0.5f)) {
            SpecularExt s;
            s.specular_factor = range(0, 2);
            s.specular_texture = slot();
            s.specular_color_factor = glm::vec3(range(0, 30), range(0, 30), range(0, 3));
            s.specular_color_texture = slot();
            m.specular = s;
        }
        if (chance(0.5f)) {
            ClearcoatExt cc;
            cc.clearcoat_factor = chance(0.2f) ? 0.0f : u();
            cc.clearcoat_texture = slot();
            cc.clearcoat_roughness_factor = u();
            cc.clearcoat_roughness_texture = slot();
            cc.clearcoat_normal_texture = slot();
            cc.clearcoat_normal_scale = range(-2, 2);
            m.clearcoat = cc;
        }
        // Extensions added later draw from their own stream, so that the cases of the
        // others stay what they were (their figures in the comments above hold).
        cur_ = &side_;
        if (chance(0.5f)) {
            SheenExt sh;
            sh.sheen_color_factor = chance(0.15f) ? glm::vec3(0.0f) : glm::vec3(u(), u(), u());
            sh.sheen_color_texture = slot();
            sh.sheen_roughness_factor = chance(0.1f) ? float(pick(2)) : u();
            sh.sheen_roughness_texture = slot();
            m.sheen = sh;
        }
        cur_ = &aniso_;
        if (chance(0.5f)) {
            AnisotropyExt an;
            an.anisotropy_strength = chance(0.15f) ? 0.0f : (chance(0.15f) ? 1.0f : u());
            an.anisotropy_rotation = range(-7, 7);
            an.anisotropy_texture = slot();
            m.anisotropy = an;
        }
        cur_ = &film_;
        if (chance(0.5f)) {
            IridescenceExt ir;
            ir.iridescence_factor = chance(0.15f) ? 0.0f : (chance(0.2f) ? 1.0f : u());
            ir.iridescence_texture = slot();
            ir.iridescence_ior = chance(0.2f) ? 1.0f : range(1.0f, 2.5f);
            ir.iridescence_thickness_minimum = chance(0.2f) ? 0.0f : range(0.0f, 400.0f);
            ir.iridescence_thickness_maximum = chance(0.1f) ? 0.0f : range(0.0f, 1200.0f);
            ir.iridescence_thickness_texture = slot();
            m.iridescence = ir;
        }
        cur_ = &dt_;
        if (chance(0.5f)) {
            DiffuseTransmissionExt dt;
            dt.diffuse_transmission_factor = chance(0.15f) ? 0.0f : (chance(0.2f) ? 1.0f : u());
            dt.diffuse_transmission_texture = slot();
            dt.diffuse_transmission_color_factor = glm::vec3(u(), u(), u());
            dt.diffuse_transmission_color_texture = slot();
            m.diffuse_transmission = dt;
        }
        cur_ = &dr_;
        if (chance(0.5f)) {
            DiffuseRoughnessExt dr;
            dr.diffuse_roughness_factor = chance(0.15f) ? 0.0f : (chance(0.2f) ? 1.0f : range(0.0f, 1.5f));
            dr.diffuse_roughness_texture = slot();
            m.diffuse_roughness = dr;
        }
        cur_ = &rng_;
        if (chance(0.3f)) {
            SpecularGlossinessExt sg;
            sg.diffuse_factor = glm::vec4(u(), u(), u(), u());
            sg.diffuse_texture = slot();
            sg.specular_factor = glm::vec3(u(), u(), u());
            sg.glossiness_factor = u();
            sg.specular_glossiness_texture = slot();
            m.specular_glossiness = sg;
        }
        c.inputs.has_uv1 = chance(0.8f);
        c.inputs.has_tangent = chance(0.85f);
        c.lod = exact ? 0.0f : (chance(0.2f) ? float(pick(5)) - 1.0f : range(-1, 4));
        for (int i = 0; i < kSide * kSide; ++i) {
            Point pt;
            SurfacePoint& p = pt.p;
            auto uv = [&]() {
                if (!exact) return glm::vec2(range(-1.5f, 2.5f), range(-1.5f, 2.5f));
                return glm::vec2(float(pick(3 * n) - n) + 0.5f, float(pick(3 * n) - n) + 0.5f) / float(n);
            };
            p.uv0 = uv();
            p.uv1 = c.inputs.has_uv1 ? uv() : p.uv0;  // pbr.vert: uv1 = uv0 without TEXCOORD_1
            p.color = chance(0.3f) ? glm::vec4(1.0f) : glm::vec4(u(), u(), u(), u());
            p.tangent = unit();
            p.bitangent = unit();
            p.normal = unit();
            p.inputs = c.inputs;
            p.lod = c.lod;
            pt.v = around(p.normal);
            pt.l = around(p.normal);
            pt.comp_d = glm::vec3(range(1, 1.5f), range(1, 1.5f), range(1, 1.5f));
            pt.comp_m = glm::vec3(range(1, 1.5f), range(1, 1.5f), range(1, 1.5f));
            c.points.push_back(pt);
        }
        // KHR_materials_diffuse_transmission: half the lights behind the surface (its own stream).
        cur_ = &dt_;
        if (m.diffuse_transmission)
            for (Point& pt : c.points)
                if (chance(0.5f)) pt.l = -pt.l;
        // The footprint regime (its own stream): derivatives from 1/16 to 8 texels a pixel of
        // the largest texture, footprints from round to 20:1, skewed, either axis the major.
        cur_ = &deriv_;
        if (regime == Regime::Footprint) {
            c.footprint = true;
            // Only the detail maps: the others are read with texture(), whose level of detail
            // is the driver's (llvmpipe takes a fast approximation of log2, up to ~0.09 off),
            // not the GL formula evaluate follows; the other regimes read them at explicit levels.
            for (int i = 0; i < kMaterialMapCount; ++i)
                if (!material_map_info(MaterialMap(i)).detail)
                    if (const TextureSlot* slot = material_map(m, MaterialMap(i))) *const_cast<TextureSlot*>(slot) = TextureSlot{};
            const float limits[] = {1.0f, 2.0f, 6.0f, 16.0f};
            c.max_anisotropy = chance(0.6f) ? limits[pick(4)] : range(1.0f, 16.0f);
            auto derivatives = [&](glm::vec2& dx, glm::vec2& dy) {
                float len = std::exp2(range(-4.0f, 3.0f)) / float(n);
                float ratio = chance(0.2f) ? 1.0f : std::exp2(range(0.0f, 4.3f));
                // A round footprint is square (perpendicular axes of one length): which axis is
                // the major one is then float rounding's choice, which only a single probe ignores.
                float angle = range(-3.2f, 3.2f), skew = ratio == 1.0f ? 0.0f : range(-0.6f, 0.6f);
                dx = len * glm::vec2(std::cos(angle), std::sin(angle));
                dy = len / ratio * glm::vec2(std::cos(angle + 1.5708f + skew), std::sin(angle + 1.5708f + skew));
                if (chance(0.5f)) std::swap(dx, dy);
            };
            // Most textures trilinear with linear magnification, the samplers the filter applies
            // to; half of them oblong (the footprint is measured in texels of each axis).
            for (TextureDesc& d : c.textures) {
                if (chance(0.6f)) d.mag = 9729, d.min = 9987;
                if (chance(0.5f)) {
                    d.image = Image8(1 << (1 + pick(3)), 1 << (1 + pick(3)), 4);
                    for (auto& b : d.image.pixels) b = std::uint8_t(pick(256));
                }
            }
            for (Point& pt : c.points) {
                pt.p.lod.reset();
                pt.p.max_anisotropy = c.max_anisotropy;
                derivatives(pt.p.duv0_dx, pt.p.duv0_dy);
                if (c.inputs.has_uv1) derivatives(pt.p.duv1_dx, pt.p.duv1_dy);
                else pt.p.duv1_dx = pt.p.duv0_dx, pt.p.duv1_dy = pt.p.duv0_dy;  // uv1 = uv0
                // What the quad's neighbours hold minus the point (float rounding as on the GPU).
                auto rounded = [](glm::vec2 uv, glm::vec2& d) { d = (uv + d) - uv; };
                rounded(pt.p.uv0, pt.p.duv0_dx), rounded(pt.p.uv0, pt.p.duv0_dy);
                rounded(pt.p.uv1, pt.p.duv1_dx), rounded(pt.p.uv1, pt.p.duv1_dy);
            }
        }
        cur_ = &rng_;
        return c;
    }

private:
    std::mt19937 rng_, side_, aniso_, film_, dt_, deriv_, dr_;  // aniso_, film_, dt_, dr_: KHR_materials_anisotropy's, _iridescence's,
    // _diffuse_transmission's, _diffuse_roughness's own streams; deriv_: the footprint regime's
    std::mt19937* cur_ = &rng_;
    std::uniform_real_distribution<float> u01_{0.0f, 1.0f};
};

constexpr glm::vec3 kProbeRadiance(1.0f, 0.8f, 0.6f);  // material_probe.frag's light

// How far shade_light moves when its directions move by float rounding (test::rounding_band):
// the shading and coat normals as direction 0, v and the anisotropy bitangent as 1, l and the
// anisotropy tangent as 2.
glm::vec3 shade_band(const EvaluatedMaterial& e, const Point& pt) {
    return test::rounding_band([&](auto&& move) {
        EvaluatedMaterial moved = e;
        moved.normal = move(e.normal, 0);
        moved.clearcoat_normal = move(e.clearcoat_normal, 0);
        moved.anisotropic_t = move(e.anisotropic_t, 2);
        moved.anisotropic_b = move(e.anisotropic_b, 1);
        return shade_light(moved, move(pt.v, 1), move(pt.l, 2), kProbeRadiance, pt.comp_d, pt.comp_m);
    });
}

// The C++ side of the probe's outputs, in u_output order; `band` (if given) receives shade_band.
std::array<glm::vec4, kOutputs> cpu_outputs(const Case& c, const TextureSource& tex, const Point& pt,
                                            glm::vec3* band = nullptr) {
    EvaluatedMaterial e = evaluate(c.material, tex, pt.p);
    if (band) *band = shade_band(e, pt);
    const brdf::Surface& s = e.surface;
    std::array<glm::vec4, kOutputs> o;
    o[0] = glm::vec4(s.base_color, e.alpha);
    o[1] = glm::vec4(s.metallic, s.perceptual_roughness, e.occlusion, e.discard ? 1.0f : 0.0f);
    o[2] = glm::vec4(e.emissive, s.specular_weight);
    o[3] = glm::vec4(s.dielectric_f0(), e.clearcoat);
    o[4] = glm::vec4(e.normal, e.clearcoat_roughness);
    o[5] = glm::vec4(e.clearcoat_normal, e.clearcoat_f0);
    o[6] = glm::vec4(shade_light(e, pt.v, pt.l, kProbeRadiance, pt.comp_d, pt.comp_m), 1.0f);
    o[7] = glm::vec4(e.sheen_color, e.sheen_roughness);
    o[8] = glm::vec4(e.anisotropic_t, e.anisotropy_strength);
    o[9] = glm::vec4(e.anisotropic_b, e.anisotropy_direction.x);
    o[10] = glm::vec4(e.iridescence, e.iridescence_thickness, e.iridescence_ior, e.diffuse_roughness);
    o[11] = glm::vec4(e.diffuse_transmission_color, e.diffuse_transmission);
    return o;
}

// The length of the scaled tangent-space vector a normal map gives at the point (1
// without a map). Filtering random texels can make it nearly 0, where normalising it
// amplifies any difference without bound; the filtered regime skips such normals.
float tangent_length(const Case& c, const TextureSource& tex, const Point& pt, MaterialMap map, float scale) {
    std::optional<glm::vec4> texel = sample_material_map(c.material, tex, pt.p, map);
    if (!texel) return 1.0f;
    glm::vec3 tn = (glm::vec3(*texel) * 2.0f - 1.0f) * glm::vec3(scale, scale, 1.0f);
    // In world space, before normalising: the random frames are not orthogonal, and a tangent
    // nearly opposite the bitangent shortens the vector as much as a short texel does.
    return glm::length(glm::mat3(pt.p.tangent, pt.p.bitangent, pt.p.normal) * tn);
}

// Whether float rounding of the derivatives (the GPU takes them as differences of transformed
// coordinates) may change a detail map's probes at the point: its anisotropy within 2e-3 of
// a half (relative: 5e-4; the probe count rounds there) or its two axes within 1e-3 of the same length
// (the major axis flips there). The footprint regime skips such points.
// `anisotropic` counts the detail maps read at the point with more than one probe, `detail`
// all detail maps read there (what shows the regime covers the anisotropic filter).
bool near_probe_change(const Case& c, const TextureSource& tex, const Point& pt, int* detail = nullptr,
                       int* anisotropic = nullptr) {
    if (!c.footprint) return false;
    for (int i = 0; i < kMaterialMapCount; ++i) {
        const MaterialMap map = MaterialMap(i);
        const TextureSlot* slot = material_map(c.material, map);
        if (!material_map_info(map).detail || !slot || !map_usable(*slot, map, c.inputs)) continue;
        const SampledTexture* t = tex.get(slot->texture, material_map_info(map).srgb);
        if (!t) continue;
        const float most = detail_anisotropy(t->sampler().mag_filter, t->sampler().mip_filter, c.max_anisotropy);
        if (detail && most <= 1.0f) ++*detail;
        if (most <= 1.0f) continue;
        const glm::mat2 linear(slot->transform);
        const glm::vec2 size(float(t->width()), float(t->height()));
        const glm::vec2 dx = linear * (slot->tex_coord == 1 ? pt.p.duv1_dx : pt.p.duv0_dx);
        const glm::vec2 dy = linear * (slot->tex_coord == 1 ? pt.p.duv1_dy : pt.p.duv0_dy);
        const DetailFootprint f = detail_footprint(slot->tex_coord == 1 ? pt.p.uv1 : pt.p.uv0, dx, dy, size, most);
        if (detail) {
            ++*detail;
            *anisotropic += f.n > 1;
        }
        const float half = f.anisotropy + 0.5f - std::round(f.anisotropy + 0.5f);
        if (std::abs(half) < 5e-4f * f.anisotropy) return true;
        const float lx = glm::dot(dx * size, dx * size), ly = glm::dot(dy * size, dy * size);
        if (f.anisotropy >= 1.4f && std::abs(lx - ly) <= 1e-3f * std::max(lx, ly)) return true;  // one probe: no axis
    }
    return false;
}

const char* kOutputNames[kOutputs][4] = {
    {"base.r", "base.g", "base.b", "alpha"},
    {"metallic", "roughness", "occlusion", "discard"},
    {"emissive.r", "emissive.g", "emissive.b", "specular_weight"},
    {"f0.r", "f0.g", "f0.b", "clearcoat"},
    {"normal.x", "normal.y", "normal.z", "clearcoat_roughness"},
    {"cc_normal.x", "cc_normal.y", "cc_normal.z", "clearcoat_f0"},
    {"shade.r", "shade.g", "shade.b", "one"},
    {"sheen.r", "sheen.g", "sheen.b", "sheen_roughness"},
    {"aniso_t.x", "aniso_t.y", "aniso_t.z", "anisotropy_strength"},
    {"aniso_b.x", "aniso_b.y", "aniso_b.z", "aniso_direction.x"},
    {"iridescence", "iridescence_thickness", "iridescence_ior", "diffuse_roughness"},
    {"dt_color.r", "dt_color.g", "dt_color.b", "diffuse_transmission"},
};

// The length of the direction the anisotropy map gives at the point (1 without a map):
// normalising a filtered direction near 0 amplifies any difference, as for normals.
float anisotropy_direction_length(const Case& c, const TextureSource& tex, const Point& pt) {
    std::optional<glm::vec4> texel = sample_material_map(c.material, tex, pt.p, MaterialMap::Anisotropy);
    if (!texel) return 1.0f;
    return glm::length(glm::vec2(texel->x, texel->y) * 2.0f - 1.0f);
}

class MaterialProbe : public test::ProbeSuite {
protected:
    static void TearDownTestSuite() {
        sheen_lut_.reset();  // a texture of the context
        ProbeSuite::TearDownTestSuite();
    }

    // Runs the probe over one case: per output, one RGBA per point.
    std::array<std::vector<glm::vec4>, kOutputs> probe(const Case& c, bool count_coverage = true) {
        const gpu::Texture& lut = sheen_lut();  // made first: creating a texture binds it to the active unit
        const std::vector<float> texels =
            test::pack_case_texels(std::size_t(kSide * kSide), kTexels, kSide, [&](std::size_t i, int k) {
                const Point& pt = c.points[i];
                const glm::vec4 in[kTexels] = {glm::vec4(pt.p.uv0, pt.p.uv1), pt.p.color,
                                               glm::vec4(pt.p.tangent, 0), glm::vec4(pt.p.bitangent, 0),
                                               glm::vec4(pt.p.normal, 0), glm::vec4(pt.v, 0), glm::vec4(pt.l, 0),
                                               glm::vec4(pt.comp_d, 0), glm::vec4(pt.comp_m, 0),
                                               glm::vec4(pt.p.duv0_dx, pt.p.duv0_dy), glm::vec4(pt.p.duv1_dx, pt.p.duv1_dy)};
                return in[k];
            });
        gpu::Device device;
        gpu::Texture points = gpu::Texture::create_2d(kSide * kTexels, kSide, gpu::TextureFormat::RGBA32F,
                                                      texels.data(), false);
        points.set_sampler(gpu::SamplerState::clamped(Filter::Nearest));
        // The footprint regime: a 2x2 quad a point (MATERIAL_PROBE_QUADS), read at its first pixel.
        const int quad = c.footprint ? 2 : 1;
        test::ProbeTarget target(kSide * quad, kSide * quad);

        // Textures and defines as the renderer makes them (draw_primitive / texture_for).
        MaterialUniforms mu = material_uniforms(c.material);
        std::vector<std::string> defines;
        for (const FeatureInfo& f : feature_table()) {
            // Anisotropy needs tangents (canonical_features drops it without; evaluate skips it).
            if (f.bit == feature::Anisotropy && !c.inputs.has_tangent) continue;
            if (material_features(c.material) & f.bit) defines.emplace_back(f.define);
        }
        defines.push_back(c.footprint ? "MATERIAL_PROBE_QUADS" : "MATERIAL_EXPLICIT_LOD");
        std::vector<gpu::Texture> maps;
        std::array<bool, kMaterialMapCount> bound{};
        std::vector<std::pair<int, int>> units;  // (unit, index into maps)
        for (int i = 0; i < kMaterialMapCount; ++i) {
            const TextureSlot* slot = mu.maps[std::size_t(i)];
            if (!slot || !map_usable(*slot, MaterialMap(i), c.inputs)) continue;
            const MaterialMapInfo& info = material_map_info(MaterialMap(i));
            const TextureDesc& d = c.textures[std::size_t(slot->texture)];
            const TextureSampler ts = test::sampler_from_gltf(d.mag, d.min, d.wrap_s, d.wrap_t);
            // Every level from the CPU chain, as the renderer uploads them (Renderer::Impl::make_texture).
            std::vector<Image8> chain;
            if (ts.mip_filter != MipFilter::None) chain = build_mip_chain(d.image, info.srgb);
            std::vector<gpu::MipLevel> levels{{d.image.width, d.image.height, d.image.pixels.data()}};
            for (const auto& l : chain) levels.push_back({l.width, l.height, l.pixels.data()});
            maps.push_back(gpu::Texture::create_2d_levels(
                info.srgb ? gpu::TextureFormat::SRGB8_ALPHA8 : gpu::TextureFormat::RGBA8, levels));
            // The detail maps' probes, as texture_for in the renderer sets them: more than one
            // minify linearly whatever the sampler's filter.
            const float most = info.detail ? detail_anisotropy(ts.mag_filter, ts.mip_filter, c.max_anisotropy) : 1.0f;
            mu.block.maps[std::size_t(i)].anisotropy = most;
            gpu::SamplerState ss;
            ss.min_filter = most > 1.0f ? Filter::Linear : ts.min_filter;
            ss.mipmap = ts.mip_filter;
            ss.mag_filter = ts.mag_filter;
            ss.wrap_s = ts.wrap_s;
            ss.wrap_t = ts.wrap_t;
            maps.back().set_sampler(ss);
            units.emplace_back(i, int(maps.size()) - 1);
            bound[std::size_t(i)] = true;
            if (count_coverage) ++maps_bound_[std::size_t(i)];
            defines.push_back(info.define);
        }
        const gpu::Program& prog = library().get("fullscreen.vert", "material_probe.frag", defines);
        target.bind(device);
        prog.use();
        // Above the maps' units (map i on unit i): llvmpipe has 32 units.
        const int points_unit = kMaterialMapCount + 1, lut_unit = kMaterialMapCount;
        device.bind_texture(points_unit, points);
        prog.set("u_points", points_unit);
        device.bind_texture(lut_unit, lut);
        prog.set("u_brdf_lut", lut_unit);
        for (auto [unit, index] : units) device.bind_texture(unit, maps[std::size_t(index)]);
        gpu::UniformBuffer block;
        set_material_uniforms(prog, mu, bound, block);
        prog.set("u_material_lod", c.lod);
        std::array<std::vector<glm::vec4>, kOutputs> out;
        for (int o = 0; o < kOutputs; ++o) {
            prog.set("u_output", o);
            std::vector<glm::vec4> px = target.draw(device, std::size_t(kSide * kSide * quad * quad));
            if (quad > 1) {
                std::vector<glm::vec4> first(std::size_t(kSide * kSide));
                for (int y = 0; y < kSide; ++y)
                    for (int x = 0; x < kSide; ++x)
                        first[std::size_t(y * kSide + x)] = px[std::size_t(2 * y * 2 * kSide + 2 * x)];
                px = std::move(first);
            }
            out[std::size_t(o)] = std::move(px);
        }
        EXPECT_EQ(device.take_errors(), "");
        return out;
    }

    // A table whose A channel is the sheen albedo shade_light reads on the CPU
    // (SheenAlbedoTable::standard()), sampled as the renderer samples its split-sum table.
    static const gpu::Texture& sheen_lut() {
        if (!sheen_lut_) {
            const brdf::SheenAlbedoTable& t = brdf::SheenAlbedoTable::standard();
            std::vector<float> px(std::size_t(t.size() * t.size() * 4), 0.0f);
            for (int y = 0; y < t.size(); ++y)
                for (int x = 0; x < t.size(); ++x) px[(std::size_t(y) * std::size_t(t.size()) + std::size_t(x)) * 4 + 3] = t.at(x, y);
            sheen_lut_ = std::make_unique<gpu::Texture>(
                gpu::Texture::create_2d(t.size(), t.size(), gpu::TextureFormat::RGBA32F, px.data(), false));
            sheen_lut_->set_sampler(gpu::SamplerState::clamped(Filter::Linear));
        }
        return *sheen_lut_;
    }

    // The driver's response to each texel byte, read through the probe at texel centres
    // (explicit LOD 0: the magnification filter), per magnification filter and colour
    // space: sRGB colour from the base colour map, its alpha with BLEND, linear data from
    // the occlusion map at strength 1. llvmpipe decodes sRGB with a polynomial
    // (lp_build_srgb_to_linear), up to 1.2e-3 off the exact curve; byte / 255 it gets
    // right. The comparisons read textures through this response, so that they test the
    // rules; DriverTexelResponseIsCloseToExact checks the response itself.
    const DriverDecode& decode() {
        if (decode_) return *decode_;
        decode_ = std::make_unique<DriverDecode>();
        for (int linear = 0; linear < 2; ++linear) {
            Case c;
            TextureDesc d;
            d.image = Image8(16, 16, 4);
            for (int i = 0; i < 256; ++i) {
                std::uint8_t* px = d.image.at(i % 16, i / 16);
                px[0] = px[1] = px[2] = px[3] = std::uint8_t(i);
            }
            d.mag = linear ? 9729 : 9728;
            d.min = 9728;
            d.wrap_s = d.wrap_t = 33071;
            c.textures.push_back(d);
            c.material.base_color.texture = 0;
            c.material.occlusion.texture = 0;
            c.material.alpha_mode = AlphaMode::Blend;
            for (int batch = 0; batch < 4; ++batch) {
                c.points.clear();
                for (int k = 0; k < kSide * kSide; ++k) {
                    int i = batch * kSide * kSide + k;
                    Point pt{};
                    pt.p.uv0 = glm::vec2((float(i % 16) + 0.5f) / 16.0f, (float(i / 16) + 0.5f) / 16.0f);
                    pt.p.uv1 = pt.p.uv0;
                    c.points.push_back(pt);
                }
                auto out = probe(c, false);
                for (int k = 0; k < kSide * kSide; ++k) {
                    std::size_t i = std::size_t(batch * kSide * kSide + k);
                    TexelDecode& srgb = (*decode_)[std::size_t(linear)][1];
                    TexelDecode& unorm = (*decode_)[std::size_t(linear)][0];
                    srgb.rgb[i] = out[0][std::size_t(k)].x;
                    srgb.alpha[i] = out[0][std::size_t(k)].w;
                    unorm.rgb[i] = unorm.alpha[i] = out[1][std::size_t(k)].z;  // occlusion
                }
            }
        }
        return *decode_;
    }

    // Compares `cases` cases; returns the largest error seen per output (relative for
    // exact sampling, absolute for filtered).
    void run(Regime regime, int cases, unsigned seed) {
        const bool exact = regime == Regime::Exact;
        const char* regime_name = exact ? "exact" : regime == Regime::Filtered ? "filtered" : "footprint";
        int near_probe_changes = 0, detail_maps = 0, anisotropic_maps = 0;
        Gen gen(seed);
        int failures = 0, compared = 0, skipped = 0;
        float worst_rel = 0.0f, worst_shade = 0.0f, worst_abs = 0.0f;
        float worst_shade_raw = 0.0f;  // shade_light without the rounding band
        int shade_in_band = 0;         // shade_light values beyond 1e-4 that the band explains
        int shown[kOutputs][4] = {};
        const char* worst_what = "-";
        for (int ci = 0; ci < cases; ++ci) {
            Case c = gen.make(regime);
            CpuTextures tex(c.textures, &decode());
            auto gpu_out = probe(c);
            for (int i = 0; i < kSide * kSide; ++i) {
                const Point& pt = c.points[std::size_t(i)];
                if (near_probe_change(c, tex, pt, &detail_maps, &anisotropic_maps)) {
                    ++near_probe_changes;
                    continue;
                }
                glm::vec3 band(0.0f);
                auto cpu = cpu_outputs(c, tex, pt, exact ? &band : nullptr);
                if (c.material.alpha_mode == AlphaMode::Mask) {
                    // The alpha before the mode is not an output; recompute it with the mode off.
                    Material blend = c.material;
                    blend.alpha_mode = AlphaMode::Blend;
                    float a = evaluate(blend, tex, pt.p).alpha;
                    if (std::abs(a - c.material.alpha_cutoff) < (exact ? 1e-4f : kFilteredAbsTol)) {
                        ++skipped;
                        continue;
                    }
                }
                bool short_normal = !exact && tangent_length(c, tex, pt, MaterialMap::Normal, c.material.normal_scale) < 0.5f;
                bool short_coat_normal =
                    !exact && c.material.clearcoat &&
                    tangent_length(c, tex, pt, MaterialMap::ClearcoatNormal, c.material.clearcoat->clearcoat_normal_scale) < 0.5f;
                const float direction_length = exact ? 1.0f : anisotropy_direction_length(c, tex, pt);
                bool short_direction = direction_length < 0.5f;
                for (int o = 0; o < kOutputs; ++o) {
                    for (int ch = 0; ch < 4; ++ch) {
                        if ((o == 4 && ch < 3 && short_normal) || (o == 5 && ch < 3 && short_coat_normal)) continue;
                        // The anisotropy frame and direction (not the strength) from a short direction.
                        if (((o == 8 && ch < 3) || o == 9) && short_direction) continue;
                        float want = cpu[std::size_t(o)][ch], got = gpu_out[std::size_t(o)][std::size_t(i)][ch];
                        float err = std::abs(want - got);
                        float scale = std::max(std::abs(want), std::abs(got));
                        if ((o == 4 || o == 5 || o == 8 || o == 9) && ch < 3) scale = 1.0f;  // components of (near-)unit vectors
                        if (o == 9 && ch == 3) scale = 1.0f;
                        bool ok;
                        if (o == 6) {
                            // shade_light: exact sampling only (filtered inputs differ already).
                            if (!exact) continue;
                            const float rounding = ch < 3 ? band[ch] : 0.0f;
                            ok = err <= kShadeRelTol * scale + rounding || err <= kShadeAbsFloor;
                            if (scale > 0 && err > kShadeAbsFloor) {
                                worst_shade = std::max(worst_shade, std::max(0.0f, err - rounding) / scale);
                                worst_shade_raw = std::max(worst_shade_raw, err / scale);
                                if (err > kShadeRelTol * scale) ++shade_in_band;
                            }
                        } else if (exact) {
                            ok = err <= kRelTol * scale || err <= kAbsFloor;
                            if (scale > 1e-3f && err / scale > worst_rel) {
                                worst_rel = err / scale;
                                worst_what = kOutputNames[o][ch];
                            }
                        } else {
                            // Filtered: an 8-bit step of a texel, times what multiplies it (emissive
                            // strength, F0 tints up to 30, normal scales).
                            float norm = 1.0f;
                            const Material& m = c.material;
                            if (o == 2 && ch < 3)
                                norm = std::max(1.0f, m.emissive_strength_value() *
                                                          std::max({m.emissive_factor.x, m.emissive_factor.y, m.emissive_factor.z}));
                            if (o == 3 && ch < 3 && m.specular && !m.specular_glossiness)
                                norm = std::max(1.0f, ior_to_f0(m.ior_value()) *
                                                          std::max({m.specular->specular_color_factor.x,
                                                                    m.specular->specular_color_factor.y,
                                                                    m.specular->specular_color_factor.z}));
                            if (o == 2 && ch == 3 && m.specular) norm = std::max(1.0f, m.specular->specular_factor);
                            if (o == 4 && ch < 3) norm = 1.0f + std::abs(m.normal_scale);
                            if (o == 7 && ch < 3 && m.sheen)
                                norm = std::max(1.0f, std::max({m.sheen->sheen_color_factor.x, m.sheen->sheen_color_factor.y,
                                                                m.sheen->sheen_color_factor.z}));
                            if (o == 5 && ch < 3 && m.clearcoat) norm = 1.0f + std::abs(m.clearcoat->clearcoat_normal_scale);
                            // The anisotropy direction and frame: normalising the filtered direction
                            // scales its error by 1 / its length.
                            if ((o == 8 && ch < 3) || o == 9) norm = std::max(1.0f, 1.0f / direction_length);
                            if (o == 10 && ch == 1 && m.iridescence)  // thickness: mix(min, max, G) in nm
                                norm = std::max(1.0f, std::abs(m.iridescence->iridescence_thickness_maximum -
                                                               m.iridescence->iridescence_thickness_minimum));
                            ok = err <= kFilteredAbsTol * norm;
                            if (err / norm > worst_abs) {
                                worst_abs = err / norm;
                                worst_what = kOutputNames[o][ch];
                            }
                        }
                        ++compared;
                        if (!ok) ++failures;
                        if (!ok && ++shown[o][ch] <= 2) {
                            ADD_FAILURE() << regime_name << " case " << ci << " point " << i << " "
                                          << kOutputNames[o][ch] << ": C++ " << want << " GPU " << got << " (lod "
                                          << c.lod << ", uv0 " << pt.p.uv0.x << "," << pt.p.uv0.y << ", SG "
                                          << bool(c.material.specular_glossiness) << ", coat "
                                          << c.material.has_clearcoat() << ", sheen " << c.material.has_sheen()
                                          << ", anisotropy " << c.material.has_anisotropy() << ", film "
                                          << c.material.has_iridescence() << ", diffuse transmission "
                                          << c.material.has_diffuse_transmission() << ", most probes "
                                          << c.max_anisotropy << ")";
                        }
                    }
                }
            }
        }
        std::printf("%s sampling: %d cases, %d values compared, %d near the cutoff skipped; worst relative %.3g (%s), "
                    "shade_light %.3g beyond its rounding band (%.3g without it, %d values within the band only), "
                    "filtered absolute %.3g\n",
                    regime_name, cases, compared, skipped, worst_rel, worst_what, worst_shade, worst_shade_raw,
                    shade_in_band, worst_abs);
        if (regime == Regime::Footprint) {
            std::printf("footprint: %d detail-map reads, %d of them with more than one probe; %d points near a change "
                        "of probes skipped\n",
                        detail_maps, anisotropic_maps, near_probe_changes);
            EXPECT_GT(anisotropic_maps, detail_maps / 5);
            EXPECT_LT(near_probe_changes, cases * kSide * kSide / 20);
        }
        EXPECT_EQ(failures, 0);
        EXPECT_GT(compared, cases * kSide * kSide * 20);
        for (int i = 0; i < kMaterialMapCount; ++i) {
            // The transmission maps are read by transmission.glsl, which gpu_transmission_test covers.
            if (MaterialMap(i) == MaterialMap::Transmission || MaterialMap(i) == MaterialMap::Thickness) continue;
            if (regime == Regime::Footprint && !material_map_info(MaterialMap(i)).detail) continue;  // only these there
            EXPECT_GT(maps_bound_[std::size_t(i)], 2) << "map " << material_map_info(MaterialMap(i)).name << " hardly covered";
        }
    }

    static std::unique_ptr<DriverDecode> decode_;
    static std::unique_ptr<gpu::Texture> sheen_lut_;
    std::array<int, kMaterialMapCount> maps_bound_{};  // coverage: draws that read each map
};
std::unique_ptr<DriverDecode> MaterialProbe::decode_;
std::unique_ptr<gpu::Texture> MaterialProbe::sheen_lut_;

// What the measured response stands in for: the driver's texel values are byte / 255 and
// the exact sRGB curve up to small errors (llvmpipe: sRGB colour at most 1.2e-3 absolute,
// near byte 230; the bound is 2e-3; linear data and alpha 1e-4 relative, measured 8e-8).
// The C++ mirrors of the std140 blocks (uniform_blocks.h) against the driver's layout: every
// member's offset and each block's size, in a program that declares both.
TEST_F(MaterialProbe, UniformBlocksMatchTheirCppMirrors) {
    const gpu::Program& prog = library().get("pbr.vert", "pbr.frag", feature::HasNormal | feature::HasUv0 | feature::BaseColorMap);
    for (auto [block, size, members] :
         {std::make_tuple("MaterialBlock", sizeof(MaterialBlock), material_block_members()),
          std::make_tuple("FrameBlock", sizeof(FrameBlock), frame_block_members())}) {
        // The mirror covers the block (std140 may round the block's size up to 16 bytes).
        EXPECT_LE(prog.uniform_block_size(block), int(size)) << block;
        EXPECT_GT(prog.uniform_block_size(block), int(size) - 16) << block;
        std::vector<std::string> names;
        for (const auto& m : members) names.push_back(m.first);
        const std::vector<int> offsets = prog.uniform_offsets(names);
        for (std::size_t i = 0; i < members.size(); ++i)
            EXPECT_EQ(offsets[i], int(members[i].second)) << block << "." << members[i].first;
        EXPECT_GT(members.size(), 4u);
    }
}

TEST_F(MaterialProbe, DriverTexelResponseIsCloseToExact) {
    const DriverDecode& d = decode();
    float worst_srgb = 0.0f, worst_rel = 0.0f;
    for (int linear = 0; linear < 2; ++linear)
        for (int i = 0; i < 256; ++i) {
            float unorm = float(i) / 255.0f, curve = srgb_to_linear(unorm);
            const TexelDecode& s = d[std::size_t(linear)][1];
            const TexelDecode& u = d[std::size_t(linear)][0];
            EXPECT_NEAR(s.rgb[i], curve, 2e-3f) << "sRGB byte " << i << (linear ? " LINEAR" : " NEAREST");
            worst_srgb = std::max(worst_srgb, std::abs(s.rgb[i] - curve));
            for (float v : {s.alpha[i], u.rgb[i]}) {
                EXPECT_NEAR(v, unorm, 1e-4f * unorm + 1e-6f) << "byte " << i << (linear ? " LINEAR" : " NEAREST");
                if (i > 0) worst_rel = std::max(worst_rel, std::abs(v - unorm) / unorm);
            }
        }
    EXPECT_EQ(d[0][1].rgb[0], 0.0f);
    EXPECT_NEAR(d[0][1].rgb[255], 1.0f, 1e-6f);
    std::printf("driver texel response: sRGB colour within %.3g of the exact curve, linear and alpha within %.3g "
                "relative of byte/255\n", worst_srgb, worst_rel);
}

TEST_F(MaterialProbe, ReadMaterialAndShadeLightMatchEvaluateAtTexelCentres) { run(Regime::Exact, 96, 20261201u); }

TEST_F(MaterialProbe, FilteredSamplingAgreesToAnEightBitStep) { run(Regime::Filtered, 48, 777u); }

// The filter the renderer draws with: screen-space derivatives, the detail maps through the
// anisotropic footprint (sample_detail_map) and the others through texture(), against
// evaluate with the same derivatives (detail_footprint, SampledTexture::sample_footprint).
TEST_F(MaterialProbe, FootprintSamplingMatchesTheRenderersFilters) { run(Regime::Footprint, 48, 4242u); }

// The comparison can fail: a rule changed on one side only is caught.
TEST_F(MaterialProbe, CatchesADifferentRule) {
    Gen gen(5);
    Case c = gen.make(Regime::Exact);
    c.material.specular_glossiness.reset();
    c.material.metallic_factor = 0.5f;
    c.material.metallic_roughness = TextureSlot{};
    CpuTextures tex(c.textures, &decode());
    auto gpu_out = probe(c);
    Material changed = c.material;
    changed.metallic_factor = 0.5f * (1.0f + 1e-3f);  // a 0.1 % change of one rule's input
    int differ = 0;
    for (int i = 0; i < kSide * kSide; ++i) {
        float want = evaluate(changed, tex, c.points[std::size_t(i)].p).surface.metallic;
        float got = gpu_out[1][std::size_t(i)].x;
        if (std::abs(want - got) > kRelTol * std::max(std::abs(want), std::abs(got))) ++differ;
    }
    EXPECT_EQ(differ, kSide * kSide);
}

}  // namespace
