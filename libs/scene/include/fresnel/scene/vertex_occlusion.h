#pragma once
// Visibility of the environment baked per vertex (`--ao baked`): what the tracer's rays
// found at each vertex of each placed primitive, which the rasteriser interpolates and
// multiplies image-based light by (pbr.frag, with the material's occlusion texture, min of
// the two) and whose bent normal it looks the diffuse irradiance up along.
//
// Made by fresnel::trace::bake_vertex_occlusion from a scene in one pose (a static scene: the
// nodes' world matrices as flatten() gives them), read by Renderer::set_vertex_occlusion.
#include <cstddef>
#include <vector>

#include <glm/vec4.hpp>

namespace fresnel {

struct VertexOcclusion {
    // By node index, then by primitive of the node's mesh, one value per vertex: xyz the bent
    // normal in world space (the mean unoccluded direction, unit length; zero where every ray
    // was blocked), w the cosine-weighted visibility in [0, 1] (1: nothing in the way). An
    // empty list: not baked (deformable primitives, points and lines, nodes not drawn).
    std::vector<std::vector<std::vector<glm::vec4>>> nodes;
    int rays_per_vertex = 0;
    std::size_t vertices = 0;  // vertices baked, over every placement
    double bake_ms = 0;        // the bake's time (with its trace scene), or the time to read it from a cache
    bool from_cache = false;   // read from the cache (trace::load_or_bake_vertex_occlusion)

    // The values of node `node`'s primitive `primitive`, or null when none were baked.
    const std::vector<glm::vec4>* find(int node, std::size_t primitive) const {
        if (node < 0 || std::size_t(node) >= nodes.size()) return nullptr;
        const auto& prims = nodes[std::size_t(node)];
        if (primitive >= prims.size() || prims[primitive].empty()) return nullptr;
        return &prims[primitive];
    }
};

}  // namespace fresnel
