#include "fresnel/scene/pick.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

namespace fresnel {

namespace {

// Slab test of a ray against an axis-aligned box: whether it enters the box before `t_max`.
bool ray_hits_box(glm::vec3 o, glm::vec3 inv_d, glm::vec3 lo, glm::vec3 hi, float t_max) {
    float t0 = 0.0f, t1 = t_max;
    for (int a = 0; a < 3; ++a) {
        float n = (lo[a] - o[a]) * inv_d[a], f = (hi[a] - o[a]) * inv_d[a];
        if (std::isnan(n) || std::isnan(f)) {  // parallel to the slab, starting on its plane
            if (o[a] < lo[a] || o[a] > hi[a]) return false;
            continue;
        }
        if (n > f) std::swap(n, f);
        t0 = std::max(t0, n);
        t1 = std::min(t1, f);
        if (t0 > t1) return false;
    }
    return true;
}

// Moller-Trumbore, both faces; the ray parameter or a negative number.
float ray_triangle(glm::vec3 o, glm::vec3 d, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const glm::vec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
    const float det = glm::dot(e1, p);
    if (!(std::fabs(det) > 1e-30f)) return -1.0f;
    const float inv = 1.0f / det;
    const glm::vec3 s = o - a;
    const float u = glm::dot(s, p) * inv;
    if (u < 0.0f || u > 1.0f) return -1.0f;
    const glm::vec3 q = glm::cross(s, e1);
    const float v = glm::dot(d, q) * inv;
    if (v < 0.0f || u + v > 1.0f) return -1.0f;
    return glm::dot(e2, q) * inv;
}

glm::mat4 draw_matrix(const Scene& scene, const NodeInstance& inst) {
    return scene.nodes[std::size_t(inst.node)].world_space_mesh ? glm::mat4(1.0f) : inst.world;
}

}  // namespace

std::optional<PickHit> pick(const Scene& scene, const std::vector<NodeInstance>& instances, glm::vec3 origin,
                            glm::vec3 direction) {
    const float len = glm::length(direction);
    if (!(len > 0.0f) || !std::isfinite(len)) return std::nullopt;
    const glm::vec3 dir = direction / len;
    std::optional<PickHit> best;
    float best_t = std::numeric_limits<float>::infinity();
    for (std::size_t i = 0; i < instances.size(); ++i) {
        const NodeInstance& inst = instances[i];
        if (!inst.visible || inst.node < 0 || std::size_t(inst.node) >= scene.nodes.size()) continue;
        const Node& node = scene.nodes[std::size_t(inst.node)];
        if (node.mesh < 0 || std::size_t(node.mesh) >= scene.meshes.size()) continue;
        const glm::mat4 world = draw_matrix(scene, inst);
        if (!(std::fabs(glm::determinant(world)) > 0.0f)) continue;  // a flattened node shows nothing
        // The ray in the node's space: hits there are points on the same line, so their
        // world distance is measured after transforming back.
        const glm::mat4 to_local = glm::inverse(world);
        const glm::vec3 o = glm::vec3(to_local * glm::vec4(origin, 1.0f));
        const glm::vec3 d = glm::vec3(to_local * glm::vec4(dir, 0.0f));
        const glm::vec3 inv_d = 1.0f / d;
        const auto& prims = scene.meshes[std::size_t(node.mesh)].primitives;
        for (std::size_t pi = 0; pi < prims.size(); ++pi) {
            const Primitive& p = prims[pi];
            if (p.topology != Topology::Triangles || p.positions.empty()) continue;
            glm::vec3 lo = p.bounds_min, hi = p.bounds_max;
            if (lo == hi && lo == glm::vec3(0.0f)) {  // no accessor box: the data's
                lo = hi = p.positions[0];
                for (const glm::vec3& v : p.positions) lo = glm::min(lo, v), hi = glm::max(hi, v);
            }
            if (!ray_hits_box(o, inv_d, lo, hi, std::numeric_limits<float>::infinity())) continue;
            const std::size_t count = p.indices.empty() ? p.positions.size() : p.indices.size();
            for (std::size_t t = 0; t + 2 < count; t += 3) {
                std::uint32_t a = p.indices.empty() ? std::uint32_t(t) : p.indices[t];
                std::uint32_t b = p.indices.empty() ? std::uint32_t(t + 1) : p.indices[t + 1];
                std::uint32_t c = p.indices.empty() ? std::uint32_t(t + 2) : p.indices[t + 2];
                if (a >= p.positions.size() || b >= p.positions.size() || c >= p.positions.size()) continue;
                float s = ray_triangle(o, d, p.positions[a], p.positions[b], p.positions[c]);
                if (!(s > 0.0f)) continue;
                const glm::vec3 w = glm::vec3(world * glm::vec4(o + s * d, 1.0f));
                const float dist = glm::dot(w - origin, dir);
                if (dist > 0.0f && dist < best_t) {
                    best_t = dist;
                    best = PickHit{int(i), inst.node, node.mesh, int(pi), int(t / 3), dist, w};
                }
            }
        }
    }
    return best;
}

Bounds primitive_world_bounds(const Scene& scene, const NodeInstance& instance, int primitive) {
    Bounds b;
    if (instance.node < 0 || std::size_t(instance.node) >= scene.nodes.size()) return b;
    const Node& node = scene.nodes[std::size_t(instance.node)];
    if (node.mesh < 0 || std::size_t(node.mesh) >= scene.meshes.size()) return b;
    const auto& prims = scene.meshes[std::size_t(node.mesh)].primitives;
    if (primitive < 0 || std::size_t(primitive) >= prims.size()) return b;
    const Primitive& p = prims[std::size_t(primitive)];
    const glm::mat4 world = draw_matrix(scene, instance);
    b.extend(world, p.bounds_min, p.bounds_max);
    return b;
}

}  // namespace fresnel
