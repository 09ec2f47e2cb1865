#pragma once
// The glTF 2.0 metallic-roughness BRDF (specification, Appendix B), once in C++.
// shaders/brdf.glsl holds the same functions; tests/gpu/brdf_gpu_test.cpp renders
// a grid of inputs through the GLSL and checks it against these.
//
// Conventions: all vectors unit length in the same space; n·l, n·v clamped by the
// caller; alpha = roughness^2 (perceptual roughness squared).
#include <algorithm>
#include <cmath>
#include <vector>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace fresnel::brdf {

inline constexpr float kPi = 3.14159265358979323846f;

// Trowbridge-Reitz (GGX) normal distribution D(h).
inline float d_ggx(float n_dot_h, float alpha) {
    float a2 = alpha * alpha;
    // f = 1 - (n.h)^2 (1 - a2), written as (1 - n.h)(1 + n.h) + (n.h)^2 a2 so that it keeps
    // its precision at the peak of glossy lobes (n.h -> 1), where the naive form cancels.
    // The floor keeps alpha = 0 (a mirror) from giving 0/0.
    float f = std::max((1.0f - n_dot_h) * (1.0f + n_dot_h) + n_dot_h * n_dot_h * a2, 1e-7f);
    return a2 / (kPi * f * f);
}

// Height-correlated Smith visibility V = G / (4 n·l n·v).
inline float v_smith_ggx_correlated(float n_dot_l, float n_dot_v, float alpha) {
    float a2 = alpha * alpha;
    float ggxv = n_dot_l * std::sqrt(n_dot_v * n_dot_v * (1.0f - a2) + a2);
    float ggxl = n_dot_v * std::sqrt(n_dot_l * n_dot_l * (1.0f - a2) + a2);
    float g = ggxv + ggxl;
    return g > 0.0f ? 0.5f / g : 0.0f;
}

// Schlick's Fresnel approximation.
inline glm::vec3 f_schlick(glm::vec3 f0, glm::vec3 f90, float v_dot_h) {
    float x = std::clamp(1.0f - v_dot_h, 0.0f, 1.0f);
    float x2 = x * x;
    return f0 + (f90 - f0) * (x2 * x2 * x);
}
inline float f_schlick(float f0, float f90, float v_dot_h) {
    float x = std::clamp(1.0f - v_dot_h, 0.0f, 1.0f);
    float x2 = x * x;
    return f0 + (f90 - f0) * (x2 * x2 * x);
}

inline glm::vec3 lambert(glm::vec3 diffuse_color) { return diffuse_color / kPi; }

// Shading inputs at one point, after textures and factors are applied.
struct Surface {
    glm::vec3 base_color{1.0f};
    float metallic = 0.0f;
    float perceptual_roughness = 1.0f;
    float specular_f0 = 0.04f;  // dielectric reflectance at normal incidence: ((ior-1)/(ior+1))^2, 0.04 at ior 1.5
    // KHR_materials_specular (and specular-glossiness): the dielectric F0 colour and a weight
    // that scales the dielectric specular lobe (F0 and F90).
    glm::vec3 specular_color{1.0f};
    float specular_weight = 1.0f;
    glm::vec3 dielectric_f0() const { return glm::min(glm::vec3(specular_f0) * specular_color, glm::vec3(1.0f)); }
};

// Smallest perceptual roughness used in shading. 0, as in the glTF spec and the Khronos
// Sample Viewer: a perfect mirror then reflects nothing from punctual lights (D = 0 away
// from the exact peak), and everything from image-based light.
inline constexpr float kMinRoughness = 0.0f;

inline float alpha_from_roughness(float perceptual) {
    float r = std::clamp(perceptual, kMinRoughness, 1.0f);
    return r * r;
}

