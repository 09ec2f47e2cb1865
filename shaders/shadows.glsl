// Shadows of punctual lights (fresnel::plan_shadows, libs/render/src/details/shadow_maps.h):
// every shadowed light's maps are square tiles of one depth atlas, read with comparison
// (sampler2DShadow: each probe is the hardware's 2x2 percentage-closer filter). A directional
// light's point is looked up in its first cascade that holds it, a point light's in the cube
// face of the direction's major axis (an area light's too, around its centre), a spot light's in
// its one map. The lookup point moves
// off the surface along the geometric normal by about a texel of the map there (normal offset),
// the depth pass adds a slope-scaled bias: neither acne nor shadows detached from their casters.
// FRAME_SHADOWS 1: one probe (hard); 2: four probes on a disk turned per pixel (soft edges a
// few texels wide); 3: as 2, and a light with a size (u_light_shadow[i].z: a point or spot
// light's bulb radius, an area light's half extent, the tangent of a directional light's
// angular radius) casts
// contact-hardening shadows (percentage-closer soft shadows, Fernando 2005): the mean depth of
// the blockers found around the point sets the width of the filter, sharp where a caster
// touches its shadow and wider away from it. Without FRAME_SHADOWS every light is unshadowed.
#include "frame_block.glsl"

#if defined(FRAME_SHADOWS) && FRAME_SHADOWS > 0
uniform highp sampler2DShadow u_shadow_atlas;

// The tile of light i whose map holds `p`, or -1.
int shadow_tile(int i, vec3 p) {
    int first = int(u_light_shadow[i].x);
    if (first < 0) return -1;
    float type = u_light_position_type[i].w;
    if ((type > 0.5 && type < 1.5) || type > 2.5) {  // point and area lights: the cube face of the major axis
        vec3 d = p - u_light_position_type[i].xyz;
        vec3 a = abs(d);
        int face = a.x >= a.y && a.x >= a.z ? (d.x < 0.0 ? 1 : 0) : (a.y >= a.z ? (d.y < 0.0 ? 3 : 2) : (d.z < 0.0 ? 5 : 4));
        return first + face;
    }
    int count = int(u_light_shadow[i].y);
    for (int c = 0; c < count; ++c) {
        vec4 q = u_shadow_matrix[first + c] * vec4(p, 1.0);
        vec3 t = q.xyz / q.w;
        float m = u_shadow_params[first + c].y;
        if (t.x >= m && t.y >= m && t.x <= 1.0 - m && t.y <= 1.0 - m && t.z <= 1.0) return first + c;
    }
    return -1;
}

// Interleaved gradient noise (Jimenez 2014): a per-pixel angle for the soft filter's disk.
float shadow_noise(vec2 pixel) { return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715)))); }

#if FRAME_SHADOWS == 3
uniform highp sampler2D u_shadow_depth;  // the same atlas read as depths (no comparison)

// A tile's depth (0..1) as a distance along its axis: a perspective tile's from the light
// (params.zw: near, far); an orthographic one's (params.z 0) from its near plane (params.w: the
// length its depths span).
float shadow_distance(vec4 params, float depth) {
    float n = params.z, f = params.w;
    if (n <= 0.0) return depth * f;
    return 2.0 * f * n / ((f + n) - (2.0 * depth - 1.0) * (f - n));
}

