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

// ---- Selectable terms (fresnel/material/brdf_model.h; `--brdf`): BRDF_D, BRDF_G, BRDF_F and
// BRDF_DIFFUSE hold the enum values of the non-default terms. Without them: glTF's terms.
#ifndef BRDF_D
#define BRDF_D 0
#endif
#ifndef BRDF_G
#define BRDF_G 0
#endif
#ifndef BRDF_F
#define BRDF_F 0
#endif
#ifndef BRDF_DIFFUSE
#define BRDF_DIFFUSE 0
#endif

#if BRDF_D == 1
float d_beckmann(float n_dot_h, float alpha) {
    float a2 = max(alpha * alpha, 1e-7);
    float c2 = n_dot_h * n_dot_h;
    if (c2 <= 0.0) return 0.0;
    return exp((c2 - 1.0) / (a2 * c2)) / (PI * a2 * c2 * c2);
}
#elif BRDF_D == 2
float d_blinn_phong(float n_dot_h, float alpha) {
    float a2 = max(alpha * alpha, 1e-7);
    float s = max(2.0 / a2 - 2.0, 0.0);
    return (s + 2.0) / (2.0 * PI) * pow(max(n_dot_h, 1e-8), s);  // floored: pow(0, 0) is undefined
}
#endif

float brdf_d(float n_dot_h, float alpha) {
#if BRDF_D == 1
    return d_beckmann(n_dot_h, alpha);
#elif BRDF_D == 2
    return d_blinn_phong(n_dot_h, alpha);
#else
    return d_ggx(n_dot_h, alpha);
#endif
}

float brdf_v(float n_dot_l, float n_dot_v, float n_dot_h, float v_dot_h, float alpha, float perceptual_roughness) {
#if BRDF_G == 1
    float a2 = alpha * alpha;
    float g = (n_dot_l + sqrt(a2 + (1.0 - a2) * n_dot_l * n_dot_l)) * (n_dot_v + sqrt(a2 + (1.0 - a2) * n_dot_v * n_dot_v));
    return g > 0.0 ? 1.0 / g : 0.0;
#elif BRDF_G == 2
    float r = clamp(perceptual_roughness, 0.0, 1.0) + 1.0;
    float k = r * r / 8.0;  // UE4's remapping for punctual lights
    float g = 4.0 * (n_dot_l * (1.0 - k) + k) * (n_dot_v * (1.0 - k) + k);
    return g > 0.0 ? 1.0 / g : 0.0;
#elif BRDF_G == 3
    if (n_dot_l <= 0.0 || n_dot_v <= 0.0) return 0.0;
    float g = 1.0;
    if (v_dot_h > 0.0) g = min(1.0, 2.0 * n_dot_h * min(n_dot_v, n_dot_l) / v_dot_h);
    return g / (4.0 * n_dot_l * n_dot_v);
#elif BRDF_G == 4
    float c = max(v_dot_h, 1e-4);
    return 0.25 / (c * c);
#else
    return v_smith_ggx_correlated(n_dot_l, n_dot_v, alpha);
#endif
}

