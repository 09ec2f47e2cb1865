// KHR_materials_transmission, KHR_materials_volume and KHR_materials_dispersion, as the
// Khronos Sample Viewer shades them: the GLSL twins of libs/material/include/fresnel/material/
// transmission.h (read there what each function does); tests/gpu/transmission_gpu_test.cpp
// keeps the two equal. Included after material_inputs.glsl (sample_map, MaterialInputs) and
// lights.glsl. Only variants with MATERIAL_TRANSMISSION declare the uniforms and read maps.

float apply_ior_to_roughness(float roughness, float ior) { return roughness * clamp(ior * 2.0 - 2.0, 0.0, 1.0); }

float transmission_framebuffer_lod(float perceptual_roughness, float ior, float size) {
    return log2(size) * apply_ior_to_roughness(perceptual_roughness, ior);
}

vec3 volume_attenuation(vec3 radiance, float distance, vec3 color, float attenuation_distance) {
    if (attenuation_distance == 0.0) return radiance;
    return radiance * pow(color, vec3(distance / attenuation_distance));
}

vec3 volume_ray(vec3 n, vec3 v, float thickness, float ior, vec3 model_scale) {
    vec3 r = refract(-v, normalize(n), 1.0 / ior);
    float len = length(r);
    if (len <= 0.0) return vec3(0.0);
    return r / len * thickness * model_scale;
}

vec3 dispersion_iors(float ior, float dispersion) {
    float half_spread = (ior - 1.0) * 0.025 * dispersion;
    return vec3(ior - half_spread, ior, ior + half_spread);
}

vec3 btdf_punctual(vec3 n, vec3 v, vec3 l, float alpha, vec3 f0, vec3 f90, vec3 base_color, float ior) {
    float a = apply_ior_to_roughness(alpha, ior);
    vec3 l_mirror = normalize(l + 2.0 * n * dot(-l, n));
    vec3 h = normalize(l_mirror + v);
    float d = d_ggx(clamp(dot(n, h), 0.0, 1.0), a);
    vec3 f = f_schlick(f0, f90, clamp(dot(v, h), 0.0, 1.0));
    float vis = v_smith_ggx_correlated(clamp(dot(n, l_mirror), 0.0, 1.0), clamp(dot(n, v), 0.0, 1.0), a);
    return (1.0 - f) * base_color * d * vis;
}

vec3 refraction_weight(vec3 f0, vec3 f90, float lut_a, float lut_b, vec3 base_color) {
    return (1.0 - (f0 * lut_a + f90 * lut_b)) * base_color;
}

struct TransmissionInputs {
    float factor;
    float thickness;
    vec3 attenuation_color;
    float attenuation_distance;  // 0 = infinite
    float dispersion;
    float ior;
};

#ifdef MATERIAL_TRANSMISSION
#include "material_block.glsl"  // the factors and the maps' transforms
#ifdef HAS_TRANSMISSION_MAP
uniform sampler2D u_transmission_map;
#endif
#ifdef HAS_THICKNESS_MAP
uniform sampler2D u_thickness_map;
#endif

// The transmission part of fresnel::evaluate (EvaluatedMaterial::transmission).
TransmissionInputs read_transmission() {
    TransmissionInputs tr;
    tr.factor = u_transmission_factor;
#ifdef HAS_TRANSMISSION_MAP
    tr.factor *= sample_map(u_transmission_map, u_transmission_uv, u_transmission_transform).r;
#endif
    tr.thickness = u_thickness_factor;
#ifdef HAS_THICKNESS_MAP
    tr.thickness *= sample_map(u_thickness_map, u_thickness_uv, u_thickness_transform).g;
#endif
    tr.attenuation_color = u_attenuation_color;
    tr.attenuation_distance = u_attenuation_distance;
    tr.dispersion = u_dispersion;
    tr.ior = u_ior;
    return tr;
}

