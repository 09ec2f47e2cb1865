// The path tracer's samplers against their pdfs, chi-squared goodness of fit as in
// libs/material/tests/sampling_test.cpp (pbrt-v4's and Mitsuba's test: expected counts
// integrated from the pdf on a fine grid, cells expecting fewer than 5 pooled, Bonferroni-
// corrected significance), here over the whole sphere of directions:
//   - GGX visible-normal reflection (sampling::sample_ggx_reflection / pdf_ggx_reflection),
//     whose samples below the horizon are lost: they fall in one extra cell that expects
//     1 - (the pdf's integral);
//   - cosine-weighted directions (sampling::sample_cosine);
//   - the BSDF mixture of the tracer (sample_bsdf / pdf_bsdf) for dielectrics,
//     metals and a clearcoat with a tilted coat normal;
//   - the environment's 2-D piecewise-constant distribution (EnvironmentLight::sample / pdf),
//     in cells of the panorama's own pixels (where its density is constant).
// Each also has a test that the harness rejects a slightly wrong sampler.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "chi2.h"
#include "fresnel/material/sampling.h"
#include "fresnel/material/bsdf.h"
#include "fresnel/trace/distribution.h"
#include "fresnel/trace/environment_light.h"

using namespace fresnel;

namespace {

constexpr double kPiD = 3.14159265358979323846;

// The chi-squared test's statistic and tail: tests/support/chi2.h.
using fresnel::test::chi2_from_counts;
using fresnel::test::Chi2Result;

// A distribution over directions: pdf over solid angle, and a sampler from [0,1)^3 that may
// return false (a lost sample: below the surface, absorbed).
struct SphereDistribution {
    std::string name;
    std::function<double(glm::vec3)> pdf;
    std::function<bool(glm::vec3, glm::vec3&)> sample;
};

glm::vec3 dir(double z, double phi) {
    double s = std::sqrt(std::max(0.0, 1.0 - z * z));
    return {float(s * std::cos(phi)), float(s * std::sin(phi)), float(z)};
}

// Cells: n_z bands of cos(theta) in [-1, 1], of equal width except that the upper hemisphere's
// top bands are split finer (narrow lobes live near z = 1), n_phi sectors; plus the lost cell.
// Expected counts from a midpoint grid of sub x sub points per cell (dz dphi: the area element).
Chi2Result chi2_sphere(const SphereDistribution& d, int samples, std::uint32_t seed) {
    std::vector<double> z_edges;
    const int coarse = 32;
    for (int i = 0; i <= coarse - 4; ++i) z_edges.push_back(-1.0 + 2.0 * i / coarse);  // up to z = 0.75
    for (double e : {0.8, 0.85, 0.9, 0.93, 0.95, 0.97, 0.98, 0.99, 0.995, 0.998, 1.0}) z_edges.push_back(e);
    const int n_z = int(z_edges.size()) - 1, n_phi = 32, sub = 24;
    std::vector<double> expected(std::size_t(n_z * n_phi) + 1, 0.0), observed(expected.size(), 0.0);
    double total = 0;
    for (int b = 0; b < n_z; ++b) {
        double z0 = z_edges[std::size_t(b)], dz = (z_edges[std::size_t(b) + 1] - z0) / sub, dp = 2.0 * kPiD / (n_phi * sub);
        for (int s = 0; s < n_phi; ++s) {
            double sum = 0;
            for (int i = 0; i < sub; ++i)
                for (int j = 0; j < sub; ++j) sum += d.pdf(dir(z0 + (i + 0.5) * dz, (s * sub + j + 0.5) * dp));
            double e = sum * dz * dp * samples;
            expected[std::size_t(b * n_phi + s)] = e;
            total += e;
        }
    }
    expected.back() = std::max(0.0, samples - total);  // lost samples
    if (expected.back() < 1e-3 * samples) expected.back() = 0.0;  // quadrature error, not a lost mass
    std::mt19937 rng(seed);
    auto uniform = [&rng] { return float(rng() >> 8) * 0x1p-24f; };
    for (int i = 0; i < samples; ++i) {
        glm::vec3 u(uniform(), uniform(), uniform()), w;
        if (!d.sample(u, w)) {
            observed.back() += 1;
            continue;
        }
        double z = std::clamp(double(w.z), -1.0, 1.0);
        double phi = std::atan2(double(w.y), double(w.x));
        if (phi < 0) phi += 2.0 * kPiD;
        int b = int(std::upper_bound(z_edges.begin(), z_edges.end(), z) - z_edges.begin()) - 1;
        b = std::clamp(b, 0, n_z - 1);
        int s = std::min(int(phi / (2.0 * kPiD) * n_phi), n_phi - 1);
        observed[std::size_t(b * n_phi + s)] += 1;
    }
    if (getenv("CHI2_DEBUG"))
        for (std::size_t i = 0; i < expected.size(); ++i)
            if ((observed[i] - expected[i]) * (observed[i] - expected[i]) > 100 * std::max(expected[i], 1.0))
                std::printf("cell %zu (band %zu sector %zu) obs %.0f exp %.1f\n", i, i / 32, i % 32, observed[i], expected[i]);
    return chi2_from_counts(observed, expected, samples);
}

glm::vec3 view(double theta_deg, double phi = 0.7) { return dir(std::cos(theta_deg * kPiD / 180.0), phi); }

SphereDistribution ggx_reflection(float alpha, double view_deg) {
    glm::vec3 v = view(view_deg);
    return {"ggx_reflection alpha " + std::to_string(alpha) + " view " + std::to_string(view_deg),
            [=](glm::vec3 l) { return l.z > 0 ? double(sampling::pdf_ggx_reflection(v, l, alpha)) : 0.0; },
            [=](glm::vec3 u, glm::vec3& l) {
                l = sampling::sample_ggx_reflection(v, glm::vec2(u.x, u.y), alpha);
                return l.z > 0.0f;
            }};
}

SphereDistribution cosine() {
    return {"cosine", [](glm::vec3 l) { return double(sampling::pdf_cosine(l)); },
            [](glm::vec3 u, glm::vec3& l) {
                l = sampling::sample_cosine(glm::vec2(u.x, u.y));
                return true;
            }};
}

EvaluatedMaterial material(float metallic, float roughness, float clearcoat = 0.0f) {
    EvaluatedMaterial m;
    m.surface.base_color = glm::vec3(0.8f, 0.5f, 0.3f);
    m.surface.metallic = metallic;
    m.surface.perceptual_roughness = roughness;
    m.normal = glm::vec3(0, 0, 1);
    if (clearcoat > 0.0f) {
        m.clearcoat = clearcoat;
        m.clearcoat_roughness = 0.3f;
        m.clearcoat_normal = glm::normalize(glm::vec3(0.2f, -0.1f, 1.0f));
    }
    return m;
}

SphereDistribution bsdf(const std::string& name, const EvaluatedMaterial& m, double view_deg) {
    glm::vec3 v = view(view_deg);
    return {"bsdf " + name + " view " + std::to_string(view_deg),
            [=](glm::vec3 l) { return double(pdf_bsdf(m, v, l)); },
            [=](glm::vec3 u, glm::vec3& l) {
                BsdfSample s = sample_bsdf(m, v, u);
                l = s.l;
                return s.pdf > 0.0f;
            }};
}

std::vector<SphereDistribution> all_distributions() {
    std::vector<SphereDistribution> out;
    for (float a : {0.1f, 0.3f, 0.6f, 1.0f})
        for (double v : {0.0, 45.0, 80.0}) out.push_back(ggx_reflection(a, v));
    out.push_back(cosine());
    for (double v : {10.0, 60.0, 85.0}) {
        out.push_back(bsdf("dielectric r0.5", material(0.0f, 0.5f), v));
        out.push_back(bsdf("metal r0.3", material(1.0f, 0.3f), v));
        out.push_back(bsdf("half-metal r0.8 clearcoat", material(0.5f, 0.8f, 1.0f), v));
    }
    // KHR_materials_diffuse_transmission: the cosine lobe about -n joins the mixture.
    EvaluatedMaterial leaf = material(0.0f, 0.5f);
    leaf.diffuse_transmission = 0.7f;
    leaf.diffuse_transmission_color = glm::vec3(0.4f, 0.9f, 0.2f);
    for (double v : {10.0, 60.0}) out.push_back(bsdf("diffuse transmission r0.5", leaf, v));
    return out;
}

constexpr int kSamples = 400000;

}  // namespace

