// GPU (llvmpipe) checks of shaders/legacy_shading.glsl against its C++ twin
// (fresnel/material/legacy_shading.h): OpenGL 1 fixed-function lighting, fog and colour sum,
// and the normalized Blinn-Phong microfacet model. shaders/legacy_probe.frag evaluates one
// case per pixel from 4 RGBA32F texels; every result is compared with the C++ function on
// the same float inputs, plus a few values known in closed form (so both cannot be wrong
// the same way unnoticed).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "fresnel/gpu/context.h"
#include "fresnel/gpu/device.h"
#include "fresnel/gpu/resources.h"
#include "fresnel/material/legacy_shading.h"
#include "fresnel/material/phong.h"
#include "details/shader_library.h"
#include "probe_harness.h"

namespace {

namespace legacy = fresnel::legacy;

enum Mode { kOgl1Diffuse = 0, kOgl1Specular = 1, kBlinnPhong = 2, kFog = 3, kCombine = 4, kScalars = 5, kBlinnPhongIbl = 6 };

constexpr int kGrid = 64;
constexpr float kRelTol = 1e-3f;
constexpr float kAbsTol = 1e-5f;

using Case = std::array<glm::vec4, 4>;

class LegacyProbe : public fresnel::test::ProbeSuite {
protected:
    // Renders legacy_probe.frag in `mode` over `cases` (kGrid per row): one RGBA per case.
    std::vector<glm::vec4> probe(Mode mode, const std::vector<Case>& cases) {
        return fresnel::test::run_mode_probe(library(), "legacy_probe.frag", int(mode), cases, kGrid);
    }
};

glm::vec3 direction(float cos_theta, float phi) {
    float s = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
    return glm::normalize(glm::vec3(s * std::cos(phi), s * std::sin(phi), cos_theta));
}

struct Rng {
    std::mt19937 rng;
    std::uniform_real_distribution<float> u{0.0f, 1.0f};
    explicit Rng(unsigned seed) : rng(seed) {}
    float operator()() { return u(rng); }
    int pick(int n) { return int(u(rng) * float(n)) % n; }
    float cosine() {
        switch (pick(8)) {
            case 0: return 0.0f;
            case 1: return u(rng) * 0.02f;
            case 2: return -u(rng) * 0.3f;
            case 3: return 1.0f;
            default: return u(rng);
        }
    }
    glm::vec3 dir() { return direction(cosine(), 6.2831853f * u(rng)); }
    glm::vec3 color(float scale = 1.0f) { return scale * glm::vec3(u(rng), u(rng), u(rng)); }
    float shininess() {
        switch (pick(6)) {
            case 0: return 0.0f;
            case 1: return 128.0f;
            case 2: return 200.0f + 800.0f * u(rng);  // above OpenGL 1's limit
            case 3: return 1.0f + 4.0f * u(rng);
            default: return 128.0f * u(rng);
        }
    }
};

bool close(float gpu, float cpu) {
    if (!std::isfinite(gpu) || !std::isfinite(cpu)) return false;
    return std::fabs(gpu - cpu) <= std::max(kRelTol * std::fabs(cpu), kAbsTol);
}

struct Mismatches {
    int count = 0;
    std::ostringstream first;
    void add(const std::string& what, float gpu, float cpu, const std::string& ctx) {
        if (count++ < 6) first << "  " << what << ": gpu " << gpu << " cpu " << cpu << " (" << ctx << ")\n";
    }
};

std::string vec(const glm::vec3& v) {
    std::ostringstream s;
    s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
    return s.str();
}

constexpr unsigned kSeed = 20261202u;

TEST_F(LegacyProbe, Ogl1LightMatchesCpp) {
    Rng r(kSeed);
    std::vector<Case> cases;
    struct In {
        glm::vec3 l, v, diffuse, specular, light;
        float shininess;
    };
    std::vector<In> ins;
    int lit = 0, highlights = 0;
    for (int i = 0; i < kGrid * kGrid; ++i) {
        In c{r.dir(), r.dir(), r.color(), r.color(), r.color(3.0f), r.shininess()};
        if (r.pick(8) == 0) c.l = glm::normalize(glm::vec3(-c.v.x, -c.v.y, c.v.z));  // h = n
        ins.push_back(c);
        cases.push_back({glm::vec4(c.l, c.shininess), glm::vec4(c.v, c.light.x), glm::vec4(c.diffuse, c.light.y),
                         glm::vec4(c.specular, c.light.z)});
    }
    auto diffuse = probe(kOgl1Diffuse, cases);
    auto specular = probe(kOgl1Specular, cases);
    Mismatches bad;
    for (std::size_t i = 0; i < ins.size(); ++i) {
        const In& c = ins[i];
        legacy::Ogl1Light o = legacy::ogl1_light(glm::vec3(0, 0, 1), glm::normalize(c.v), glm::normalize(c.l), c.light,
                                                 c.diffuse, c.specular, legacy::ogl1_shininess(c.shininess));
        lit += o.diffuse.x > 0;
        highlights += o.specular.x > 1e-3f;
        std::string ctx = "l " + vec(c.l) + " v " + vec(c.v) + " s " + std::to_string(c.shininess);
        for (int k = 0; k < 3; ++k) {
            if (!close(diffuse[i][k], o.diffuse[k])) bad.add("diffuse", diffuse[i][k], o.diffuse[k], ctx);
            if (!close(specular[i][k], o.specular[k])) bad.add("specular", specular[i][k], o.specular[k], ctx);
        }
    }
    EXPECT_EQ(bad.count, 0) << bad.count << " channels differ:\n" << bad.first.str();
    EXPECT_GT(lit, kGrid * kGrid / 2);  // the grid is not mostly unlit
    EXPECT_GT(highlights, kGrid * kGrid / 10);
}

TEST_F(LegacyProbe, BlinnPhongNormalizedMatchesCpp) {
    Rng r(kSeed + 1);
    std::vector<Case> cases;
    std::vector<std::pair<legacy::BlinnPhongMaterial, std::array<glm::vec3, 3>>> ins;
    int nonzero = 0;
    for (int i = 0; i < kGrid * kGrid; ++i) {
        legacy::BlinnPhongMaterial m;
        m.base_color = r.color();
        m.shininess = r.pick(5) == 0 ? 2000.0f * r() : r.shininess();
        m.fresnel = r.pick(3) == 0 ? 0.04f : r();
        m.metalness = r.pick(3) == 0 ? float(r.pick(2)) : r();
        m.reflectivity = r.pick(3) == 0 ? 1.0f : r();
        glm::vec3 l = r.dir(), v = r.dir(), light = r.color(3.0f);
        if (r.pick(8) == 0) l = glm::normalize(glm::vec3(-v.x, -v.y, v.z));
        ins.push_back({m, {l, v, light}});
        cases.push_back({glm::vec4(l, m.shininess), glm::vec4(v, m.fresnel), glm::vec4(m.base_color, m.metalness),
                         glm::vec4(light, m.reflectivity)});
    }
    auto gpu = probe(kBlinnPhong, cases);
    Mismatches bad;
    for (std::size_t i = 0; i < ins.size(); ++i) {
        const auto& [m, dirs] = ins[i];
        glm::vec3 cpu = legacy::blinn_phong_normalized(m, glm::vec3(0, 0, 1), glm::normalize(dirs[1]),
                                                       glm::normalize(dirs[0]), dirs[2]);
        nonzero += cpu.x > 0;
        for (int k = 0; k < 3; ++k)
            if (!close(gpu[i][k], cpu[k]))
                bad.add("f", gpu[i][k], cpu[k], "l " + vec(dirs[0]) + " v " + vec(dirs[1]) + " s " + std::to_string(m.shininess));
    }
    EXPECT_EQ(bad.count, 0) << bad.count << " channels differ:\n" << bad.first.str();
    EXPECT_GT(nonzero, kGrid * kGrid / 3);
}

// The image-based path (pre-convolved irradiance and prefiltered radiance as inputs).
TEST_F(LegacyProbe, BlinnPhongNormalizedIblMatchesCpp) {
    Rng r(kSeed + 3);
    std::vector<Case> cases;
    std::vector<std::pair<legacy::BlinnPhongMaterial, std::array<glm::vec3, 3>>> ins;
    for (int i = 0; i < kGrid * kGrid; ++i) {
        legacy::BlinnPhongMaterial m;
        m.base_color = r.color();
        m.fresnel = r.pick(3) == 0 ? 0.04f : r();
        m.metalness = r.pick(3) == 0 ? float(r.pick(2)) : r();
        m.reflectivity = r.pick(3) == 0 ? 1.0f : r();
        glm::vec3 irradiance = r.color(2.0f), prefiltered = r.color(4.0f);
        float n_dot_v = r.pick(10) == 0 ? 0.0f : r();
        ins.push_back({m, {irradiance, prefiltered, glm::vec3(n_dot_v)}});
        cases.push_back({glm::vec4(m.base_color, m.metalness), glm::vec4(irradiance, m.fresnel),
                         glm::vec4(prefiltered, m.reflectivity), glm::vec4(n_dot_v, 0, 0, 0)});
    }
    auto gpu = probe(kBlinnPhongIbl, cases);
    Mismatches bad;
    int positive = 0;
    for (std::size_t i = 0; i < ins.size(); ++i) {
        const auto& [m, in] = ins[i];
        glm::vec3 cpu = legacy::blinn_phong_normalized_ibl(m, in[2].x, in[0], in[1]);
        positive += cpu.x > 0;
        for (int k = 0; k < 3; ++k)
            if (!close(gpu[i][k], cpu[k])) bad.add("ibl", gpu[i][k], cpu[k], "n.v " + std::to_string(in[2].x));
    }
    EXPECT_EQ(bad.count, 0) << bad.count << " channels differ:\n" << bad.first.str();
    EXPECT_GT(positive, kGrid * kGrid / 2);
    // Closed form: a white mirror-like metal at normal incidence reflects R0 of the prefiltered light.
    legacy::BlinnPhongMaterial metal;
    metal.fresnel = 0.9f;
    metal.metalness = 1.0f;
    glm::vec3 f = legacy::blinn_phong_normalized_ibl(metal, 1.0f, glm::vec3(5.0f), glm::vec3(2.0f));
    EXPECT_NEAR(f.x, 0.9f * 2.0f, 1e-5f);
}

TEST_F(LegacyProbe, FogCombineAndScalarsMatchCpp) {
    Rng r(kSeed + 2);
    std::vector<Case> fog, combine, scalars;
    for (int i = 0; i < kGrid * 4; ++i) {
        float mode = float(r.pick(4)), z = 20.0f * r(), start = 5.0f * r(), end = r.pick(6) == 0 ? start : start + 15.0f * r();
        fog.push_back({glm::vec4(mode, z, start, end), glm::vec4(0.3f * r(), 0, 0, 0), glm::vec4(0), glm::vec4(0)});
        combine.push_back({glm::vec4(r.color(1.5f), float(r.pick(2))), glm::vec4(r.color(1.5f), 0), glm::vec4(r.color(), 0),
                           glm::vec4(0)});
        scalars.push_back({glm::vec4(r.shininess(), r(), 0, 0), glm::vec4(0), glm::vec4(0), glm::vec4(0)});
    }
    auto gf = probe(kFog, fog), gc = probe(kCombine, combine), gs = probe(kScalars, scalars);
    Mismatches bad;
    for (std::size_t i = 0; i < fog.size(); ++i) {
        const glm::vec4& a = fog[i][0];
        float f = legacy::ogl1_fog_factor(legacy::FogMode(int(a.x)), a.y, a.z, a.w, fog[i][1].x);
        if (!close(gf[i].x, f)) bad.add("fog", gf[i].x, f, "mode " + std::to_string(int(a.x)) + " z " + std::to_string(a.y));
        glm::vec3 c = legacy::ogl1_combine(glm::vec3(combine[i][0]), glm::vec3(combine[i][1]), glm::vec3(combine[i][2]),
                                           combine[i][0].w > 0.5f);
        for (int k = 0; k < 3; ++k)
            if (!close(gc[i][k], c[k])) bad.add("combine", gc[i][k], c[k], "");
        float s = scalars[i][0].x, nh = scalars[i][0].y;
        if (!close(gs[i].x, legacy::blinn_phong_ibl_roughness(s))) bad.add("ibl roughness", gs[i].x, legacy::blinn_phong_ibl_roughness(s), "");
        if (!close(gs[i].y, legacy::ogl1_shininess(s))) bad.add("shininess", gs[i].y, legacy::ogl1_shininess(s), "");
        if (!close(gs[i].z, legacy::blinn_phong_d(nh, s))) bad.add("D", gs[i].z, legacy::blinn_phong_d(nh, s), "");
    }
    EXPECT_EQ(bad.count, 0) << bad.count << " values differ:\n" << bad.first.str();
}

// Values known without either implementation.
TEST(LegacyShading, ClosedFormValues) {
    const glm::vec3 n(0, 0, 1);
    // Light and eye along the normal: n.l = n.h = 1, so diffuse + specular exactly.
    auto o = legacy::ogl1_light(n, n, n, glm::vec3(2.0f), glm::vec3(0.25f), glm::vec3(0.125f), 50.0f);
    EXPECT_FLOAT_EQ(o.diffuse.x, 0.5f);
    EXPECT_FLOAT_EQ(o.specular.x, 0.25f);
    // n.l = cos 60 = 0.5; v mirrored: h = n, so the highlight is at full strength.
    glm::vec3 l = glm::normalize(glm::vec3(std::sqrt(3.0f), 0, 1)), v(-l.x, 0, l.z);
    o = legacy::ogl1_light(n, v, l, glm::vec3(1.0f), glm::vec3(1.0f), glm::vec3(1.0f), 10.0f);
    EXPECT_NEAR(o.diffuse.x, 0.5f, 1e-6f);
    EXPECT_NEAR(o.specular.x, 1.0f, 1e-6f);
    // Light below the horizon: no diffuse and, however shiny, no highlight.
    o = legacy::ogl1_light(n, n, glm::vec3(0, 0, -1), glm::vec3(1.0f), glm::vec3(1.0f), glm::vec3(1.0f), 0.0f);
    EXPECT_EQ(o.diffuse, glm::vec3(0.0f));
    EXPECT_EQ(o.specular, glm::vec3(0.0f));
    EXPECT_EQ(legacy::ogl1_shininess(256.0f), 128.0f);
    EXPECT_EQ(legacy::ogl1_specular_power(0.0f, 0.0f), 1.0f);  // 0^0 = 1
    EXPECT_FLOAT_EQ(legacy::ogl1_fog_factor(legacy::FogMode::Linear, 5.0f, 0.0f, 10.0f, 0.0f), 0.5f);
    EXPECT_FLOAT_EQ(legacy::ogl1_fog_factor(legacy::FogMode::Exp, 2.0f, 0, 0, 0.5f), std::exp(-1.0f));
    EXPECT_FLOAT_EQ(legacy::ogl1_fog_factor(legacy::FogMode::Exp2, 2.0f, 0, 0, 0.5f), std::exp(-1.0f));
    EXPECT_EQ(legacy::ogl1_combine(glm::vec3(0.8f), glm::vec3(0.5f), glm::vec3(0.5f), false), glm::vec3(0.5f));
    EXPECT_EQ(legacy::ogl1_combine(glm::vec3(0.8f), glm::vec3(0.5f), glm::vec3(0.5f), true), glm::vec3(0.9f));
    // The normalized distribution integrates to 1 over projected solid angle: integral of
    // D(h) (n.h) dw_h over the hemisphere, for several exponents.
    for (float s : {1.0f, 10.0f, 100.0f}) {
        double sum = 0;
        const int steps = 20000;
        for (int i = 0; i < steps; ++i) {
            double t = (i + 0.5) / steps * (M_PI / 2);
            sum += legacy::blinn_phong_d(float(std::cos(t)), s) * std::cos(t) * std::sin(t) * (M_PI / 2 / steps) * 2 * M_PI;
        }
        EXPECT_NEAR(sum, 1.0, 2e-3) << "shininess " << s;
    }
    // Lambert limit: reflectivity 0 gives base / pi (n.l) E.
    legacy::BlinnPhongMaterial m;
    m.base_color = glm::vec3(0.6f);
    m.reflectivity = 0.0f;
    glm::vec3 lit = legacy::blinn_phong_normalized(m, n, n, l, glm::vec3(2.0f));
    EXPECT_NEAR(lit.x, 0.6f / legacy::kPi * 0.5f * 2.0f, 1e-6f);
    EXPECT_NEAR(legacy::blinn_phong_ibl_roughness(98.0f), std::pow(0.02f, 0.25f), 1e-6f);
    EXPECT_FLOAT_EQ(legacy::blinn_phong_ibl_roughness(30.0f), fresnel::phong_shininess_to_roughness(30.0f));
}

}  // namespace
