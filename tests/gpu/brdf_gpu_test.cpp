// GPU (llvmpipe) checks of the GLSL shading code against its C++ twin.
//
// shaders/brdf_probe.frag evaluates brdf.glsl, tonemap.glsl and color.glsl once
// per pixel, reading its inputs from an RGBA32F texture (3 texels per case).
// These tests render a seeded random grid of cases into an RGBA32F framebuffer,
// read it back and compare each pixel with libs/material/.../brdf.h and
// libs/core/.../color.h evaluated on exactly the same float inputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "fresnel/core/color.h"
#include "fresnel/core/error.h"
#include "fresnel/gpu/context.h"
#include "fresnel/gpu/device.h"
#include "fresnel/gpu/resources.h"
#include "fresnel/material/brdf.h"
#include "fresnel/material/brdf_model.h"
#include "details/shader_library.h"
#include "probe_harness.h"

namespace {

using fresnel::brdf::Surface;
using fresnel::brdf::Terms;

// brdf_probe.frag's u_mode values.
enum ProbeMode { kModeBrdf = 0, kModeDvf = 1, kModeToneMap = 2, kModeEncode = 3, kModeClearcoat = 4 };

constexpr int kGrid = 64;                  // cases per side: kGrid x kGrid per draw
constexpr float kRelTol = 1e-4f;           // BRDF values, D, V, F: relative error ...
constexpr float kAbsTolNearZero = 1e-5f;   // ... or this absolute error near zero
constexpr float kColorAbsTol = 1e-4f;      // tone mappers and encodings: absolute error

using Case = std::array<glm::vec4, 3>;  // texels a, b, c of one case

class BrdfProbe : public fresnel::test::ProbeSuite {
protected:
    // Renders brdf_probe.frag in `mode` over `cases` (row-major, kGrid per row) and
    // returns one RGBA result per case. Fails the test on GL errors or unwritten pixels.
    std::vector<glm::vec4> probe(ProbeMode mode, const std::vector<Case>& cases,
                                 const std::vector<std::string>& defines = {}) {
        return fresnel::test::run_mode_probe(library(), "brdf_probe.frag", int(mode), cases, kGrid, defines);
    }
};

// ---------------------------------------------------------------------------
// Case generation.

// A unit direction around n = +Z with the given cosine to n and azimuth phi.
glm::vec3 direction(float cos_theta, float phi) {
    float s = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
    return glm::normalize(glm::vec3(s * std::cos(phi), s * std::sin(phi), cos_theta));
}

struct BrdfCase {
    Surface surface;
    glm::vec3 v, l;
};

// Seeded random BRDF inputs with deliberate edge cases: roughness exactly 0 and 1,
// metallic exactly 0 and 1 and in between, grazing and below-horizon directions,
// mirror and retro-reflection configurations.
std::vector<BrdfCase> make_brdf_cases(int count, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u01(0.0f, 1.0f);
    auto pick = [&](int n) { return int(u01(rng) * float(n)) % n; };
    const float two_pi = 2.0f * fresnel::brdf::kPi;
    auto random_cosine = [&]() -> float {
        switch (pick(8)) {
            case 0: return 0.0f;                    // exactly at the horizon
            case 1: return u01(rng) * 0.02f;        // grazing
            case 2: return -u01(rng) * 0.3f;        // below the horizon (n.v or n.l clamps to 0)
            case 3: return 1.0f;                    // along the normal
            default: return u01(rng);               // anywhere above
        }
    };
    std::vector<BrdfCase> cases;
    cases.reserve(std::size_t(count));
    for (int i = 0; i < count; ++i) {
        BrdfCase c;
        c.surface.base_color = glm::vec3(u01(rng), u01(rng), u01(rng));
        switch (pick(4)) {
            case 0: c.surface.metallic = 0.0f; break;
            case 1: c.surface.metallic = 1.0f; break;
            default: c.surface.metallic = u01(rng); break;
        }
        switch (pick(6)) {
            case 0: c.surface.perceptual_roughness = 0.0f; break;
            case 1: c.surface.perceptual_roughness = 1.0f; break;
            case 2: c.surface.perceptual_roughness = 0.05f + 0.15f * u01(rng); break;  // glossy
            default: c.surface.perceptual_roughness = u01(rng); break;
        }
        c.surface.specular_f0 = 0.04f;  // what brdf_probe.frag passes
        c.v = direction(random_cosine(), two_pi * u01(rng));
        switch (pick(8)) {
            case 0: c.l = glm::normalize(glm::vec3(-c.v.x, -c.v.y, c.v.z)); break;  // mirror: h = n
            case 1: c.l = c.v; break;                                               // retro-reflection
            default: c.l = direction(random_cosine(), two_pi * u01(rng)); break;
        }
        cases.push_back(c);
    }
    return cases;
}

Case to_probe_case(const BrdfCase& c) {
    const Surface& s = c.surface;
    return {glm::vec4(s.base_color, s.metallic), glm::vec4(c.l, s.perceptual_roughness), glm::vec4(c.v, 0.0f)};
}

Terms cpu_terms(const BrdfCase& c, const fresnel::brdf::BrdfModel& model = {}) {
    // The probe normalizes v and l; so does the reference (both are unit already).
    return fresnel::brdf::evaluate_terms(c.surface, glm::vec3(0, 0, 1), glm::normalize(c.v), glm::normalize(c.l), model);
}

std::string describe(const BrdfCase& c) {
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "base (%.4g, %.4g, %.4g) metallic %.4g roughness %.4g v (%.5g, %.5g, %.5g) l (%.5g, %.5g, %.5g)",
                  c.surface.base_color.x, c.surface.base_color.y, c.surface.base_color.z, c.surface.metallic,
                  c.surface.perceptual_roughness, c.v.x, c.v.y, c.v.z, c.l.x, c.l.y, c.l.z);
    return buf;
}

