#pragma once
// Shading models older assets were made for, once in C++: OpenGL 1's fixed-function
// lighting and the normalized Blinn-Phong microfacet model. shaders/legacy_shading.glsl
// holds the same functions; tests/gpu/legacy_shading_gpu_test.cpp renders a grid of inputs
// through the GLSL and checks it against these.
//
// Conventions as in brdf.h: unit vectors in one space; n the shading normal, v towards the
// eye (local viewer), l towards the light. A light of intensity I acts as an OpenGL light
// of colour I (GL_DIFFUSE = GL_SPECULAR = I, GL_AMBIENT = 0), directional, no attenuation.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace fresnel::legacy {

inline constexpr float kPi = 3.14159265358979323846f;

// ---- OpenGL 1 fixed function (OpenGL 1.5 specification, 2.14.1 Lighting) ----------------
//
// Per vertex (Gouraud) or per fragment, the lit colour is
//   emission + ambient * global_ambient
//     + sum over lights [ max(n.l, 0) diffuse I + (n.l > 0) max(n.h, 0)^shininess specular I ]
// with h = normalize(l + v) (GL_LIGHT_MODEL_LOCAL_VIEWER true). With GL_SINGLE_COLOR the sum
// is clamped to [0, 1] as a whole, then modulated by the texture; with
// GL_SEPARATE_SPECULAR_COLOR the specular sum is clamped on its own and added after the
// texture (ogl1_combine). Fog then blends towards the fog colour.

// GL_SHININESS accepts 0..128 only (OpenGL 1 refuses more); MTL's Ns is clamped to that.
inline float ogl1_shininess(float ns) { return std::clamp(std::isnan(ns) ? 0.0f : ns, 0.0f, 128.0f); }

// max(n.h, 0)^s with 0^0 = 1 (the LIT instruction's rule, which Mesa's fixed-function
// program uses).
inline float ogl1_specular_power(float n_dot_h, float shininess) {
    if (shininess <= 0.0f) return 1.0f;
    return std::pow(std::max(n_dot_h, 0.0f), shininess);
}

// One light's diffuse and specular contributions (unclamped).
struct Ogl1Light {
    glm::vec3 diffuse{0.0f};
    glm::vec3 specular{0.0f};
};
inline Ogl1Light ogl1_light(const glm::vec3& n, const glm::vec3& v, const glm::vec3& l, const glm::vec3& light_color,
                            const glm::vec3& diffuse, const glm::vec3& specular, float shininess) {
    Ogl1Light out;
    float n_dot_l = glm::dot(n, l);
    out.diffuse = std::max(n_dot_l, 0.0f) * diffuse * light_color;
    if (n_dot_l > 0.0f) {
        glm::vec3 h = l + v;
        float len2 = glm::dot(h, h);
        float n_dot_h = len2 > 1e-20f ? glm::dot(n, h) / std::sqrt(len2) : 0.0f;
        out.specular = ogl1_specular_power(n_dot_h, shininess) * specular * light_color;
    }
    return out;
}

// emission + ambient * global ambient: the part of the colour no light changes.
inline glm::vec3 ogl1_base(const glm::vec3& emission, const glm::vec3& ambient, const glm::vec3& global_ambient) {
    return emission + ambient * global_ambient;
}

// The colour written for a fragment: `primary` = base + the diffuse sums, `secondary` = the
// specular sums (both unclamped, as summed), `texel` the modulating texture colour (1 without
// a texture). GL_SINGLE_COLOR: clamp(primary + secondary) * texel; separate: clamp(primary) *
// texel + clamp(secondary).
inline glm::vec3 ogl1_combine(const glm::vec3& primary, const glm::vec3& secondary, const glm::vec3& texel,
                              bool separate_specular) {
    const glm::vec3 zero(0.0f), one(1.0f);
    if (separate_specular) return glm::clamp(primary, zero, one) * texel + glm::clamp(secondary, zero, one);
    return glm::clamp(primary + secondary, zero, one) * texel;
}

// GL_FOG: the factor f of the fragment's own colour (1 - f of the fog colour), at eye-space
// depth z (the distance along the view axis, |z_eye|). Linear: (end - z) / (end - start);
// exp: e^(-density z); exp2: e^(-(density z)^2); clamped to [0, 1]. A linear range of zero
// width gives 1 before `end` and 0 from it.
enum class FogMode { None = 0, Linear = 1, Exp = 2, Exp2 = 3 };
inline float ogl1_fog_factor(FogMode mode, float z, float start, float end, float density) {
    float f = 1.0f;
    switch (mode) {
        case FogMode::None: return 1.0f;
        case FogMode::Linear: f = end != start ? (end - z) / (end - start) : (z < end ? 1.0f : 0.0f); break;
        case FogMode::Exp: f = std::exp(-density * z); break;
        case FogMode::Exp2: f = std::exp(-(density * z) * (density * z)); break;
    }
    return std::clamp(f, 0.0f, 1.0f);
}
inline glm::vec3 ogl1_apply_fog(const glm::vec3& color, const glm::vec3& fog_color, float factor) {
    return factor * color + (1.0f - factor) * fog_color;
}

