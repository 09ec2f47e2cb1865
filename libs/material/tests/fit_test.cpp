// fresnel::fit (fit.h): the fast per-channel path equals the library BRDF, the fit beats the
// formula conversion, round trips print and bound their residuals, the table is what
// tools/fit_table_gen writes, specular-glossiness converts exactly.
#include <gtest/gtest.h>

#include <cstdio>

#include "fresnel/core/color.h"
#include "fresnel/material/fit.h"

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
        std::printf("Phong Kd %.2f,%.2f,%.2f Ks %.2f,%.2f,%.2f Ns %5.1f -> fit %.1f dB (rms %.4f), formula %.1f dB\n",
                    p.kd.x, p.kd.y, p.kd.z, p.ks.x, p.ks.y, p.ks.z, p.ns, f.residual.psnr_db, f.residual.rms,
                    f.formula_residual.psnr_db);
        EXPECT_LT(f.residual.rms, f.formula_residual.rms * 0.8f);
        EXPECT_LT(f.residual.rms, 0.1f);  // 20 dB or better on every case
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

TEST(Fit, RoundTripsPrintAndBoundTheirResiduals) {
    const Phong phongs[] = {{glm::vec3(0.5f, 0.1f, 0.1f), glm::vec3(0.5f), 32.0f},
                            {glm::vec3(0.05f), glm::vec3(0.9f, 0.6f, 0.2f), 64.0f}};
    for (const Phong& p : phongs) {
        PhongToPbr f = fit_phong_to_pbr(p);
        PbrToPhong back = fit_pbr_to_phong(f.pbr);
        Residual trip = residual(p, back.phong);
        std::printf("Phong -> PBR -> Phong: Ns %.1f -> roughness %.3f -> Ns %.1f, round trip %.1f dB (rms %.4f)\n", p.ns,
                    f.pbr.roughness, back.phong.ns, trip.psnr_db, trip.rms);
        EXPECT_LT(trip.rms, 0.04f);  // better than 28 dB
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
        EXPECT_LT(trip.rms, 0.05f);
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
