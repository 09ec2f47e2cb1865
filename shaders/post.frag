// Output pass over the resolved frame: un-premultiplies transparent results
// (PNG stores straight alpha) and shows any NaN / Inf that survived as magenta.
in vec2 v_texcoord;
out vec4 frag_color;

uniform sampler2D u_frame;
uniform int u_transparent;  // 1: un-premultiply (a transparent frame going to PNG)

bool bad(vec4 c) { return any(isnan(c)) || any(isinf(c)); }

void main() {
    vec4 c = texture(u_frame, v_texcoord);
    if (bad(c)) {
        frag_color = vec4(1.0, 0.0, 1.0, 1.0);
        return;
    }
    if (u_transparent == 1) {
        float a = clamp(c.a, 0.0, 1.0);
        frag_color = vec4(a > 0.0 ? c.rgb / a : vec3(0.0), a);
    } else {
        frag_color = c;
    }
}
