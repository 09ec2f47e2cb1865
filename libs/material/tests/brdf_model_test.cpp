// The selectable BRDF terms (brdf_model.h): parsing, the default being glTF's BRDF exactly,
// normalisation of every distribution, reciprocity of every combination, the exact Fresnel
// equations against textbook values, and the diffuse alternatives' limits.
#include "fresnel/material/brdf_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
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
    for (int i = 1; i < 4; ++i) out.push_back(BrdfModel{{}, {}, Fresnel(i), {}});
    for (int i = 1; i < 3; ++i) out.push_back(BrdfModel{{}, {}, {}, Diffuse(i)});
    // F=exact with every measured metal.
    for (int i = 1; i < int(brdf_conductor_names().size()); ++i)
        out.push_back(BrdfModel{{}, {}, Fresnel::Exact, {}, Conductor(i)});
    out.push_back(BrdfModel{Distribution::Beckmann, Geometry::CookTorrance, Fresnel::ExactDielectric, Diffuse::OrenNayar});
    out.push_back(BrdfModel{Distribution::BlinnPhong, Geometry::Kelemen, Fresnel::Exact, Diffuse::Burley, Conductor::Gold});
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

// F=exact and its metals: every name parses and prints back, the text is what job and scene
// files hold ("F=exact:gold"), and a wrong metal names the choices.
TEST(BrdfModel, ExactFresnelNamesRoundTrip) {
    auto plain = parse_brdf_model("F=exact");
    ASSERT_TRUE(plain);
    EXPECT_EQ(plain->f, Fresnel::Exact);
    EXPECT_EQ(plain->conductor, Conductor::BaseColor);
    EXPECT_EQ(to_string(*plain), "D=ggx,G=smith-height-correlated,F=exact,diffuse=lambert");
    EXPECT_EQ(brdf_model_defines(*plain), std::vector<std::string>{"BRDF_F 3"});
    EXPECT_EQ(brdf_conductor_names().front(), "base-color");
    for (std::size_t i = 0; i < brdf_conductor_names().size(); ++i) {
        const std::string& name = brdf_conductor_names()[i];
        auto m = parse_brdf_model("D=beckmann,F=exact:" + name);
        ASSERT_TRUE(m) << name;
        EXPECT_EQ(m->conductor, Conductor(i)) << name;
        EXPECT_EQ(parse_brdf_model(to_string(*m)), m) << name;
        if (i == 0) continue;
        EXPECT_NE(to_string(*m).find("F=exact:" + name), std::string::npos) << to_string(*m);
        // The measured metal's n and k go to the shader as defines that read back to the same floats.
        auto defines = brdf_model_defines(*m);
        ASSERT_EQ(defines.size(), 4u) << name;
        ComplexIor ior = measured_conductor(Conductor(i));
        char expected[160];
        std::snprintf(expected, sizeof expected, "BRDF_CONDUCTOR_N vec3(%.9g, %.9g, %.9g)", double(ior.n.x),
                      double(ior.n.y), double(ior.n.z));
        EXPECT_EQ(defines[2], expected);
        float x = 0, y = 0, z = 0;
        ASSERT_EQ(std::sscanf(defines[3].c_str(), "BRDF_CONDUCTOR_K vec3(%f, %f, %f)", &x, &y, &z), 3) << defines[3];
        EXPECT_EQ(glm::vec3(x, y, z), ior.k) << name;
    }
    EXPECT_EQ(to_string(*parse_brdf_model("F=exact:gold")), "D=ggx,G=smith-height-correlated,F=exact:gold,diffuse=lambert");
    // A later F= replaces the metal with the rest.
    EXPECT_EQ(parse_brdf_model("F=exact:gold,F=exact")->conductor, Conductor::BaseColor);
    EXPECT_EQ(*parse_brdf_model("F=exact:gold,F=schlick"), BrdfModel{});
    std::string why;
    EXPECT_FALSE(parse_brdf_model("F=exact:unobtainium", &why));
    EXPECT_NE(why.find("unknown metal 'unobtainium'"), std::string::npos) << why;
    EXPECT_NE(why.find("gold|aluminium"), std::string::npos) << why;  // the list of names
    for (const char* bad : {"F=schlick:gold", "D=ggx:gold", "F=exact:", "F=exact-dielectric:gold", "F=exact:Gold"}) {
        why.clear();
        EXPECT_FALSE(parse_brdf_model(bad, &why)) << bad;
        EXPECT_NE(why.find("F=exact:base-color|iron|gold"), std::string::npos) << bad << ": " << why;
    }
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

namespace {

// The Fresnel equations with a complex ior, in double: r_s = (c - eta c_t) / (c + eta c_t),
// r_p = (eta c - c_t) / (eta c + c_t), c_t = sqrt(1 - sin^2 / eta^2), F = (|r_s|^2 + |r_p|^2) / 2.
double conductor_reference(double c, double n, double k) {
    std::complex<double> eta(n, k);
    std::complex<double> ct = std::sqrt(1.0 - (1.0 - c * c) / (eta * eta));
    std::complex<double> rs = (c - eta * ct) / (c + eta * ct), rp = (eta * c - ct) / (eta * c + ct);
    return 0.5 * (std::norm(rs) + std::norm(rp));
}

}  // namespace

TEST(BrdfModel, ConductorFresnelMatchesTheFresnelEquations) {
    // Normal incidence: ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2); grazing: 1.
    for (auto [n, k] : {std::pair{0.18299f, 3.4242f}, {1.3456f, 7.4746f}, {2.9114f, 3.0893f}, {0.05f, 4.0f},
                        {0.135f, 2.38f}, {1.0f, 0.0f}, {1.5f, 0.0f}, {0.3f, 0.0f}, {0.0f, 1.0f}, {1.0f, 0.01f}}) {
        float f0 = ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
        EXPECT_NEAR(f_conductor_exact(1.0f, n, k), f0, 1e-6f) << n << " " << k;
        if (n != 1.0f || k != 0.0f) {
            EXPECT_NEAR(f_conductor_exact(0.0f, n, k), 1.0f, 1e-6f) << n << " " << k;
        }
        // Every angle against the complex-valued equations in double.
        for (int i = 0; i <= 100; ++i) {
            float c = float(i) / 100.0f;
            double ref = conductor_reference(c, n, k);
            // Total internal reflection (k = 0, n < 1): the complex form's branch differs; n = 1 at grazing: 0 / 0.
            if ((k == 0.0f && n < 1.0f) || std::isnan(ref)) continue;
            EXPECT_NEAR(f_conductor_exact(c, n, k), ref, 2e-6 + 2e-6 * ref) << "n " << n << " k " << k << " c " << c;
            float f = f_conductor_exact(c, n, k);
            EXPECT_TRUE(f >= 0.0f && f <= 1.0f) << f;
        }
    }
    // k = 0 is the dielectric's equations.
    for (float eta : {1.1f, 1.5f, 2.4f, 4.0f})
        for (float c = 0.0f; c <= 1.0f; c += 0.01f)
            EXPECT_NEAR(f_conductor_exact(c, eta, 0.0f), f_dielectric_exact(c, eta), 2e-6f) << eta << " " << c;
    // Gold (Johnson and Christy 1972 at 550 nm: n = 0.43, k = 2.455): 0.787 at normal incidence;
    // with p-polarisation's dip the unpolarised curve still rises monotonically to 1 past 70 degrees.
    EXPECT_NEAR(f_conductor_exact(1.0f, 0.43f, 2.455f), 0.7869f, 1e-4f);
    float previous = 0.0f;
    for (float deg = 70.0f; deg <= 90.0f; deg += 1.0f) {
        float f = f_conductor_exact(std::cos(deg * 0.0174532925f), 0.43f, 2.455f);
        EXPECT_GE(f, previous) << deg;
        previous = f;
    }
}

// The base colour's conductor (Gulbrandsen 2014, edge tint 1) reproduces F0 exactly at normal
// incidence; towards grazing it is above Schlick's curve (at most by 0.157 at 60 degrees, at
// F0 = 0.25, and by 0.200 at 80 degrees, at F0 = 0.21).
TEST(BrdfModel, ConductorFromF0ReproducesF0) {
    for (float r = 0.0f; r <= 1.0f; r += 0.01f) {
        ComplexIor ior = conductor_from_f0(glm::vec3(r));
        EXPECT_NEAR(ior.n.x, (1 - r) / (1 + r), 1e-6f);
        EXPECT_NEAR(f_conductor_exact(1.0f, ior.n.x, ior.k.x), r, 2e-6f) << r;
        EXPECT_NEAR(f_exact_metal(glm::vec3(r), Conductor::BaseColor, 1.0f).x, r, 2e-6f) << r;
        EXPECT_NEAR(f_exact_metal(glm::vec3(r), Conductor::BaseColor, 0.0f).x, 1.0f, 1e-6f) << r;
        for (float deg : {60.0f, 80.0f}) {
            if (r < 0.005f) continue;  // F0 = 0: n = 1, k = 0, no interface (0 but at grazing; Schlick's is not)
            float c = std::cos(deg * 0.0174532925f);
            float d = f_conductor_exact(c, ior.n.x, ior.k.x) - f_schlick(r, 1.0f, c);
            EXPECT_GE(d, -1e-6f) << r << " " << deg;
            EXPECT_LE(d, deg == 60.0f ? 0.158f : 0.201f) << r << " " << deg;
        }
    }
    // Per channel.
    glm::vec3 f0(1.0f, 0.766f, 0.336f);
    glm::vec3 f = f_exact_metal(f0, Conductor::BaseColor, 1.0f);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(f[i], f0[i], 2e-6f);
    // A measured metal ignores the base colour; gold is yellow: red > green > blue at every angle.
    for (float c = 0.0f; c <= 1.0f; c += 0.1f) {
        glm::vec3 a = f_exact_metal(glm::vec3(0.2f), Conductor::Gold, c), b = f_exact_metal(glm::vec3(0.9f), Conductor::Gold, c);
        EXPECT_EQ(a, b);
        if (c > 0.05f) {
            EXPECT_TRUE(a.x > a.y && a.y > a.z) << c;
        }
    }
    glm::vec3 gold = f_exact_metal(glm::vec3(0.0f), Conductor::Gold, 1.0f);
    EXPECT_NEAR(gold.x, 0.944f, 1e-3f);
    EXPECT_NEAR(gold.y, 0.776f, 1e-3f);
    EXPECT_NEAR(gold.z, 0.373f, 1e-3f);
}

// Energy: a white furnace of the metal lobe alone (metallic 1) reflects at most what comes in,
// with every F choice, at every view angle; F=exact of a perfect reflector (F0 = 1) is 1 everywhere.
TEST(BrdfModel, ExactConductorConservesEnergy) {
    EXPECT_FLOAT_EQ(f_exact_metal(glm::vec3(1.0f), Conductor::BaseColor, 0.3f).x, 1.0f);
    for (const BrdfModel& m : models()) {
        // GGX with correlated Smith reflects at most 1 with F = 1: what F=exact adds is F <= 1.
        if (m.f != Fresnel::Exact || m.d != Distribution::Ggx || m.g != Geometry::SmithHeightCorrelated) continue;
        for (float roughness : {0.4f, 0.7f, 1.0f}) {
            Surface s;
            s.base_color = glm::vec3(1.0f, 0.8f, 0.5f);
            s.metallic = 1.0f;
            s.perceptual_roughness = roughness;
            for (float mu : {0.1f, 0.5f, 0.9f}) {
                glm::vec3 v(std::sqrt(1.0f - mu * mu), 0.0f, mu), n(0, 0, 1);
                glm::dvec3 e(0.0);
                const int nc = 96, nphi = 96;
                for (int a = 0; a < nc; ++a) {
                    double c = (a + 0.5) / nc;
                    for (int b = 0; b < nphi; ++b) {
                        glm::vec3 l = direction(c, 2.0 * kPiD * (b + 0.5) / nphi);
                        e += glm::dvec3(evaluate(s, n, v, l, m)) * c;
                    }
                }
                e *= 2.0 * kPiD / (nc * nphi);
                for (int k = 0; k < 3; ++k) EXPECT_LE(e[k], 1.02) << to_string(m) << " roughness " << roughness << " mu " << mu;
            }
        }
    }
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
