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
// Exact: the dielectric lobe as ExactDielectric, the metal lobe by the Fresnel equations of a
// conductor (f_conductor_exact) of the complex ior BrdfModel::conductor names.
enum class Fresnel { Schlick, ExactDielectric, SphericalGaussian, Exact };
// The conductor of Fresnel::Exact's metal lobe: BaseColor maps the base colour (its F0, per
// channel) to n, k (conductor_from_f0); the others are measured metals (measured_conductor)
// that replace the base colour in the metal lobe.
enum class Conductor { BaseColor, Iron, Gold, Aluminium, Chromium, Copper, Lead, Platinum, Silver };
enum class Diffuse { Lambert, Burley, OrenNayar };

struct BrdfModel {
    Distribution d = Distribution::Ggx;
    Geometry g = Geometry::SmithHeightCorrelated;
    Fresnel f = Fresnel::Schlick;
    Diffuse diffuse = Diffuse::Lambert;
    Conductor conductor = Conductor::BaseColor;  // read with Fresnel::Exact only ("F=exact:gold")
    bool is_default() const { return *this == BrdfModel{}; }
    bool operator==(const BrdfModel&) const = default;
};

// "D=beckmann,G=kelemen,F=schlick,diffuse=burley" (any subset, any order; the terms' names as
// in brdf_model_names; F=exact takes a metal, "F=exact:gold", of brdf_conductor_names). nullopt
// with `error` set for an unknown key, value or metal.
std::optional<BrdfModel> parse_brdf_model(std::string_view text, std::string* error = nullptr);
// The canonical text of a model ("D=ggx,G=smith-height-correlated,F=schlick,diffuse=lambert";
// "F=exact:gold" with a measured metal).
std::string to_string(const BrdfModel& m);
// Every accepted value of one key ("D", "G", "F", "diffuse"), in enum order.
const std::vector<std::string>& brdf_model_names(std::string_view key);
// The conductors of F=exact, in enum order ("base-color", the default, then the metals).
const std::vector<std::string>& brdf_conductor_names();
// The shader defines of a model: none for the default, else "BRDF_D 1" etc. for the
// non-default terms (the enum values), and for a measured metal its n and k as
// "BRDF_CONDUCTOR_N vec3(...)" and "BRDF_CONDUCTOR_K vec3(...)" (the floats of
// measured_conductor, printed so that they read back exactly).
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

// ---- Conductors (Fresnel::Exact) ----

// The Fresnel equations of a conductor of complex ior n + ik (relative to the outside; k = 0
// is a dielectric) for unpolarised light at the cosine c of the angle of incidence, as
// (Rs + Rp) / 2 (Born and Wolf; pbrt-v4's FrComplex computes the same with complex numbers):
// with a + ib = sqrt(eta^2 - sin^2),
//   Rs = ((a - c)^2 + b^2) / ((a + c)^2 + b^2),
//   Rp = Rs ((a c - sin^2)^2 + b^2 c^2) / ((a c + sin^2)^2 + b^2 c^2).
// a^2 and b^2 are each taken from whichever form has no cancellation (k >> n makes
// |eta^2 - sin^2| + Re(eta^2 - sin^2) a difference), and the sums of squares keep Rs and Rp
// in [0, 1]: exact at normal incidence (((n-1)^2 + k^2) / ((n+1)^2 + k^2)) and 1 at grazing.
inline float f_conductor_exact(float c, float n, float k) {
    c = std::clamp(c, 0.0f, 1.0f);
    float c2 = c * c, s2 = 1.0f - c2;
    float t0 = n * n - k * k - s2;             // Re(eta^2 - sin^2)
    float nk2 = 4.0f * n * n * k * k;          // Im(eta^2 - sin^2)^2
    float m = std::sqrt(t0 * t0 + nk2);        // |eta^2 - sin^2| = a^2 + b^2
    float a2 = t0 >= 0.0f ? 0.5f * (m + t0) : (m - t0 > 0.0f ? 0.5f * nk2 / (m - t0) : 0.0f);
    float b2 = t0 <= 0.0f ? 0.5f * (m - t0) : 0.5f * nk2 / (m + t0);
    float a = std::sqrt(a2);
    float ds = (a + c) * (a + c) + b2;
    if (!(ds > 0.0f)) return 1.0f;  // n = 1, k = 0 at grazing: the limit of the dielectric
    float rs = ((a - c) * (a - c) + b2) / ds;
    float ac = a * c;
    float dp = (ac + s2) * (ac + s2) + b2 * c2;
    float rp = dp > 0.0f ? rs * ((ac - s2) * (ac - s2) + b2 * c2) / dp : rs;
    return std::min(0.5f * (rs + rp), 1.0f);
}