bool close_rel(float gpu, float cpu) {
    if (!std::isfinite(gpu) || !std::isfinite(cpu)) return false;
    return std::fabs(gpu - cpu) <= std::max(kRelTol * std::fabs(cpu), kAbsTolNearZero);
}

// Collects mismatches and prints the first few.
struct Mismatches {
    int count = 0;
    float worst_rel = 0.0f;
    std::ostringstream first;
    std::string worst;
    void add(const std::string& what, float gpu, float cpu, const std::string& context) {
        float rel = std::fabs(gpu - cpu) / std::max(std::fabs(cpu), 1e-30f);
        std::ostringstream line;
        line << "  " << what << ": gpu " << gpu << " cpu " << cpu << " (" << context << ")\n";
        if (std::isnan(rel) || rel > worst_rel) {
            worst_rel = std::isnan(rel) ? INFINITY : rel;
            worst = line.str();
        }
        if (count++ < 6) first << line.str();
    }
    std::string report() const { return first.str() + (count > 6 ? "  ...\n" : "") + " worst:\n" + worst; }
};

// ---------------------------------------------------------------------------
// BRDF.
//
// Both implementations write D_GGX's denominator as f = (n.h)^2 (a^2 - 1) + 1.
// On the specular peak of a glossy surface (n.h -> 1, small alpha) f ~ a^2 is the
// difference of numbers near 1: evaluated literally in float, rounding (~6e-8
// absolute) becomes a relative error of ~1e-7 / f in f and twice that in D (C++
// brdf.h: 9% at roughness 0.025, 30% at 0.018). Mesa evaluates the GLSL without
// that loss, so there the two disagree. The algebraically equal form
// f = (1 - n.h)(1 + n.h) + (n.h)^2 a^2 has no cancellation (see exact_d below).
// Cases with f < 1e-3 are checked in their own tests (GlossyPeak*), at the same
// tolerance, so a failure there is told apart from a divergence elsewhere; their
// messages print the double-precision D next to the C++ one.

constexpr double kPeakDenominator = 1e-3;

// D_GGX's denominator for this case, in double precision.
double ggx_denominator(const BrdfCase& c) {
    glm::dvec3 v = glm::normalize(glm::dvec3(c.v)), l = glm::normalize(glm::dvec3(c.l));
    glm::dvec3 h = v + l;
    double hl = glm::length(h);
    double nh = hl > 0 ? std::clamp(h.z / hl, 0.0, 1.0) : 1.0;
    double r = std::clamp(double(c.surface.perceptual_roughness), 0.0, 1.0);
    double a2 = r * r * r * r;
    return (1.0 - nh) * (1.0 + nh) + nh * nh * a2;  // = nh^2 (a2 - 1) + 1 without cancellation
}