#if BRDF_F == 1 || BRDF_F == 3
float f_dielectric_exact(float c, float eta) {
    c = clamp(c, 0.0, 1.0);
    float g2 = eta * eta - 1.0 + c * c;
    if (g2 <= 0.0) return 1.0;
    float g = sqrt(g2);
    float a = (g - c) / (g + c);
    float b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    return min(0.5 * a * a * (1.0 + b * b), 1.0);
}
float f_exact_channel(float f0, float f90, float v_dot_h) {
    float s = sqrt(clamp(f0 / max(f90, 1e-6), 0.0, 0.9999));
    float e = (1.0 + s) / (1.0 - s);
    float f0e = f_dielectric_exact(1.0, e);
    float t = f0e < 1.0 ? (f_dielectric_exact(v_dot_h, e) - f0e) / (1.0 - f0e) : 1.0;
    return f0 + (f90 - f0) * t;
}
#endif
#if BRDF_F == 3
// brdf::f_conductor_exact: the Fresnel equations of a conductor n + ik, (Rs + Rp) / 2, with
// a + ib = sqrt(eta^2 - sin^2) and a^2, b^2 each from the form without cancellation.
float f_conductor_exact(float c, float n, float k) {
    c = clamp(c, 0.0, 1.0);
    float c2 = c * c, s2 = 1.0 - c2;
    float t0 = n * n - k * k - s2;
    float nk2 = 4.0 * n * n * k * k;
    float m = sqrt(t0 * t0 + nk2);
    float a2 = t0 >= 0.0 ? 0.5 * (m + t0) : (m - t0 > 0.0 ? 0.5 * nk2 / (m - t0) : 0.0);
    float b2 = t0 <= 0.0 ? 0.5 * (m - t0) : 0.5 * nk2 / (m + t0);
    float a = sqrt(a2);
    float ds = (a + c) * (a + c) + b2;
    if (!(ds > 0.0)) return 1.0;
    float rs = ((a - c) * (a - c) + b2) / ds;
    float ac = a * c;
    float dp = (ac + s2) * (ac + s2) + b2 * c2;
    float rp = dp > 0.0 ? rs * ((ac - s2) * (ac - s2) + b2 * c2) / dp : rs;
    return min(0.5 * (rs + rp), 1.0);
}
vec3 f_conductor_exact(vec3 n, vec3 k, float v_dot_h) {
    return vec3(f_conductor_exact(v_dot_h, n.r, k.r), f_conductor_exact(v_dot_h, n.g, k.g),
                f_conductor_exact(v_dot_h, n.b, k.b));
}
// The metal lobe: a measured metal's n, k (BRDF_CONDUCTOR_N, BRDF_CONDUCTOR_K: brdf_model_defines)
// or brdf::conductor_from_f0 of the base colour (Gulbrandsen 2014 with edge tint 1).
vec3 f_exact_metal(vec3 base_color, float v_dot_h) {
#ifdef BRDF_CONDUCTOR_N
    return f_conductor_exact(BRDF_CONDUCTOR_N, BRDF_CONDUCTOR_K, v_dot_h);
#else
    vec3 r = clamp(base_color, 0.0, 1.0);
    return f_conductor_exact((1.0 - r) / (1.0 + r), 2.0 * sqrt(r) / (1.0 + r), v_dot_h);
#endif
}
#endif
#if BRDF_F == 2
vec3 f_spherical_gaussian(vec3 f0, vec3 f90, float v_dot_h) {
    float c = clamp(v_dot_h, 0.0, 1.0);
    return f0 + (f90 - f0) * exp2((-5.55473 * c - 6.98316) * c);
}
#endif

// The dielectric lobe's Fresnel (F90 = the specular weight) and the conductor's (F90 = 1).
vec3 brdf_f_dielectric(vec3 f0, vec3 f90, float v_dot_h) {
#if BRDF_F == 1 || BRDF_F == 3
    return vec3(f_exact_channel(f0.r, f90.r, v_dot_h), f_exact_channel(f0.g, f90.g, v_dot_h),
                f_exact_channel(f0.b, f90.b, v_dot_h));
#elif BRDF_F == 2
    return f_spherical_gaussian(f0, f90, v_dot_h);
#else
    return f_schlick(f0, f90, v_dot_h);
#endif
}
vec3 brdf_f_metal(vec3 base_color, float v_dot_h) {
#if BRDF_F == 3
    return f_exact_metal(base_color, v_dot_h);
#elif BRDF_F == 2
    return f_spherical_gaussian(base_color, vec3(1.0), v_dot_h);
#else
    return f_schlick(base_color, vec3(1.0), v_dot_h);
#endif
}

