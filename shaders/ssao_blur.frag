// The 4x4 average of ssao.frag's visibility (its pattern repeats every 4 pixels, so each output
// sees all 16 turns once), weighted by depth so that occlusion does not bleed across edges.
in vec2 v_texcoord;
out vec4 frag_color;

uniform sampler2D u_occlusion;     // ssao.frag's output
uniform highp sampler2D u_depth;
uniform vec2 u_texel;
uniform vec4 u_projection;  // as ssao.frag's

float view_depth(vec2 uv) {
    float nz = texture(u_depth, uv).r * 2.0 - 1.0;
#ifdef SSAO_ORTHOGRAPHIC
    return (nz - u_projection.w) / u_projection.z;
#else
    return -u_projection.w / (nz + u_projection.z);
#endif
}

void main() {
    vec2 uv = (floor(gl_FragCoord.xy) + 0.5) * u_texel;
    float z = view_depth(uv);
    float sum = 0.0, weight = 0.0;
    for (int y = -2; y < 2; ++y)
        for (int x = -2; x < 2; ++x) {
            vec2 q = uv + vec2(float(x), float(y)) * u_texel;
            float w = max(1.0 - abs(view_depth(q) - z) / (0.05 * abs(z) + 1e-6), 0.0) + 1e-4;
            sum += w * texture(u_occlusion, q).r;
            weight += w;
        }
    frag_color = vec4(vec3(sum / weight), 1.0);
}