// fresnel::shade_light_transmission: what the transmission adds to shade_light for one light.
vec3 shade_light_transmission(MaterialInputs m, TransmissionInputs tr, vec3 v, vec3 l, vec3 lt, float ray_length,
                              vec3 radiance) {
    vec3 h = l + v;
    float hl = length(h);
    h = hl > 0.0 ? h / hl : m.normal;
    float v_dot_h = clamped_dot(v, h);
    float n_dot_l = clamped_dot(m.normal, l);
    vec3 f_dielectric = f_schlick(m.f0_dielectric * m.specular_weight, vec3(m.specular_weight), v_dot_h);
    vec3 btdf = btdf_punctual(m.normal, v, lt, alpha_from_roughness(m.roughness), m.f0_dielectric, vec3(1.0),
                              m.base_color.rgb, tr.ior);
    vec3 transmitted = volume_attenuation(radiance * btdf, ray_length, tr.attenuation_color, tr.attenuation_distance);
    // The diffuse it replaces (with diffuse transmission, the mix of both Lambert lobes), under
    // its weight 1 - F (under a thin film brdf's film_diffuse_weight).
    vec3 lambert = m.base_color.rgb / PI * eon_factor(m.base_color.rgb, m.diffuse_roughness, n_dot_l, clamped_dot(m.normal, v), dot(l, v));
    vec3 diffuse = diffuse_transmission_mix(n_dot_l * lambert, clamped_dot(-m.normal, l),
                                            m.diffuse_transmission, m.diffuse_transmission_color);
    vec3 term = (1.0 - m.metallic) * film_diffuse_weight(f_dielectric, material_film(m, v)) * tr.factor *
                (transmitted - radiance * diffuse);
#ifdef MATERIAL_CLEARCOAT
    term *= 1.0 - m.clearcoat * f_schlick(m.clearcoat_f0, 1.0, clamped_dot(m.clearcoat_normal, v));
#endif
    return term;
}

#ifndef TRANSMISSION_PROBE
#include "frame_block.glsl"  // u_view_projection and the lights
// The opaque scene in linear radiance with its mip chain (Renderer: the transmission pass),
// and the matrices that project the refracted ray's exit into it.
uniform sampler2D u_transmission_framebuffer;
uniform float u_transmission_framebuffer_size;  // width = height
uniform mat4 u_model;

vec3 model_scale() { return vec3(length(u_model[0].xyz), length(u_model[1].xyz), length(u_model[2].xyz)); }

// The unnormalised vector to light i, as Khronos' pointToLight (directional: -direction).
vec3 point_to_light(int i, vec3 position) {
    vec4 pt = u_light_position_type[i];
    return pt.w < 0.5 ? -u_light_direction_range[i].xyz : pt.xyz - position;
}

vec3 transmission_sample(vec3 exit_point, float perceptual_roughness, float ior) {
    vec4 ndc = u_view_projection * vec4(exit_point, 1.0);
    vec2 uv = (ndc.xy / ndc.w + 1.0) * 0.5;
    float lod = transmission_framebuffer_lod(perceptual_roughness, ior, u_transmission_framebuffer_size);
    return textureLod(u_transmission_framebuffer, uv, lod).rgb;
}

// Khronos' getIBLVolumeRefraction: the refracted opaque scene, attenuated by the volume and
// weighted by (1 - the split-sum specular albedo) and the base colour.
vec3 ibl_transmission(MaterialInputs m, TransmissionInputs tr, vec3 n, vec3 v, vec3 position) {
    vec3 scale = model_scale();
    vec3 transmitted;
    float ray_length;
    if (tr.dispersion > 0.0) {
        vec3 iors = dispersion_iors(tr.ior, tr.dispersion);
        for (int i = 0; i < 3; ++i) {
            vec3 ray = volume_ray(n, v, tr.thickness, iors[i], scale);
            ray_length = length(ray);
            transmitted[i] = transmission_sample(position + ray, m.roughness, iors[i])[i];
        }
    } else {
        vec3 ray = volume_ray(n, v, tr.thickness, tr.ior, scale);
        ray_length = length(ray);
        transmitted = transmission_sample(position + ray, m.roughness, tr.ior);
    }
    vec3 attenuated = volume_attenuation(transmitted, ray_length, tr.attenuation_color, tr.attenuation_distance);
    vec2 ab = brdf_lut(clamped_dot(n, v), m.roughness).rg;
    return refraction_weight(m.f0_dielectric, vec3(1.0), ab.x, ab.y, m.base_color.rgb) * attenuated;
}
#endif
#endif
