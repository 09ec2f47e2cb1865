// fresnel::fit (fit.h): the fast per-channel path equals the library BRDF, the fit beats the
// formula conversion, round trips print and bound their residuals, the table is what
// tools/fit_table_gen writes, specular-glossiness converts exactly.
#include <gtest/gtest.h>

#include <cstdio>

#include "fresnel/core/color.h"
#include "fresnel/material/brdf.h"
#include "fresnel/material/fit.h"
#include "fresnel/material/legacy_shading.h"

using namespace fresnel;
using namespace fresnel::fit;

TEST(Fit, SamplesAreWeightedAndOnTheHemisphere) {
    const auto& s = fit_samples();
    ASSERT_GT(s.size(), 1000u);
    double total = 0.0;
    for (const Sample& x : s) {
        EXPECT_GT(x.l.z, 0.0f);
        EXPECT_GT(x.v.z, 0.0f);
        EXPECT_NEAR(glm::length(x.l), 1.0f, 1e-5f);
        total += x.weight;
    }
    EXPECT_NEAR(total, 1.0, 1e-5);
}

TEST(Fit, ResidualIsZeroForIdenticalAndCatchesADifference) {
    Pbr p;
    p.base_color = glm::vec3(0.3f, 0.5f, 0.7f);
    p.roughness = 0.4f;
    EXPECT_EQ(residual(p, p).rms, 0.0f);
    Pbr q = p;
    q.base_color.x = 0.35f;
    EXPECT_GT(residual(p, q).rms, 1e-3f);
    Phong a{glm::vec3(0.5f), glm::vec3(0.5f), 32.0f};
    EXPECT_EQ(residual(a, a).rms, 0.0f);
    // A PBR material that displays exactly what Phong does: black, no specular, against a black Phong.
    Pbr black;
    black.base_color = glm::vec3(0.0f);
    black.specular_weight = 0.0f;
    EXPECT_EQ(residual(Phong{glm::vec3(0.0f), glm::vec3(0.0f), 0.0f}, black).rms, 0.0f);
}

TEST(Fit, PhongDisplayIsOpenGl1) {
    // Light along the normal, view along the normal: Kd + Ks (clamped), whatever Ns.
    Sample s{glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), 1.0f};
    glm::vec3 c = phong_display(Phong{glm::vec3(0.3f), glm::vec3(0.2f, 0.9f, 0.0f), 50.0f}, s);
    EXPECT_NEAR(c.x, 0.5f, 1e-6f);
    EXPECT_NEAR(c.y, 1.0f, 1e-6f);
    EXPECT_NEAR(c.z, 0.3f, 1e-6f);
    // A rough white dielectric lit head-on: pi * (diffuse + specular) n.l, sRGB-encoded.
    Pbr p;
    p.base_color = glm::vec3(0.2f);
    glm::vec3 d = pbr_display(p, s);
    EXPECT_GT(d.x, linear_to_srgb(0.2f * 0.96f) - 1e-4f);
}

TEST(Fit, PhongToPbrBeatsTheFormula) {
    const Phong cases[] = {
        {glm::vec3(0.8f), glm::vec3(0.0f), 0.0f},                         // matte
        {glm::vec3(0.5f, 0.1f, 0.1f), glm::vec3(0.5f), 32.0f},            // red plastic
        {glm::vec3(0.05f), glm::vec3(0.9f, 0.6f, 0.2f), 64.0f},           // gold-like metal
        {glm::vec3(0.2f, 0.4f, 0.8f), glm::vec3(0.2f), 8.0f},             // broad highlight
        {glm::vec3(0.3f), glm::vec3(1.0f), 128.0f},                       // sharp, saturated
    };
    for (const Phong& p : cases) {
        PhongToPbr f = fit_phong_to_pbr(p);
        const Residual formula_image = residual_image_based(p, f.formula);
        std::printf("Phong Kd %.2f,%.2f,%.2f Ks %.2f,%.2f,%.2f Ns %5.1f -> fit %.1f dB (rms %.4f), formula %.1f dB; "
                    "image-based: fit %.1f dB, formula %.1f dB\n",
                    p.kd.x, p.kd.y, p.kd.z, p.ks.x, p.ks.y, p.ks.z, p.ns, f.residual.psnr_db, f.residual.rms,
                    f.formula_residual.psnr_db, f.image_based.psnr_db, formula_image.psnr_db);
        EXPECT_LT(f.residual.rms, f.formula_residual.rms * 0.8f);
        EXPECT_LT(f.image_based.rms, formula_image.rms * 0.8f);
        // One light: 19 dB or better on every case (the image-based parts pull the fit away from
        // the one light's optimum, by up to 2 dB); image-based: 20 dB or better.
        EXPECT_LT(f.residual.rms, 0.11f);
        EXPECT_LT(f.image_based.rms, 0.1f);
        EXPECT_GE(f.pbr.metallic, 0.0f);
        EXPECT_LE(f.pbr.metallic, 1.0f);
        EXPECT_GE(f.pbr.roughness, 0.0f);
        EXPECT_LE(f.pbr.roughness, 1.0f);
    }
}