// The diffuse lobe relative to Lambert.
float brdf_diffuse_factor(float n_dot_l, float n_dot_v, float v_dot_h, float l_dot_v, float perceptual_roughness) {
#if BRDF_DIFFUSE == 1
    float f90 = 0.5 + 2.0 * perceptual_roughness * v_dot_h * v_dot_h;
    float xl = 1.0 - n_dot_l, xv = 1.0 - n_dot_v;
    float pl = xl * xl * xl * xl * xl, pv = xv * xv * xv * xv * xv;
    return (1.0 + (f90 - 1.0) * pl) * (1.0 + (f90 - 1.0) * pv);
#elif BRDF_DIFFUSE == 2
    float s2 = perceptual_roughness * perceptual_roughness;
    float a = 1.0 - 0.5 * s2 / (s2 + 0.33);
    float b = 0.45 * s2 / (s2 + 0.09);
    float s = l_dot_v - n_dot_l * n_dot_v;
    float t = max(max(n_dot_l, n_dot_v), 1e-4);
    return a + b * max(s, 0.0) / t;
#else
    return 1.0;
#endif
}

float alpha_from_roughness(float perceptual) {
    float r = clamp(perceptual, MIN_ROUGHNESS, 1.0);
    return r * r;
}

struct BrdfTerms {
    float d;
    float v;
    vec3 f;
    vec3 f_dielectric, f_metal;  // the two lobes' Fresnel terms
    vec3 diffuse;
    vec3 diffuse_weight;       // (1 - metallic) (1 - F_dielectric), film_diffuse_weight under a film
    vec3 specular;             // specular_dielectric + specular_metal
    vec3 specular_dielectric;  // (1 - metallic) F_dielectric V D
    vec3 specular_metal;       // metallic F_metal V D
};

// KHR_materials_iridescence: the film's Fresnel over the dielectric and the metallic base at
// one view, and its weight (brdf::IridescenceFresnel; iridescence.glsl evaluates it).
struct IridescenceFresnel {
    float factor;  // 0: no film
    vec3 dielectric;
    vec3 metal;
};
IridescenceFresnel no_film() { return IridescenceFresnel(0.0, vec3(0.0), vec3(0.0)); }

// brdf::film_diffuse_weight: what the diffuse (or the transmission replacing it) keeps below
// the dielectric's Fresnel, 1 - F, under a film mix(1 - F, 1 - max(F_film), factor).
vec3 film_diffuse_weight(vec3 f_dielectric, IridescenceFresnel film) {
    vec3 weight = 1.0 - f_dielectric;
    if (film.factor > 0.0) {
        float film_max = max(max(film.dielectric.r, film.dielectric.g), film.dielectric.b);
        weight = mix(weight, vec3(1.0 - film_max), film.factor);
    }
    return weight;
}

// brdf::diffuse_transmission_mix (KHR_materials_diffuse_transmission, as the Khronos viewer):
// the diffuse lobe of one light times its cosine, mix(reflected_cos, lambert(color) n.(-l), factor).
vec3 diffuse_transmission_mix(vec3 reflected_cos, float n_dot_minus_l, float factor, vec3 color) {
    if (!(factor > 0.0)) return reflected_cos;
    return mix(reflected_cos, color / PI * n_dot_minus_l, factor);
}

