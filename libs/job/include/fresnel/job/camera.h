#pragma once
// Camera conventions. The orbit camera is defined exactly as the Khronos
// reference tool's (../shared/tools/khronos-ref), so images line up:
//   target = centre of the scene bounds, R = half the bounds' diagonal,
//   eye = target + D (cos p sin y, sin p, cos p cos y), up = +Y,
//   D = K R, K default 1/sin(a), a = min(vfov/2, atan(tan(vfov/2) W/H)),
//   far = D + 2R, near = max(D - 2R, far/1000).
// A given target (a viewer's pan) replaces the centre; R and the rest stay.
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <optional>

#include "fresnel/scene/scene.h"

namespace fresnel {

struct CameraSetup {
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f};
    glm::vec3 eye{0.0f};
    glm::vec3 target{0.0f};
    float znear = 0.1f, zfar = 100.0f;
    float yfov_deg = 45.0f;
    bool orthographic = false;
};

struct OrbitParams {
    float yaw_deg = 0.0f;
    float pitch_deg = 0.0f;
    std::optional<float> distance_k;  // D = K * R
    float yfov_deg = 45.0f;
    std::optional<glm::vec3> target;  // nullopt = the bounds' centre
};

CameraSetup orbit_camera(const Bounds& bounds, const OrbitParams& params, int width, int height);

// A perspective camera at `eye` looking at `target` (`up` roughly up), vertical FOV
// `yfov_deg`; near and far from the bounds as the orbit camera's, with D = |eye - centre|.
CameraSetup look_at_camera(const Bounds& bounds, const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up,
                           float yfov_deg, int width, int height);

// The file's camera `index` (Scene::cameras) as placed by the first node of the flattened
// scene that uses it (scale removed; the image's aspect replaces the camera's aspectRatio);
// nullopt when no node of the scene uses it.
std::optional<CameraSetup> scene_camera(const Scene& scene, const std::vector<NodeInstance>& instances, int index,
                                        int width, int height);

}  // namespace fresnel
