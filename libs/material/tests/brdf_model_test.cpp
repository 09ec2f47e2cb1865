// The selectable BRDF terms (brdf_model.h): parsing, the default being glTF's BRDF exactly,
// normalisation of every distribution, reciprocity of every combination, the exact Fresnel
// equations against textbook values, and the diffuse alternatives' limits.
#include "fresnel/material/brdf_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

using namespace fresnel::brdf;

namespace {

constexpr double kPiD = 3.14159265358979323846;

glm::vec3 direction(double cos_theta, double phi) {
    double s = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    return glm::vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(cos_theta));
}

// Every model with one term changed from the default, and one with all changed.
std::vector<BrdfModel> models() {
    std::vector<BrdfModel> out;
    for (int i = 0; i < 3; ++i) out.push_back(BrdfModel{Distribution(i), {}, {}, {}});
    for (int i = 1; i < 5; ++i) out.push_back(BrdfModel{{}, Geometry(i), {}, {}});
    for (int i = 1; i < 3; ++i) out.push_back(BrdfModel{{}, {}, Fresnel(i), {}});
    for (int i = 1; i < 3; ++i) out.push_back(BrdfModel{{}, {}, {}, Diffuse(i)});
    out.push_back(BrdfModel{Distribution::Beckmann, Geometry::CookTorrance, Fresnel::ExactDielectric, Diffuse::OrenNayar});
    return out;
}

}  // namespace

TEST(BrdfModel, ParsesAndPrints) {
    auto m = parse_brdf_model("D=beckmann,G=kelemen,F=spherical-gaussian,diffuse=burley");
    ASSERT_TRUE(m);
    EXPECT_EQ(m->d, Distribution::Beckmann);
    EXPECT_EQ(m->g, Geometry::Kelemen);
    EXPECT_EQ(m->f, Fresnel::SphericalGaussian);
    EXPECT_EQ(m->diffuse, Diffuse::Burley);
    EXPECT_EQ(parse_brdf_model(to_string(*m)), m);
    auto partial = parse_brdf_model("diffuse=oren-nayar");
    ASSERT_TRUE(partial);
    EXPECT_EQ(partial->d, Distribution::Ggx);
    EXPECT_EQ(partial->diffuse, Diffuse::OrenNayar);
    EXPECT_TRUE(parse_brdf_model("")->is_default());
    EXPECT_EQ(to_string(BrdfModel{}), "D=ggx,G=smith-height-correlated,F=schlick,diffuse=lambert");
    EXPECT_TRUE(brdf_model_defines(BrdfModel{}).empty());
    EXPECT_EQ(brdf_model_defines(*m).size(), 4u);
    for (const char* bad : {"D=phong", "X=ggx", "ggx", "D=ggx,", "D=", "=ggx", "D=ggx,,G=kelemen"}) {
        std::string why;
        EXPECT_FALSE(parse_brdf_model(bad, &why)) << bad;
        EXPECT_FALSE(why.empty()) << bad;
    }
    for (const char* key : {"D", "G", "F", "diffuse"})
        for (const auto& name : brdf_model_names(key))
            EXPECT_TRUE(parse_brdf_model(std::string(key) + "=" + name)) << key << "=" << name;
}

TEST(BrdfModel, DefaultIsTheGltfBrdf) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < 200; ++i) {
        Surface s;
        s.base_color = {u(rng), u(rng), u(rng)};
        s.metallic = u(rng);
        s.perceptual_roughness = u(rng);
        glm::vec3 n(0, 0, 1), v = direction(u(rng), 6.28 * u(rng)), l = direction(u(rng), 6.28 * u(rng));
        Terms a = evaluate_terms(s, n, v, l), b = evaluate_terms(s, n, v, l, BrdfModel{});
        EXPECT_EQ(a.d, b.d);
        EXPECT_EQ(a.v, b.v);
        EXPECT_EQ(a.diffuse, b.diffuse);
        EXPECT_EQ(a.specular, b.specular);
        // Term by term the explicit choice of the defaults is the same function too.
        Terms c = evaluate_terms(s, n, v, l, BrdfModel{Distribution::Ggx, Geometry::SmithHeightCorrelated,
                                                       Fresnel::Schlick, Diffuse::Lambert});
        EXPECT_EQ(a.specular, c.specular);
    }
}

// Every distribution is normalised: the integral of D(h) (n.h) over the hemisphere is 1.
TEST(BrdfModel, DistributionsAreNormalised) {
    for (Distribution d : {Distribution::Ggx, Distribution::Beckmann, Distribution::BlinnPhong}) {
        for (float roughness : {0.3f, 0.5f, 0.8f, 1.0f}) {
            float alpha = alpha_from_roughness(roughness);
            const int n = 4000;
            double sum = 0;
            for (int i = 0; i < n; ++i) {  // midpoint rule in cos(theta_h): d(omega) = 2 pi d(cos)
                double c = (i + 0.5) / n;
                float dv = d == Distribution::Ggx        ? d_ggx(float(c), alpha)
                           : d == Distribution::Beckmann ? d_beckmann(float(c), alpha)
                                                         : d_blinn_phong(float(c), alpha);
                sum += dv * c * 2.0 * kPiD / n;
            }
            EXPECT_NEAR(sum, 1.0, 0.01) << "D " << int(d) << " roughness " << roughness;
        }
    }
}

