#include "fresnel/trace/area_lights.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace fresnel::trace {
namespace {

constexpr float kPi = 3.14159265358979323846f;

// The plane coordinates (s, t) of q - centre in the basis (u, v): q = centre + s u + t v.
glm::vec2 plane_coordinates(glm::vec3 d, glm::vec3 u, glm::vec3 v) {
    const glm::vec3 n = glm::cross(u, v);
    const float n2 = glm::dot(n, n);
    return {glm::dot(glm::cross(d, v), n) / n2, glm::dot(glm::cross(u, d), n) / n2};
}

// The cone a sphere subtends from p: cos of its half-angle, or -2 when p is inside.
float sphere_cos_max(const LightInstance& light, glm::vec3 p, float& d) {
    d = glm::length(light.position - p);
    if (!(d > light.radius * (1.0f + 1e-5f))) return -2.0f;
    const float s = light.radius / d;
    return std::sqrt(std::max(0.0f, 1.0f - s * s));
}

// The nearer intersection of origin + t dir with the sphere, t > 0; -1 if none.
float sphere_hit(glm::vec3 centre, float radius, glm::vec3 origin, glm::vec3 dir) {
    const glm::vec3 oc = origin - centre;
    const float b = glm::dot(oc, dir);
    // The discriminant as r^2 - |oc - b dir|^2, which keeps its precision far from the sphere.
    const glm::vec3 perp = oc - b * dir;
    const float disc = radius * radius - glm::dot(perp, perp);
    if (disc < 0.0f) return -1.0f;
    const float root = std::sqrt(disc);
    float t = -b - root;
    if (t <= 0.0f) t = -b + root;
    return t > 0.0f ? t : -1.0f;
}

// A tube (a capsule around the segment centre +- axis_u): the nearest t > 0 where the ray meets
// it, -1 if none (Quilez's capsule intersection).
float capsule_hit(const LightInstance& light, glm::vec3 origin, glm::vec3 dir) {
    const glm::vec3 pa = light.position - light.axis_u, ba = 2.0f * light.axis_u;
    const float r = light.radius;
    const glm::vec3 oa = origin - pa;
    const float baba = glm::dot(ba, ba), bard = glm::dot(ba, dir), baoa = glm::dot(ba, oa);
    const float rdoa = glm::dot(dir, oa), oaoa = glm::dot(oa, oa);
    const float a = baba - bard * bard, b = baba * rdoa - baoa * bard, c = baba * oaoa - baoa * baoa - r * r * baba;
    const float h = b * b - a * c;
    if (h >= 0.0f && a > 1e-12f) {
        const float t = (-b - std::sqrt(h)) / a;
        const float y = baoa + t * bard;
        if (y > 0.0f && y < baba) return t > 0.0f ? t : -1.0f;  // the cylinder's side
        const glm::vec3 oc = y <= 0.0f ? oa : origin - (pa + ba);  // the end it passes
        const float bb = glm::dot(dir, oc), cc = glm::dot(oc, oc) - r * r, hh = bb * bb - cc;
        if (hh > 0.0f) {
            const float tc = -bb - std::sqrt(hh);
            return tc > 0.0f ? tc : -1.0f;
        }
        return -1.0f;
    }
    // Along the axis (a = 0): only the ends.
    float best = -1.0f;
    for (const glm::vec3& end : {pa, pa + ba}) {
        const glm::vec3 oc = origin - end;
        const float bb = glm::dot(dir, oc), cc = glm::dot(oc, oc) - r * r, hh = bb * bb - cc;
        if (hh > 0.0f) {
            const float tc = -bb - std::sqrt(hh);
            if (tc > 0.0f && (best < 0.0f || tc < best)) best = tc;
        }
    }
    return best;
}

// The capsule's outward normal at a point q on it.
glm::vec3 capsule_normal(const LightInstance& light, glm::vec3 q) {
    const glm::vec3 pa = light.position - light.axis_u, ba = 2.0f * light.axis_u;
    const float baba = glm::dot(ba, ba);
    const float s = baba > 0.0f ? std::clamp(glm::dot(q - pa, ba) / baba, 0.0f, 1.0f) : 0.0f;
    return glm::normalize(q - (pa + s * ba));
}

bool inside_capsule(const LightInstance& light, glm::vec3 p) {
    const glm::vec3 pa = light.position - light.axis_u, ba = 2.0f * light.axis_u;
    const float baba = glm::dot(ba, ba);
    const float s = baba > 0.0f ? std::clamp(glm::dot(p - pa, ba) / baba, 0.0f, 1.0f) : 0.0f;
    return glm::length(p - (pa + s * ba)) <= light.radius * (1.0f + 1e-5f);
}

}  // namespace

