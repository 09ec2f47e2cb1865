#include "fresnel/job/camera.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace fresnel {

CameraSetup orbit_camera(const Bounds& bounds, const OrbitParams& p, int width, int height) {
    CameraSetup c;
    const float deg = 3.14159265358979f / 180.0f;
    float aspect = float(width) / float(std::max(height, 1));
    float vfov = p.yfov_deg * deg;
    float R = bounds.empty ? 1.0f : std::max(bounds.radius(), 1e-6f);
    glm::vec3 target = p.target ? *p.target : bounds.empty ? glm::vec3(0.0f) : bounds.center();
    float a = std::min(vfov * 0.5f, std::atan(std::tan(vfov * 0.5f) * aspect));
    float k = p.distance_k.value_or(1.0f / std::sin(a));
    float D = k * R;
    float y = p.yaw_deg * deg, pt = p.pitch_deg * deg;
    glm::vec3 dir(std::cos(pt) * std::sin(y), std::sin(pt), std::cos(pt) * std::cos(y));
    c.eye = target + D * dir;
    c.target = target;
    // Orientation Ry(yaw) * Rx(-pitch): valid also at |pitch| = 90 where lookAt(up=+Y) degenerates.
    glm::vec3 right(std::cos(y), 0.0f, -std::sin(y));
    glm::vec3 up(-std::sin(pt) * std::sin(y), std::cos(pt), -std::sin(pt) * std::cos(y));
    glm::vec3 back = dir;  // camera +Z points away from the target
    glm::mat4 cam_to_world(glm::vec4(right, 0), glm::vec4(up, 0), glm::vec4(back, 0), glm::vec4(c.eye, 1));
    c.view = glm::inverse(cam_to_world);
    c.zfar = D + 2.0f * R;
    c.znear = std::max(D - 2.0f * R, c.zfar / 1000.0f);
    c.yfov_deg = p.yfov_deg;
    c.projection = glm::perspective(vfov, aspect, c.znear, c.zfar);
    return c;
}

CameraSetup look_at_camera(const Bounds& bounds, const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up,
                           float yfov_deg, int width, int height) {
    CameraSetup c;
    const float deg = 3.14159265358979f / 180.0f;
    float aspect = float(width) / float(std::max(height, 1));
    float R = bounds.empty ? 1.0f : std::max(bounds.radius(), 1e-6f);
    glm::vec3 centre = bounds.empty ? glm::vec3(0.0f) : bounds.center();
    float D = glm::length(eye - centre);
    c.eye = eye;
    c.target = target;
    glm::vec3 forward = target - eye;
    glm::vec3 u = up;
    if (glm::length(forward) < 1e-12f) forward = glm::vec3(0, 0, -1);
    if (glm::length(glm::cross(forward, u)) < 1e-6f * glm::length(forward) * std::max(glm::length(u), 1e-30f))
        u = std::fabs(forward.y) > std::fabs(forward.z) ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    c.view = glm::lookAt(eye, eye + forward, u);
    c.zfar = std::max(D + 2.0f * R, 1e-4f);
    c.znear = std::max(D - 2.0f * R, c.zfar / 1000.0f);
    c.yfov_deg = yfov_deg;
    c.projection = glm::perspective(yfov_deg * deg, aspect, c.znear, c.zfar);
    return c;
}

std::optional<CameraSetup> scene_camera(const Scene& scene, const std::vector<NodeInstance>& instances, int index,
                                        int width, int height) {
    for (const auto& inst : instances) {
        const Node& node = scene.nodes[std::size_t(inst.node)];
        if (node.camera != index) continue;
        const Camera& cam = scene.cameras[std::size_t(node.camera)];
        CameraSetup c;
        // The camera looks down its local -Z; remove scale from the node's world matrix.
        glm::mat4 w = inst.world;
        for (int i = 0; i < 3; ++i) {
            float len = glm::length(glm::vec3(w[i]));
            if (len > 0) w[i] /= len;
        }
        c.view = glm::inverse(w);
        c.eye = glm::vec3(w[3]);
        c.target = c.eye - glm::vec3(w[2]);
        float aspect = float(width) / float(std::max(height, 1));
        c.znear = cam.znear;
        if (cam.type == Camera::Type::Perspective) {
            c.yfov_deg = cam.yfov * 180.0f / 3.14159265f;
            if (cam.zfar) {
                c.zfar = *cam.zfar;
                c.projection = glm::perspective(cam.yfov, aspect, cam.znear, *cam.zfar);
            } else {
                c.zfar = cam.znear * 1e6f;
                c.projection = glm::infinitePerspective(cam.yfov, aspect, cam.znear);
            }
        } else {
            c.orthographic = true;
            c.zfar = cam.zfar.value_or(100.0f);
            // Keep ymag and fit x to the image's aspect so the picture is not stretched.
            float ymag = std::fabs(cam.ymag), xmag = ymag * aspect;
            c.projection = glm::ortho(-xmag, xmag, -ymag, ymag, cam.znear, c.zfar);
        }
        return c;
    }
    return std::nullopt;
}

}  // namespace fresnel
