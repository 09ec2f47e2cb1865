// Screen-space ambient occlusion: ground-truth ambient occlusion (Jimenez, Wu, Pesce and Jarabo
// 2016, "Practical Realtime Strategies for Accurate Indirect Occlusion") from the depth of the
// frame's opaque draws. Per pixel, SSAO_DIRECTIONS slices through the view direction, turned by a
// 4x4 pattern (ssao_blur.frag averages the 16 turns back out); in each slice the highest horizon
// on either side within u_radius (view space, fading over its last third; steps spaced
// quadratically), clamped to the
// hemisphere of the normal projected into the slice, and the cosine-weighted visible arc
// integrated in closed form. The normal comes from the depth (the nearer neighbour each way, so
// silhouettes do not bend it). Output: the visibility, 1 where nothing is near or no surface is.
in vec2 v_texcoord;
out vec4 frag_color;

uniform highp sampler2D u_depth;   // the depth pass (nearest texel), at the target's size
uniform vec4 u_projection;         // the camera's projection: (P00, P11, P22, P32)
uniform vec2 u_projection_offset;  // perspective: (P20, P21); orthographic (SSAO_ORTHOGRAPHIC): (P30, P31)
uniform vec2 u_texel;              // 1 / the target's size
uniform float u_radius;            // view space
uniform float u_pixels_per_unit;   // P11 / 2 * height: pixels per view-space unit (perspective: at depth 1)

#define SSAO_DIRECTIONS 2
#define SSAO_STEPS 6
const float kPi = 3.14159265358979;

// The view-space point at uv: the projection undone term by term (cheaper than a matrix, which a
// software rasteriser pays at every tap).
vec3 view_position(vec2 uv) {
    float nz = texture(u_depth, uv).r * 2.0 - 1.0;
    vec2 nxy = uv * 2.0 - 1.0;
#ifdef SSAO_ORTHOGRAPHIC
    return vec3((nxy - u_projection_offset) / u_projection.xy, (nz - u_projection.w) / u_projection.z);
#else
    float z = -u_projection.w / (nz + u_projection.z);
    return vec3(-z * (nxy + u_projection_offset) / u_projection.xy, z);
#endif
}

void main() {
    vec2 uv = (floor(gl_FragCoord.xy) + 0.5) * u_texel;
    float depth = texture(u_depth, uv).r;
    if (depth >= 1.0) {
        frag_color = vec4(1.0);
        return;
    }
    vec3 p = view_position(uv);
    vec3 pl = view_position(uv - vec2(u_texel.x, 0.0)), pr = view_position(uv + vec2(u_texel.x, 0.0));
    vec3 pd = view_position(uv - vec2(0.0, u_texel.y)), pu = view_position(uv + vec2(0.0, u_texel.y));
    vec3 dx = abs(pr.z - p.z) < abs(p.z - pl.z) ? pr - p : p - pl;
    vec3 dy = abs(pu.z - p.z) < abs(p.z - pd.z) ? pu - p : p - pd;
#ifdef SSAO_ORTHOGRAPHIC
    vec3 v = vec3(0.0, 0.0, 1.0);
    float pixels = u_radius * u_pixels_per_unit;  // the radius on screen
#else
    vec3 v = normalize(-p);
    float pixels = u_radius * u_pixels_per_unit / max(-p.z, 1e-6);
#endif
    vec3 n = normalize(cross(dx, dy));
    if (dot(n, v) < 0.0) n = -n;
    if (pixels < 1.0) {
        frag_color = vec4(1.0);
        return;
    }
    float reach = min(pixels, 256.0);
    // Horizons are measured from half a pixel's footprint above the surface, so that the depth's
    // quantisation does not let a plane occlude itself.
#ifdef SSAO_ORTHOGRAPHIC
    vec3 origin = p + n * (0.5 / u_pixels_per_unit);
#else
    vec3 origin = p + n * (0.5 * -p.z / u_pixels_per_unit);
#endif
    // The 4x4 pattern: 16 turns of the slices and offsets along them.
    ivec2 cell = ivec2(mod(gl_FragCoord.xy, 4.0));
    int index = cell.x + 4 * cell.y;
    float turn = (float((index * 5) % 16) + 0.5) / 16.0;
    float jitter = (float((index * 11) % 16) + 0.5) / 16.0;
    float visibility = 0.0;
    for (int k = 0; k < SSAO_DIRECTIONS; ++k) {
        float phi = (float(k) + turn) * kPi / float(SSAO_DIRECTIONS);
        vec2 d = vec2(cos(phi), sin(phi));
        // The slice: the plane of v and the screen direction d; angles from v towards `ortho`.
        vec3 ortho = normalize(vec3(d, 0.0) - dot(vec3(d, 0.0), v) * v);
        vec3 axis = cross(ortho, v);
        vec3 projected = n - axis * dot(n, axis);
        float projected_length = length(projected);
        if (projected_length < 1e-4) continue;
        float n_angle = atan(dot(projected, ortho), dot(projected, v));
        float h[2];
        for (int side = 0; side < 2; ++side) {
            float sgn = side == 0 ? -1.0 : 1.0;
            float horizon = -1.0;  // the cosine of the highest horizon so far
            for (int s = 0; s < SSAO_STEPS; ++s) {
                // Steps spaced quadratically: dense near the point, where contact occlusion is.
                float t = (float(s) + jitter) / float(SSAO_STEPS);
                vec2 offset = d * sgn * (t * t * reach);
                if (dot(offset, offset) < 1.0) offset = d * sgn;  // at least the next pixel
                vec3 w = view_position(uv + offset * u_texel) - origin;
                float len = length(w);
                if (len < 1e-6) continue;
                float c = dot(w, v) / len;
                c = mix(c, -1.0, clamp((len / u_radius - 0.667) * 3.0, 0.0, 1.0));
                horizon = max(horizon, c);
            }
            float angle = sgn * acos(clamp(horizon, -1.0, 1.0));
            h[side] = n_angle + clamp(angle - n_angle, -0.5 * kPi, 0.5 * kPi);
        }
        float cos_n = cos(n_angle), sin_n = sin(n_angle);
        float arc = 0.25 * (-cos(2.0 * h[0] - n_angle) + cos_n + 2.0 * h[0] * sin_n) +
                    0.25 * (-cos(2.0 * h[1] - n_angle) + cos_n + 2.0 * h[1] * sin_n);
        visibility += projected_length * arc;
    }
    frag_color = vec4(vec3(clamp(visibility / float(SSAO_DIRECTIONS), 0.0, 1.0)), 1.0);
}