struct ComplexIor {
    glm::vec3 n, k;  // per RGB channel
};

// The conductor whose normal-incidence reflectance is f0 (per channel): Gulbrandsen's
// "Artist Friendly Metallic Fresnel" (JCGT 3(4), 2014) maps a reflectivity r and an edge tint
// g to n = g (1 - r)/(1 + r) + (1 - g)(1 + sqrt r)/(1 - sqrt r), k = sqrt((r (n+1)^2 - (n-1)^2)/(1 - r)).
// We take g = 1, which has the closed form n = (1 - r)/(1 + r), k = 2 sqrt(r)/(1 + r): it
// reproduces r exactly at normal incidence for every r in [0, 1] (no division by 1 - r), and
// it is near the edge tint of the bright metals of the measured table below (their g: 0.96 to
// 1 for silver, aluminium and gold's and copper's red and green). The others' are lower (gold's
// blue 0.75, lead and platinum about 0.8, iron and chromium 0.54 to 0.69): their curves dip
// below this one towards grazing; name them (F=exact:iron) for that.
inline ComplexIor conductor_from_f0(glm::vec3 f0) {
    ComplexIor c;
    for (int i = 0; i < 3; ++i) {
        float r = std::clamp(f0[i], 0.0f, 1.0f);
        c.n[i] = (1.0f - r) / (1.0f + r);
        c.k[i] = 2.0f * std::sqrt(r) / (1.0f + r);
    }
    return c;
}

// Measured metals: n and k at red, green and blue, as the labPBR 1.3 material standard's
// table of predefined metals gives them (shaderLABS, "labPBR Material Standard", the f0 / metal
// channel values 230 to 237). Their normal-incidence reflectances: iron (0.53, 0.51, 0.50),
// gold (0.94, 0.78, 0.37), aluminium (0.91, 0.91, 0.92), chromium (0.56, 0.55, 0.55), copper
// (0.93, 0.72, 0.50), lead (0.63, 0.63, 0.64), platinum (0.68, 0.64, 0.59), silver (0.96, 0.95, 0.92).
inline ComplexIor measured_conductor(Conductor c) {
    switch (c) {
        case Conductor::BaseColor: break;
        case Conductor::Iron: return {{2.9114f, 2.9497f, 2.5845f}, {3.0893f, 2.9318f, 2.7670f}};
        case Conductor::Gold: return {{0.18299f, 0.42108f, 1.3734f}, {3.4242f, 2.3459f, 1.7704f}};
        case Conductor::Aluminium: return {{1.3456f, 0.96521f, 0.61722f}, {7.4746f, 6.3995f, 5.3031f}};
        case Conductor::Chromium: return {{3.1071f, 3.1812f, 2.3230f}, {3.3314f, 3.3291f, 3.1350f}};
        case Conductor::Copper: return {{0.27105f, 0.67693f, 1.3164f}, {3.6092f, 2.6248f, 2.2921f}};
        case Conductor::Lead: return {{1.9100f, 1.8300f, 1.4400f}, {3.5100f, 3.4000f, 3.1800f}};
        case Conductor::Platinum: return {{2.3757f, 2.0847f, 1.8453f}, {4.2655f, 3.7153f, 3.1365f}};
        case Conductor::Silver: return {{0.15943f, 0.14512f, 0.13547f}, {3.9291f, 3.1900f, 2.3808f}};
    }
    return {glm::vec3(1.0f), glm::vec3(0.0f)};  // BaseColor has no table: conductor_from_f0
}

inline glm::vec3 f_conductor_exact(const ComplexIor& ior, float v_dot_h) {
    return {f_conductor_exact(v_dot_h, ior.n.x, ior.k.x), f_conductor_exact(v_dot_h, ior.n.y, ior.k.y),
            f_conductor_exact(v_dot_h, ior.n.z, ior.k.z)};
}
// Fresnel::Exact's metal lobe: the conductor of `which`, or of the base colour.
inline glm::vec3 f_exact_metal(glm::vec3 base_color, Conductor which, float v_dot_h) {
    return f_conductor_exact(which == Conductor::BaseColor ? conductor_from_f0(base_color) : measured_conductor(which),
                             v_dot_h);
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
        case Fresnel::Exact:
            f_metal = f_exact_metal(s.base_color, m.conductor, v_dot_h);
            f_dielectric = f_exact_dielectric(f0d, f90d, v_dot_h);
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