// The separate terms of the BRDF for debugging views and tests.
struct Terms {
    float d = 0, v = 0;
    glm::vec3 f{0.0f};        // the metal/dielectric-mixed Fresnel
    glm::vec3 f_dielectric{0.0f}, f_metal{0.0f};  // the two lobes' Fresnel terms
    glm::vec3 diffuse{0.0f};  // f_diffuse (already weighted by 1 - F_dielectric and 1 - metallic)
    glm::vec3 diffuse_weight{0.0f};  // that weight: (1 - metallic) (1 - F_dielectric), film_diffuse_weight under a film
    glm::vec3 specular{0.0f}; // f_specular = specular_dielectric + specular_metal
    glm::vec3 specular_dielectric{0.0f};  // (1 - metallic) F_dielectric V D
    glm::vec3 specular_metal{0.0f};     // metallic F_metal V D
};

// The clamped cosines of one (n, v, l), with h = normalize(l + v) (n when l = -v).
struct Cosines {
    float n_dot_l, n_dot_v, n_dot_h, v_dot_h;
};
inline Cosines cosines(glm::vec3 n, glm::vec3 v, glm::vec3 l) {
    glm::vec3 h = l + v;
    float hl = glm::length(h);
    h = hl > 0.0f ? h / hl : n;
    return {std::clamp(glm::dot(n, l), 0.0f, 1.0f), std::clamp(glm::dot(n, v), 0.0f, 1.0f),
            std::clamp(glm::dot(n, h), 0.0f, 1.0f), std::clamp(glm::dot(v, h), 0.0f, 1.0f)};
}

// ---- KHR_materials_iridescence: thin-film interference (Belcour & Barla 2017) ----------
// The Fresnel of a dielectric film (ior film_ior, thickness in nm) between the outside and
// the base, as the extension and the Khronos Sample Viewer evaluate it (evalIridescence): the
// base's ior from its F0, Schlick reflectances at both interfaces, the phase shifts of each
// reflection, and the Airy sum's first two orders integrated against the CIE XYZ matching
// functions in Fourier space (Gaussian fits), in linear Rec.709. The same functions as
// shaders/iridescence.glsl.

// The spectral sensitivity term: the XYZ matching functions' Fourier transform at optical
// path difference opd (nm) with phase shift `shift` (per channel), in linear Rec.709.
glm::vec3 iridescence_sensitivity(float opd, glm::vec3 shift);

// F_iridescence for light from a medium of outside_ior at cos_theta1 = n.v. The film's ior
// eases to outside_ior below 0.03 nm (so thickness 0 is no film); total internal reflection
// in the film gives 1.
glm::vec3 iridescence_fresnel(float outside_ior, float film_ior, float cos_theta1, float thickness,
                              glm::vec3 base_f0);

// The film's Fresnel over the dielectric and the metallic base at one view, and its weight.
struct IridescenceFresnel {
    float factor = 0.0f;          // 0: no film
    glm::vec3 dielectric{0.0f};   // over the dielectric base (F0 = its F0 colour)
    glm::vec3 metal{0.0f};        // over the metal (F0 = base colour)
};
// The film at n.v: factor 0 when factor or thickness is 0 (the Khronos viewer turns the
// film off at thickness 0), else both Fresnels from air (outside ior 1).
IridescenceFresnel iridescence_at(float factor, float film_ior, float thickness, float n_dot_v,
                                  glm::vec3 f0_dielectric, glm::vec3 base_color);

// What the diffuse keeps below the dielectric's Fresnel f_dielectric: 1 - F, and under a thin
// film mix(1 - F, 1 - max(F_film), factor) (the Khronos viewer's rgb_mix). Also the weight of
// the transmission that replaces the diffuse (KHR_materials_transmission).
inline glm::vec3 film_diffuse_weight(glm::vec3 f_dielectric, const IridescenceFresnel& film) {
    glm::vec3 weight = 1.0f - f_dielectric;
    if (film.factor > 0.0f) {
        float film_max = std::max({film.dielectric.x, film.dielectric.y, film.dielectric.z});
        weight = glm::mix(weight, glm::vec3(1.0f - film_max), film.factor);
    }
    return weight;
}