TEST(TraceSamplerChi2, EveryDirectionSamplerDrawsFromItsPdf) {
    auto dists = all_distributions();
    const double significance = 0.01 / double(dists.size());
    std::uint32_t seed = 11;
    for (const auto& d : dists) {
        Chi2Result r = chi2_sphere(d, kSamples, seed++);
        EXPECT_TRUE(r.message.empty()) << d.name << ": " << r.message;
        EXPECT_GT(r.dof, 50) << d.name;
        std::printf("%-50s chi2 %8.1f  dof %4d  p-value %.3g\n", d.name.c_str(), r.chi2, r.dof, r.p_value);
        EXPECT_GE(r.p_value, significance) << d.name;
    }
}

TEST(TraceSamplerChi2, CatchesAWrongDirectionSampler) {
    struct Case {
        SphereDistribution pdf_of, sampler_of;
    };
    std::vector<Case> cases = {
        {ggx_reflection(0.3f, 45.0), ggx_reflection(0.32f, 45.0)},
        {ggx_reflection(0.5f, 80.0), ggx_reflection(0.5f, 75.0)},
        {bsdf("a", material(0.0f, 0.5f), 60.0), bsdf("b", material(0.0f, 0.55f), 60.0)},
        {bsdf("a", material(0.5f, 0.8f, 1.0f), 30.0), bsdf("b", material(0.5f, 0.8f, 0.8f), 30.0)},
    };
    for (const auto& c : cases) {
        SphereDistribution mixed{c.pdf_of.name + " sampled as " + c.sampler_of.name, c.pdf_of.pdf, c.sampler_of.sample};
        Chi2Result r = chi2_sphere(mixed, kSamples, 5);
        std::printf("%-80s chi2 %8.1f  p-value %.3g\n", mixed.name.c_str(), r.chi2, r.p_value);
        EXPECT_TRUE(!r.message.empty() || r.p_value < 1e-6) << mixed.name;
    }
}