// A material without a highlight never becomes a mirror: it gets no specular lobe at all, so
// it stays matte under any light (image-based light included). Its base colour is Kd under the
// albedo intent (the default of fit and convert); the OpenGL 1 look under one light, whose
// output is not sRGB-encoded, fits a darker one.
TEST(Fit, MatteStaysMatte) {
    for (Match match : {Match::OpenGl1, Match::Albedo}) {
        const PhongToPbr f = fit_phong_to_pbr(Phong{glm::vec3(0.8f, 0.0f, 0.0f), glm::vec3(0.0f), 0.0f}, match);
        EXPECT_EQ(f.pbr.specular_weight, 0.0f) << match_name(match);
        EXPECT_EQ(f.pbr.roughness, 1.0f) << match_name(match);
        EXPECT_EQ(f.pbr.metallic, 0.0f) << match_name(match);
        EXPECT_GT(f.pbr.base_color.x, match == Match::Albedo ? 0.79f : 0.35f) << match_name(match);
        EXPECT_LT(f.pbr.base_color.y, 0.01f) << match_name(match);
    }
    EXPECT_FLOAT_EQ(fit_phong_to_pbr(Phong{glm::vec3(0.8f), glm::vec3(0.0f), 0.0f}, Match::Albedo).pbr.base_color.x, 0.8f);
}

// The image-based parts' building blocks against brute-force quadrature over the hemisphere
// (a fine grid in cos theta and phi): a uniform environment of radiance 1 seen through the PBR
// BRDF (brdf::evaluate, the library's truth) and through OpenGL 1 (legacy::ogl1_light, lights of
// colour dw / pi from every direction).
TEST(Fit, UniformEnvironmentMatchesQuadrature) {
    const int kTheta = 1024, kPhi = 512;
    auto integrate = [&](const glm::vec3& v, const auto& radiance_of) {
        glm::dvec3 sum(0.0);
        for (int i = 0; i < kTheta; ++i) {
            const double cos_t = (i + 0.5) / kTheta, sin_t = std::sqrt(1.0 - cos_t * cos_t);
            for (int j = 0; j < kPhi; ++j) {
                const double phi = 2.0 * brdf::kPi * (j + 0.5) / kPhi;
                glm::vec3 l(float(sin_t * std::cos(phi)), float(sin_t * std::sin(phi)), float(cos_t));
                sum += glm::dvec3(radiance_of(l));  // d omega = d(cos theta) d phi
            }
        }
        return glm::vec3(sum * (2.0 * brdf::kPi / (double(kTheta) * kPhi)));
    };
    const glm::vec3 n(0, 0, 1);
    struct PbrCase { Pbr p; float tolerance; };
    std::vector<PbrCase> pbr_cases;
    for (float roughness : {0.3f, 0.6f, 1.0f})
        for (float metallic : {0.0f, 1.0f}) {
            Pbr p;
            p.base_color = glm::vec3(0.8f, 0.5f, 0.2f);
            p.metallic = metallic;
            p.roughness = roughness;
            pbr_cases.push_back({p, 0.03f});
        }
    Pbr coated;  // KHR_materials_specular
    coated.base_color = glm::vec3(0.3f);
    coated.roughness = 0.5f;
    coated.specular_f0 = glm::vec3(0.2f, 0.1f, 0.05f);
    coated.specular_weight = 0.7f;
    pbr_cases.push_back({coated, 0.03f});
    for (int view = 0; view < view_count(); ++view) {
        const glm::vec3 v = view_at(view);
        for (const PbrCase& c : pbr_cases) {
            brdf::Surface s;
            s.base_color = c.p.base_color;
            s.metallic = c.p.metallic;
            s.perceptual_roughness = c.p.roughness;
            s.specular_f0 = 0.04f;
            s.specular_color = c.p.specular_f0 / 0.04f;
            s.specular_weight = c.p.specular_weight;
            const glm::vec3 truth = integrate(v, [&](const glm::vec3& l) { return brdf::evaluate(s, n, v, l) * l.z; });
            const glm::vec3 ours = uniform_environment(c.p, view);
            for (int k = 0; k < 3; ++k)
                EXPECT_NEAR(ours[k], truth[k], c.tolerance * std::max(truth[k], 0.1f))
                    << "view " << view << " roughness " << c.p.roughness << " metallic " << c.p.metallic;
        }
        for (float ns : {1.0f, 10.0f, 32.0f, 128.0f}) {
            const Phong p{glm::vec3(0.4f, 0.2f, 0.1f), glm::vec3(0.5f), ns};
            const glm::vec3 truth = integrate(v, [&](const glm::vec3& l) {
                legacy::Ogl1Light o = legacy::ogl1_light(n, v, l, glm::vec3(1.0f), p.kd, p.ks, legacy::ogl1_shininess(ns));
                return (o.diffuse + o.specular) / brdf::kPi;
            });
            const glm::vec3 ours = uniform_environment(p, view);
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(ours[k], truth[k], 0.02f * truth[k]) << "view " << view << " Ns " << ns;
        }
    }
}

