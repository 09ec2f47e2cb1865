// Test shader: evaluates the GLSL BRDF and tone mappers on a grid of inputs
// so tests/gpu can compare them with the C++ functions. Each pixel reads its
// inputs from u_inputs (RGBA32F, 3 texels per case) and writes one result.
in vec2 v_texcoord;
out vec4 frag_color;
uniform sampler2D u_inputs;
uniform int u_mode;  // 0: BRDF diffuse+specular, 1: D,V,F.r, 2: tone map, 3: encode, 4: clearcoat

#include "common.glsl"
#include "color.glsl"
#include "tonemap.glsl"
#include "brdf.glsl"

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 a = texelFetch(u_inputs, ivec2(p.x * 3 + 0, p.y), 0);
    vec4 b = texelFetch(u_inputs, ivec2(p.x * 3 + 1, p.y), 0);
    vec4 c = texelFetch(u_inputs, ivec2(p.x * 3 + 2, p.y), 0);
    if (u_mode == 0 || u_mode == 1) {
        // a = (base rgb, metallic), b = (l.xyz, roughness), c = (v.xyz, unused); n = +Z
        vec3 n = vec3(0.0, 0.0, 1.0);
        BrdfTerms t = brdf_terms(a.rgb, a.a, b.a, vec3(0.04), 1.0, n, normalize(c.xyz), normalize(b.xyz));
        if (u_mode == 0) frag_color = vec4(t.diffuse + t.specular, 1.0);
        else frag_color = vec4(t.d, t.v, t.f.r, 1.0);
    } else if (u_mode == 4) {
        // a = (l.xyz, coat roughness), b = (v.xyz, clearcoat), c = (coat normal.xyz, coat F0)
        vec3 nc = normalize(c.xyz), v = normalize(b.xyz);
        float spec = clearcoat_specular(nc, v, normalize(a.xyz), alpha_from_roughness(a.w));
        frag_color = vec4(spec, b.w * f_schlick(c.w, 1.0, clamped_dot(nc, v)), 0.0, 1.0);
    } else if (u_mode == 2) {
        frag_color = vec4(tone_map(int(b.x), a.rgb), 1.0);
    } else {
        frag_color = vec4(encode_display(int(b.x), a.rgb), 1.0);
    }
}