// brdf::eon_factor (KHR_materials_diffuse_roughness): the energy-preserving Oren-Nayar lobe as
// a factor of Lambert's, per channel; brdf::eon_albedo_factor its directional albedo's.
const float EON_C1 = 0.5 - 2.0 / (3.0 * PI);
const float EON_C2 = 2.0 / 3.0 - 28.0 / (15.0 * PI);
float eon_single_albedo(float mu, float r) {
    float c = 1.0 - mu;
    float g_over_pi = c * (0.0571085289 + c * (0.491881867 + c * (-0.332181442 + c * 0.0714429953)));
    return (1.0 + r * g_over_pi) / (1.0 + EON_C1 * r);
}
vec3 eon_factor(vec3 rho, float r, float n_dot_l, float n_dot_v, float l_dot_v) {
    if (!(r > 0.0)) return vec3(1.0);
    float mu_l = max(n_dot_l, 1e-4), mu_v = max(n_dot_v, 1e-4);
    float s = l_dot_v - mu_l * mu_v;
    float s_over_t = s > 0.0 ? s / max(mu_l, mu_v) : s;
    float a = 1.0 / (1.0 + EON_C1 * r);
    float e_avg = a * (1.0 + EON_C2 * r);
    float ms = max(1.0 - eon_single_albedo(mu_l, r), 1e-7) * max(1.0 - eon_single_albedo(mu_v, r), 1e-7) /
               max(1.0 - e_avg, 1e-7);
    vec3 c = clamp(rho, 0.0, 1.0);
    vec3 ms_over_rho = c * e_avg / (vec3(1.0) - c * (1.0 - e_avg));
    return vec3(a * (1.0 + r * s_over_t)) + ms_over_rho * ms;
}
vec3 eon_albedo_factor(vec3 rho, float r, float n_dot_v) {
    if (!(r > 0.0)) return vec3(1.0);
    float e = eon_single_albedo(max(n_dot_v, 1e-4), r);
    float e_avg = (1.0 + EON_C2 * r) / (1.0 + EON_C1 * r);
    vec3 c = clamp(rho, 0.0, 1.0);
    return vec3(e) + c * e_avg / (vec3(1.0) - c * (1.0 - e_avg)) * (1.0 - e);
}

// f0_dielectric: the dielectric F0 colour (0.04 by default); specular_weight scales the
// dielectric lobe's F0 and F90 (KHR_materials_specular; 1 by default). `film`: a thin film
// over both (brdf::layer): the Fresnel terms become mix(F, F_film, factor), the diffuse keeps
// mix(1 - F, 1 - max(F_film), factor).
BrdfTerms brdf_terms_film(vec3 base_color, float metallic, float perceptual_roughness, vec3 f0_dielectric,
                          float specular_weight, vec3 n, vec3 v, vec3 l, IridescenceFresnel film) {
    BrdfTerms t;
    vec3 h = l + v;
    float hl = length(h);
    h = hl > 0.0 ? h / hl : n;
    float n_dot_l = clamped_dot(n, l);
    float n_dot_v = clamped_dot(n, v);
    float n_dot_h = clamped_dot(n, h);
    float v_dot_h = clamped_dot(v, h);
    float alpha = alpha_from_roughness(perceptual_roughness);
    t.d = brdf_d(n_dot_h, alpha);
    t.v = brdf_v(n_dot_l, n_dot_v, n_dot_h, v_dot_h, alpha, perceptual_roughness);
    float spec = t.v * t.d;
    vec3 f_metal = brdf_f_metal(base_color, v_dot_h);
    vec3 f_dielectric = brdf_f_dielectric(f0_dielectric * specular_weight, vec3(specular_weight), v_dot_h);
    vec3 diffuse_weight = film_diffuse_weight(f_dielectric, film);
    if (film.factor > 0.0) {
        f_dielectric = mix(f_dielectric, film.dielectric, film.factor);
        f_metal = mix(f_metal, film.metal, film.factor);
    }
    t.f_dielectric = f_dielectric;  // with the film: what apply_anisotropy weights its lobes by
    t.f_metal = f_metal;
    t.f = mix(f_dielectric, f_metal, metallic);
    t.diffuse_weight = (1.0 - metallic) * diffuse_weight;
    t.diffuse = t.diffuse_weight * (base_color / PI *
                brdf_diffuse_factor(n_dot_l, n_dot_v, v_dot_h, dot(l, v), perceptual_roughness));
    t.specular_dielectric = (1.0 - metallic) * f_dielectric * spec;
    t.specular_metal = metallic * f_metal * spec;
    t.specular = t.specular_dielectric + t.specular_metal;
    return t;
}

