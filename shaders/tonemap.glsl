// Tone mappers; the same functions as libs/core/src/color.cpp (tests/gpu keeps them equal).
// Selected by TONEMAP: 0 neutral, 1 aces (Narkowicz), 2 aces-hill, 3 reinhard, 4 agx, 5 none.
#include "color.glsl"

vec3 tone_map_neutral(vec3 color) {
    const float start_compression = 0.8 - 0.04;
    const float desaturation = 0.15;
    float x = min(color.r, min(color.g, color.b));
    float offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
    color -= offset;
    float peak = max(color.r, max(color.g, color.b));
    if (peak < start_compression) return color;
    const float d = 1.0 - start_compression;
    float new_peak = 1.0 - d * d / (peak + d - start_compression);
    color *= new_peak / peak;
    float g = 1.0 - 1.0 / (desaturation * (peak - new_peak) + 1.0);
    return mix(color, vec3(new_peak), g);
}

vec3 tone_map_aces_narkowicz(vec3 c) {
    const float a = 2.51, b = 0.03, cc = 2.43, d = 0.59, e = 0.14;
    return clamp((c * (a * c + b)) / (c * (cc * c + d) + e), 0.0, 1.0);
}

vec3 tone_map_aces_hill(vec3 c) {
    const mat3 input_mat = mat3(0.59719, 0.07600, 0.02840, 0.35458, 0.90834, 0.13383, 0.04823, 0.01566, 0.83777);
    const mat3 output_mat = mat3(1.60475, -0.10208, -0.00327, -0.53108, 1.10813, -0.07276, -0.07367, -0.00605, 1.07602);
    c = input_mat * c;
    vec3 a = c * (c + 0.0245786) - 0.000090537;
    vec3 b = c * (0.983729 * c + 0.4329510) + 0.238081;
    return clamp(output_mat * (a / b), 0.0, 1.0);
}

vec3 tone_map_reinhard(vec3 c) { return c / (1.0 + max(c, 0.0)); }

vec3 tone_map_agx(vec3 c) {
    const mat3 agx = mat3(0.842479062253094, 0.0423282422610123, 0.0423756549057051, 0.0784335999999992,
                          0.878468636469772, 0.0784336, 0.0792237451477643, 0.0791661274605434, 0.879142973793104);
    const mat3 agx_inv = mat3(1.19687900512017, -0.0528968517574562, -0.0529716355144438, -0.0980208811401368,
                              1.15190312990417, -0.0980434501171241, -0.0990297440797205, -0.0989611768448433,
                              1.15107367264116);
    const float min_ev = -12.47393, max_ev = 4.026069;
    c = agx * max(c, vec3(1e-10));
    c = clamp(log2(c), min_ev, max_ev);
    c = (c - min_ev) / (max_ev - min_ev);
    vec3 x2 = c * c, x4 = x2 * x2;
    c = 15.5 * x4 * x2 - 40.14 * x4 * c + 31.96 * x4 - 6.868 * x2 * c + 0.4298 * x2 + 0.1191 * c - 0.00232;
    c = agx_inv * c;
    return pow(clamp(c, 0.0, 1.0), vec3(2.2));
}

vec3 tone_map(int mapper, vec3 c) {
    if (mapper == 0) return tone_map_neutral(c);
    if (mapper == 1) return tone_map_aces_narkowicz(c);
    if (mapper == 2) return tone_map_aces_hill(c);
    if (mapper == 3) return tone_map_reinhard(c);
    if (mapper == 4) return tone_map_agx(c);
    return c;
}

// A frame's display transform: exposure, tone map, then encoding (-1: none, linear output).
// Where FRAME_TONEMAP and FRAME_ENCODING are defined (the renderer's frame variant,
// fresnel::FrameVariant) they replace the run-time choice and the compiler keeps one path:
// on a software rasteriser a switch on a uniform costs every branch (llvmpipe: ~10 % of
// DamagedHelmet's frame). Without them (probes, tests) the arguments choose.
vec3 display_transform(vec3 c, float exposure, int tonemap, int encoding) {
#ifdef FRAME_TONEMAP
    tonemap = FRAME_TONEMAP;
    encoding = FRAME_ENCODING;
#endif
    c = tone_map(tonemap, c * exposure);
    if (encoding >= 0) c = encode_display(encoding, c);
    return c;
}