bool on_glossy_peak(const BrdfCase& c) {
    return c.surface.perceptual_roughness > 0.0f && ggx_denominator(c) < kPeakDenominator;
}

// D_GGX for this case evaluated in double precision: what both float versions approximate.
double exact_d(const BrdfCase& c) {
    double r = std::clamp(double(c.surface.perceptual_roughness), 0.0, 1.0);
    double a2 = r * r * r * r;
    double f = std::max(ggx_denominator(c), 1e-7);
    return a2 / (3.141592653589793 * f * f);
}

enum class Subset { AwayFromPeak, GlossyPeak };

std::vector<BrdfCase> select(const std::vector<BrdfCase>& all, Subset subset) {
    std::vector<BrdfCase> out;
    for (const auto& c : all)
        if (on_glossy_peak(c) == (subset == Subset::GlossyPeak)) out.push_back(c);
    return out;
}

std::string peak_note(const BrdfCase& c, const Terms& cpu) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "; f = %.3g, D: C++ %.7g, exact (double) %.7g", ggx_denominator(c), cpu.d,
                  exact_d(c));
    return buf;
}

class BrdfValues : public BrdfProbe {
protected:
    // f(l, v) = diffuse + specular per channel.
    void check_brdf(const std::vector<BrdfCase>& cases, bool peak, const fresnel::brdf::BrdfModel& model = {}) {
        std::vector<Case> inputs;
        for (const auto& c : cases) inputs.push_back(to_probe_case(c));
        std::vector<glm::vec4> gpu = probe(kModeBrdf, inputs, fresnel::brdf::brdf_model_defines(model));
        ASSERT_EQ(gpu.size(), cases.size());
        Mismatches bad;
        for (std::size_t i = 0; i < cases.size(); ++i) {
            Terms t = cpu_terms(cases[i], model);
            glm::vec3 cpu = t.diffuse + t.specular;
            for (int k = 0; k < 3; ++k)
                if (!close_rel(gpu[i][k], cpu[k]))
                    bad.add("f[" + std::to_string(k) + "]", gpu[i][k], cpu[k],
                            describe(cases[i]) + (peak ? peak_note(cases[i], t) : ""));
        }
        EXPECT_EQ(bad.count, 0) << bad.count << " of " << 3 * cases.size()
                                << " BRDF channels differ by more than " << kRelTol
                                << " relative (worst " << bad.worst_rel << "):\n" << bad.report();
    }
    // D, V and F.r separately.
    void check_dvf(const std::vector<BrdfCase>& cases, bool peak, const fresnel::brdf::BrdfModel& model = {}) {
        std::vector<Case> inputs;
        for (const auto& c : cases) inputs.push_back(to_probe_case(c));
        std::vector<glm::vec4> gpu = probe(kModeDvf, inputs, fresnel::brdf::brdf_model_defines(model));
        ASSERT_EQ(gpu.size(), cases.size());
        Mismatches bad_d, bad_v, bad_f;
        for (std::size_t i = 0; i < cases.size(); ++i) {
            Terms t = cpu_terms(cases[i], model);
            std::string ctx = describe(cases[i]) + (peak ? peak_note(cases[i], t) : "");
            if (!close_rel(gpu[i].x, t.d)) bad_d.add("D", gpu[i].x, t.d, ctx);
            if (!close_rel(gpu[i].y, t.v)) bad_v.add("V", gpu[i].y, t.v, ctx);
            if (!close_rel(gpu[i].z, t.f.x)) bad_f.add("F.r", gpu[i].z, t.f.x, ctx);
        }
        EXPECT_EQ(bad_d.count, 0) << "D differs in " << bad_d.count << " of " << cases.size()
                                  << " cases (worst relative error " << bad_d.worst_rel << "):\n" << bad_d.report();
        EXPECT_EQ(bad_v.count, 0) << "V differs in " << bad_v.count << " of " << cases.size()
                                  << " cases (worst relative error " << bad_v.worst_rel << "):\n" << bad_v.report();
        EXPECT_EQ(bad_f.count, 0) << "F.r differs in " << bad_f.count << " of " << cases.size()
                                  << " cases (worst relative error " << bad_f.worst_rel << "):\n" << bad_f.report();
    }
};