namespace {

// A test panorama: a dim sky gradient, a bright sun disc and a small bright square, 64x32
// (or wider: above 512 pixels the distribution's cells are 2x2 pixels).
ImageF test_panorama(int width = 64, int height = 32) {
    ImageF p(width, height);
    for (int y = 0; y < p.height; ++y)
        for (int x = 0; x < p.width; ++x) {
            float* t = p.at(x, y);
            float v = 0.1f + 0.5f * float(p.height - y) / float(p.height);
            float dx = float(x - 20 * width / 64), dy = float(y - 8 * height / 32);
            if (dx * dx + dy * dy < 6.0f) v = 50.0f;
            if (x >= 50 * width / 64 && x < 53 * width / 64 && y >= 20 * height / 32 && y < 22 * height / 32) v = 20.0f;
            if (y == height - 1) v = 0.0f;
            t[0] = v;
            t[1] = 0.8f * v;
            t[2] = 0.6f * v;
            t[3] = 1.0f;
        }
    return p;
}

// Cells: the panorama's pixels in the environment's frame; the expected count of a pixel is
// the integral of pdf(dir) over it, a midpoint rule in (u, v) with the Jacobian
// 2 pi^2 sin(theta) (4 x 4 points per pixel).
Chi2Result chi2_environment(const trace::EnvironmentLight& env, const std::function<trace::EnvironmentLight::Sample(glm::vec2)>& sampler,
                            int samples, std::uint32_t seed) {
    const int w = env.panorama().width, h = env.panorama().height, sub = 4;
    std::vector<double> expected(std::size_t(w) * h, 0.0), observed(expected.size(), 0.0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double sum = 0;
            for (int i = 0; i < sub; ++i)
                for (int j = 0; j < sub; ++j) {
                    double u = (x + (j + 0.5) / sub) / w, v = (y + (i + 0.5) / sub) / h;
                    double theta = v * kPiD, phi = (u - 0.5) * 2.0 * kPiD;
                    glm::vec3 e(float(-std::sin(theta) * std::sin(phi)), float(std::cos(theta)), float(std::sin(theta) * std::cos(phi)));
                    sum += env.pdf(env.to_world(e)) * 2.0 * kPiD * kPiD * std::sin(theta);
                }
            expected[std::size_t(y) * w + x] = sum / (sub * sub) / (double(w) * h) * samples;
        }
    std::mt19937 rng(seed);
    auto uniform = [&rng] { return float(rng() >> 8) * 0x1p-24f; };
    for (int i = 0; i < samples; ++i) {
        trace::EnvironmentLight::Sample s = sampler(glm::vec2(uniform(), uniform()));
        if (s.pdf <= 0.0f) continue;
        glm::vec3 e = env.to_environment(s.direction);
        double u = 0.5 + std::atan2(-double(e.x), double(e.z)) / (2.0 * kPiD);
        double v = std::acos(std::clamp(double(e.y), -1.0, 1.0)) / kPiD;
        int x = std::clamp(int(u * w), 0, w - 1), y = std::clamp(int(v * h), 0, h - 1);
        observed[std::size_t(y) * w + x] += 1;
    }
    return chi2_from_counts(observed, expected, samples);
}

}  // namespace

