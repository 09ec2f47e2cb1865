// GPU (llvmpipe) checks of shaders/transmission.glsl against its C++ twins: the functions of
// fresnel/material/transmission.h (volume ray, attenuation, lod, dispersion iors, BTDF,
// refraction weight), fresnel::shade_light_transmission, and the transmission part of
// fresnel::evaluate (read_transmission: factors times the transmission (R) and thickness (G)
// maps, attenuation, dispersion, ior). shaders/transmission_probe.frag evaluates one point per
// pixel over seeded random inputs.
//
// Tolerance: relative 1e-4 with an absolute floor 1e-5 for the smooth functions (transcendentals
// in float; measured below 1e-5), and for the BTDF and the transmission term 1e-4 beyond the
// band that float rounding of their directions explains (test::rounding_band: their GGX peak
// amplifies the rounding of n.h, as material_gpu_test's shade_band allows for shade_light).
// The maps are read at texel centres of level 0 with NEAREST filtering (exact in both).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "fresnel/gpu/context.h"
#include "fresnel/gpu/device.h"
#include "fresnel/gpu/resources.h"
#include "fresnel/material/evaluate.h"
#include "fresnel/material/transmission.h"
#include "details/material_uniforms.h"
#include "details/shader_library.h"
#include "probe_harness.h"
#include "gltf_sampler.h"

