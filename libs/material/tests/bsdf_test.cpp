// The sampled BSDF (fresnel/material/bsdf.h) against the BSDF it samples: for every lobe
// combination of the glTF material (diffuse, its EON form, metal, clearcoat over a tilted coat
// normal, sheen, anisotropy, a thin film, thin-walled transmission, diffuse transmission and
// their mixes) and two views, the one-sample estimator mean(f cos / pdf * g) of a smooth
// "environment" g converges to the quadrature of shade_bsdf * g over the sphere; Bsdf::eval is
// shade_light itself without transmission, and the pdf integrates to at most 1. (The tracer's
// chi-squared tests in libs/trace hold the samples to the pdf.)
#include "fresnel/material/bsdf.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

using namespace fresnel;

namespace {

constexpr double kPiD = 3.14159265358979323846;

struct Case {
    std::string name;
    EvaluatedMaterial m;
};

std::vector<Case> cases() {
    auto base = [](glm::vec3 color, float metallic, float roughness) {
        EvaluatedMaterial m;
        m.surface.base_color = color;
        m.surface.metallic = metallic;
        m.surface.perceptual_roughness = roughness;
        return m;
    };
    std::vector<Case> out;
    out.push_back({"diffuse", base({0.8f, 0.5f, 0.2f}, 0.0f, 0.7f)});
    out.push_back({"metal", base({0.9f, 0.6f, 0.3f}, 1.0f, 0.45f)});
    Case c{"clearcoat", base({0.3f, 0.6f, 0.9f}, 0.3f, 0.6f)};
    c.m.clearcoat = 0.8f, c.m.clearcoat_roughness = 0.4f;
    c.m.clearcoat_normal = glm::normalize(glm::vec3(0.15f, -0.1f, 1.0f));
    out.push_back(c);
    c = {"sheen", base({0.5f, 0.2f, 0.2f}, 0.0f, 0.8f)};
    c.m.sheen_color = {0.6f, 0.7f, 0.9f}, c.m.sheen_roughness = 0.5f;
    out.push_back(c);
    c = {"anisotropy", base({0.7f, 0.7f, 0.7f}, 0.7f, 0.6f)};
    c.m.anisotropy_strength = 0.6f;
    out.push_back(c);
    c = {"iridescence", base({0.4f, 0.4f, 0.9f}, 0.2f, 0.5f)};
    c.m.iridescence = 1.0f, c.m.iridescence_ior = 1.6f, c.m.iridescence_thickness = 420.0f;
    out.push_back(c);
    c = {"diffuse roughness", base({0.9f, 0.8f, 0.3f}, 0.0f, 0.8f)};
    c.m.diffuse_roughness = 0.8f;
    out.push_back(c);
    c = {"transmission", base({0.9f, 0.9f, 0.6f}, 0.0f, 0.5f)};
    c.m.transmission.factor = 0.7f, c.m.transmission.ior = 1.5f;
    out.push_back(c);
    c = {"diffuse transmission", base({0.6f, 0.9f, 0.4f}, 0.0f, 0.6f)};
    c.m.diffuse_transmission = 0.6f, c.m.diffuse_transmission_color = {1.0f, 0.5f, 0.25f};
    out.push_back(c);
    c = {"everything", base({0.8f, 0.6f, 0.5f}, 0.1f, 0.55f)};
    c.m.transmission.factor = 0.5f, c.m.transmission.ior = 1.4f;
    c.m.diffuse_transmission = 0.4f;
    c.m.diffuse_roughness = 0.5f;
    c.m.clearcoat = 0.5f, c.m.clearcoat_roughness = 0.5f;
    c.m.sheen_color = glm::vec3(0.3f), c.m.sheen_roughness = 0.6f;
    c.m.iridescence = 0.5f, c.m.iridescence_thickness = 300.0f;
    out.push_back(c);
    return out;
}

// A smooth, positive stand-in for incident radiance over the whole sphere.
glm::dvec3 environment(glm::vec3 l) {
    return glm::dvec3(1.0 + 0.5 * l.x - 0.3 * l.y + 0.4 * l.z * l.z, 1.0 + 0.3 * l.z, 1.2 - 0.4 * l.x * l.y);
}

glm::vec3 direction(double cos_theta, double phi) {
    double s = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    return glm::vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(cos_theta));
}

// Midpoint quadrature over the sphere (uniform in cos(theta) and phi): the integral of g(l).
template <class G>
glm::dvec3 sphere_integral(G&& g, int n = 700) {
    glm::dvec3 sum(0.0);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < 2 * n; ++j) sum += g(direction(-1.0 + 2.0 * (i + 0.5) / n, (j + 0.5) * kPiD / n));
    return sum * (2.0 / n) * (kPiD / n);
}

}  // namespace

TEST(Bsdf, EvalIsShadeLightWithoutTransmission) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (const Case& c : cases()) {
        if (c.m.transmission.factor > 0.0f) continue;
        const glm::vec3 v = glm::normalize(glm::vec3(0.3f, 0.2f, 0.9f));
        const Bsdf bsdf(c.m, v);
        for (int i = 0; i < 200; ++i) {
            glm::vec3 l = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
            EXPECT_EQ(bsdf.eval(l), shade_light(c.m, v, l, glm::vec3(1.0f))) << c.name;
        }
    }
}

TEST(Bsdf, EstimatorConvergesToTheQuadratureOfEveryLobeCombination) {
    for (const Case& c : cases())
        for (float mu : {0.85f, 0.35f}) {
            const glm::vec3 v = direction(mu, 0.4);
            const Bsdf bsdf(c.m, v);
            const glm::dvec3 want = sphere_integral([&](glm::vec3 l) { return glm::dvec3(bsdf.eval(l)) * environment(l); });
            const double pdf_total = sphere_integral([&](glm::vec3 l) { return glm::dvec3(bsdf.pdf(l)); }).x;
            EXPECT_LE(pdf_total, 1.0 + 5e-3) << c.name;
            std::mt19937 rng(11);
            std::uniform_real_distribution<float> u01(0.0f, 1.0f);
            const int n = 300000;
            glm::dvec3 sum(0.0), sum2(0.0);
            for (int i = 0; i < n; ++i) {
                const BsdfSample s = bsdf.sample(glm::vec3(u01(rng), u01(rng), u01(rng)));
                if (!(s.pdf > 0.0f)) continue;
                // Transmitted samples lie below (a tilted coat normal may reflect below too).
                EXPECT_TRUE(!s.transmitted || glm::dot(s.l, c.m.normal) < 0.0f) << c.name;
                const glm::dvec3 x = glm::dvec3(s.f_cos) / double(s.pdf) * environment(s.l);
                sum += x, sum2 += x * x;
            }
            const glm::dvec3 mean = sum / double(n);
            std::printf("%-22s view cos %.2f: estimate %.4f %.4f %.4f, quadrature %.4f %.4f %.4f, pdf integral %.4f\n",
                        c.name.c_str(), mu, mean.x, mean.y, mean.z, want.x, want.y, want.z, pdf_total);
            for (int ch = 0; ch < 3; ++ch) {
                const double sigma = std::sqrt(std::max(0.0, sum2[ch] / n - mean[ch] * mean[ch]) / n);
                // Five standard errors of the estimate, plus the quadrature's own error.
                EXPECT_NEAR(mean[ch], want[ch], 5.0 * sigma + 4e-3 * want[ch] + 1e-4)
                    << c.name << " view cos " << mu << " channel " << ch;
            }
        }
}