TEST(TraceSamplerChi2, EnvironmentDrawsFromItsPdf) {
    for (float rotation : {0.0f, 37.0f}) {
        trace::EnvironmentLight env(test_panorama(), rotation, 2.0f);
        Chi2Result r = chi2_environment(env, [&](glm::vec2 u) { return env.sample(u); }, kSamples, 3);
        EXPECT_TRUE(r.message.empty()) << r.message;
        std::printf("environment rotation %.0f: chi2 %8.1f  dof %4d  p-value %.3g\n", rotation, r.chi2, r.dof, r.p_value);
        EXPECT_GT(r.dof, 1000);
        EXPECT_GE(r.p_value, 0.005);
    }
    // A wide panorama, whose distribution has cells of 2x2 pixels.
    trace::EnvironmentLight wide(test_panorama(1024, 32), 10.0f);
    Chi2Result r = chi2_environment(wide, [&](glm::vec2 u) { return wide.sample(u); }, kSamples, 4);
    EXPECT_TRUE(r.message.empty()) << r.message;
    std::printf("environment 1024x32: chi2 %8.1f  dof %4d  p-value %.3g\n", r.chi2, r.dof, r.p_value);
    EXPECT_GT(r.dof, 1000);
    EXPECT_GE(r.p_value, 0.005);
}

TEST(TraceSamplerChi2, CatchesAWrongEnvironmentSampler) {
    // Samples of one rotation checked against the pdf of another, 2 degrees apart.
    trace::EnvironmentLight env(test_panorama(), 0.0f), turned(test_panorama(), 2.0f);
    Chi2Result r = chi2_environment(env, [&](glm::vec2 u) { return turned.sample(u); }, kSamples, 3);
    EXPECT_TRUE(!r.message.empty() || r.p_value < 1e-6) << r.chi2;
}

TEST(EnvironmentLight, SampleAgreesWithPdfAndRadiance) {
    trace::EnvironmentLight env(test_panorama(), 20.0f, 3.0f);
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    double integral = 0;  // E[1 / pdf] over samples = 4 pi where the pdf is positive everywhere
    const int n = 200000;
    int pdf_mismatches = 0;  // samples at a pixel's edge may round into its neighbour
    for (int i = 0; i < n; ++i) {
        auto s = env.sample({U(rng), U(rng)});
        ASSERT_GT(s.pdf, 0.0f);
        ASSERT_NEAR(glm::length(s.direction), 1.0f, 1e-4f);
        if (std::fabs(s.pdf - env.pdf(s.direction)) > 1e-3f * s.pdf) ++pdf_mismatches;
        glm::vec3 r = env.radiance(s.direction);
        EXPECT_NEAR(s.radiance.x, r.x, 1e-3f * std::max(1.0f, r.x));
        integral += 1.0 / s.pdf;
    }
    EXPECT_LT(pdf_mismatches, n / 200);
    EXPECT_NEAR(integral / n, 4.0 * kPiD, 0.05 * 4.0 * kPiD);
    // The renderer's orientation at rotation 0: +Z is the panorama's centre column (u = 0.5),
    // +Y its top row; turning by +90 degrees brings what was at -X (u = 0.75) to +Z.
    ImageF p(8, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) p.at(x, y)[0] = float(x), p.at(x, y)[3] = 1.0f;
    trace::EnvironmentLight plain(p, 0.0f), turned(p, 90.0f);
    const float phi = 0.0625f * 2.0f * 3.14159265f;  // u = 0.5625, the centre of texel 4
    EXPECT_NEAR(plain.radiance({-std::sin(phi), 0, std::cos(phi)}).x, 4.0f, 1e-6f);
    EXPECT_NEAR(plain.radiance({-1, 0, 0}).x, 6.0f, 1e-6f);  // -X: u = 0.75, texel 6
    EXPECT_NEAR(turned.radiance({0, 0, 1}).x, plain.radiance({-1, 0, 0}).x, 1e-4f);
}

TEST(Distribution2D, PdfMatchesSampledFrequencies) {
    std::vector<float> w = {0, 1, 2, 0, 3, 0, 1, 1};
    trace::Distribution2D d(w, 4, 2);
    std::mt19937 rng(2);
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    std::vector<int> counts(8, 0);
    const int n = 80000;
    for (int i = 0; i < n; ++i) {
        float pdf = 0;
        glm::vec2 uv = d.sample({U(rng), U(rng)}, pdf);
        int x = std::min(int(uv.x * 4), 3), y = std::min(int(uv.y * 2), 1);
        ++counts[std::size_t(y * 4 + x)];
        ASSERT_NEAR(pdf, d.pdf(uv), 1e-5f);
    }
    for (int i = 0; i < 8; ++i) {
        EXPECT_NEAR(double(counts[std::size_t(i)]) / n, w[std::size_t(i)] / 8.0, 0.01) << i;
        if (w[std::size_t(i)] == 0) {
            EXPECT_EQ(counts[std::size_t(i)], 0) << i;
        }
    }
}