// KHR_materials_diffuse_transmission, as the Khronos Sample Viewer shades it: the diffuse lobe
// of one light times its cosine, mix(reflected_cos, lambert(color) n.(-l), factor), where
// reflected_cos is the reflected lobe times n.l and n_dot_minus_l = max(-n.l, 0): the share
// `factor` of the diffuse light goes through the surface as a Lambert lobe of `color` (not the
// base colour), lit from behind. The result takes the diffuse's weights (1 - F, 1 - metallic).
// For image-based light the same mix holds with the irradiance at n and at -n.
inline glm::vec3 diffuse_transmission_mix(glm::vec3 reflected_cos, float n_dot_minus_l, float factor,
                                          glm::vec3 color) {
    if (!(factor > 0.0f)) return reflected_cos;
    return glm::mix(reflected_cos, lambert(color) * n_dot_minus_l, factor);
}

// KHR_materials_diffuse_roughness: the energy-preserving Oren-Nayar lobe (EON: Portsmouth,
// Kutz and Hill 2025, the diffuse of OpenPBR), written as a factor of Lambert's lobe rho/pi per
// channel so that the glTF layering around it (1 - F, 1 - metallic) is unchanged. r is the
// diffuse roughness in [0, 1] (0: Lambert, factor 1).
//   f = rho/pi [A (1 + r s/t) + rho_ms/rho (1 - E(n.l)) (1 - E(n.v)) / (1 - E_avg)]
//   A = 1 / (1 + c1 r), s = l.v - n.l n.v, t = max(n.l, n.v) where s > 0 (else 1): Fujii's
//       Oren-Nayar single scattering; E its directional albedo (the paper's quartic fit),
//       E_avg = A (1 + c2 r) its average; rho_ms = rho^2 E_avg / (1 - rho (1 - E_avg)) the
//       multiple scattering that restores the energy the single-scattering lobe loses.
// With rho = 1 every direction's albedo is 1 (the white furnace). The twin of eon_factor in
// shaders/brdf.glsl.
inline constexpr float kEonC1 = 0.5f - 2.0f / (3.0f * kPi);
inline constexpr float kEonC2 = 2.0f / 3.0f - 28.0f / (15.0f * kPi);
inline float eon_single_albedo(float mu, float r) {
    float c = 1.0f - mu;
    float g_over_pi = c * (0.0571085289f + c * (0.491881867f + c * (-0.332181442f + c * 0.0714429953f)));
    return (1.0f + r * g_over_pi) / (1.0f + kEonC1 * r);
}
inline glm::vec3 eon_factor(glm::vec3 rho, float r, float n_dot_l, float n_dot_v, float l_dot_v) {
    if (!(r > 0.0f)) return glm::vec3(1.0f);
    float mu_l = std::max(n_dot_l, 1e-4f), mu_v = std::max(n_dot_v, 1e-4f);
    float s = l_dot_v - mu_l * mu_v;
    float s_over_t = s > 0.0f ? s / std::max(mu_l, mu_v) : s;
    float a = 1.0f / (1.0f + kEonC1 * r);
    float e_avg = a * (1.0f + kEonC2 * r);
    float ms = std::max(1.0f - eon_single_albedo(mu_l, r), 1e-7f) * std::max(1.0f - eon_single_albedo(mu_v, r), 1e-7f) /
               std::max(1.0f - e_avg, 1e-7f);
    glm::vec3 c = glm::clamp(rho, 0.0f, 1.0f);
    glm::vec3 ms_over_rho = c * e_avg / (glm::vec3(1.0f) - c * (1.0f - e_avg));
    return glm::vec3(a * (1.0f + r * s_over_t)) + ms_over_rho * ms;
}
// The lobe's directional albedo at n.v relative to Lambert's (rho): E(n.v) + rho_ms/rho (1 - E(n.v)),
// what image-based light's diffuse term is scaled by (1 for r = 0, and for rho = 1).
inline glm::vec3 eon_albedo_factor(glm::vec3 rho, float r, float n_dot_v) {
    if (!(r > 0.0f)) return glm::vec3(1.0f);
    float e = eon_single_albedo(std::max(n_dot_v, 1e-4f), r);
    float e_avg = (1.0f + kEonC2 * r) / (1.0f + kEonC1 * r);
    glm::vec3 c = glm::clamp(rho, 0.0f, 1.0f);
    return glm::vec3(e) + c * e_avg / (glm::vec3(1.0f) - c * (1.0f - e_avg)) * (1.0f - e);
}

