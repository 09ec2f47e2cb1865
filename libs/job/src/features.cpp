#include "fresnel/job/features.h"

#include <algorithm>

#include "fresnel/material/properties.h"
#include "fresnel/scene/pose.h"

namespace fresnel {
namespace mp = material_properties;

const std::vector<std::string>& feature_names() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> n = {"skinning", "morphing", "occlusion"};
        for (const mp::Block& b : mp::blocks()) n.emplace_back(b.name);
        return n;
    }();
    return names;
}

std::string feature_name(std::string_view name) {
    for (const std::string& n : feature_names())
        if (n == name || (n.starts_with("KHR_materials_") && n.substr(14) == name)) return n;
    return {};
}

std::vector<std::string> scene_features(const Scene& scene) {
    bool skins = false, morphs = false, occlusion = false;
    for (const Node& n : scene.nodes) skins = skins || n.skin >= 0;
    for (const Mesh& m : scene.meshes)
        for (const Primitive& p : m.primitives) morphs = morphs || !p.targets.empty();
    for (const Material& m : scene.materials) occlusion = occlusion || m.occlusion.valid();
    std::vector<std::string> out;
    if (skins) out.push_back("skinning");
    if (morphs) out.push_back("morphing");
    if (occlusion) out.push_back("occlusion");
    for (const mp::Block& b : mp::blocks()) {
        const std::string name(b.name);
        bool used = std::find(scene.extensions_used.begin(), scene.extensions_used.end(), name) != scene.extensions_used.end();
        for (const Material& m : scene.materials) used = used || b.present(m);
        if (used) out.push_back(name);
    }
    return out;
}

void disable_features(Scene& scene, const std::vector<std::string>& features) {
    auto off = [&](std::string_view f) { return std::find(features.begin(), features.end(), f) != features.end(); };
    if (off("skinning"))
        for (Node& n : scene.nodes) n.skin = -1;
    if (off("morphing")) {
        for (Mesh& m : scene.meshes) {
            m.weights.clear();
            for (Primitive& p : m.primitives) {
                apply_morph_weights(p, {});  // back to the base shape (the loader applied the mesh's weights)
                p.targets.clear();
                p.applied_weights.clear();
            }
        }
        for (Node& n : scene.nodes) n.weights.clear();
    }
    for (Material& m : scene.materials) {
        if (off("occlusion")) m.occlusion = TextureSlot{};
        for (const mp::Block& b : mp::blocks())
            if (off(b.name) && b.present(m)) b.remove(m);
    }
}

}  // namespace fresnel