constexpr unsigned kBrdfSeed = 20240611u;

TEST_F(BrdfValues, GridCoversEdgeCases) {
    auto cases = make_brdf_cases(kGrid * kGrid, kBrdfSeed);
    int rough0 = 0, rough1 = 0, metal0 = 0, metal1 = 0, metal_mid = 0, grazing = 0, below = 0, peak = 0;
    for (const auto& c : cases) {
        rough0 += c.surface.perceptual_roughness == 0.0f;
        rough1 += c.surface.perceptual_roughness == 1.0f;
        metal0 += c.surface.metallic == 0.0f;
        metal1 += c.surface.metallic == 1.0f;
        metal_mid += c.surface.metallic > 0.0f && c.surface.metallic < 1.0f;
        grazing += (c.v.z >= 0.0f && c.v.z < 0.02f) || (c.l.z >= 0.0f && c.l.z < 0.02f);
        below += c.v.z < 0.0f || c.l.z < 0.0f;
        peak += on_glossy_peak(c);
    }
    EXPECT_GT(rough0, 200);
    EXPECT_GT(rough1, 200);
    EXPECT_GT(metal0, 200);
    EXPECT_GT(metal1, 200);
    EXPECT_GT(metal_mid, 200);
    EXPECT_GT(grazing, 500);
    EXPECT_GT(below, 200);
    EXPECT_GT(peak, 20);
    std::printf("grid: %zu cases, roughness 0: %d, 1: %d; metallic 0: %d, 1: %d, between: %d; grazing: %d, "
                "below horizon: %d, on a glossy peak: %d\n",
                cases.size(), rough0, rough1, metal0, metal1, metal_mid, grazing, below, peak);
}

TEST_F(BrdfValues, BrdfMatchesCpp) {
    check_brdf(select(make_brdf_cases(kGrid * kGrid, kBrdfSeed), Subset::AwayFromPeak), false);
}

TEST_F(BrdfValues, DistributionVisibilityFresnelMatchCpp) {
    check_dvf(select(make_brdf_cases(kGrid * kGrid, kBrdfSeed), Subset::AwayFromPeak), false);
}

// The selectable terms (`--brdf`, brdf_model.h): each alternative alone and all together, the
// GLSL (BRDF_* defines) against the C++. Left out: glossy surfaces (roughness < 0.15), where
// Beckmann's exp and Blinn-Phong's power of n.h amplify the last bit of n.h in either language,
// and l nearly opposite to v (|l + v| < 0.1, both at the horizon), where h = normalize(l + v)
// carries the rounding of a tiny sum into v.h, which Kelemen's 1 / (v.h)^2 and the Fresnel terms read.
TEST_F(BrdfValues, AlternativeTermsMatchCpp) {
    using namespace fresnel::brdf;
    std::vector<BrdfCase> cases;
    for (const auto& c : select(make_brdf_cases(kGrid * kGrid, kBrdfSeed), Subset::AwayFromPeak))
        if (c.surface.perceptual_roughness >= 0.15f && glm::length(c.l + c.v) >= 0.1f) cases.push_back(c);
    ASSERT_GT(cases.size(), 2000u);
    std::vector<BrdfModel> models;
    for (int i = 1; i < 3; ++i) models.push_back(BrdfModel{Distribution(i), {}, {}, {}});
    for (int i = 1; i < 5; ++i) models.push_back(BrdfModel{{}, Geometry(i), {}, {}});
    for (int i = 1; i < 4; ++i) models.push_back(BrdfModel{{}, {}, Fresnel(i), {}});
    for (int i = 1; i < 3; ++i) models.push_back(BrdfModel{{}, {}, {}, Diffuse(i)});
    // F=exact with measured metals (their n, k as defines): a noble metal, a transition metal.
    models.push_back(BrdfModel{{}, {}, Fresnel::Exact, {}, Conductor::Gold});
    models.push_back(BrdfModel{{}, {}, Fresnel::Exact, {}, Conductor::Iron});
    models.push_back(BrdfModel{Distribution::BlinnPhong, Geometry::SchlickGgx, Fresnel::ExactDielectric, Diffuse::Burley});
    models.push_back(BrdfModel{Distribution::Beckmann, Geometry::SmithSeparable, Fresnel::Exact, Diffuse::OrenNayar,
                               Conductor::Aluminium});
    for (const BrdfModel& m : models) {
        SCOPED_TRACE(to_string(m));
        check_brdf(cases, false, m);
        check_dvf(cases, false, m);
    }
}