// ---- KHR_materials_anisotropy (brdf.h): the anisotropic GGX lobe, stretched along the
// direction at (bt = ng x at): alpha_t = mix(alpha, 1, strength^2), alpha_b = max(alpha, 1e-3).
float d_ggx_anisotropic(float n_dot_h, float t_dot_h, float b_dot_h, float at, float ab) {
    float a2 = at * ab;
    vec3 f = vec3(ab * t_dot_h, at * b_dot_h, a2 * n_dot_h);
    float w2 = a2 / dot(f, f);
    return a2 * w2 * w2 / PI;
}
float v_ggx_anisotropic(float n_dot_l, float n_dot_v, float b_dot_v, float t_dot_v, float t_dot_l, float b_dot_l,
                        float at, float ab) {
    float ggxv = n_dot_l * length(vec3(at * t_dot_v, ab * b_dot_v, n_dot_v));
    float ggxl = n_dot_v * length(vec3(at * t_dot_l, ab * b_dot_l, n_dot_l));
    float g = ggxv + ggxl;
    return g != 0.0 ? clamp(0.5 / g, 0.0, 1.0) : 0.0;
}
float anisotropic_alpha_t(float alpha, float strength) { return alpha + (1.0 - alpha) * strength * strength; }
// brdf::apply_anisotropy: the specular lobes' D and V replaced by the anisotropic ones.
void apply_anisotropy(inout BrdfTerms t, float metallic, float perceptual_roughness, vec3 n, vec3 v, vec3 l,
                      vec3 at_dir, vec3 bt_dir, float strength) {
    vec3 h = l + v;
    float hl = length(h);
    h = hl > 0.0 ? h / hl : n;
    float alpha = alpha_from_roughness(perceptual_roughness);
    float at = anisotropic_alpha_t(alpha, strength);
    float ab = clamp(alpha, 1e-3, 1.0);
    float n_dot_l = clamp(dot(n, l), 0.0, 1.0);
    float n_dot_h = clamp(dot(n, h), 1e-3, 1.0);
    float n_dot_v = dot(n, v);
    t.v = v_ggx_anisotropic(n_dot_l, n_dot_v, dot(bt_dir, v), dot(at_dir, v), dot(at_dir, l), dot(bt_dir, l), at, ab);
    t.d = d_ggx_anisotropic(n_dot_h, dot(at_dir, h), dot(bt_dir, h), at, ab);
    float spec = t.v * t.d;
    t.specular_dielectric = (1.0 - metallic) * t.f_dielectric * spec;
    t.specular_metal = metallic * t.f_metal * spec;
    t.specular = t.specular_dielectric + t.specular_metal;
}
// brdf::anisotropic_bent_normal: the normal the anisotropic lobe's image-based light reflects about.
vec3 anisotropic_bent_normal(vec3 n, vec3 v, float perceptual_roughness, float strength, vec3 bt_dir) {
    vec3 tangent = cross(bt_dir, v);
    vec3 normal = cross(tangent, bt_dir);
    float bend = 1.0 - strength * (1.0 - perceptual_roughness);
    float bend4 = bend * bend * bend * bend;
    return normalize(normal + (n - normal) * bend4);
}

BrdfTerms brdf_terms(vec3 base_color, float metallic, float perceptual_roughness, vec3 f0_dielectric,
                     float specular_weight, vec3 n, vec3 v, vec3 l) {
    return brdf_terms_film(base_color, metallic, perceptual_roughness, f0_dielectric, specular_weight, n, v, l,
                           no_film());
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

// Multiple-bounce ambient occlusion (Jimenez et al. 2016, "Practical Real-Time Strategies for
// Accurate Indirect Occlusion", the GTAO fit): visibility `ao` of a surface of diffuse albedo
// `albedo`, raised by the light its surroundings (taken to have the same albedo) send back.
// 1 at ao = 1 for any albedo; fresnel::brdf::ao_multibounce.
vec3 ao_multibounce(float ao, vec3 albedo) {
    vec3 a = 2.0404 * albedo - 0.3324;
    vec3 b = -4.7951 * albedo + 0.6417;
    vec3 c = 2.7552 * albedo + 0.6903;
    return max(vec3(ao), ((ao * a + b) * ao + c) * ao);
}
