// Test shader: read_material (material_inputs.glsl) and shade_light at one surface point
// per pixel, so tests/gpu/material_gpu_test.cpp can compare them with fresnel::evaluate
// and fresnel::shade_light. Inputs: u_points (RGBA32F), kTexels texels per point:
//   0 (uv0.xy, uv1.xy)  1 vertex colour  2 tangent  3 bitangent  4 geometric normal
//   5 view  6 light  7 energy compensation (dielectric)  8 energy compensation (metal)
//   9 (d uv0/dx, d uv0/dy)  10 (d uv1/dx, d uv1/dy)
// With MATERIAL_PROBE_QUADS each point covers a 2x2 quad whose pixels hold uv + i d/dx +
// j d/dy (i, j = 0, 1), so that dFdx / dFdy give the point's derivatives to the renderer's
// filters (sample_detail_map, texture()); its result is the quad's first pixel.
// u_output selects which results the pixel writes (see main). u_brdf_lut's A channel is
// the sheen albedo table (brdf::SheenAlbedoTable::standard() on the C++ side).
in vec2 v_texcoord;
out vec4 frag_color;
uniform sampler2D u_points;
uniform int u_output;

// What pbr.vert's varyings carry, here read from u_points.
vec2 v_uv0;
vec2 v_uv1;
vec4 v_color;

#include "common.glsl"
#include "color.glsl"
#include "brdf.glsl"
#include "ibl.glsl"
#include "material_inputs.glsl"

const int kTexels = 11;

vec4 point_texel(int k) {
    ivec2 p = ivec2(gl_FragCoord.xy);
#ifdef MATERIAL_PROBE_QUADS
    p /= 2;
#endif
    return texelFetch(u_points, ivec2(p.x * kTexels + k, p.y), 0);
}

void main() {
    vec4 uv = point_texel(0);
    v_uv0 = uv.xy;
    v_uv1 = uv.zw;
#ifdef MATERIAL_PROBE_QUADS
    vec2 ij = vec2(ivec2(gl_FragCoord.xy) % 2);
    vec4 d0 = point_texel(9), d1 = point_texel(10);
    v_uv0 += ij.x * d0.xy + ij.y * d0.zw;
    v_uv1 += ij.x * d1.xy + ij.y * d1.zw;
#endif
    v_color = point_texel(1);
    MaterialInputs m = read_material(point_texel(2).xyz, point_texel(3).xyz, point_texel(4).xyz);
    if (u_output == 0) frag_color = m.base_color;
    else if (u_output == 1) frag_color = vec4(m.metallic, m.roughness, m.occlusion, m.discard_fragment ? 1.0 : 0.0);
    else if (u_output == 2) frag_color = vec4(m.emissive, m.specular_weight);
    else if (u_output == 3) frag_color = vec4(m.f0_dielectric, m.clearcoat);
    else if (u_output == 4) frag_color = vec4(m.normal, m.clearcoat_roughness);
    else if (u_output == 5) frag_color = vec4(m.clearcoat_normal, m.clearcoat_f0);
    else if (u_output == 7) frag_color = vec4(m.sheen_color, m.sheen_roughness);
    else if (u_output == 8) frag_color = vec4(m.anisotropic_t, m.anisotropy_strength);
    else if (u_output == 9) frag_color = vec4(m.anisotropic_b, m.anisotropy_direction.x);
    else if (u_output == 10) frag_color = vec4(m.iridescence, m.iridescence_thickness, m.iridescence_ior, m.diffuse_roughness);
    else if (u_output == 11) frag_color = vec4(m.diffuse_transmission_color, m.diffuse_transmission);
    else {
        vec3 radiance = vec3(1.0, 0.8, 0.6);
        frag_color = vec4(shade_light(m, point_texel(5).xyz, point_texel(6).xyz, radiance, point_texel(7).xyz,
                                      point_texel(8).xyz), 1.0);
    }
}
