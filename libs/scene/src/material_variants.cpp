// KHR_materials_variants: choosing a variant after loading (the loader keeps the mappings).
#include <string>

#include "fresnel/core/error.h"
#include "fresnel/scene/mesh_ops.h"
#include "fresnel/scene/scene.h"

namespace fresnel {

int find_material_variant(const Scene& scene, const std::string& name) {
    for (std::size_t i = 0; i < scene.material_variants.size(); ++i)
        if (scene.material_variants[i] == name) return int(i);
    std::string known;
    for (const auto& v : scene.material_variants) known += (known.empty() ? "" : ", ") + ("'" + v + "'");
    throw Error(scene.source, "--variant " + name,
                scene.material_variants.empty()
                    ? std::string("the file has no KHR_materials_variants")
                    : "unknown material variant; the file has " + known);
}

void apply_material_variant(Scene& scene, int variant) {
    if (variant < 0 || std::size_t(variant) >= scene.material_variants.size()) return;
    for (auto& mesh : scene.meshes)
        for (auto& p : mesh.primitives) {
            if (std::size_t(variant) >= p.variant_materials.size()) continue;
            int m = p.variant_materials[std::size_t(variant)];
            if (m < 0 || std::size_t(m) >= scene.materials.size()) continue;
            p.material = m;
            const Material& mat = scene.materials[std::size_t(m)];
            const TextureSlot* map = tangent_source(mat);
            if (map && p.tangents.empty() && p.topology == Topology::Triangles) generate_tangents(p, map->tex_coord);
        }
}

}  // namespace fresnel
