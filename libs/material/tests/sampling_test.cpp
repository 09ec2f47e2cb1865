// Tests of the sampling routines (fresnel/material/sampling.h) in the style of pbrt-v4's
// bsdfs_test and Mitsuba's chi2 test:
//  - every pdf integrates to 1 over its domain (midpoint quadrature in (theta, phi),
//    independent of the samplers);
//  - every sampler draws from its pdf: a chi-squared goodness-of-fit test of 5 x 10^5 samples
//    against expected counts integrated from the pdf over cells in (cos theta, phi), cells
//    with expected counts below 5 pooled, the p-value from the chi-squared distribution and
//    a Bonferroni-corrected significance level;
//  - the test catches a wrong sampler (a sampler tested against a slightly different pdf);
//  - basis() is orthonormal.
// A fixed-seed std::mt19937 makes every run draw the same samples.
#include "fresnel/material/sampling.h"

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

using namespace fresnel;

namespace {

constexpr double kPiD = 3.14159265358979323846;

// The chi-squared distribution's upper tail and the pooled statistic: tests/support/chi2.h.
using fresnel::test::chi2_from_counts;
using fresnel::test::chi2_p_value;
using fresnel::test::Chi2Result;

TEST(Chi2Distribution, MatchesClosedForms) {
    // dof 2: exp(-x/2); dof 1: erfc(sqrt(x/2)); dof 4: (1 + x/2) exp(-x/2).
    for (double x : {0.01, 0.5, 1.0, 2.0, 3.0, 7.5, 20.0, 60.0}) {
        EXPECT_NEAR(chi2_p_value(x, 2), std::exp(-x / 2), 1e-12) << x;
        EXPECT_NEAR(chi2_p_value(x, 1), std::erfc(std::sqrt(x / 2)), 1e-12) << x;
        EXPECT_NEAR(chi2_p_value(x, 4), (1 + x / 2) * std::exp(-x / 2), 1e-12) << x;
    }
    // Tabulated quantiles: P(X >= 124.342) = 0.05 at 100 dof, P(X >= 1106.97) = 0.01 at 1000 dof.
    EXPECT_NEAR(chi2_p_value(124.342, 100), 0.05, 1e-5);
    EXPECT_NEAR(chi2_p_value(1106.97, 1000), 0.01, 1e-4);
    // The median of a chi-squared sits near dof (1 - 2 / (9 dof))^3.
    for (int dof : {10, 300, 3000}) {
        double median = dof * std::pow(1.0 - 2.0 / (9.0 * dof), 3.0);
        EXPECT_NEAR(chi2_p_value(median, dof), 0.5, 0.01) << dof;
    }
}

// ---------------------------------------------------------------------------
// Distributions over directions around +Z, as (pdf, sampler) pairs.

struct Distribution {
    std::string name;
    std::function<double(glm::vec3)> pdf;                 // over solid angle
    std::function<glm::vec3(glm::vec2)> sample;           // from a uniform point in [0,1)^2
};

glm::vec3 dir(double cos_theta, double phi) {
    double s = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    return {float(s * std::cos(phi)), float(s * std::sin(phi)), float(cos_theta)};
}

glm::vec3 view(double theta_deg, double phi = 0.7) { return dir(std::cos(theta_deg * kPiD / 180.0), phi); }

Distribution ggx_half(float alpha) {
    return {"ggx_half alpha " + std::to_string(alpha),
            [alpha](glm::vec3 h) { return h.z > 0 ? double(sampling::pdf_ggx_half(h, alpha)) : 0.0; },
            [alpha](glm::vec2 u) { return sampling::sample_ggx_half(u, alpha); }};
}

Distribution ggx_vndf(float alpha, double view_deg) {
    glm::vec3 v = view(view_deg);
    return {"ggx_vndf alpha " + std::to_string(alpha) + " view " + std::to_string(view_deg) + " deg",
            [alpha, v](glm::vec3 h) { return h.z > 0 ? double(sampling::pdf_ggx_vndf(v, h, alpha)) : 0.0; },
            [alpha, v](glm::vec2 u) { return sampling::sample_ggx_vndf(v, u, alpha); }};
}

Distribution cosine() {
    return {"cosine", [](glm::vec3 l) { return double(sampling::pdf_cosine(l)); },
            [](glm::vec2 u) { return sampling::sample_cosine(u); }};
}

const std::vector<float> kAlphas = {0.05f, 0.2f, 0.5f, 1.0f};
const std::vector<double> kViewsDeg = {0.0, 45.0, 80.0, 89.0};  // 89: grazing

std::vector<Distribution> all_distributions() {
    std::vector<Distribution> out;
    for (float a : kAlphas) out.push_back(ggx_half(a));
    for (float a : kAlphas)
        for (double v : kViewsDeg) out.push_back(ggx_vndf(a, v));
    out.push_back(cosine());
    return out;
}

// The integral of a pdf over the sphere: midpoint rule in (theta, phi) with sin(theta)
// as the Jacobian, fine in theta for the narrow GGX lobes (alpha 0.05: width ~ 0.05 rad).
double integrate_sphere(const std::function<double(glm::vec3)>& pdf, int n_theta = 2048, int n_phi = 128) {
    double sum = 0;
    const double dt = kPiD / n_theta, dp = 2.0 * kPiD / n_phi;
    for (int i = 0; i < n_theta; ++i) {
        double t = (i + 0.5) * dt, row = 0;
        for (int j = 0; j < n_phi; ++j) row += pdf(dir(std::cos(t), (j + 0.5) * dp));
        sum += row * std::sin(t);
    }
    return sum * dt * dp;
}

TEST(SamplingPdf, IntegratesToOne) {
    for (const auto& d : all_distributions()) EXPECT_NEAR(integrate_sphere(d.pdf), 1.0, 2e-3) << d.name;
}

TEST(SamplingPdf, QuadratureCatchesAWrongNormalisation) {
    // D(h) alone (without h.z) is not a pdf over directions: its integral is not 1.
    double d_only = integrate_sphere([](glm::vec3 h) { return h.z > 0 ? double(brdf::d_ggx(h.z, 0.5f)) : 0.0; });
    EXPECT_GT(std::fabs(d_only - 1.0), 0.05) << d_only;
    // The VNDF without G1(v) neither, away from normal incidence.
    glm::vec3 v = view(80.0);
    double no_g1 = integrate_sphere([v](glm::vec3 h) {
        return h.z > 0 ? double(sampling::pdf_ggx_vndf(v, h, 0.5f) / sampling::smith_g1(v, 0.5f)) : 0.0;
    });
    EXPECT_GT(std::fabs(no_g1 - 1.0), 0.05) << no_g1;
}

// ---------------------------------------------------------------------------
// The chi-squared test.

// Cells: n_cos bands of the upper hemisphere in theta with equal-ish probability, one band
// for the lower hemisphere (where every pdf here is 0), n_phi equal sectors in phi. The pdf
// is integrated once on a fine midpoint grid in (theta, phi) (sin theta as the Jacobian),
// n_fine rows in theta over the upper hemisphere, sub_phi columns per sector. The band edges
// fall on rows of that grid, at quantiles of the marginal in theta; each cell's expected
// count is the sum of its grid points times the sample count.
Chi2Result chi2_test(const Distribution& d, int samples, std::uint32_t seed, int n_cos = 24, int n_phi = 24) {
    const int n_fine = 2048, sub_phi = 8;
    const double dt = 0.5 * kPiD / n_fine, dp = 2.0 * kPiD / (n_phi * sub_phi);
    std::vector<double> row_sector(std::size_t(n_fine * n_phi), 0.0);  // integral over (row, sector)
    std::vector<double> cdf(n_fine + 1, 0.0);
    for (int i = 0; i < n_fine; ++i) {
        double t = (i + 0.5) * dt, c = std::cos(t), w = std::sin(t) * dt * dp, row = 0;
        for (int s = 0; s < n_phi; ++s) {
            double sum = 0;
            for (int j = 0; j < sub_phi; ++j) sum += d.pdf(dir(c, (s * sub_phi + j + 0.5) * dp));
            row_sector[std::size_t(i * n_phi + s)] = sum * w;
            row += sum * w;
        }
        cdf[i + 1] = cdf[i] + row;
    }
    // Band b covers rows [first_row[b], first_row[b + 1]); the last band is the lower hemisphere.
    std::vector<int> first_row = {0};
    for (int k = 1; k < n_cos; ++k) {
        int i = int(std::lower_bound(cdf.begin(), cdf.end(), cdf[n_fine] * k / n_cos) - cdf.begin());
        if (i > first_row.back() && i < n_fine) first_row.push_back(i);
    }
    first_row.push_back(n_fine);
    const int bands = int(first_row.size());  // upper bands + the lower hemisphere
    std::vector<double> edges_cos;            // lower cos theta edge of each upper band
    for (int b = 0; b + 1 < bands; ++b) edges_cos.push_back(std::cos(first_row[b + 1] * dt));
    edges_cos.back() = 0.0;  // the horizon, exactly
    std::vector<double> expected(std::size_t(bands * n_phi), 0.0);
    for (int b = 0; b + 1 < bands; ++b)
        for (int i = first_row[b]; i < first_row[b + 1]; ++i)
            for (int s = 0; s < n_phi; ++s)
                expected[std::size_t(b * n_phi + s)] += row_sector[std::size_t(i * n_phi + s)] * samples;

    // Observed counts.
    std::mt19937 rng(seed);
    auto uniform = [&rng] { return float(rng() >> 8) * 0x1p-24f; };  // [0, 1), exactly 24 bits
    std::vector<double> observed(expected.size(), 0.0);
    for (int i = 0; i < samples; ++i) {
        glm::vec2 u(uniform(), uniform());
        glm::vec3 w = d.sample(u);
        double len = glm::length(w);
        if (!std::isfinite(len) || std::fabs(len - 1.0) > 1e-3) {
            Chi2Result r;
            r.message = "sample " + std::to_string(i) + " is not a unit vector (length " + std::to_string(len) + ")";
            return r;
        }
        double c = std::clamp(double(w.z) / len, -1.0, 1.0);
        double phi = std::atan2(double(w.y), double(w.x));
        if (phi < 0) phi += 2.0 * kPiD;
        int b = 0;  // the first band whose lower edge lies below c (the last: below the horizon)
        while (b < bands - 1 && c < edges_cos[std::size_t(b)]) ++b;
        int s = std::min(int(phi / (2.0 * kPiD) * n_phi), n_phi - 1);
        observed[std::size_t(b * n_phi + s)] += 1.0;
    }

    return chi2_from_counts(observed, expected, samples);
}

constexpr int kSamples = 500000;

TEST(SamplingChi2, EverySamplerDrawsFromItsPdf) {
    auto dists = all_distributions();
    // Bonferroni: the family of tests together fails by chance at most 1 % of the time.
    const double significance = 0.01 / double(dists.size());
    std::uint32_t seed = 1;
    for (const auto& d : dists) {
        Chi2Result r = chi2_test(d, kSamples, seed++);
        EXPECT_TRUE(r.message.empty()) << d.name << ": " << r.message;
        EXPECT_GT(r.dof, 100) << d.name << ": too few cells to say much";
        std::printf("%-40s chi2 %8.1f  dof %3d  p-value %.3g\n", d.name.c_str(), r.chi2, r.dof, r.p_value);
        EXPECT_GE(r.p_value, significance) << d.name << ": chi2 " << r.chi2 << " with " << r.dof << " dof, p-value "
                                           << r.p_value << " < " << significance;
    }
}

TEST(SamplingChi2, CatchesAWrongSampler) {
    // Samplers checked against pdfs that differ a little: each must be rejected clearly.
    struct Case {
        Distribution pdf_of, sampler_of;
    };
    std::vector<Case> cases = {
        {ggx_half(0.30f), ggx_half(0.32f)},            // roughness off by 3 %
        {ggx_vndf(0.5f, 80.0), ggx_vndf(0.5f, 75.0)},  // view direction off by 5 degrees
        {ggx_vndf(0.5f, 45.0), ggx_vndf(0.53f, 45.0)}, // roughness off by 6 % (same support)
        {ggx_vndf(0.5f, 60.0), ggx_half(0.5f)},        // D sampling where the VNDF is due
    };
    // A cosine lobe raised to the power 1.1 instead of 1.
    Distribution wrong_cosine = cosine();
    wrong_cosine.name = "cosine^1.1";
    wrong_cosine.sample = [](glm::vec2 u) {
        float z = std::pow(1.0f - u.x, 1.0f / 2.1f);
        float r = std::sqrt(std::max(0.0f, 1.0f - z * z)), phi = 2.0f * brdf::kPi * u.y;
        return glm::vec3(r * std::cos(phi), r * std::sin(phi), z);
    };
    cases.push_back({cosine(), wrong_cosine});
    for (const auto& c : cases) {
        Distribution mixed{c.pdf_of.name + " sampled as " + c.sampler_of.name, c.pdf_of.pdf, c.sampler_of.sample};
        Chi2Result r = chi2_test(mixed, kSamples, 12345);
        std::printf("%-60s chi2 %8.1f  dof %3d  p-value %.3g\n", mixed.name.c_str(), r.chi2, r.dof, r.p_value);
        // Rejected either by the chi-squared statistic or outright (samples where the pdf is 0).
        EXPECT_LT(r.p_value, 1e-6) << mixed.name << ": chi2 " << r.chi2 << " with " << r.dof << " dof";
    }
}

TEST(SamplingChi2, RejectsSamplesWherePdfIsZero) {
    // The VNDF has no normals facing away from v; a sampler that puts some there is caught
    // even when few of them land there.
    Distribution d = ggx_vndf(1.0f, 89.0);
    Distribution bad = d;
    bad.sample = [s = d.sample](glm::vec2 u) {
        glm::vec3 h = s(u);
        return u.x < 0.001f ? glm::vec3(-h.x, -h.y, h.z) : h;
    };
    Chi2Result r = chi2_test(bad, 200000, 7);
    EXPECT_TRUE(!r.message.empty() || r.p_value < 1e-6) << "chi2 " << r.chi2 << " p " << r.p_value;
}

// ---------------------------------------------------------------------------
// basis(): orthonormal, right-handed, n as the third axis; also at and near the poles.

TEST(SamplingBasis, IsOrthonormal) {
    std::vector<glm::vec3> normals = {{0, 0, 1},       {0, 0, -1},        {1, 0, 0},   {0, 1, 0},
                                      {-1, 0, 0},      {0, -1, 0},        {0, 1e-4f, -1.0f}, {1e-4f, 0, 1.0f},
                                      {3e-4f, -2e-4f, -1.0f}};
    std::mt19937 rng(99);
    std::normal_distribution<float> g;
    for (int i = 0; i < 10000; ++i) normals.push_back(glm::vec3(g(rng), g(rng), g(rng)));
    for (glm::vec3 n : normals) {
        n = glm::normalize(n);
        glm::vec3 t, b;
        sampling::basis(n, t, b);
        const float eps = 1e-5f;
        EXPECT_NEAR(glm::length(t), 1.0f, eps) << n.x << " " << n.y << " " << n.z;
        EXPECT_NEAR(glm::length(b), 1.0f, eps) << n.x << " " << n.y << " " << n.z;
        EXPECT_NEAR(glm::dot(t, b), 0.0f, eps) << n.x << " " << n.y << " " << n.z;
        EXPECT_NEAR(glm::dot(t, n), 0.0f, eps) << n.x << " " << n.y << " " << n.z;
        EXPECT_NEAR(glm::dot(b, n), 0.0f, eps) << n.x << " " << n.y << " " << n.z;
        EXPECT_LT(glm::length(glm::cross(t, b) - n), 1e-5f) << "not right-handed at " << n.x << " " << n.y << " " << n.z;
    }
}

}  // namespace