// Appendix B's layering of the lobes, given t.d and t.v, the two Fresnel terms and the diffuse
// lobe before its weights: fresnel_mix of the dielectric, conductor_fresnel of the metal.
// With a thin film (KHR_materials_iridescence, as the Khronos Sample Viewer layers it) both
// Fresnel terms become mix(F, F_film, factor), and the diffuse below the dielectric keeps
// mix(1 - F, 1 - max(F_film), factor) (the viewer's rgb_mix).
inline void layer(Terms& t, const Surface& s, glm::vec3 f_dielectric, glm::vec3 f_metal, glm::vec3 diffuse,
                  const IridescenceFresnel& film = {}) {
    float spec = t.v * t.d;
    const glm::vec3 diffuse_weight = film_diffuse_weight(f_dielectric, film);
    if (film.factor > 0.0f) {
        f_dielectric = glm::mix(f_dielectric, film.dielectric, film.factor);
        f_metal = glm::mix(f_metal, film.metal, film.factor);
    }
    t.f_dielectric = f_dielectric;  // with the film: what apply_anisotropy weights its lobes by
    t.f_metal = f_metal;
    t.f = glm::mix(f_dielectric, f_metal, s.metallic);
    t.diffuse_weight = (1.0f - s.metallic) * diffuse_weight;
    t.diffuse = t.diffuse_weight * diffuse;
    t.specular_dielectric = (1.0f - s.metallic) * f_dielectric * spec;
    t.specular_metal = s.metallic * f_metal * spec;
    t.specular = t.specular_dielectric + t.specular_metal;
}

// Evaluates f(l, v) following Appendix B:
//   dielectric = mix(lambert(base), V*D, F_schlick(f0 w, w, v·h))  (fresnel_mix; f0 = 0.04 and the
//                specular weight w = 1 unless KHR_materials_ior / _specular say otherwise)
//   metal      = F_schlick(base, 1, v·h) * V*D                      (conductor_fresnel)
//   f          = mix(dielectric, metal, metallic)
// `film`: a thin film over both (KHR_materials_iridescence; see layer()).
inline Terms evaluate_terms(const Surface& s, glm::vec3 n, glm::vec3 v, glm::vec3 l,
                            const IridescenceFresnel& film = {}) {
    Terms t;
    const Cosines c = cosines(n, v, l);
    float alpha = alpha_from_roughness(s.perceptual_roughness);
    t.d = d_ggx(c.n_dot_h, alpha);
    t.v = v_smith_ggx_correlated(c.n_dot_l, c.n_dot_v, alpha);
    glm::vec3 f_metal = f_schlick(s.base_color, glm::vec3(1.0f), c.v_dot_h);
    glm::vec3 f_dielectric = f_schlick(s.dielectric_f0() * s.specular_weight, glm::vec3(s.specular_weight), c.v_dot_h);
    layer(t, s, f_dielectric, f_metal, lambert(s.base_color), film);
    return t;
}

inline glm::vec3 evaluate(const Surface& s, glm::vec3 n, glm::vec3 v, glm::vec3 l) {
    Terms t = evaluate_terms(s, n, v, l);
    return t.diffuse + t.specular;
}

// ---- KHR_materials_anisotropy: the anisotropic GGX lobe --------------------------------
// As the Khronos Sample Viewer evaluates it; the same functions as shaders/brdf.glsl. The
// lobe is stretched along the anisotropy direction t (b = ng x t): alpha_t = mix(alpha, 1,
// strength^2) along t, alpha_b = alpha (floored at 1e-3) along b.

