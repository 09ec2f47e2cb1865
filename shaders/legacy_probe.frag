// Test shader: evaluates legacy_shading.glsl on a grid of inputs so tests/gpu can compare it
// with the C++ functions (legacy_shading.h). Each pixel reads 4 RGBA32F texels of u_inputs.
in vec2 v_texcoord;
out vec4 frag_color;
uniform sampler2D u_inputs;
// 0: ogl1 diffuse part, 1: ogl1 specular part, 2: normalized Blinn-Phong, 3: fog factor,
// 4: ogl1_combine (single colour; separate specular in .a's case), 5: IBL roughness and shininess clamp,
// 6: the normalized Blinn-Phong model's image-based path
uniform int u_mode;

#include "common.glsl"
#include "legacy_shading.glsl"

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 a = texelFetch(u_inputs, ivec2(p.x * 4 + 0, p.y), 0);
    vec4 b = texelFetch(u_inputs, ivec2(p.x * 4 + 1, p.y), 0);
    vec4 c = texelFetch(u_inputs, ivec2(p.x * 4 + 2, p.y), 0);
    vec4 d = texelFetch(u_inputs, ivec2(p.x * 4 + 3, p.y), 0);
    vec3 n = vec3(0.0, 0.0, 1.0);
    if (u_mode == 0 || u_mode == 1) {
        // a = (l, shininess), b = (v, light r), c = (diffuse, light g), d = (specular, light b)
        Ogl1Light o = ogl1_light(n, normalize(b.xyz), normalize(a.xyz), vec3(b.w, c.w, d.w), c.rgb, d.rgb,
                                 ogl1_shininess(a.w));
        frag_color = vec4(u_mode == 0 ? o.diffuse : o.specular, 1.0);
    } else if (u_mode == 2) {
        // a = (l, shininess), b = (v, fresnel), c = (base, metalness), d = (light, reflectivity)
        frag_color = vec4(blinn_phong_normalized(c.rgb, a.w, b.w, c.w, d.w, n, normalize(b.xyz), normalize(a.xyz), d.rgb), 1.0);
    } else if (u_mode == 3) {
        // a = (mode, z, start, end), b.x = density
        frag_color = vec4(ogl1_fog_factor(int(a.x), a.y, a.z, a.w, b.x), 0.0, 0.0, 1.0);
    } else if (u_mode == 4) {
        // a = (primary, separate), b = secondary, c = texel
        frag_color = vec4(ogl1_combine(a.rgb, b.rgb, c.rgb, a.w > 0.5), 1.0);
    } else if (u_mode == 6) {
        // a = (base, metalness), b = (irradiance, fresnel), c = (prefiltered, reflectivity), d.x = n.v
        frag_color = vec4(blinn_phong_normalized_ibl(a.rgb, b.w, a.w, c.w, d.x, b.rgb, c.rgb), 1.0);
    } else {
        frag_color = vec4(blinn_phong_ibl_roughness(a.x), ogl1_shininess(a.x), blinn_phong_d(a.y, a.x), 1.0);
    }
}
