// Image-based lighting: the irradiance cube map, the GGX-prefiltered cube map and
// the split-sum table (libs/ibl bakes all three). Roughness k/(levels-1) lives at
// level k, so lod = roughness * (levels - 1).
uniform sampler2D u_brdf_lut;  // R = A, G = B, B = A + B (directional albedo E); column 0 = grazing (ibl/precompute.h)
#ifdef USE_IBL
uniform samplerCube u_specular_env;
uniform samplerCube u_irradiance_env;  // irradiance / pi
#include "frame_block.glsl"  // u_env_levels, u_env_intensity, u_env_rotation
#endif

// The tables and the irradiance cube have one level, filtered linearly whether magnified or
// minified: textureLod(.., 0) reads what texture() would, without the derivatives, and two
// reads of the same coordinates are one (a software rasteriser pays for every lookup).
vec3 brdf_lut(float n_dot_v, float roughness) {
    return textureLod(u_brdf_lut, clamp(vec2(n_dot_v, roughness), vec2(0.0), vec2(1.0)), 0.0).rgb;
}

// Multiple-scattering energy compensation for a lobe with reflectance f0
// (Fdez-Aguera 2019, as Filament applies it): 1 + f0 (1/E - 1).
vec3 energy_compensation(vec3 f0, float e) { return 1.0 + f0 * (1.0 / max(e, 1e-4) - 1.0); }

// Fdez-Aguera's single + multiple scattering Fresnel-weighted albedo with the
// roughness-dependent Fresnel term (what the Khronos Sample Viewer uses).
vec3 ibl_ggx_fresnel(float n_dot_v, float roughness, vec3 f0, float specular_weight) {
    vec2 ab = brdf_lut(n_dot_v, roughness).rg;
    vec3 fr = max(vec3(1.0 - roughness), f0) - f0;
    float x = 1.0 - n_dot_v;  // (1 - n.v)^5 by multiplication, as f_schlick (a pow is exp2(log2) on llvmpipe)
    float x2 = x * x;
    vec3 k_s = f0 + fr * (x2 * x2 * x);
    vec3 fss_ess = specular_weight * (k_s * ab.x + ab.y);
    float ems = 1.0 - (ab.x + ab.y);
    vec3 f_avg = specular_weight * (f0 + (1.0 - f0) / 21.0);
    vec3 fms_ems = ems * fss_ess * f_avg / (1.0 - f_avg * ems);
    return fss_ess + fms_ems;
}

#ifdef USE_IBL
vec3 ibl_irradiance(vec3 n) {
    return textureLod(u_irradiance_env, u_env_rotation * n, 0.0).rgb * u_env_intensity;
}

vec3 ibl_radiance(vec3 r, float roughness) {
    return textureLod(u_specular_env, u_env_rotation * r, roughness * (u_env_levels - 1.0)).rgb * u_env_intensity;
}

#ifdef MATERIAL_ANISOTROPY
// KHR_materials_anisotropy: the prefiltered cube along the view reflected about the bent
// normal (anisotropic_bent_normal in brdf.glsl), at the material's roughness.
vec3 ibl_radiance_anisotropic(vec3 n, vec3 v, float roughness, float strength, vec3 bt_dir) {
    vec3 r = normalize(reflect(-v, anisotropic_bent_normal(n, v, roughness, strength, bt_dir)));
    return ibl_radiance(r, roughness);
}
#endif

// Specular occlusion from ambient occlusion (Lagarde & de Rousiers 2014). With ao = 1 it is 1
// (pow(n.v + 1, e) >= 1 for e > 0): variants without an occlusion map skip it (pbr.frag).
float specular_occlusion(float n_dot_v, float ao, float roughness) {
    return clamp(pow(n_dot_v + ao, exp2(-16.0 * roughness - 1.0)) - 1.0 + ao, 0.0, 1.0);
}
#endif