AreaLightSample sample_area_light(const LightInstance& light, glm::vec3 p, glm::vec2 u) {
    AreaLightSample s;
    if (light.type == Light::Type::Tube) {
        // Uniform over the capsule's area (its side, then its two round ends as one sphere); a
        // point whose side faces away is hidden by the rest (the capsule is convex): no sample.
        if (inside_capsule(light, p)) return s;
        const float half = glm::length(light.axis_u), r = light.radius;
        const glm::vec3 a = half > 0.0f ? light.axis_u / half : glm::vec3(1.0f, 0.0f, 0.0f);
        const glm::vec3 t1 = glm::normalize(glm::cross(std::abs(a.x) > 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0), a));
        const glm::vec3 t2 = glm::cross(a, t1);
        const float side = 4.0f * kPi * r * half, area = light.area();
        const float p_side = side / area;
        glm::vec3 q, n;
        if (u.x < p_side) {
            const float axial = (2.0f * (u.x / p_side) - 1.0f) * half, phi = 2.0f * kPi * u.y;
            n = std::cos(phi) * t1 + std::sin(phi) * t2;
            q = light.position + axial * a + r * n;
        } else {
            const float z = 1.0f - 2.0f * std::min((u.x - p_side) / (1.0f - p_side), 1.0f), phi = 2.0f * kPi * u.y;
            const float rr = std::sqrt(std::max(0.0f, 1.0f - z * z));
            n = z * a + rr * (std::cos(phi) * t1 + std::sin(phi) * t2);
            q = light.position + (z >= 0.0f ? half : -half) * a + r * n;
        }
        const glm::vec3 to = q - p;
        const float d2 = glm::dot(to, to);
        if (!(d2 > 0.0f)) return s;
        s.distance = std::sqrt(d2);
        s.l = to / s.distance;
        const float cos_light = glm::dot(n, -s.l);
        if (!(cos_light > 0.0f)) return s;
        s.radiance = light.radiance;
        s.pdf = d2 / (area * cos_light);
        return s;
    }
    if (light.type == Light::Type::Sphere) {
        float d = 0.0f;
        const float cos_max = sphere_cos_max(light, p, d);
        if (cos_max < -1.0f) return s;
        const glm::vec3 w = (light.position - p) / d;
        const glm::vec3 a = std::abs(w.x) > 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
        const glm::vec3 t1 = glm::normalize(glm::cross(a, w)), t2 = glm::cross(w, t1);
        const float cos_t = 1.0f - u.x * (1.0f - cos_max);
        const float sin_t = std::sqrt(std::max(0.0f, 1.0f - cos_t * cos_t));
        const float phi = 2.0f * kPi * u.y;
        s.l = glm::normalize(w * cos_t + (t1 * std::cos(phi) + t2 * std::sin(phi)) * sin_t);
        const float t = sphere_hit(light.position, light.radius, p, s.l);
        s.distance = t > 0.0f ? t : d;  // a grazing sample that rounding put beside the sphere: at its centre's distance
        s.radiance = light.radiance;
        s.pdf = 1.0f / (2.0f * kPi * std::max(1.0f - cos_max, 1e-12f));
        return s;
    }
    glm::vec3 q;
    if (light.type == Light::Type::Rect) {
        q = light.position + (2.0f * u.x - 1.0f) * light.axis_u + (2.0f * u.y - 1.0f) * light.axis_v;
    } else {  // disk: Shirley and Chiu's concentric map of the square onto it
        const glm::vec2 o = 2.0f * u - 1.0f;
        float r = 0.0f, phi = 0.0f;
        if (o.x != 0.0f || o.y != 0.0f) {
            if (std::abs(o.x) > std::abs(o.y)) {
                r = o.x;
                phi = (kPi / 4.0f) * (o.y / o.x);
            } else {
                r = o.y;
                phi = kPi / 2.0f - (kPi / 4.0f) * (o.x / o.y);
            }
        }
        q = light.position + r * (std::cos(phi) * light.axis_u + std::sin(phi) * light.axis_v);
    }
    const glm::vec3 to = q - p;
    const float d2 = glm::dot(to, to);
    if (!(d2 > 0.0f)) return s;
    s.distance = std::sqrt(d2);
    s.l = to / s.distance;
    const float cos_light = glm::dot(light.direction, -s.l);  // the emitting side faces along `direction`
    const float area = light.area();
    if (!(cos_light > 0.0f) || !(area > 0.0f)) return s;
    s.radiance = light.radiance;
    s.pdf = d2 / (area * cos_light);
    return s;
}

glm::vec3 area_light_hit(const LightInstance& light, glm::vec3 origin, glm::vec3 dir, float tmax, float& pdf, float& t) {
    pdf = 0.0f;
    t = 0.0f;
    if (light.type == Light::Type::Tube) {
        if (inside_capsule(light, origin)) return glm::vec3(0.0f);
        const float th = capsule_hit(light, origin, dir);
        if (!(th > 0.0f && th < tmax)) return glm::vec3(0.0f);
        const float cos_light = -glm::dot(dir, capsule_normal(light, origin + th * dir));
        if (!(cos_light > 0.0f)) return glm::vec3(0.0f);
        t = th;
        pdf = th * th / (light.area() * cos_light);
        return light.radiance;
    }
    if (light.type == Light::Type::Sphere) {
        float d = 0.0f;
        const float cos_max = sphere_cos_max(light, origin, d);
        if (cos_max < -1.0f) return glm::vec3(0.0f);
        const float th = sphere_hit(light.position, light.radius, origin, dir);
        if (!(th > 0.0f && th < tmax)) return glm::vec3(0.0f);
        t = th;
        pdf = 1.0f / (2.0f * kPi * std::max(1.0f - cos_max, 1e-12f));
        return light.radiance;
    }
    const float cos_light = -glm::dot(dir, light.direction);
    if (!(cos_light > 0.0f)) return glm::vec3(0.0f);  // the back, or edge on
    const float th = glm::dot(light.position - origin, light.direction) / glm::dot(dir, light.direction);
    if (!(th > 0.0f && th < tmax)) return glm::vec3(0.0f);
    const glm::vec2 st = plane_coordinates(origin + th * dir - light.position, light.axis_u, light.axis_v);
    // (A hair of tolerance: points sampled on the edge stay on the light after rounding.)
    constexpr float kEdge = 1.0f + 1e-5f;
    const bool inside = light.type == Light::Type::Rect ? std::abs(st.x) <= kEdge && std::abs(st.y) <= kEdge
                                                        : st.x * st.x + st.y * st.y <= kEdge * kEdge;
    const float area = light.area();
    if (!inside || !(area > 0.0f)) return glm::vec3(0.0f);
    t = th;
    pdf = th * th / (area * cos_light);
    return light.radiance;
}

}  // namespace fresnel::trace