// Under image-based light OpenGL 1's highlight, not energy-normalised, reflects little: a
// Ks 1, Ns 32 highlight returns about a quarter of a uniform environment (raw). The one-light
// fit's material (a bright metal, kept here as the objective of the last version gave it)
// shows the environment at full brightness; the fit must show it about as OpenGL 1 does.
TEST(Fit, ImageBasedLightKeepsHighlightsAsBrightAsOpenGl1) {
    const Phong spec{glm::vec3(0.0f), glm::vec3(1.0f), 32.0f};
    const int view = view_count() - 1;  // nearly head on
    const float gl = uniform_environment(spec, view).x;
    EXPECT_GT(gl, 0.15f);
    EXPECT_LT(gl, 0.35f);
    const PhongToPbr f = fit_phong_to_pbr(spec);
    Pbr one_light;
    one_light.base_color = glm::vec3(1.0f);
    one_light.metallic = 1.0f;
    one_light.roughness = 0.1701f;
    const float fitted = linear_to_srgb(std::min(uniform_environment(f.pbr, view).x, 1.0f));
    const float before = linear_to_srgb(std::min(uniform_environment(one_light, view).x, 1.0f));
    EXPECT_NEAR(fitted, gl, 0.1f);
    EXPECT_GT(before, gl + 0.5f);
    EXPECT_LT(f.image_based.rms, 0.5f * residual_image_based(spec, one_light).rms);
    std::printf("Ks 1, Ns 32 under a uniform environment: OpenGL 1 shows %.3f, the fit %.3f, the one-light fit %.3f; "
                "image-based residual %.1f dB (one-light fit %.1f dB), one-light residual %.1f dB\n",
                gl, fitted, before, f.image_based.psnr_db, residual_image_based(spec, one_light).psnr_db,
                f.residual.psnr_db);
}

// --match albedo: Kd is the base colour as given; the highlight (Ks, Ns) sets roughness and the
// specular F0, sharper for a higher Ns.
TEST(Fit, AlbedoIntentKeepsKd) {
    const Phong plastic{glm::vec3(0.5f, 0.1f, 0.1f), glm::vec3(0.5f), 32.0f};
    const Phong sharp{glm::vec3(0.5f, 0.1f, 0.1f), glm::vec3(0.5f), 128.0f};
    const PhongToPbr a = fit_phong_to_pbr(plastic, Match::Albedo), b = fit_phong_to_pbr(sharp, Match::Albedo);
    EXPECT_EQ(a.pbr.base_color, plastic.kd);
    EXPECT_EQ(a.pbr.metallic, 0.0f);
    EXPECT_GT(a.pbr.roughness, 0.05f);
    EXPECT_LT(a.pbr.roughness, 0.9f);
    EXPECT_LT(b.pbr.roughness, a.pbr.roughness);
    EXPECT_GT(a.pbr.specular_f0.x, 0.0f);
    EXPECT_LE(a.pbr.specular_f0.x, 1.0f);
    EXPECT_EQ(parse_match("albedo"), Match::Albedo);
    EXPECT_EQ(parse_match("opengl1"), Match::OpenGl1);
    EXPECT_FALSE(parse_match("blender"));
}

