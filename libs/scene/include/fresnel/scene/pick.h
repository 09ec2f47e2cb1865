#pragma once
// Picking: the first triangle a ray meets in the flattened scene (the viewer's click
// selection). Brute force over the triangles of the primitives whose world box the ray
// crosses; hidden nodes (NodeInstance::visible) and primitives that are not triangles are
// skipped. Both faces of a triangle count (a single-sided material still shows its front to
// the camera, and the back is where a click through the surface would land).
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "fresnel/scene/scene.h"

namespace fresnel {

struct PickHit {
    int instance = -1;   // index into the instances given
    int node = -1, mesh = -1, primitive = -1;
    int triangle = -1;   // index of the triangle within the primitive
    float distance = 0;  // along the ray, in world units (the direction is normalised first)
    glm::vec3 point{0.0f};  // world space
};

// `origin`, `direction`: the ray in world space (direction need not be unit length; zero:
// no hit). Returns the nearest hit at distance > 0.
std::optional<PickHit> pick(const Scene& scene, const std::vector<NodeInstance>& instances, glm::vec3 origin,
                            glm::vec3 direction);

// The world-space box of one primitive of an instance (its POSITION min/max box's 8
// corners through the node's world matrix), for highlighting a pick.
Bounds primitive_world_bounds(const Scene& scene, const NodeInstance& instance, int primitive);

}  // namespace fresnel
