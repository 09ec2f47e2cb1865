// OpenGL 1 fixed-function lighting and the normalized Blinn-Phong microfacet model. The C++
// twin, with the formulas and conventions, is libs/material/include/fresnel/material/
// legacy_shading.h; tests/gpu/legacy_shading_gpu_test.cpp keeps the two equal.
// Needs common.glsl (PI).

float ogl1_shininess(float ns) { return clamp(ns, 0.0, 128.0); }

// max(n.h, 0)^s with 0^0 = 1.
float ogl1_specular_power(float n_dot_h, float shininess) {
    if (shininess <= 0.0) return 1.0;
    return pow(max(n_dot_h, 0.0), shininess);
}

struct Ogl1Light {
    vec3 diffuse;
    vec3 specular;
};

Ogl1Light ogl1_light(vec3 n, vec3 v, vec3 l, vec3 light_color, vec3 diffuse, vec3 specular, float shininess) {
    Ogl1Light o;
    float n_dot_l = dot(n, l);
    o.diffuse = max(n_dot_l, 0.0) * diffuse * light_color;
    o.specular = vec3(0.0);
    if (n_dot_l > 0.0) {
        vec3 h = l + v;
        float len2 = dot(h, h);
        float n_dot_h = len2 > 1e-20 ? dot(n, h) / sqrt(len2) : 0.0;
        o.specular = ogl1_specular_power(n_dot_h, shininess) * specular * light_color;
    }
    return o;
}

vec3 ogl1_base(vec3 emission, vec3 ambient, vec3 global_ambient) { return emission + ambient * global_ambient; }

vec3 ogl1_combine(vec3 primary, vec3 secondary, vec3 texel, bool separate_specular) {
    if (separate_specular) return clamp(primary, 0.0, 1.0) * texel + clamp(secondary, 0.0, 1.0);
    return clamp(primary + secondary, 0.0, 1.0) * texel;
}

// mode: 0 none, 1 linear, 2 exp, 3 exp2 (FogMode).
float ogl1_fog_factor(int mode, float z, float fog_start, float fog_end, float density) {
    float f = 1.0;
    if (mode == 0) return 1.0;
    if (mode == 1) f = fog_end != fog_start ? (fog_end - z) / (fog_end - fog_start) : (z < fog_end ? 1.0 : 0.0);
    else if (mode == 2) f = exp(-density * z);
    else if (mode == 3) f = exp(-(density * z) * (density * z));
    return clamp(f, 0.0, 1.0);
}
vec3 ogl1_apply_fog(vec3 color, vec3 fog_color, float factor) { return factor * color + (1.0 - factor) * fog_color; }

float blinn_phong_d(float n_dot_h, float shininess) {
    float s = max(shininess, 0.0);
    return (s + 2.0) / (2.0 * PI) * (s > 0.0 ? pow(max(n_dot_h, 0.0), s) : 1.0);
}
float cook_torrance_g(float n_dot_h, float n_dot_v, float n_dot_l, float v_dot_h) {
    float vh = max(v_dot_h, 1e-7);
    return min(1.0, min(2.0 * n_dot_h * n_dot_v / vh, 2.0 * n_dot_h * n_dot_l / vh));
}
float blinn_phong_fresnel(float r0, float l_dot_h) {
    float x = clamp(1.0 - l_dot_h, 0.0, 1.0);
    float x2 = x * x;
    return r0 + (1.0 - r0) * (x2 * x2 * x);
}

vec3 blinn_phong_normalized(vec3 base_color, float shininess, float fresnel_r0, float metalness, float reflectivity,
                            vec3 n, vec3 v, vec3 l, vec3 light) {
    float n_dot_l = dot(n, l), n_dot_v = dot(n, v);
    if (n_dot_l <= 0.0 || n_dot_v <= 0.0) return vec3(0.0);
    vec3 h = l + v;
    float len2 = dot(h, h);
    h = len2 > 1e-20 ? h / sqrt(len2) : n;
    float n_dot_h = max(dot(n, h), 0.0), v_dot_h = max(dot(v, h), 0.0);
    float f = blinn_phong_fresnel(fresnel_r0, max(dot(l, h), 0.0));
    float d = blinn_phong_d(n_dot_h, shininess);
    float g = cook_torrance_g(n_dot_h, n_dot_v, n_dot_l, v_dot_h);
    float spec = f * d * g / (4.0 * n_dot_v * n_dot_l);
    vec3 diffuse = base_color / PI * n_dot_l * light;
    vec3 dielectric = spec * n_dot_l * light + (1.0 - f) * diffuse;
    vec3 metal = spec * base_color * n_dot_l * light;
    vec3 micro = metalness * metal + (1.0 - metalness) * dielectric;
    return reflectivity * micro + (1.0 - reflectivity) * diffuse;
}

float blinn_phong_ibl_roughness(float shininess) { return pow(2.0 / (max(shininess, 0.0) + 2.0), 0.25); }

// The image-based path: `irradiance` = the cosine-convolved environment / pi at n (what the
// Lambert term reflects), `prefiltered` = the GGX-prefiltered environment along reflect(-v, n)
// at blinn_phong_ibl_roughness(s); Fresnel at n.v.
vec3 blinn_phong_normalized_ibl(vec3 base_color, float fresnel_r0, float metalness, float reflectivity, float n_dot_v,
                                vec3 irradiance, vec3 prefiltered) {
    float f = blinn_phong_fresnel(fresnel_r0, clamp(n_dot_v, 0.0, 1.0));
    vec3 diffuse = base_color * irradiance;
    vec3 dielectric = f * prefiltered + (1.0 - f) * diffuse;
    vec3 metal = f * base_color * prefiltered;
    vec3 micro = metalness * metal + (1.0 - metalness) * dielectric;
    return reflectivity * micro + (1.0 - reflectivity) * diffuse;
}
