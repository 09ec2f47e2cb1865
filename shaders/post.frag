// Resolve to output: exposure, tone map, display encoding, background, NaN check.
in vec2 v_texcoord;
out vec4 frag_color;

uniform sampler2D u_hdr;       // premultiplied linear radiance (or debug values)
uniform float u_exposure;      // linear multiplier, 2^EV
uniform int u_tonemap;         // see tonemap.glsl
uniform int u_encoding;        // -1 = none (float output), 0 = sRGB, 1 = gamma 2.2
uniform int u_passthrough;     // 1 = debug view: no exposure, no tone map, no encoding
uniform vec4 u_background;     // display-referred background; .a = 0 keeps transparency

#include "common.glsl"
#include "color.glsl"
#include "tonemap.glsl"

bool bad(vec4 c) { return any(isnan(c)) || any(isinf(c)); }

void main() {
    vec4 hdr = texture(u_hdr, v_texcoord);
    if (bad(hdr)) {  // NaN / Inf shows as magenta
        frag_color = vec4(1.0, 0.0, 1.0, 1.0);
        return;
    }
    float a = clamp(hdr.a, 0.0, 1.0);
    vec3 c = a > 0.0 ? hdr.rgb / a : vec3(0.0);  // straight colour of the covered part
    if (u_passthrough == 0) {
        c = tone_map(u_tonemap, c * u_exposure);
        if (u_encoding >= 0) c = encode_display(u_encoding, c);
    }
    if (bad(vec4(c, 1.0))) c = vec3(1.0, 0.0, 1.0);
    if (u_background.a > 0.0) {
        // Opaque background: composite in the output space (as display renderers do).
        frag_color = vec4(mix(u_background.rgb, c, a), 1.0);
    } else {
        frag_color = vec4(c, a);
    }
}