// Anisotropic GGX D(h) with t.h, b.h, n.h (n.h floored at 1e-3 by the caller).
inline float d_ggx_anisotropic(float n_dot_h, float t_dot_h, float b_dot_h, float at, float ab) {
    float a2 = at * ab;
    glm::vec3 f(ab * t_dot_h, at * b_dot_h, a2 * n_dot_h);
    float w2 = a2 / glm::dot(f, f);
    return a2 * w2 * w2 / kPi;
}
// Anisotropic height-correlated Smith visibility V = G / (4 n.l n.v), clamped to [0, 1].
inline float v_ggx_anisotropic(float n_dot_l, float n_dot_v, float b_dot_v, float t_dot_v, float t_dot_l,
                               float b_dot_l, float at, float ab) {
    float ggxv = n_dot_l * glm::length(glm::vec3(at * t_dot_v, ab * b_dot_v, n_dot_v));
    float ggxl = n_dot_v * glm::length(glm::vec3(at * t_dot_l, ab * b_dot_l, n_dot_l));
    float g = ggxv + ggxl;
    return g != 0.0f ? std::clamp(0.5f / g, 0.0f, 1.0f) : 0.0f;
}
// The lobe's roughness along the anisotropy direction.
inline float anisotropic_alpha_t(float alpha, float strength) {
    return alpha + (1.0f - alpha) * strength * strength;
}
// Replaces the specular lobes' D and V in t (from evaluate_terms) with the anisotropic ones at
// (n, v, l) and the direction frame (at, bt); the Fresnel terms and the diffuse lobe stay.
// As the Khronos viewer: n.l clamped, n.h clamped to [1e-3, 1], n.v not clamped.
inline void apply_anisotropy(Terms& t, const Surface& s, glm::vec3 n, glm::vec3 v, glm::vec3 l, glm::vec3 at_dir,
                             glm::vec3 bt_dir, float strength) {
    glm::vec3 h = l + v;
    float hl = glm::length(h);
    h = hl > 0.0f ? h / hl : n;
    float alpha = alpha_from_roughness(s.perceptual_roughness);
    float at = anisotropic_alpha_t(alpha, strength);
    float ab = std::clamp(alpha, 1e-3f, 1.0f);
    float n_dot_l = std::clamp(glm::dot(n, l), 0.0f, 1.0f);
    float n_dot_h = std::clamp(glm::dot(n, h), 1e-3f, 1.0f);
    float n_dot_v = glm::dot(n, v);
    t.v = v_ggx_anisotropic(n_dot_l, n_dot_v, glm::dot(bt_dir, v), glm::dot(at_dir, v), glm::dot(at_dir, l),
                            glm::dot(bt_dir, l), at, ab);
    t.d = d_ggx_anisotropic(n_dot_h, glm::dot(at_dir, h), glm::dot(bt_dir, h), at, ab);
    float spec = t.v * t.d;
    t.specular_dielectric = (1.0f - s.metallic) * t.f_dielectric * spec;
    t.specular_metal = s.metallic * t.f_metal * spec;
    t.specular = t.specular_dielectric + t.specular_metal;
}

// The bent normal the image-based light of an anisotropic lobe reflects the view about
// (the Khronos viewer's getIBLRadianceAnisotropy): the normal tilted towards the one
// perpendicular to the anisotropy bitangent bt and to bt x v, the more the stronger and
// smoother the lobe; the prefiltered cube is then read along reflect(-v, bent) at the
// material's roughness.
inline glm::vec3 anisotropic_bent_normal(glm::vec3 n, glm::vec3 v, float perceptual_roughness, float strength,
                                         glm::vec3 bt_dir) {
    glm::vec3 tangent = glm::cross(bt_dir, v);
    glm::vec3 normal = glm::cross(tangent, bt_dir);
    float bend = 1.0f - strength * (1.0f - perceptual_roughness);
    float bend4 = bend * bend * bend * bend;
    return glm::normalize(normal + (n - normal) * bend4);
}

