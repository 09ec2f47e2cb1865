// KHR_lights_punctual: directional (lux), point and spot (candela) lights; area lights (nits),
// packed as frame_block.glsl says.
#ifndef MAX_LIGHTS
#define MAX_LIGHTS 16
#endif
#include "frame_block.glsl"  // u_light_count and the packed lights, uploaded once per frame

// The extension's recommended range window: smooth fall to zero at `range`, on top of 1/d^2.
float range_attenuation(float range, float distance) {
    float d2 = max(distance * distance, 1e-8);
    if (range <= 0.0) return 1.0 / d2;
    float r = distance / range;
    return clamp(1.0 - r * r * r * r, 0.0, 1.0) / d2;
}

float spot_attenuation(vec3 light_to_point_dir, vec3 spot_dir, vec2 cone) {
    float cd = dot(spot_dir, light_to_point_dir);
    float a = clamp(cd * cone.x + cone.y, 0.0, 1.0);
    return a * a;
}

// Light i's colour at `position` and the unit direction to the light, with the spot cone's
// window; `falloff`: with the distance attenuation of point and spot lights (range_attenuation;
// OpenGL 1's default attenuation has none). Callers pass a constant, which the compiler folds.
vec3 light_arriving(int i, vec3 position, bool falloff, out vec3 l) {
    vec4 pt = u_light_position_type[i];
    vec4 dr = u_light_direction_range[i];
    vec3 radiance = u_light_color[i].rgb;
    if (pt.w < 0.5) {
        l = -dr.xyz;
        return radiance;
    }
    if (pt.w > 2.5) {
        // An area light seen as a point at its centre: luminance x projected area (the
        // Blinn-Phong and OpenGL 1 shading's view of it; pbr.frag integrates the area, ltc.glsl).
        vec3 to_center = pt.xyz - position;
        float d2 = max(dot(to_center, to_center), 1e-8);
        l = to_center * inversesqrt(d2);
        float r = u_light_cone[i].w;
        float projected = pt.w > 5.5   ? 3.14159265 * r * r + 4.0 * r * length(cross(u_light_cone[i].xyz, l))  // a tube's silhouette
                          : pt.w > 4.5 ? 3.14159265 * r * r
                                       : (pt.w > 3.5 ? 3.14159265 : 4.0) * length(cross(u_light_cone[i].xyz, u_light_axis[i].xyz)) *
                                             max(dot(dr.xyz, -l), 0.0);
        return radiance * (projected / d2);
    }
    vec3 to_light = pt.xyz - position;
    float dist = length(to_light);
    l = dist > 0.0 ? to_light / dist : vec3(0.0, 0.0, 1.0);
    if (falloff) radiance *= range_attenuation(dr.w, dist);
    if (pt.w > 1.5) radiance *= spot_attenuation(-l, dr.xyz, u_light_cone[i].xy);
    return radiance;
}

// Returns the irradiance-scaled light colour at `position` and the unit direction to the light.
vec3 light_incident(int i, vec3 position, out vec3 l) { return light_arriving(i, position, true, l); }
