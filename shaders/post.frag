// Output pass over the resolved frame: un-premultiplies transparent results
// (PNG stores straight alpha) and shows any NaN / Inf that survived as magenta.
in vec2 v_texcoord;
out vec4 frag_color;

#ifdef MSAA_RESOLVE
// Desktop GL: the multisampled frame itself, resolved here (the box average of its samples,
// what glBlitFramebuffer does) instead of by a blit first. GLSL ES 3.00 has no sampler2DMS:
// ES contexts blit, then run this pass without the define.
uniform highp sampler2DMS u_frame_ms;
uniform int u_samples;
#else
uniform sampler2D u_frame;
#endif
uniform int u_transparent;  // 1: un-premultiply (a transparent frame going to PNG)
// The renderer compiles both choices in (as it does the frame variants, shader_features.h): a
// loop over a uniform count and a branch on a uniform cost a software rasteriser extra on every
// pixel. MSAA_SAMPLES: the sample count; STRAIGHT_ALPHA 0/1: u_transparent.
#ifdef MSAA_SAMPLES
#define RESOLVE_SAMPLES MSAA_SAMPLES
#else
#define RESOLVE_SAMPLES u_samples
#endif
#ifdef STRAIGHT_ALPHA
#define UNPREMULTIPLY (STRAIGHT_ALPHA == 1)
#else
#define UNPREMULTIPLY (u_transparent == 1)
#endif

bool bad(vec4 c) { return any(isnan(c)) || any(isinf(c)); }

void main() {
#ifdef MSAA_RESOLVE
    ivec2 p = ivec2(v_texcoord * vec2(textureSize(u_frame_ms)));  // pixel of the frame, wherever the viewport is
    vec4 c = vec4(0.0);
    for (int i = 0; i < RESOLVE_SAMPLES; ++i) c += texelFetch(u_frame_ms, p, i);
    c /= float(RESOLVE_SAMPLES);
#else
    vec4 c = texture(u_frame, v_texcoord);
#endif
    if (bad(c)) {
        frag_color = vec4(1.0, 0.0, 1.0, 1.0);
        return;
    }
    if (UNPREMULTIPLY) {
        float a = clamp(c.a, 0.0, 1.0);
        frag_color = vec4(a > 0.0 ? c.rgb / a : vec3(0.0), a);
    } else {
        frag_color = c;
    }
}
