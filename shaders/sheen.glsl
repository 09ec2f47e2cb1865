// KHR_materials_sheen: the Charlie sheen lobe (Estevez & Kulla 2017) as the Khronos Sample
// Viewer evaluates it; the same functions as the sheen part of
// libs/material/include/fresnel/material/brdf.h. Included by material_inputs.glsl with
// MATERIAL_SHEEN only. Needs u_brdf_lut (ibl.glsl): its A channel is the sheen albedo E.

// Charlie distribution D(h) = (2 + 1/alpha_g) sin(theta_h)^(1/alpha_g) / (2 pi), alpha_g = r^2.
float d_charlie(float sheen_roughness, float n_dot_h) {
    float r = max(sheen_roughness, 1e-6);
    float inv_alpha = 1.0 / (r * r);
    float sin2h = max(1.0 - n_dot_h * n_dot_h, 0.0);
    return (2.0 + inv_alpha) * pow(sin2h, inv_alpha * 0.5) / (2.0 * PI);
}

// brdf::sheen_lambda_fit: Estevez-Kulla's fit of the shadowing exponent.
float sheen_lambda_fit(float x, float alpha_g) {
    float t = (1.0 - alpha_g) * (1.0 - alpha_g);
    float a = mix(21.5473, 25.3245, t);
    float b = mix(3.82987, 3.32435, t);
    float c = mix(0.19823, 0.16801, t);
    float d = mix(-1.97760, -1.27393, t);
    float e = mix(-4.32054, -4.85967, t);
    return a / (1.0 + b * pow(x, c)) + d * x + e;
}

float sheen_lambda(float cos_theta, float alpha_g) {
    if (abs(cos_theta) < 0.5) return exp(sheen_lambda_fit(cos_theta, alpha_g));
    return exp(2.0 * sheen_lambda_fit(0.5, alpha_g) - sheen_lambda_fit(1.0 - cos_theta, alpha_g));
}

float v_sheen(float n_dot_l, float n_dot_v, float sheen_roughness) {
    float r = max(sheen_roughness, 1e-6);
    float alpha_g = r * r;
    float denom = (1.0 + sheen_lambda(n_dot_v, alpha_g) + sheen_lambda(n_dot_l, alpha_g)) * (4.0 * n_dot_v * n_dot_l);
    return denom > 0.0 ? clamp(1.0 / denom, 0.0, 1.0) : 1.0;
}

vec3 sheen_specular(vec3 sheen_color, float sheen_roughness, float n_dot_l, float n_dot_v, float n_dot_h) {
    return sheen_color * (d_charlie(sheen_roughness, n_dot_h) * v_sheen(n_dot_l, n_dot_v, sheen_roughness));
}

// Directional albedo E of the white sheen lobe (brdf::SheenAlbedoTable).
float sheen_albedo(float n_dot_v, float sheen_roughness) {
    return textureLod(u_brdf_lut, clamp(vec2(n_dot_v, sheen_roughness), vec2(0.0), vec2(1.0)), 0.0).a;  // one level (ibl.glsl)
}

float max3(vec3 c) { return max(max(c.r, c.g), c.b); }

#ifdef USE_IBL
uniform samplerCube u_sheen_env;  // Charlie-prefiltered (ibl::prefilter_charlie), lod = roughness * (levels - 1)
uniform sampler2D u_charlie_lut;  // R: the Khronos Sample Viewer's Charlie table (ibl::compute_charlie_lut)

// Image-based light on the sheen lobe, as the Khronos Sample Viewer's getIBLRadianceCharlie:
// the Charlie-prefiltered radiance in the mirror direction * sheen colour * its table at (n.v, r).
vec3 ibl_sheen(vec3 n, vec3 v, vec3 sheen_color, float sheen_roughness) {
    vec3 r = normalize(reflect(-v, n));
    vec3 light = textureLod(u_sheen_env, u_env_rotation * r, sheen_roughness * (u_env_levels - 1.0)).rgb * u_env_intensity;
    float brdf = textureLod(u_charlie_lut, clamp(vec2(clamped_dot(n, v), sheen_roughness), vec2(0.0), vec2(1.0)), 0.0).r;
    return light * sheen_color * brdf;
}
#endif
