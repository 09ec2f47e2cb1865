#include "fresnel/viewer/geometry.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/trigonometric.hpp>

namespace fresnel::viewer {

std::optional<Ray> window_ray(const CameraSetup& camera, glm::ivec2 window_size, glm::vec2 point) {
    if (window_size.x <= 0 || window_size.y <= 0) return std::nullopt;
    const glm::mat4 inv = glm::inverse(camera.projection * camera.view);
    const float x = 2.0f * point.x / float(window_size.x) - 1.0f, y = 1.0f - 2.0f * point.y / float(window_size.y);
    glm::vec4 a = inv * glm::vec4(x, y, -1.0f, 1.0f), b = inv * glm::vec4(x, y, 1.0f, 1.0f);
    if (a.w == 0.0f || b.w == 0.0f) return std::nullopt;
    Ray r;
    r.origin = glm::vec3(a) / a.w;
    r.direction = glm::normalize(glm::vec3(b) / b.w - r.origin);
    if (!std::isfinite(r.direction.x)) return std::nullopt;
    return r;
}

std::optional<glm::vec2> to_window(const CameraSetup& camera, glm::ivec2 window_size, glm::vec3 p) {
    glm::vec4 c = camera.projection * camera.view * glm::vec4(p, 1.0f);
    if (!(c.w > 1e-6f)) return std::nullopt;
    return glm::vec2((c.x / c.w * 0.5f + 0.5f) * float(window_size.x), (0.5f - c.y / c.w * 0.5f) * float(window_size.y));
}

std::optional<PickHit> pick_at(const Scene& scene, const std::vector<NodeInstance>& instances, const CameraSetup& camera,
                               glm::ivec2 window_size, glm::vec2 point) {
    std::optional<Ray> r = window_ray(camera, window_size, point);
    if (!r) return std::nullopt;
    return pick(scene, instances, r->origin, r->direction);
}

glm::vec3 handle_centre(const Bounds& bounds) { return bounds.empty ? glm::vec3(0.0f) : bounds.center(); }

float handle_radius(const Bounds& bounds) { return bounds.empty ? 1.0f : std::max(bounds.radius() * 1.25f, 1e-3f); }

glm::vec3 light_handle(const LightInstance& light, const Bounds& bounds) {
    if (light.type != Light::Type::Directional) return light.position;
    return handle_centre(bounds) - light.direction * handle_radius(bounds);
}

int nearest_handle(const std::vector<LightInstance>& lights, const Bounds& bounds, const CameraSetup& camera,
                   glm::ivec2 window_size, glm::vec2 mouse, float max_points) {
    int nearest = -1;
    float best = max_points;
    for (int i = 0; i < int(lights.size()); ++i)
        if (auto s = to_window(camera, window_size, light_handle(lights[std::size_t(i)], bounds));
            s && glm::distance(*s, mouse) < best)
            best = glm::distance(*s, mouse), nearest = i;
    return nearest;
}

void drag_light(LightInstance& light, const Ray& ray, const Bounds& bounds, const CameraSetup& camera) {
    const glm::vec3 o = ray.origin, d = ray.direction;
    if (light.type == Light::Type::Directional) {
        const glm::vec3 c = handle_centre(bounds);
        const float r = handle_radius(bounds);
        // The point of the ray nearest the centre, pushed out to the sphere.
        const float t = glm::dot(c - o, d);
        glm::vec3 p = o + d * t;
        const float h2 = r * r - glm::dot(p - c, p - c);
        if (h2 > 0.0f) p = o + d * (t - std::sqrt(h2));  // the near side
        if (glm::length(p - c) > 1e-6f) light.direction = -glm::normalize(p - c);
    } else {
        const glm::vec3 n = glm::normalize(camera.eye - camera.target);
        const float den = glm::dot(d, n);
        if (std::fabs(den) > 1e-6f) {
            const float t = glm::dot(light.position - o, n) / den;
            if (t > 0.0f) light.position = o + d * t;
        }
    }
}

void orbit_lights(std::vector<LightInstance>& lights, const Bounds& bounds, float degrees) {
    const float a = glm::radians(degrees);
    const glm::mat3 r(glm::vec3(std::cos(a), 0.0f, -std::sin(a)), glm::vec3(0.0f, 1.0f, 0.0f),
                      glm::vec3(std::sin(a), 0.0f, std::cos(a)));
    const glm::vec3 c = handle_centre(bounds);
    for (LightInstance& l : lights) {
        l.direction = glm::normalize(r * l.direction);
        l.position = c + r * (l.position - c);
    }
}

float spin_degrees(double seconds) { return float(std::min(seconds, 0.25) * 30.0); }

}  // namespace fresnel::viewer
