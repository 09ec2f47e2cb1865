#include "fresnel/scene/merge.h"

#include <algorithm>
#include <iterator>

#include "fresnel/core/error.h"
#include "fresnel/material/properties.h"

namespace fresnel {

namespace {
void offset(int& index, std::size_t by) {
    if (index >= 0) index += int(by);
}
void offset(TextureSlot& slot, std::size_t by) {
    if (slot.texture >= 0) slot.texture += int(by);
}
}  // namespace

Scene make_composite_scene(std::string source) {
    Scene s;
    s.source = std::move(source);
    s.scenes.emplace_back();
    return s;
}

int append_model(Scene& dst, Scene model, const glm::mat4& transform, int scene_index) {
    if (dst.scenes.empty()) dst.scenes.emplace_back();
    int index = scene_index < 0 ? model.default_scene : scene_index;
    std::vector<int> roots;
    if (!model.scenes.empty() || index > 0) {
        if (index < 0 || index >= int(model.scenes.size()))
            throw Error(model.source, "scene " + std::to_string(index),
                        "the file has " + std::to_string(model.scenes.size()) + " scenes");
        roots = model.scenes[std::size_t(index)];
    }
    const std::size_t nodes = dst.nodes.size(), meshes = dst.meshes.size(), materials = dst.materials.size(),
                      textures = dst.textures.size(), images = dst.images.size(), cameras = dst.cameras.size(),
                      lights = dst.lights.size();
    for (Node& n : model.nodes) {
        offset(n.mesh, meshes);
        offset(n.camera, cameras);
        offset(n.light, lights);
        n.skin = -1;  // skins are applied by the loader (world_space_mesh); no table to offset
        for (int& c : n.children) offset(c, nodes);
    }
    for (Mesh& m : model.meshes)
        for (Primitive& p : m.primitives) offset(p.material, materials);
    for (Material& m : model.materials) {
        // Every texture reference of the material property registry (of the blocks the
        // material has), and the specular-glossiness block's, which converts at load.
        for (const material_properties::Texture& t : material_properties::textures())
            if (t.get(m)) offset(*t.slot(m), textures);
        if (m.specular_glossiness) {
            offset(m.specular_glossiness->diffuse_texture, textures);
            offset(m.specular_glossiness->specular_glossiness_texture, textures);
        }
    }
    for (Texture& t : model.textures) offset(t.image, images);

    Scene::Part part;
    part.source = model.source;
    part.first_camera = int(cameras);
    part.camera_count = int(model.cameras.size());
    part.first_material = int(materials);
    part.material_count = int(model.materials.size());

    auto move_into = [](auto& to, auto& from) {
        to.insert(to.end(), std::make_move_iterator(from.begin()), std::make_move_iterator(from.end()));
    };
    move_into(dst.nodes, model.nodes);
    move_into(dst.meshes, model.meshes);
    move_into(dst.materials, model.materials);
    move_into(dst.textures, model.textures);
    move_into(dst.images, model.images);
    move_into(dst.cameras, model.cameras);
    move_into(dst.lights, model.lights);
    for (const auto& e : model.extensions_used)
        if (std::find(dst.extensions_used.begin(), dst.extensions_used.end(), e) == dst.extensions_used.end())
            dst.extensions_used.push_back(e);

    Node root;
    root.name = "model " + std::to_string(dst.parts.size());
    root.local = transform;
    for (int r : roots) root.children.push_back(r + int(nodes));
    part.root = int(dst.nodes.size());
    dst.nodes.push_back(std::move(root));
    dst.scenes[0].push_back(part.root);
    dst.parts.push_back(std::move(part));
    return int(dst.parts.size()) - 1;
}

int append_instance(Scene& dst, int part, const glm::mat4& transform) {
    if (part < 0 || part >= int(dst.parts.size())) throw Error(dst.source, "model " + std::to_string(part), "no such model");
    Scene::Part copy = dst.parts[std::size_t(part)];
    // The subtree under the part's root, copied depth first (iteratively: a deep graph must not
    // exhaust the stack); children renumbered to the copies.
    std::vector<int> old_of;  // copy k is a copy of node old_of[k]
    std::vector<std::pair<int, int>> stack{{copy.root, -1}};  // node, its copy's parent copy
    const std::size_t base = dst.nodes.size();
    std::vector<Node> added;
    while (!stack.empty()) {
        auto [node, parent] = stack.back();
        stack.pop_back();
        if (node < 0 || node >= int(dst.nodes.size())) continue;
        const int k = int(added.size());
        added.push_back(dst.nodes[std::size_t(node)]);
        added.back().children.clear();
        if (parent >= 0) added[std::size_t(parent)].children.push_back(int(base) + k);
        const auto& children = dst.nodes[std::size_t(node)].children;
        for (auto it = children.rbegin(); it != children.rend(); ++it) stack.emplace_back(*it, k);
    }
    if (added.empty()) throw Error(dst.source, "model " + std::to_string(part), "has no root node");
    added.front().local = transform;
    added.front().name = "model " + std::to_string(dst.parts.size());
    for (Node& n : added) dst.nodes.push_back(std::move(n));
    copy.root = int(base);
    dst.scenes[0].push_back(copy.root);
    dst.parts.push_back(std::move(copy));
    return int(dst.parts.size()) - 1;
}

}  // namespace fresnel