TEST_F(BrdfValues, GlossyPeakBrdfMatchesCpp) {
    check_brdf(select(make_brdf_cases(kGrid * kGrid, kBrdfSeed), Subset::GlossyPeak), true);
}

TEST_F(BrdfValues, GlossyPeakDistributionVisibilityFresnelMatchCpp) {
    check_dvf(select(make_brdf_cases(kGrid * kGrid, kBrdfSeed), Subset::GlossyPeak), true);
}

// ---------------------------------------------------------------------------
// Tone mappers and display encodings, inputs over [0, 64].

std::vector<glm::vec3> make_color_inputs(int count, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u01(0.0f, 1.0f);
    const float special[] = {0.0f, 1e-4f, 0.0031308f, 0.04f, 0.08f, 0.5f, 0.76f, 0.8f, 1.0f, 2.0f, 16.0f, 64.0f};
    auto channel = [&]() -> float {
        switch (int(u01(rng) * 5.0f) % 5) {
            case 0: return special[int(u01(rng) * 12.0f) % 12];
            case 1: return std::exp2(-14.0f + 20.0f * u01(rng));  // log-uniform 6e-5 .. 64
            case 2: return 64.0f * u01(rng);
            default: return u01(rng);
        }
    };
    std::vector<glm::vec3> out;
    out.reserve(std::size_t(count));
    for (int i = 0; i < count; ++i) {
        if (i % 8 == 0) {  // greys: the neutral mapper's equal-channel path
            float g = channel();
            out.emplace_back(g);
        } else {
            out.emplace_back(channel(), channel(), channel());
        }
    }
    return out;
}

std::string vec_str(glm::vec3 v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.7g, %.7g, %.7g)", v.x, v.y, v.z);
    return buf;
}

TEST_F(BrdfProbe, ToneMappersMatchCpp) {
    using fresnel::ToneMapper;
    const ToneMapper mappers[] = {ToneMapper::Neutral, ToneMapper::Aces, ToneMapper::AcesHill,
                                  ToneMapper::Reinhard, ToneMapper::Agx, ToneMapper::None};
    auto colors = make_color_inputs(kGrid * kGrid, 4242u);
    for (ToneMapper m : mappers) {
        SCOPED_TRACE(std::string("tone mapper ") + std::string(fresnel::tone_mapper_name(m)));
        std::vector<Case> inputs;
        for (const auto& c : colors) inputs.push_back({glm::vec4(c, 1.0f), glm::vec4(float(int(m)), 0, 0, 0), glm::vec4(0)});
        std::vector<glm::vec4> gpu = probe(kModeToneMap, inputs);
        ASSERT_EQ(gpu.size(), colors.size());
        Mismatches bad;
        float worst = 0.0f;
        for (std::size_t i = 0; i < colors.size(); ++i) {
            glm::vec3 cpu = fresnel::tone_map(m, colors[i]);
            for (int k = 0; k < 3; ++k) {
                float err = std::fabs(gpu[i][k] - cpu[k]);
                if (!(err <= kColorAbsTol)) bad.add("channel " + std::to_string(k), gpu[i][k], cpu[k], "input " + vec_str(colors[i]));
                if (err > worst || std::isnan(err)) worst = std::isnan(err) ? INFINITY : err;
            }
        }
        EXPECT_EQ(bad.count, 0) << bad.count << " channels differ by more than " << kColorAbsTol
                                << " (worst " << worst << "):\n" << bad.report();
    }
}

