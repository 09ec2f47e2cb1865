#include "fresnel/scene/merge.h"

#include <algorithm>
#include <iterator>

#include "fresnel/core/error.h"

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
        for (TextureSlot* slot : {&m.base_color, &m.metallic_roughness, &m.normal, &m.occlusion, &m.emissive})
            offset(*slot, textures);
        if (m.specular) {
            offset(m.specular->specular_texture, textures);
            offset(m.specular->specular_color_texture, textures);
        }
        if (m.clearcoat) {
            offset(m.clearcoat->clearcoat_texture, textures);
            offset(m.clearcoat->clearcoat_roughness_texture, textures);
            offset(m.clearcoat->clearcoat_normal_texture, textures);
        }
        if (m.specular_glossiness) {
            offset(m.specular_glossiness->diffuse_texture, textures);
            offset(m.specular_glossiness->specular_glossiness_texture, textures);
        }
        if (m.sheen) {
            offset(m.sheen->sheen_color_texture, textures);
            offset(m.sheen->sheen_roughness_texture, textures);
        }
        if (m.transmission) offset(m.transmission->transmission_texture, textures);
        if (m.volume) offset(m.volume->thickness_texture, textures);
        if (m.iridescence) {
            offset(m.iridescence->iridescence_texture, textures);
            offset(m.iridescence->iridescence_thickness_texture, textures);
        }
        if (m.anisotropy) offset(m.anisotropy->anisotropy_texture, textures);
        if (m.diffuse_transmission) {
            offset(m.diffuse_transmission->diffuse_transmission_texture, textures);
            offset(m.diffuse_transmission->diffuse_transmission_color_texture, textures);
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

}  // namespace fresnel
