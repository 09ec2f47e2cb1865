#include "fresnel/scene/scene.h"

#include <algorithm>
#include <span>

#include <glm/geometric.hpp>

#include "fresnel/core/error.h"
#include "fresnel/scene/mesh_ops.h"
#include "webp_decoder.h"

namespace fresnel {

bool SceneImage::release_pixels() {
    if (!valid() || !encoded || encoded->empty()) return false;
    std::vector<std::uint8_t>().swap(pixels.pixels);
    return true;
}

Image8 decode_again(const SceneImage& image) {
    if (!image.encoded || image.encoded->empty())
        throw Error(image.name, "", "the decoded image was released and its encoded bytes were not kept");
    const std::span<const std::uint8_t> bytes(*image.encoded);
    // The bytes decoded within the load's limits once; these limits admit their own size.
    ImageLimits limits;
    limits.max_dimension = std::max({limits.max_dimension, image.pixels.width, image.pixels.height});
    limits.max_decoded_bytes = std::max(limits.max_decoded_bytes, std::size_t(image.pixels.width) * std::size_t(image.pixels.height) * 4);
    Image8 out = gltf::is_webp(bytes) ? gltf::decode_webp(bytes, image.name, limits) : decode_image8(bytes, image.name, limits);
    if (out.width != image.pixels.width || out.height != image.pixels.height)
        throw Error(image.name, "", "decoded again to " + std::to_string(out.width) + "x" + std::to_string(out.height) +
                                        ", not the " + std::to_string(image.pixels.width) + "x" +
                                        std::to_string(image.pixels.height) + " first decoded");
    return out;
}

std::size_t Primitive::triangle_count() const {
    if (topology != Topology::Triangles) return 0;
    return (indices.empty() ? positions.size() : indices.size()) / 3;
}

std::vector<NodeInstance> flatten(const Scene& scene, int index) {
    std::vector<NodeInstance> out;
    if (index < 0) index = scene.default_scene;
    if (index < 0 || std::size_t(index) >= scene.scenes.size()) return out;
    // The loader guarantees a forest (no cycles, one parent each), so this terminates.
    const std::vector<glm::mat4> world = world_matrices(scene.nodes);
    std::vector<std::pair<int, bool>> stack;  // node, whether its ancestors are visible
    for (auto it = scene.scenes[std::size_t(index)].rbegin(); it != scene.scenes[std::size_t(index)].rend(); ++it)
        stack.emplace_back(*it, true);
    while (!stack.empty()) {
        auto [n, parents_visible] = stack.back();
        stack.pop_back();
        const Node& node = scene.nodes[std::size_t(n)];
        const bool visible = parents_visible && node.visible;
        out.push_back({n, world[std::size_t(n)], visible});
        for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) stack.emplace_back(*it, visible);
    }
    return out;
}

float Bounds::radius() const { return glm::length(max - min) * 0.5f; }

void Bounds::extend(const glm::mat4& transform, const glm::vec3& box_min, const glm::vec3& box_max) {
    for (int c = 0; c < 8; ++c) {
        const glm::vec3 corner((c & 1) ? box_max.x : box_min.x, (c & 2) ? box_max.y : box_min.y,
                               (c & 4) ? box_max.z : box_min.z);
        const glm::vec3 w = glm::vec3(transform * glm::vec4(corner, 1.0f));
        if (empty) {
            min = max = w;
            empty = false;
        } else {
            min = glm::min(min, w);
            max = glm::max(max, w);
        }
    }
}

Bounds scene_bounds(const Scene& scene, const std::vector<NodeInstance>& instances) {
    Bounds b;
    for (const auto& inst : instances) {
        const Node& node = scene.nodes[std::size_t(inst.node)];
        if (node.mesh < 0) continue;
        for (const auto& prim : scene.meshes[std::size_t(node.mesh)].primitives)
            b.extend(inst.world, prim.bounds_min, prim.bounds_max);
    }
    return b;
}

Bounds framing_bounds(const Scene& scene, int index, const std::vector<NodeInstance>& instances) {
    const std::size_t k = std::size_t(index + 1);
    if (index >= -1 && k < scene.framing.size()) return scene.framing[k];
    return scene_bounds(scene, instances);
}

void keep_framing(Scene& scene) {
    std::vector<Bounds> framing;
    framing.reserve(scene.scenes.size() + 1);
    for (int i = -1; i < int(scene.scenes.size()); ++i) framing.push_back(scene_bounds(scene, flatten(scene, i)));
    scene.framing = std::move(framing);
}

}  // namespace fresnel