namespace {
using namespace fresnel;

constexpr int kSide = 16;
constexpr int kTexels = 11;
constexpr int kOutputs = 8;
constexpr float kRelTol = 1e-4f, kAbsFloor = 1e-5f;
constexpr float kShadeRelTol = 1e-4f;

struct Point {
    glm::vec4 t[kTexels];
};

class OneTexture final : public TextureSource {
public:
    explicit OneTexture(const Image8& image)
        : tex_(image, test::sampler_from_gltf(9728, 9728, 33071, 33071), false) {}
    const SampledTexture* get(int texture, bool srgb) const override { return texture == 0 && !srgb ? &tex_ : nullptr; }

private:
    SampledTexture tex_;
};

// `band`: what float rounding of the inputs alone moves the value by (test::rounding_band), allowed on top.
float rel_error(float gpu, float cpu, float rel, float band = 0.0f) {
    float e = std::abs(gpu - cpu);
    float bound = std::max(kAbsFloor, rel * std::abs(cpu) + band);
    return e / bound;  // <= 1 passes
}

class TransmissionProbe : public test::ProbeSuite {};

TEST_F(TransmissionProbe, GlslMatchesCpp) {
    ShaderLibrary& library = this->library();
    std::mt19937 rng(1234);
    std::uniform_real_distribution<float> u01(0.0f, 1.0f);
    auto u = [&] { return u01(rng); };
    auto range = [&](float a, float b) { return a + (b - a) * u(); };
    auto unit = [&] {
        for (;;) {
            glm::vec3 d(range(-1, 1), range(-1, 1), range(-1, 1));
            float l = glm::length(d);
            if (l > 0.1f && l <= 1.0f) return d / l;
        }
    };

    // The material read by read_transmission / evaluate: factors and two maps from one 4x4 texture.
    Image8 image(4, 4, 4);
    for (auto& b : image.pixels) b = std::uint8_t(u() * 255.0f);
    OneTexture textures(image);

    int compared = 0, failures = 0;
    float worst = 0.0f, worst_shade = 0.0f;
    for (int round = 0; round < 4; ++round) {
        Material mat;
        mat.base_color_factor = glm::vec4(u(), u(), u(), 1.0f);
        TransmissionExt tx;
        tx.transmission_factor = u();
        if (round % 2 == 0) tx.transmission_texture.texture = 0;
        mat.transmission = tx;
        if (round != 3) {
            VolumeExt vol;
            vol.thickness_factor = range(0, 3);
            if (round < 2) vol.thickness_texture.texture = 0;
            vol.attenuation_color = glm::vec3(u(), u(), u());
            vol.attenuation_distance = round == 1 ? std::numeric_limits<float>::infinity() : range(0.1f, 4.0f);
            mat.volume = vol;
        }
        if (round >= 2) mat.dispersion = DispersionExt{range(0, 20)};
        if (round != 1) mat.ior = IorExt{range(1.0f, 2.5f)};
        ASSERT_TRUE(is_transmissive(mat));

        std::vector<Point> points(std::size_t(kSide * kSide));
        for (int i = 0; i < kSide * kSide; ++i) {
            Point& p = points[std::size_t(i)];
            glm::vec3 n = unit();
            glm::vec3 v = unit();
            if (glm::dot(v, n) < 0.05f) v = glm::normalize(v + n * (0.05f - glm::dot(v, n) + 0.3f));
            glm::vec3 l = unit(), lt = unit();
            float ior = range(1.0f, 2.5f), alpha = range(0.05f, 1.0f), rough = range(0, 1);
            p.t[0] = glm::vec4(n, ior);
            p.t[1] = glm::vec4(v, range(0, 3));
            p.t[2] = glm::vec4(l, alpha);
            p.t[3] = glm::vec4(range(0, 0.2f), range(0, 0.2f), range(0, 0.2f), range(0, 20));
            p.t[4] = glm::vec4(u(), u(), u(), rough);
            p.t[5] = glm::vec4(range(0.2f, 3), range(0.2f, 3), range(0.2f, 3), u() < 0.2f ? 0.0f : range(0.1f, 4));
            p.t[6] = glm::vec4(u(), u(), u(), range(0, 5));
            p.t[7] = glm::vec4(range(0, 4), range(0, 4), range(0, 4), u());
            p.t[8] = glm::vec4(lt, u() < 0.3f ? 0.0f : u());
            p.t[9] = glm::vec4(u(), range(0, 0.2f), range(0, 1.5f), range(0, 3));
            // uv at a texel centre of the 4x4 texture.
            glm::vec2 uv((float(int(u() * 4)) + 0.5f) / 4.0f, (float(int(u() * 4)) + 0.5f) / 4.0f);
            p.t[10] = glm::vec4(u() < 0.5f ? 0.0f : u(), range(0, 0.1f), uv);
        }
        const std::vector<float> texels = test::pack_case_texels(
            points.size(), kTexels, kSide, [&](std::size_t i, int k) { return points[i].t[k]; });

        gpu::Device device;
        gpu::Texture pts = gpu::Texture::create_2d(kSide * kTexels, kSide, gpu::TextureFormat::RGBA32F, texels.data(), false);
        pts.set_sampler(gpu::SamplerState::clamped(Filter::Nearest));
        gpu::Texture map = gpu::Texture::create_2d(4, 4, gpu::TextureFormat::RGBA8, image.pixels.data(), false);
        map.set_sampler(gpu::SamplerState::clamped(Filter::Nearest));
        test::ProbeTarget target(kSide, kSide);

        MaterialUniforms mu = material_uniforms(mat);
        std::vector<std::string> defines = {"MATERIAL_TRANSMISSION", "MATERIAL_CLEARCOAT", "MATERIAL_EXPLICIT_LOD"};
        std::array<bool, kMaterialMapCount> bound{};
        for (MaterialMap mm : {MaterialMap::Transmission, MaterialMap::Thickness}) {
            if (!mu.maps[std::size_t(mm)]) continue;
            bound[std::size_t(mm)] = true;
            defines.emplace_back(material_map_info(mm).define);
            device.bind_texture(int(mm), map);
        }
        const gpu::Program& prog = library.get("fullscreen.vert", "transmission_probe.frag", defines);
        target.bind(device);
        prog.use();
        device.bind_texture(15, pts);
        prog.set("u_points", 15);
        gpu::UniformBuffer block;
        set_material_uniforms(prog, mu, bound, block);
        prog.set("u_material_lod", 0.0f);
        std::vector<std::vector<glm::vec4>> out(kOutputs);
        for (int o = 0; o < kOutputs; ++o) {
            prog.set("u_output", o);
            out[std::size_t(o)] = target.draw(device, std::size_t(kSide * kSide));
        }
        EXPECT_EQ(device.take_errors(), "");

        for (int i = 0; i < kSide * kSide; ++i) {
            const Point& p = points[std::size_t(i)];
            const auto& t = p.t;
            glm::vec3 n(t[0]), v(t[1]), l(t[2]), lt(t[8]);
            float ior = t[0].w;
            glm::vec4 cpu[kOutputs];
            cpu[0] = glm::vec4(transmission::volume_ray(n, v, t[1].w, ior, glm::vec3(t[5])),
                               transmission::apply_ior_to_roughness(t[4].w, ior));
            cpu[1] = glm::vec4(transmission::volume_attenuation(glm::vec3(t[7]), t[6].w, glm::vec3(t[6]), t[5].w),
                               transmission::framebuffer_lod(t[4].w, ior));
            auto btdf = [&](glm::vec3 n_, glm::vec3 v_, glm::vec3 l_, glm::vec3) {
                return transmission::btdf_punctual(n_, v_, l_, t[2].w, glm::vec3(t[3]), glm::vec3(1.0f), glm::vec3(t[4]), ior);
            };
            cpu[2] = glm::vec4(btdf(n, v, l, lt), 0.0f);
            glm::vec3 band[kOutputs] = {};
            // n, v, l, lt as directions 0..3 of test::rounding_band.
            auto band_of = [&](auto&& f) {
                return test::rounding_band([&](auto&& move) { return f(move(n, 0), move(v, 1), move(l, 2), move(lt, 3)); });
            };
            band[2] = band_of(btdf);
            cpu[3] = glm::vec4(transmission::dispersion_iors(ior, t[3].w), 0.0f);
            cpu[4] = glm::vec4(transmission::refraction_weight(glm::vec3(t[3]), glm::vec3(1.0f), t[9].x, t[9].y,
                                                               glm::vec3(t[4])), 0.0f);
            EvaluatedMaterial e;
            e.surface.base_color = glm::vec3(t[4]);
            e.surface.metallic = t[8].w;
            e.surface.perceptual_roughness = t[4].w;
            e.surface.specular_f0 = 1.0f;
            e.surface.specular_color = glm::vec3(t[3]);
            e.surface.specular_weight = t[9].z;
            e.normal = n;
            e.clearcoat = t[10].x;
            e.clearcoat_f0 = t[10].y;
            e.clearcoat_normal = n;
            e.transmission.factor = t[7].w;
            e.transmission.thickness = t[1].w;
            e.transmission.attenuation_color = glm::vec3(t[6]);
            e.transmission.attenuation_distance = t[5].w;
            e.transmission.dispersion = t[3].w;
            e.transmission.ior = ior;
            auto lobe_light = [&](glm::vec3 n_, glm::vec3 v_, glm::vec3 l_, glm::vec3 lt_) {
                EvaluatedMaterial moved = e;
                moved.normal = moved.clearcoat_normal = n_;
                return shade_light_transmission(moved, v_, l_, lt_, t[9].w, glm::vec3(t[7]));
            };
            cpu[5] = glm::vec4(lobe_light(n, v, l, lt), 0.0f);
            band[5] = band_of(lobe_light);
            SurfacePoint sp;
            sp.uv0 = sp.uv1 = glm::vec2(t[10].z, t[10].w);
            sp.lod = 0.0f;
            TransmissionInputs tr = evaluate(mat, textures, sp).transmission;
            cpu[6] = glm::vec4(tr.factor, tr.thickness, tr.attenuation_distance, tr.dispersion);
            cpu[7] = glm::vec4(tr.attenuation_color, tr.ior);
            for (int o = 0; o < kOutputs; ++o)
                for (int c = 0; c < 4; ++c) {
                    float g = out[std::size_t(o)][std::size_t(i)][c];
                    float want = cpu[o][c];
                    const bool lobe = o == 2 || o == 5;
                    // GGX lobes of very smooth transmission peak far above 1: skip values the
                    // float peak makes meaningless (as gpu_brdf_test skips D beyond 1e4).
                    if (lobe && std::abs(want) > 1e3f) continue;
                    float r = rel_error(g, want, lobe ? kShadeRelTol : kRelTol, lobe && c < 3 ? band[o][c] : 0.0f);
                    ++compared;
                    (lobe ? worst_shade : worst) = std::max(lobe ? worst_shade : worst, r);
                    if (r > 1.0f && failures++ < 10)
                        ADD_FAILURE() << "round " << round << " point " << i << " output " << o << "." << c << ": GLSL " << g
                                      << ", C++ " << want;
                }
        }
    }
    std::printf("transmission probe: %d values compared, worst error %.3f of the tolerance (lobes %.3f)\n", compared,
                worst, worst_shade);
    EXPECT_GT(compared, kSide * kSide * kOutputs * 4 * 3);
    EXPECT_EQ(failures, 0);
}

// evaluate's transmission rules on the CPU: factors, the infinite default distance, no transmission with specular-glossiness.
TEST(TransmissionEvaluate, Rules) {
    Material mat;
    mat.transmission = TransmissionExt{0.5f, {}};
    mat.volume = VolumeExt{};
    mat.volume->thickness_factor = 2.0f;
    OneTexture none(Image8(1, 1, 4));
    SurfacePoint sp;
    sp.lod = 0.0f;
    TransmissionInputs tr = evaluate(mat, none, sp).transmission;
    EXPECT_FLOAT_EQ(tr.factor, 0.5f);
    EXPECT_FLOAT_EQ(tr.thickness, 2.0f);
    EXPECT_EQ(tr.attenuation_distance, 0.0f);  // the default infinity is passed as 0
    mat.specular_glossiness = SpecularGlossinessExt{};
    EXPECT_FALSE(is_transmissive(mat));
    EXPECT_EQ(evaluate(mat, none, sp).transmission.factor, 0.0f);
}

}  // namespace