TEST(BrdfModel, EveryCombinationIsReciprocalAndFinite) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (const BrdfModel& m : models()) {
        for (int i = 0; i < 300; ++i) {
            Surface s;
            s.base_color = {u(rng), u(rng), u(rng)};
            s.metallic = i % 3 == 0 ? 0.0f : u(rng);
            s.perceptual_roughness = 0.05f + 0.95f * u(rng);
            glm::vec3 n(0, 0, 1);
            glm::vec3 v = direction(0.02 + 0.98 * u(rng), 6.28 * u(rng)), l = direction(0.02 + 0.98 * u(rng), 6.28 * u(rng));
            glm::vec3 a = evaluate(s, n, v, l, m), b = evaluate(s, n, l, v, m);
            for (int k = 0; k < 3; ++k) {
                ASSERT_TRUE(std::isfinite(a[k]) && a[k] >= 0.0f) << to_string(m);
                EXPECT_NEAR(a[k], b[k], 1e-4f * std::max(1.0f, std::abs(a[k]))) << to_string(m);
            }
        }
    }
}

TEST(BrdfModel, ExactFresnelMatchesTheFresnelEquations) {
    // Glass (n = 1.5): 0.04 at normal incidence, Rs = 0.0920 and Rp = 0.0085 at 45 degrees, 1 at grazing.
    EXPECT_NEAR(f_dielectric_exact(1.0f, 1.5f), 0.04f, 1e-6f);
    EXPECT_NEAR(f_dielectric_exact(std::cos(0.785398f), 1.5f), 0.5f * (0.092013f + 0.008466f), 2e-5f);
    EXPECT_NEAR(f_dielectric_exact(0.0f, 1.5f), 1.0f, 1e-6f);
    EXPECT_NEAR(ior_from_f0(0.04f), 1.5f, 1e-5f);
    // The dielectric lobe of the model: F0 at normal incidence, weight w scales it all.
    glm::vec3 f = f_exact_dielectric(glm::vec3(0.04f), glm::vec3(1.0f), 1.0f);
    EXPECT_NEAR(f.x, 0.04f, 1e-6f);
    glm::vec3 g = f_exact_dielectric(glm::vec3(0.02f), glm::vec3(0.5f), 0.3f);
    EXPECT_NEAR(g.x, 0.5f * f_dielectric_exact(0.3f, 1.5f), 1e-5f);
    // Schlick's approximation stays within 0.04 of the exact curve for glass (the most near 80 degrees).
    for (float c = 0.0f; c <= 1.0f; c += 0.05f)
        EXPECT_NEAR(f_schlick(0.04f, 1.0f, c), f_dielectric_exact(c, 1.5f), 0.04f) << c;
    // The spherical-Gaussian form approximates Schlick's power closely.
    for (float c = 0.0f; c <= 1.0f; c += 0.05f)
        EXPECT_NEAR(f_spherical_gaussian(glm::vec3(0.04f), glm::vec3(1.0f), c).x, f_schlick(0.04f, 1.0f, c), 0.01f) << c;
}

TEST(BrdfModel, DiffuseAlternativesReduceToLambert) {
    // Oren-Nayar with sigma = 0 is Lambert; Burley at r = 0.25 and v.h = 1 has F90 = 1: Lambert.
    EXPECT_FLOAT_EQ(diffuse_oren_nayar_factor(0.3f, 0.8f, 0.1f, 0.0f), 1.0f);
    EXPECT_FLOAT_EQ(diffuse_burley_factor(0.3f, 0.8f, 1.0f, 0.25f), 1.0f);
    // Rough Oren-Nayar is darker than Lambert head-on and brighter towards retro-reflection at grazing.
    EXPECT_LT(diffuse_oren_nayar_factor(1.0f, 1.0f, 1.0f, 1.0f), 1.0f);
    glm::vec3 l = direction(0.2, 0.0);
    EXPECT_GT(diffuse_oren_nayar_factor(0.2f, 0.2f, glm::dot(l, l), 1.0f), diffuse_oren_nayar_factor(0.2f, 0.2f, -0.9f, 1.0f));
    // Burley's retro-reflection: rough surfaces brighten at grazing angles, smooth ones darken.
    EXPECT_GT(diffuse_burley_factor(0.1f, 0.1f, 1.0f, 1.0f), 1.0f);
    EXPECT_LT(diffuse_burley_factor(0.1f, 0.1f, 1.0f, 0.0f), 1.0f);
}