// KHR_materials_clearcoat. The coat's lobe times n.l, at the coat normal nc (no Fresnel:
// the layering weight carries it). The same as clearcoat_specular in shaders/brdf.glsl.
inline float clearcoat_specular(glm::vec3 nc, glm::vec3 v, glm::vec3 l, float alpha) {
    float n_dot_l = std::clamp(glm::dot(nc, l), 0.0f, 1.0f);
    if (n_dot_l <= 0.0f) return 0.0f;
    glm::vec3 h = l + v;
    float hl = glm::length(h);
    h = hl > 0.0f ? h / hl : nc;
    float n_dot_v = std::clamp(glm::dot(nc, v), 0.0f, 1.0f);
    return n_dot_l * d_ggx(std::clamp(glm::dot(nc, h), 0.0f, 1.0f), alpha) * v_smith_ggx_correlated(n_dot_l, n_dot_v, alpha);
}

// The extension's layering, fresnel_coat: mix(base, coat, weight * Fc), where Fc is the
// Schlick Fresnel of the coat (F0 from the ior, 0.04 at 1.5) at its normal and the view.
// Returns the weight given to the coat; the base keeps 1 minus it.
inline float clearcoat_mix(float clearcoat, float coat_f0, glm::vec3 nc, glm::vec3 v) {
    return clearcoat * f_schlick(coat_f0, 1.0f, std::clamp(glm::dot(nc, v), 0.0f, 1.0f));
}

// ---- KHR_materials_sheen: the Charlie sheen lobe (Estevez & Kulla 2017) ----------------
// The extension's BRDF, as the Khronos Sample Viewer evaluates it; the same functions as
// shaders/sheen.glsl. Sheen roughness r is perceptual; alpha_g = r^2.

// Charlie distribution D(h) = (2 + 1/alpha_g) sin(theta_h)^(1/alpha_g) / (2 pi).
inline float d_charlie(float sheen_roughness, float n_dot_h) {
    float r = std::max(sheen_roughness, 1e-6f);
    float inv_alpha = 1.0f / (r * r);
    float sin2h = std::max(1.0f - n_dot_h * n_dot_h, 0.0f);
    return (2.0f + inv_alpha) * std::pow(sin2h, inv_alpha * 0.5f) / (2.0f * kPi);
}

// Estevez-Kulla's fit of the Charlie shadowing exponent L(x) at one alpha_g.
inline float sheen_lambda_fit(float x, float alpha_g) {
    float t = (1.0f - alpha_g) * (1.0f - alpha_g);
    float a = 21.5473f + (25.3245f - 21.5473f) * t;
    float b = 3.82987f + (3.32435f - 3.82987f) * t;
    float c = 0.19823f + (0.16801f - 0.19823f) * t;
    float d = -1.97760f + (-1.27393f + 1.97760f) * t;
    float e = -4.32054f + (-4.85967f + 4.32054f) * t;
    return a / (1.0f + b * std::pow(x, c)) + d * x + e;
}
// Lambda(cos theta): exp(L(cos)) below 0.5, exp(2 L(0.5) - L(1 - cos)) above (the fit's
// symmetric extension).
inline float sheen_lambda(float cos_theta, float alpha_g) {
    if (std::fabs(cos_theta) < 0.5f) return std::exp(sheen_lambda_fit(cos_theta, alpha_g));
    return std::exp(2.0f * sheen_lambda_fit(0.5f, alpha_g) - sheen_lambda_fit(1.0f - cos_theta, alpha_g));
}
// Visibility V = G / (4 n.l n.v) with G = 1 / (1 + Lambda(v) + Lambda(l)), clamped to [0, 1].
inline float v_sheen(float n_dot_l, float n_dot_v, float sheen_roughness) {
    float r = std::max(sheen_roughness, 1e-6f);
    float alpha_g = r * r;
    float denom = (1.0f + sheen_lambda(n_dot_v, alpha_g) + sheen_lambda(n_dot_l, alpha_g)) * (4.0f * n_dot_v * n_dot_l);
    return denom > 0.0f ? std::clamp(1.0f / denom, 0.0f, 1.0f) : 1.0f;
}
// The sheen lobe f_sheen = sheen colour * D * V (no n.l); n.l, n.v, n.h clamped by the caller.
inline glm::vec3 sheen_specular(glm::vec3 sheen_color, float sheen_roughness, float n_dot_l, float n_dot_v, float n_dot_h) {
    return sheen_color * (d_charlie(sheen_roughness, n_dot_h) * v_sheen(n_dot_l, n_dot_v, sheen_roughness));
}