TEST_F(BrdfProbe, DisplayEncodingsMatchCpp) {
    using fresnel::Encoding;
    auto colors = make_color_inputs(kGrid * kGrid, 31337u);
    for (Encoding e : {Encoding::Srgb, Encoding::Gamma22}) {
        SCOPED_TRACE(e == Encoding::Srgb ? "encoding srgb" : "encoding gamma2.2");
        std::vector<Case> inputs;
        for (const auto& c : colors) inputs.push_back({glm::vec4(c, 1.0f), glm::vec4(float(int(e)), 0, 0, 0), glm::vec4(0)});
        std::vector<glm::vec4> gpu = probe(kModeEncode, inputs);
        ASSERT_EQ(gpu.size(), colors.size());
        Mismatches bad;
        float worst = 0.0f;
        for (std::size_t i = 0; i < colors.size(); ++i) {
            glm::vec3 cpu = fresnel::encode_display(e, colors[i]);
            for (int k = 0; k < 3; ++k) {
                float err = std::fabs(gpu[i][k] - cpu[k]);
                if (!(err <= kColorAbsTol)) bad.add("channel " + std::to_string(k), gpu[i][k], cpu[k], "input " + vec_str(colors[i]));
                if (err > worst || std::isnan(err)) worst = std::isnan(err) ? INFINITY : err;
            }
        }
        EXPECT_EQ(bad.count, 0) << bad.count << " channels differ by more than " << kColorAbsTol
                                << " (worst " << worst << "):\n" << bad.report();
    }
}

}  // namespace

// ---------------------------------------------------------------------------
// KHR_materials_clearcoat: the coat lobe and the layering weight, GLSL against C++.

TEST_F(BrdfProbe, ClearcoatMatchesCpp) {
    std::mt19937 rng(2024);
    std::uniform_real_distribution<float> u01(0.0f, 1.0f);
    const float two_pi = 2.0f * fresnel::brdf::kPi;
    struct CoatCase {
        glm::vec3 nc, v, l;
        float roughness, clearcoat, f0;
    };
    std::vector<CoatCase> cases;
    std::vector<Case> inputs;
    for (int i = 0; i < kGrid * 32; ++i) {
        CoatCase c;
        c.nc = direction(0.7f + 0.3f * u01(rng), two_pi * u01(rng));  // a coat normal map tilts it
        c.v = direction(i % 17 == 0 ? 0.0f : u01(rng), two_pi * u01(rng));
        c.l = i % 11 == 0 ? glm::normalize(glm::vec3(-c.v.x, -c.v.y, c.v.z)) : direction(u01(rng) * 1.2f - 0.2f, two_pi * u01(rng));
        c.roughness = i % 9 == 0 ? 1.0f : 0.05f + 0.95f * u01(rng);
        c.clearcoat = i % 7 == 0 ? 1.0f : u01(rng);
        c.f0 = i % 5 == 0 ? 0.04f : 0.1f * u01(rng);
        cases.push_back(c);
        inputs.push_back({glm::vec4(c.l, c.roughness), glm::vec4(c.v, c.clearcoat), glm::vec4(c.nc, c.f0)});
    }
    std::vector<glm::vec4> gpu = probe(kModeClearcoat, inputs);
    ASSERT_EQ(gpu.size(), cases.size());
    Mismatches bad;
    int lit = 0;
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const CoatCase& c = cases[i];
        glm::vec3 nc = glm::normalize(c.nc), v = glm::normalize(c.v), l = glm::normalize(c.l);
        float spec = fresnel::brdf::clearcoat_specular(nc, v, l, fresnel::brdf::alpha_from_roughness(c.roughness));
        float mix = fresnel::brdf::clearcoat_mix(c.clearcoat, c.f0, nc, v);
        ASSERT_GE(spec, 0.0f);
        ASSERT_LE(mix, c.clearcoat + 1e-6f);  // the coat never takes more than its weight
        lit += spec > 0.0f;
        std::string ctx = "case " + std::to_string(i) + ", roughness " + std::to_string(c.roughness);
        if (!close_rel(gpu[i].x, spec)) bad.add("coat specular", gpu[i].x, spec, ctx);
        if (!close_rel(gpu[i].y, mix)) bad.add("coat weight", gpu[i].y, mix, ctx);
    }
    EXPECT_GT(lit, int(cases.size()) / 2) << "most cases should light the coat";
    EXPECT_EQ(bad.count, 0) << bad.report();
}
