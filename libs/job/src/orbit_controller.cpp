#include "fresnel/job/orbit_controller.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace fresnel {
namespace {
constexpr float kDeg = 3.14159265358979f / 180.0f;
float radius(const Bounds& b) { return b.empty ? 1.0f : std::max(b.radius(), 1e-6f); }
glm::vec3 target_of(const Job::Camera& c, const Bounds& b) {
    return c.target ? *c.target : b.empty ? glm::vec3(0.0f) : b.center();
}
}  // namespace

float fit_distance_k(float yfov_deg, int width, int height) {
    float vfov = yfov_deg * kDeg;
    float aspect = float(width) / float(std::max(height, 1));
    float a = std::min(vfov * 0.5f, std::atan(std::tan(vfov * 0.5f) * aspect));
    return 1.0f / std::sin(a);
}

float distance_k(const Job::Camera& camera, int width, int height) {
    return camera.distance_k.value_or(fit_distance_k(camera.yfov_deg, width, height));
}

Job::Camera orbit(Job::Camera c, float dx, float dy, float deg_per_pixel) {
    c.scene_camera.reset();
    c.yaw_deg = std::remainder(c.yaw_deg - dx * deg_per_pixel, 360.0f);
    c.pitch_deg = std::clamp(c.pitch_deg + dy * deg_per_pixel, -89.9f, 89.9f);
    return c;
}

Job::Camera pan(Job::Camera c, const OrbitViewport& v, float dx, float dy) {
    c.scene_camera.reset();
    float y = c.yaw_deg * kDeg, p = c.pitch_deg * kDeg;
    // The camera's right and up axes, as orbit_camera() builds them.
    glm::vec3 right(std::cos(y), 0.0f, -std::sin(y));
    glm::vec3 up(-std::sin(p) * std::sin(y), std::cos(p), -std::sin(p) * std::cos(y));
    float D = distance_k(c, v.width, v.height) * radius(v.bounds);
    float world_per_pixel = 2.0f * D * std::tan(c.yfov_deg * kDeg * 0.5f) / float(std::max(v.height, 1));
    c.target = target_of(c, v.bounds) + world_per_pixel * (-dx * right + dy * up);
    return c;
}

Job::Camera dolly(Job::Camera c, const OrbitViewport& v, float factor) {
    c.scene_camera.reset();
    c.distance_k = std::clamp(distance_k(c, v.width, v.height) * factor, 0.01f, 1e4f);
    return c;
}

float dolly_factor(float clicks) { return std::pow(0.9f, clicks); }

Job::Camera frame_all(Job::Camera c) {
    c.scene_camera.reset();
    c.target.reset();
    c.distance_k.reset();
    return c;
}

Job::Camera orbit_from_setup(const CameraSetup& s, const Bounds& b, float yfov_deg) {
    Job::Camera c;
    c.yfov_deg = yfov_deg;
    glm::vec3 forward = s.target - s.eye;
    float len = glm::length(forward);
    forward = len > 0 ? forward / len : glm::vec3(0, 0, -1);
    float R = radius(b);
    glm::vec3 centre = b.empty ? glm::vec3(0.0f) : b.center();
    float depth = std::max(glm::dot(centre - s.eye, forward), R / 100.0f);
    glm::vec3 target = s.eye + depth * forward;
    glm::vec3 back = -forward;  // eye = target + D * back
    c.yaw_deg = std::atan2(back.x, back.z) / kDeg;
    c.pitch_deg = std::clamp(std::asin(std::clamp(back.y, -1.0f, 1.0f)) / kDeg, -89.9f, 89.9f);
    c.distance_k = depth / R;
    c.target = target;
    return c;
}

}  // namespace fresnel