// The two directions fit different lightings (Phong -> PBR the one light and image-based light,
// PBR -> Phong the one light: OpenGL 1 viewers draw no environment), so a round trip is not the
// identity; it stays within 20 dB (28 dB for a plastic).
TEST(Fit, RoundTripsPrintAndBoundTheirResiduals) {
    const Phong phongs[] = {{glm::vec3(0.5f, 0.1f, 0.1f), glm::vec3(0.5f), 32.0f},
                            {glm::vec3(0.05f), glm::vec3(0.9f, 0.6f, 0.2f), 64.0f}};
    for (const Phong& p : phongs) {
        PhongToPbr f = fit_phong_to_pbr(p);
        PbrToPhong back = fit_pbr_to_phong(f.pbr);
        Residual trip = residual(p, back.phong);
        std::printf("Phong -> PBR -> Phong: Ns %.1f -> roughness %.3f -> Ns %.1f, round trip %.1f dB (rms %.4f)\n", p.ns,
                    f.pbr.roughness, back.phong.ns, trip.psnr_db, trip.rms);
        EXPECT_LT(trip.rms, p.ns < 40.0f ? 0.04f : 0.1f);  // better than 28 dB (plastic), 20 dB (metal)
    }
    const Pbr pbrs[] = {[] { Pbr p; p.base_color = glm::vec3(0.8f); p.metallic = 1.0f; p.roughness = 0.3f; return p; }(),
                        [] { Pbr p; p.base_color = glm::vec3(0.5f); p.roughness = 0.5f; return p; }()};
    for (const Pbr& p : pbrs) {
        PbrToPhong f = fit_pbr_to_phong(p);
        PhongToPbr back = fit_phong_to_pbr(f.phong);
        Residual trip = residual(p, back.pbr);
        std::printf("PBR -> Phong -> PBR: metallic %.1f roughness %.2f -> Ns %.1f -> roughness %.3f, fit %.1f dB "
                    "(naive %.1f dB), round trip %.1f dB\n",
                    p.metallic, p.roughness, f.phong.ns, back.pbr.roughness, f.residual.psnr_db,
                    f.naive_residual.psnr_db, trip.psnr_db);
        EXPECT_LT(f.residual.rms, f.naive_residual.rms * 0.5f);
        EXPECT_LT(trip.rms, 0.1f);
    }
}

TEST(Fit, TableIsWhatTheGeneratorWrites) {
    // tools/fit_table_gen fits these grid points with the full search; spot-check three.
    for (int i : {4, 16, 28}) {
        Phong p{glm::vec3(0.5f), glm::vec3(0.5f), table_ns_at(i)};
        EXPECT_NEAR(fit_phong_to_pbr_full(p).pbr.roughness, table_roughness(table_ns_at(i)), 2e-3f) << i;
    }
    EXPECT_EQ(table_ns_at(0), 0.0f);
    EXPECT_EQ(table_ns_at(kTableSize - 1), 128.0f);
    EXPECT_FLOAT_EQ(table_roughness_at(kTableSize - 1), 1.0f);
}

TEST(Fit, SpecularGlossinessIsExact) {
    SpecularGlossinessToPbr f = fit_specular_glossiness(glm::vec3(0.5f, 0.3f, 0.2f), glm::vec3(0.2f, 0.1f, 0.05f), 0.7f);
    std::printf("specular-glossiness -> metallic-roughness residual rms %.2g\n", f.residual.rms);
    EXPECT_LT(f.residual.rms, 1e-5f);
    EXPECT_NEAR(f.pbr.roughness, 0.3f, 1e-6f);
    EXPECT_TRUE(f.pbr.uses_specular());
}

TEST(Fit, MaterialRoundTrip) {
    Material m;
    Pbr p;
    p.base_color = glm::vec3(0.2f, 0.3f, 0.4f);
    p.metallic = 0.25f;
    p.roughness = 0.6f;
    p.specular_f0 = glm::vec3(0.08f, 0.04f, 0.02f);
    p.specular_weight = 0.5f;
    apply_pbr(p, m);
    ASSERT_TRUE(m.specular.has_value());
    Pbr q = from_material(m);
    EXPECT_NEAR(glm::length(q.specular_f0 - p.specular_f0), 0.0f, 1e-6f);
    EXPECT_EQ(q.specular_weight, 0.5f);
    p.specular_f0 = glm::vec3(0.04f);
    p.specular_weight = 1.0f;
    apply_pbr(p, m);
    EXPECT_FALSE(m.specular.has_value());
}
