#pragma once
// Selectable terms of the microfacet BRDF (`--brdf D=...,G=...,F=...,diffuse=...`), once in
// C++. The defaults are the glTF specification's (GGX, height-correlated Smith, Schlick,
// Lambert: brdf.h); the others are the classic alternatives a renderer is compared with.
// shaders/brdf.glsl holds the same terms behind the BRDF_D, BRDF_G, BRDF_F and BRDF_DIFFUSE
// defines (brdf_model_defines); tests/gpu/brdf_gpu_test.cpp holds the two together.
//
// They shade punctual lights. Image-based light keeps the split-sum table baked for the
// default terms (GGX, correlated Smith, Schlick) and Lambert irradiance, so that an
// alternative term changes what lights show, and the debug views (d, g, f, diffuse,
// specular) show each term, without a table per combination.
//
// Conventions as in brdf.h: unit vectors, alpha = perceptual roughness squared, V = G / (4 n.l n.v).
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fresnel/material/brdf.h"

namespace fresnel::brdf {

enum class Distribution { Ggx, Beckmann, BlinnPhong };
enum class Geometry { SmithHeightCorrelated, SmithSeparable, SchlickGgx, CookTorrance, Kelemen };
enum class Fresnel { Schlick, ExactDielectric, SphericalGaussian };
enum class Diffuse { Lambert, Burley, OrenNayar };

struct BrdfModel {
    Distribution d = Distribution::Ggx;
    Geometry g = Geometry::SmithHeightCorrelated;
    Fresnel f = Fresnel::Schlick;
    Diffuse diffuse = Diffuse::Lambert;
    bool is_default() const { return *this == BrdfModel{}; }
    bool operator==(const BrdfModel&) const = default;
};

// "D=beckmann,G=kelemen,F=schlick,diffuse=burley" (any subset, any order; the terms' names as
// in brdf_model_names). nullopt with `error` set for an unknown key or value.
std::optional<BrdfModel> parse_brdf_model(std::string_view text, std::string* error = nullptr);
// The canonical text of a model ("D=ggx,G=smith-height-correlated,F=schlick,diffuse=lambert").
std::string to_string(const BrdfModel& m);
// Every accepted value of one key ("D", "G", "F", "diffuse"), in enum order.
const std::vector<std::string>& brdf_model_names(std::string_view key);
// The shader defines of a model: none for the default, else "BRDF_D 1" etc. for the
// non-default terms (the enum values).
std::vector<std::string> brdf_model_defines(const BrdfModel& m);

// ---- The alternative terms ----

// Beckmann: exp(-tan^2(theta_h) / alpha^2) / (pi alpha^2 cos^4(theta_h)).
inline float d_beckmann(float n_dot_h, float alpha) {
    float a2 = std::max(alpha * alpha, 1e-7f);
    float c2 = n_dot_h * n_dot_h;
    if (c2 <= 0.0f) return 0.0f;
    return std::exp((c2 - 1.0f) / (a2 * c2)) / (kPi * a2 * c2 * c2);
}

// Normalised Blinn-Phong, (s + 2) / (2 pi) (n.h)^s, with the exponent that matches Beckmann's
// width: s = 2 / alpha^2 - 2 (Walter et al. 2007), alpha floored so that s stays finite.
inline float blinn_phong_exponent(float alpha) {
    float a2 = std::max(alpha * alpha, 1e-7f);
    return std::max(2.0f / a2 - 2.0f, 0.0f);
}
inline float d_blinn_phong(float n_dot_h, float alpha) {
    float s = blinn_phong_exponent(alpha);
    // n.h floored: pow(0, 0) is 1 here and undefined in GLSL (s = 0 at alpha = 1: D = 1 / pi).
    return (s + 2.0f) / (2.0f * kPi) * std::pow(std::max(n_dot_h, 1e-8f), s);
}

// Separable Smith for GGX: G1(l) G1(v) / (4 n.l n.v), with
// G1(x) = 2x / (x + sqrt(alpha^2 + (1 - alpha^2) x^2)), written without the n.l n.v division.
inline float v_smith_ggx_separable(float n_dot_l, float n_dot_v, float alpha) {
    float a2 = alpha * alpha;
    float gl = n_dot_l + std::sqrt(a2 + (1.0f - a2) * n_dot_l * n_dot_l);
    float gv = n_dot_v + std::sqrt(a2 + (1.0f - a2) * n_dot_v * n_dot_v);
    float g = gl * gv;
    return g > 0.0f ? 1.0f / g : 0.0f;
}

// Schlick-GGX (UE4, Karis 2013): G1(x) = x / (x (1 - k) + k) with k = (r + 1)^2 / 8 for
// punctual lights (the remapping that tames hot rough highlights; image-based light would use
// k = alpha / 2), r the perceptual roughness.
inline float schlick_ggx_k_punctual(float perceptual_roughness) {
    float r = std::clamp(perceptual_roughness, 0.0f, 1.0f) + 1.0f;
    return r * r / 8.0f;
}
inline float v_schlick_ggx(float n_dot_l, float n_dot_v, float k) {
    float g = 4.0f * (n_dot_l * (1.0f - k) + k) * (n_dot_v * (1.0f - k) + k);
    return g > 0.0f ? 1.0f / g : 0.0f;
}

// Cook-Torrance's V-cavity: G = min(1, 2 n.h n.v / v.h, 2 n.h n.l / v.h).
inline float v_cook_torrance(float n_dot_l, float n_dot_v, float n_dot_h, float v_dot_h) {
    if (n_dot_l <= 0.0f || n_dot_v <= 0.0f) return 0.0f;
    float g = 1.0f;
    if (v_dot_h > 0.0f) g = std::min(1.0f, 2.0f * n_dot_h * std::min(n_dot_v, n_dot_l) / v_dot_h);
    return g / (4.0f * n_dot_l * n_dot_v);
}

// Kelemen and Szirmay-Kalos: G / (n.l n.v) ~ 1 / (v.h)^2, so V = 1 / (4 (v.h)^2).
inline float v_kelemen(float v_dot_h) {
    float c = std::max(v_dot_h, 1e-4f);
    return 0.25f / (c * c);
}

// The Fresnel equations of a dielectric for unpolarised light, at the cosine c of the angle
// of incidence, for the ior eta (eta >= 1: no total internal reflection from outside).
inline float f_dielectric_exact(float c, float eta) {
    c = std::clamp(c, 0.0f, 1.0f);
    float g2 = eta * eta - 1.0f + c * c;
    if (g2 <= 0.0f) return 1.0f;
    float g = std::sqrt(g2);
    float a = (g - c) / (g + c);
    float b = (c * (g + c) - 1.0f) / (c * (g - c) + 1.0f);
    return std::min(0.5f * a * a * (1.0f + b * b), 1.0f);
}
// The ior whose normal-incidence reflectance is f0: (1 + sqrt f0) / (1 - sqrt f0).
inline float ior_from_f0(float f0) {
    float s = std::sqrt(std::clamp(f0, 0.0f, 0.9999f));
    return (1.0f + s) / (1.0f - s);
}
// Exact Fresnel of the dielectric lobe: per channel, the ior of its F0, scaled between F0 and
// F90 as Schlick's form is (F90 = the specular weight of KHR_materials_specular).
inline glm::vec3 f_exact_dielectric(glm::vec3 f0, glm::vec3 f90, float v_dot_h) {
    glm::vec3 out;
    for (int k = 0; k < 3; ++k) {
        float e = ior_from_f0(f0[k] / std::max(f90[k], 1e-6f));
        float f0e = f_dielectric_exact(1.0f, e);
        float fe = f_dielectric_exact(v_dot_h, e);
        // The exact curve rescaled so that it runs from f0 at normal incidence to f90 at grazing.
        float t = f0e < 1.0f ? (fe - f0e) / (1.0f - f0e) : 1.0f;
        out[k] = f0[k] + (f90[k] - f0[k]) * t;
    }
    return out;
}

// The spherical-Gaussian approximation of Schlick's power (UE4): 2^((-5.55473 c - 6.98316) c).
inline glm::vec3 f_spherical_gaussian(glm::vec3 f0, glm::vec3 f90, float v_dot_h) {
    float c = std::clamp(v_dot_h, 0.0f, 1.0f);
    return f0 + (f90 - f0) * std::exp2((-5.55473f * c - 6.98316f) * c);
}

// Burley (Disney 2012) diffuse, relative to Lambert: (1 + (F90 - 1)(1 - n.l)^5)(1 + (F90 - 1)(1 - n.v)^5)
// with F90 = 0.5 + 2 r (v.h)^2, r the perceptual roughness.
inline float diffuse_burley_factor(float n_dot_l, float n_dot_v, float v_dot_h, float perceptual_roughness) {
    float f90 = 0.5f + 2.0f * perceptual_roughness * v_dot_h * v_dot_h;
    auto p5 = [](float x) {
        float x2 = x * x;
        return x2 * x2 * x;
    };
    return (1.0f + (f90 - 1.0f) * p5(1.0f - n_dot_l)) * (1.0f + (f90 - 1.0f) * p5(1.0f - n_dot_v));
}

// Oren-Nayar (1994, the qualitative model), relative to Lambert: A + B max(0, cos(phi)) sin(a) tan(b),
// written as A + B s / max(n.l, n.v) with s = l.v - n.l n.v (exactly that product when s > 0),
// with the surface's slope deviation sigma = the perceptual roughness in radians.
inline float diffuse_oren_nayar_factor(float n_dot_l, float n_dot_v, float l_dot_v, float perceptual_roughness) {
    float s2 = perceptual_roughness * perceptual_roughness;
    float a = 1.0f - 0.5f * s2 / (s2 + 0.33f);
    float b = 0.45f * s2 / (s2 + 0.09f);
    float s = l_dot_v - n_dot_l * n_dot_v;
    float t = std::max(std::max(n_dot_l, n_dot_v), 1e-4f);
    return a + b * std::max(s, 0.0f) / t;
}

// evaluate_terms (brdf.h) with the model's terms in place of the defaults: the same layering
// (fresnel_mix of the dielectric, conductor_fresnel of the metal), D, V and F chosen by `m`,
// and the diffuse lobe scaled by the Burley or Oren-Nayar factor; `film` as in brdf.h.
inline Terms evaluate_terms(const Surface& s, glm::vec3 n, glm::vec3 v, glm::vec3 l, const BrdfModel& m,
                            const IridescenceFresnel& film = {}) {
    if (m.is_default()) return evaluate_terms(s, n, v, l, film);
    Terms t;
    const auto [n_dot_l, n_dot_v, n_dot_h, v_dot_h] = cosines(n, v, l);
    float alpha = alpha_from_roughness(s.perceptual_roughness);
    switch (m.d) {
        case Distribution::Ggx: t.d = d_ggx(n_dot_h, alpha); break;
        case Distribution::Beckmann: t.d = d_beckmann(n_dot_h, alpha); break;
        case Distribution::BlinnPhong: t.d = d_blinn_phong(n_dot_h, alpha); break;
    }
    switch (m.g) {
        case Geometry::SmithHeightCorrelated: t.v = v_smith_ggx_correlated(n_dot_l, n_dot_v, alpha); break;
        case Geometry::SmithSeparable: t.v = v_smith_ggx_separable(n_dot_l, n_dot_v, alpha); break;
        case Geometry::SchlickGgx:
            t.v = v_schlick_ggx(n_dot_l, n_dot_v, schlick_ggx_k_punctual(s.perceptual_roughness));
            break;
        case Geometry::CookTorrance: t.v = v_cook_torrance(n_dot_l, n_dot_v, n_dot_h, v_dot_h); break;
        case Geometry::Kelemen: t.v = v_kelemen(v_dot_h); break;
    }
    glm::vec3 f0d = s.dielectric_f0() * s.specular_weight, f90d(s.specular_weight);
    glm::vec3 f_metal(0.0f), f_dielectric(0.0f);
    switch (m.f) {
        case Fresnel::Schlick:
            f_metal = f_schlick(s.base_color, glm::vec3(1.0f), v_dot_h);
            f_dielectric = f_schlick(f0d, f90d, v_dot_h);
            break;
        case Fresnel::ExactDielectric:  // conductors keep Schlick's form (their F0 is a colour, not an ior)
            f_metal = f_schlick(s.base_color, glm::vec3(1.0f), v_dot_h);
            f_dielectric = f_exact_dielectric(f0d, f90d, v_dot_h);
            break;
        case Fresnel::SphericalGaussian:
            f_metal = f_spherical_gaussian(s.base_color, glm::vec3(1.0f), v_dot_h);
            f_dielectric = f_spherical_gaussian(f0d, f90d, v_dot_h);
            break;
    }
    float diffuse = 1.0f;
    switch (m.diffuse) {
        case Diffuse::Lambert: break;
        case Diffuse::Burley: diffuse = diffuse_burley_factor(n_dot_l, n_dot_v, v_dot_h, s.perceptual_roughness); break;
        case Diffuse::OrenNayar:
            diffuse = diffuse_oren_nayar_factor(n_dot_l, n_dot_v, glm::dot(l, v), s.perceptual_roughness);
            break;
    }
    layer(t, s, f_dielectric, f_metal, lambert(s.base_color) * diffuse, film);
    return t;
}

inline glm::vec3 evaluate(const Surface& s, glm::vec3 n, glm::vec3 v, glm::vec3 l, const BrdfModel& m) {
    Terms t = evaluate_terms(s, n, v, l, m);
    return t.diffuse + t.specular;
}

}  // namespace fresnel::brdf
