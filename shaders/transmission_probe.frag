// Test shader: the functions of transmission.glsl and read_transmission at one point per
// pixel, so tests/gpu/transmission_gpu_test.cpp can compare them with their C++ twins
// (fresnel/material/transmission.h, fresnel::evaluate, fresnel::shade_light_transmission).
// Inputs: u_points (RGBA32F), kTexels texels per point:
//   0 n, ior            1 v, thickness          2 l, alpha            3 f0, dispersion
//   4 base colour, roughness                    5 model scale, attenuation distance
//   6 attenuation colour, distance              7 radiance, transmission factor
//   8 l transmitted, metallic                   9 (lut A, lut B, specular weight, ray length)
//  10 (clearcoat, clearcoat F0, uv0.xy)
// u_output selects which results the pixel writes (see main).
#define TRANSMISSION_PROBE
in vec2 v_texcoord;
out vec4 frag_color;
uniform sampler2D u_points;
uniform int u_output;

vec2 v_uv0;
vec2 v_uv1;
vec4 v_color;

#include "common.glsl"
#include "color.glsl"
#include "brdf.glsl"
#include "material_inputs.glsl"
#include "transmission.glsl"

const int kTexels = 11;

vec4 point_texel(int k) {
    ivec2 p = ivec2(gl_FragCoord.xy);
    return texelFetch(u_points, ivec2(p.x * kTexels + k, p.y), 0);
}

void main() {
    vec4 t0 = point_texel(0), t1 = point_texel(1), t2 = point_texel(2), t3 = point_texel(3), t4 = point_texel(4),
         t5 = point_texel(5), t6 = point_texel(6), t7 = point_texel(7), t8 = point_texel(8), t9 = point_texel(9),
         t10 = point_texel(10);
    v_uv0 = t10.zw;
    v_uv1 = t10.zw;
    v_color = vec4(1.0);
    if (u_output == 0) {
        frag_color = vec4(volume_ray(t0.xyz, t1.xyz, t1.w, t0.w, t5.xyz), apply_ior_to_roughness(t4.w, t0.w));
    } else if (u_output == 1) {
        frag_color = vec4(volume_attenuation(t7.xyz, t6.w, t6.xyz, t5.w), transmission_framebuffer_lod(t4.w, t0.w, 1024.0));
    } else if (u_output == 2) {
        frag_color = vec4(btdf_punctual(t0.xyz, t1.xyz, t2.xyz, t2.w, t3.xyz, vec3(1.0), t4.xyz, t0.w), 0.0);
    } else if (u_output == 3) {
        frag_color = vec4(dispersion_iors(t0.w, t3.w), 0.0);
    } else if (u_output == 4) {
        frag_color = vec4(refraction_weight(t3.xyz, vec3(1.0), t9.x, t9.y, t4.xyz), 0.0);
    } else if (u_output == 5) {
        MaterialInputs m;
        m.base_color = vec4(t4.xyz, 1.0);
        m.discard_fragment = false;
        m.metallic = t8.w;
        m.roughness = t4.w;
        m.occlusion = 1.0;
        m.emissive = vec3(0.0);
        m.f0_dielectric = t3.xyz;
        m.specular_weight = t9.z;
        m.normal = t0.xyz;
        m.clearcoat = t10.x;
        m.clearcoat_roughness = 0.0;
        m.clearcoat_f0 = t10.y;
        m.clearcoat_normal = t0.xyz;
        TransmissionInputs tr;
        tr.factor = t7.w;
        tr.thickness = t1.w;
        tr.attenuation_color = t6.xyz;
        tr.attenuation_distance = t5.w;
        tr.dispersion = t3.w;
        tr.ior = t0.w;
        frag_color = vec4(shade_light_transmission(m, tr, t1.xyz, t2.xyz, t8.xyz, t9.w, t7.xyz), 0.0);
    } else {
        TransmissionInputs tr = read_transmission();
        if (u_output == 6) frag_color = vec4(tr.factor, tr.thickness, tr.attenuation_distance, tr.dispersion);
        else frag_color = vec4(tr.attenuation_color, tr.ior);
    }
}