// ---- Normalized Blinn-Phong microfacet model --------------------------------------------
//
// As in the Chalmers computer graphics course lab (a Phong-era material made energy
// aware): with shininess s, material fresnel R0, metalness m and reflectivity r,
//   D = (s + 2) / (2 pi) (n.h)^s,  G = min(1, 2 (n.h)(n.v) / (v.h), 2 (n.h)(n.l) / (v.h)),
//   F = R0 + (1 - R0) (1 - l.h)^5,  f_spec = F D G / (4 (n.v)(n.l)),
//   diffuse = base / pi (n.l) E
//   dielectric = f_spec (n.l) E + (1 - F) diffuse,  metal = f_spec base (n.l) E
//   result = r (m metal + (1 - m) dielectric) + (1 - r) diffuse
// for irradiance direction l and light colour E; 0 where n.l <= 0 or n.v <= 0.

struct BlinnPhongMaterial {
    glm::vec3 base_color{1.0f};
    float shininess = 0.0f;     // s
    float fresnel = 0.04f;      // R0 at normal incidence
    float metalness = 0.0f;
    float reflectivity = 1.0f;  // the weight of the microfacet term against plain Lambert
};

inline float blinn_phong_d(float n_dot_h, float shininess) {
    float s = std::max(shininess, 0.0f);
    return (s + 2.0f) / (2.0f * kPi) * (s > 0.0f ? std::pow(std::max(n_dot_h, 0.0f), s) : 1.0f);
}
inline float cook_torrance_g(float n_dot_h, float n_dot_v, float n_dot_l, float v_dot_h) {
    float vh = std::max(v_dot_h, 1e-7f);
    return std::min(1.0f, std::min(2.0f * n_dot_h * n_dot_v / vh, 2.0f * n_dot_h * n_dot_l / vh));
}
inline float blinn_phong_fresnel(float r0, float l_dot_h) {
    float x = std::clamp(1.0f - l_dot_h, 0.0f, 1.0f);
    float x2 = x * x;
    return r0 + (1.0f - r0) * (x2 * x2 * x);
}

// Outgoing radiance towards v from one light of colour `light` arriving from l.
inline glm::vec3 blinn_phong_normalized(const BlinnPhongMaterial& m, const glm::vec3& n, const glm::vec3& v,
                                        const glm::vec3& l, const glm::vec3& light) {
    float n_dot_l = glm::dot(n, l), n_dot_v = glm::dot(n, v);
    if (n_dot_l <= 0.0f || n_dot_v <= 0.0f) return glm::vec3(0.0f);
    glm::vec3 h = l + v;
    float len2 = glm::dot(h, h);
    h = len2 > 1e-20f ? h / std::sqrt(len2) : n;
    float n_dot_h = std::max(glm::dot(n, h), 0.0f), v_dot_h = std::max(glm::dot(v, h), 0.0f);
    float f = blinn_phong_fresnel(m.fresnel, std::max(glm::dot(l, h), 0.0f));
    float d = blinn_phong_d(n_dot_h, m.shininess);
    float g = cook_torrance_g(n_dot_h, n_dot_v, n_dot_l, v_dot_h);
    float spec = f * d * g / (4.0f * n_dot_v * n_dot_l);
    glm::vec3 diffuse = m.base_color / kPi * n_dot_l * light;
    glm::vec3 dielectric = spec * n_dot_l * light + (1.0f - f) * diffuse;
    glm::vec3 metal = spec * m.base_color * n_dot_l * light;
    glm::vec3 micro = m.metalness * metal + (1.0f - m.metalness) * dielectric;
    return m.reflectivity * micro + (1.0f - m.reflectivity) * diffuse;
}

// The roughness at which this model's image-based path reads GGX-prefiltered maps:
// (2 / (s + 2))^(1/4), the same mapping as phong_shininess_to_roughness (phong.h).
inline float blinn_phong_ibl_roughness(float shininess) {
    return std::pow(2.0f / (std::max(shininess, 0.0f) + 2.0f), 0.25f);
}

// The image-based path (as the course lab): `irradiance` = the cosine-convolved environment
// / pi at n (what the Lambert term reflects), `prefiltered` = the GGX-prefiltered environment
// along reflect(-v, n) read at blinn_phong_ibl_roughness(s); Fresnel at n.v:
//   dielectric = F prefiltered + (1 - F) base irradiance,  metal = F base prefiltered,
//   result = r (m metal + (1 - m) dielectric) + (1 - r) base irradiance.
inline glm::vec3 blinn_phong_normalized_ibl(const BlinnPhongMaterial& m, float n_dot_v, const glm::vec3& irradiance,
                                            const glm::vec3& prefiltered) {
    float f = blinn_phong_fresnel(m.fresnel, std::clamp(n_dot_v, 0.0f, 1.0f));
    glm::vec3 diffuse = m.base_color * irradiance;
    glm::vec3 dielectric = f * prefiltered + (1.0f - f) * diffuse;
    glm::vec3 metal = f * m.base_color * prefiltered;
    glm::vec3 micro = m.metalness * metal + (1.0f - m.metalness) * dielectric;
    return m.reflectivity * micro + (1.0f - m.reflectivity) * diffuse;
}

}  // namespace fresnel::legacy
