// The glTF 2.0 metallic-roughness BRDF (Appendix B); the same functions as
// libs/material/include/fresnel/material/brdf.h.
const float MIN_ROUGHNESS = 0.0;

float d_ggx(float n_dot_h, float alpha) {
    float a2 = alpha * alpha;
    // Precise at the peak of glossy lobes (see brdf.h); the floor keeps alpha = 0 from 0/0.
    float f = max((1.0 - n_dot_h) * (1.0 + n_dot_h) + n_dot_h * n_dot_h * a2, 1e-7);
    return a2 / (PI * f * f);
}

float v_smith_ggx_correlated(float n_dot_l, float n_dot_v, float alpha) {
    float a2 = alpha * alpha;
    float ggxv = n_dot_l * sqrt(n_dot_v * n_dot_v * (1.0 - a2) + a2);
    float ggxl = n_dot_v * sqrt(n_dot_l * n_dot_l * (1.0 - a2) + a2);
    float g = ggxv + ggxl;
    return g > 0.0 ? 0.5 / g : 0.0;
}

vec3 f_schlick(vec3 f0, vec3 f90, float v_dot_h) {
    float x = clamp(1.0 - v_dot_h, 0.0, 1.0);
    float x2 = x * x;
    return f0 + (f90 - f0) * (x2 * x2 * x);
}
float f_schlick(float f0, float f90, float v_dot_h) {
    float x = clamp(1.0 - v_dot_h, 0.0, 1.0);
    float x2 = x * x;
    return f0 + (f90 - f0) * (x2 * x2 * x);
}

float alpha_from_roughness(float perceptual) {
    float r = clamp(perceptual, MIN_ROUGHNESS, 1.0);
    return r * r;
}

struct BrdfTerms {
    float d;
    float v;
    vec3 f;
    vec3 diffuse;
    vec3 specular;             // specular_dielectric + specular_metal
    vec3 specular_dielectric;  // (1 - metallic) F_dielectric V D
    vec3 specular_metal;       // metallic F_metal V D
};

// f0_dielectric: the dielectric F0 colour (0.04 by default); specular_weight scales the
// dielectric lobe's F0 and F90 (KHR_materials_specular; 1 by default).
BrdfTerms brdf_terms(vec3 base_color, float metallic, float perceptual_roughness, vec3 f0_dielectric,
                     float specular_weight, vec3 n, vec3 v, vec3 l) {
    BrdfTerms t;
    vec3 h = l + v;
    float hl = length(h);
    h = hl > 0.0 ? h / hl : n;
    float n_dot_l = clamped_dot(n, l);
    float n_dot_v = clamped_dot(n, v);
    float n_dot_h = clamped_dot(n, h);
    float v_dot_h = clamped_dot(v, h);
    float alpha = alpha_from_roughness(perceptual_roughness);
    t.d = d_ggx(n_dot_h, alpha);
    t.v = v_smith_ggx_correlated(n_dot_l, n_dot_v, alpha);
    float spec = t.v * t.d;
    vec3 f_metal = f_schlick(base_color, vec3(1.0), v_dot_h);
    vec3 f_dielectric = f_schlick(f0_dielectric * specular_weight, vec3(specular_weight), v_dot_h);
    t.f = mix(f_dielectric, f_metal, metallic);
    t.diffuse = (1.0 - metallic) * (1.0 - f_dielectric) * base_color / PI;
    t.specular_dielectric = (1.0 - metallic) * f_dielectric * spec;
    t.specular_metal = metallic * f_metal * spec;
    t.specular = t.specular_dielectric + t.specular_metal;
    return t;
}

// KHR_materials_clearcoat: the coat's specular lobe times n.l (no Fresnel: the layering
// weight carries it). The same as brdf::clearcoat_specular in brdf.h.
float clearcoat_specular(vec3 nc, vec3 v, vec3 l, float alpha) {
    float n_dot_l = clamped_dot(nc, l);
    if (n_dot_l <= 0.0) return 0.0;
    vec3 h = l + v;
    float hl = length(h);
    h = hl > 0.0 ? h / hl : nc;
    return n_dot_l * d_ggx(clamped_dot(nc, h), alpha) * v_smith_ggx_correlated(n_dot_l, clamped_dot(nc, v), alpha);
}