// Directional albedo E(n.v, r) of the white sheen lobe (integral of D V cos over the
// hemisphere), by a cosine-weighted midpoint grid of samples_per_axis^2 points.
// The layer under the sheen is scaled by 1 - max(sheen colour) E (the extension's albedo
// scaling); libs/ibl bakes E into the A channel of the split-sum table.
float sheen_albedo_integral(float n_dot_v, float sheen_roughness, int samples_per_axis = 64);

// E tabulated on the split-sum table's grid (ibl/precompute.h: x = n.v at texel centres with
// column 0 at the grazing limit, y = roughness at texel centres) and read back with the
// bilinear, clamp-to-edge lookup a GL sampler does at u = n.v, v = roughness, so the CPU
// reads the same values the shader reads from the table's A channel.
class SheenAlbedoTable {
public:
    explicit SheenAlbedoTable(int size = 32, int samples_per_axis = 64);
    float operator()(float n_dot_v, float sheen_roughness) const;
    int size() const { return size_; }
    float at(int column, int row) const { return values_[std::size_t(row) * std::size_t(size_) + std::size_t(column)]; }
    // The n.v of a column (the split-sum table's convention).
    static float column_n_dot_v(int column, int size);
    // The table fresnel::shade_light uses (built on first use, then shared read-only).
    static const SheenAlbedoTable& standard();

private:
    int size_;
    std::vector<float> values_;
};

// The extension's albedo scaling of the layer below the sheen for a punctual light:
// min(1 - max(c) E(n.v), 1 - max(c) E(n.l)). For image-based light only the n.v term.
inline float sheen_albedo_scaling(glm::vec3 sheen_color, float e_v, float e_l) {
    float m = std::max({sheen_color.x, sheen_color.y, sheen_color.z});
    return std::min(1.0f - m * e_v, 1.0f - m * e_l);
}

// Directional albedo: the integral of f(l, v) cos(theta_l) over the hemisphere, by a
// deterministic quadrature with `samples_per_axis`^2 points per lobe (see brdf.cpp).
// Used by tests (energy conservation; ibl_test's check of the split-sum table).
glm::vec3 directional_albedo(const Surface& s, float n_dot_v, int samples_per_axis = 256);

// Multiple-bounce ambient occlusion (Jimenez et al. 2016, "Practical Real-Time Strategies for
// Accurate Indirect Occlusion", the GTAO fit): visibility `ao` of a surface of diffuse albedo
// `albedo`, raised by the light its surroundings (taken to have the same albedo) send back.
// 1 at ao = 1 for any albedo; never below `ao`. brdf.glsl's ao_multibounce (pbr.frag applies it
// to the diffuse share of indirect light under `--ao baked`).
inline glm::vec3 ao_multibounce(float ao, glm::vec3 albedo) {
    glm::vec3 out;
    for (int i = 0; i < 3; ++i) {
        const float a = 2.0404f * albedo[i] - 0.3324f, b = -4.7951f * albedo[i] + 0.6417f, c = 2.7552f * albedo[i] + 0.6903f;
        out[i] = std::max(ao, ((ao * a + b) * ao + c) * ao);
    }
    return out;
}

}  // namespace fresnel::brdf
