#pragma once
// What the area light and screen-space occlusion GPU suites share: the point of the floor y = 0
// that a pixel's centre sees (the image's rows run top down), for their per-pixel C++ references.
#include <optional>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>

#include "fresnel/job/camera.h"

namespace fresnel::test {

// nullopt when the pixel looks away from the floor.
inline std::optional<glm::vec3> floor_point(const CameraSetup& camera, int x, int y, int width, int height) {
    const glm::mat4 inv_vp = glm::inverse(camera.projection * camera.view);
    const glm::vec2 ndc((float(x) + 0.5f) / float(width) * 2.0f - 1.0f, 1.0f - (float(y) + 0.5f) / float(height) * 2.0f);
    const glm::vec4 b = inv_vp * glm::vec4(ndc, 0.0f, 1.0f);
    const glm::vec3 d = glm::normalize(glm::vec3(b) / b.w - camera.eye);
    const float t = -camera.eye.y / d.y;
    if (!(t > 0.0f)) return std::nullopt;
    return camera.eye + t * d;
}

}  // namespace fresnel::test