// Contact-hardening shadows (`size`: u_light_shadow[i].z) from the blockers within reach on
// twelve taps of a Vogel spiral turned by `turn` (nearest depths): their mean distance d_b and the
// receiver's d_r give the penumbra there, in texels,
//   a bulb of radius `size` seen from a perspective map's centre (an area light: its half
//   extent, as if it were a sphere): size (d_r - d_b) / (d_b d_r tau)
//     (tau: the map's texel at unit distance; searched out to blockers a tenth of the way to the
//     receiver, or at the near plane),
//   a directional light of angular radius a (`size` = tan a), orthographic: (d_r - d_b) size / tau
//     (tau: the texel's length; searched out to blockers at the map's near plane).
// Then 24 probes of the hardware's 2x2 filter on a Vogel spiral turned alike, at least the soft
// filter's radius, at most 32 texels wide (against the tracer's 0.5 m bulb on tests/data/shadows
// at 384^2, with twelve probes: 37.2 dB at most 32 texels, 35.1 dB at 16, 36.3 dB at 64; 24
// probes: 37.4 dB, and a 6-degree sun 37.8 against 37.7 dB with less visible noise).
float contact_hardening(vec4 params, vec2 uv, float depth, vec2 lo, vec2 hi, float size, mat2 turn) {
    const vec2 kVogel[12] = vec2[12](vec2(0.204, 0.000), vec2(-0.261, 0.239), vec2(0.040, -0.455), vec2(0.329, 0.429),
                                     vec2(-0.603, -0.107), vec2(0.571, -0.363), vec2(-0.191, 0.711), vec2(-0.364, -0.702),
                                     vec2(0.791, 0.289), vec2(-0.822, 0.339), vec2(0.396, -0.847), vec2(0.293, 0.934));
    bool orthographic = params.z <= 0.0;
    float tau = params.x;
    float d_r = shadow_distance(params, depth);
    vec2 atlas_texel = u_shadow_atlas_info.xy;
    float reach = max(params.z, 0.1 * d_r);
    float search = clamp(orthographic ? d_r * size / tau : size * (d_r - reach) / (reach * d_r * tau), 1.0, 32.0);
    float blockers = 0.0, sum = 0.0;
    for (int k = 0; k < 12; ++k) {
        float z = texture(u_shadow_depth, clamp(uv + atlas_texel * (turn * kVogel[k]) * search, lo, hi)).r;
        if (z < depth) {
            sum += shadow_distance(params, z);
            blockers += 1.0;
        }
    }
    if (blockers == 0.0) return 1.0;
    float d_b = sum / blockers;
    float penumbra = orthographic ? (d_r - d_b) * size / tau : size * (d_r - d_b) / (d_b * d_r * tau);
    float width = clamp(penumbra, u_shadow_atlas_info.z, 32.0);
    const vec2 kVogel24[24] = vec2[24](vec2(0.144, 0.000), vec2(-0.184, 0.169), vec2(0.028, -0.322), vec2(0.232, 0.303),
        vec2(-0.426, -0.075), vec2(0.404, -0.257), vec2(-0.135, 0.503), vec2(-0.258, -0.496), vec2(0.559, 0.204),
        vec2(-0.582, 0.240), vec2(0.280, -0.599), vec2(0.207, 0.660), vec2(-0.624, -0.362), vec2(0.733, -0.161),
        vec2(-0.447, 0.636), vec2(-0.103, -0.797), vec2(0.634, 0.534), vec2(-0.853, 0.035), vec2(0.622, -0.619),
        vec2(-0.042, 0.900), vec2(-0.592, -0.710), vec2(0.938, 0.126), vec2(-0.795, 0.553), vec2(0.217, -0.965));
    float lit = 0.0;
    for (int k = 0; k < 24; ++k)
        lit += texture(u_shadow_atlas, vec3(clamp(uv + atlas_texel * (turn * kVogel24[k]) * width, lo, hi), depth));
    return lit / 24.0;
}
#endif

// The fraction of light i that reaches `p` (1: lit), `ng` the geometric normal, `l` the
// direction to the light.
float shadow_visibility(int i, vec3 p, vec3 ng, vec3 l) {
    int t = shadow_tile(i, p);
    if (t < 0) return 1.0;
    vec4 params = u_shadow_params[t];
    float texel = params.x;
    if (u_light_position_type[i].w > 0.5) texel *= length(u_light_position_type[i].xyz - p);  // perspective
    vec3 n = dot(ng, l) < 0.0 ? -ng : ng;
    float n_dot_l = clamp(dot(n, l), 0.0, 1.0);
    // About a texel and a half off the surface, more where the light grazes it.
    vec3 q = p + n * texel * (1.5 + 2.0 * (1.0 - n_dot_l));
    vec4 c = u_shadow_matrix[t] * vec4(q, 1.0);
    vec3 s = c.xyz / c.w;
    if (s.z >= 1.0) return 1.0;  // beyond the map's depth range: nothing behind casts
    vec4 rect = u_shadow_rect[t];
    vec2 half_texel = 0.5 * u_shadow_atlas_info.xy;
    vec2 lo = rect.xy + half_texel, hi = rect.xy + rect.zw - half_texel;
    vec2 uv = rect.xy + clamp(s.xy, 0.0, 1.0) * rect.zw;
#if FRAME_SHADOWS == 1
    return texture(u_shadow_atlas, vec3(clamp(uv, lo, hi), s.z));
#else
    // Four probes on a disk turned per pixel, each the hardware's 2x2 filter: 16 texels in
    // all. (Twelve probes, or four first and eight more where the four disagree, gave the same
    // picture against the tracer, 33-37 dB on tests/data/shadows, at 1.5-2x the cost.)
    const vec2 kDisk[4] = vec2[4](vec2(-0.840, -0.074), vec2(0.962, -0.195), vec2(0.519, 0.767), vec2(-0.322, -0.933));
    float angle = 6.2831853 * shadow_noise(gl_FragCoord.xy);
    float cs = cos(angle), sn = sin(angle);
#if FRAME_SHADOWS == 3
    float size = u_light_shadow[i].z;
    if (size > 0.0) return contact_hardening(params, uv, s.z, lo, hi, size, mat2(cs, sn, -sn, cs));
#endif
    mat2 turn = mat2(cs, sn, -sn, cs) * u_shadow_atlas_info.z;
    vec2 atlas_texel = u_shadow_atlas_info.xy;
    float sum = 0.0;
    for (int k = 0; k < 4; ++k)
        sum += texture(u_shadow_atlas, vec3(clamp(uv + atlas_texel * (turn * kDisk[k]), lo, hi), s.z));
    return sum * 0.25;
#endif
}
#else
float shadow_visibility(int i, vec3 p, vec3 ng, vec3 l) { return 1.0; }
#endif
