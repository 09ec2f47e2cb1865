// Jobs with several models (Job::Source::models): each model is loaded exactly as a
// one-model job would load it (load_scene, so every format load_scene reads), its
// material overrides applied, and moved under a root node with its transform.
#include "fresnel/job/job.h"
#include "fresnel/scene/merge.h"

#include <algorithm>

namespace fresnel {

namespace {

void apply_override(Material& m, const Job::Source::MaterialOverride& o) {
    for (const auto& [name, value] : o.values)
        if (const material_properties::Property* p = material_properties::find(name)) p->put(m, value);
}

}  // namespace

Scene load_models(const Job& job, Diagnostics& diag, LoadKeep keep) {
    Scene merged = make_composite_scene(job.source.models.front().path);
    // A model named again (the same file, scene and material overrides) is loaded once and
    // placed again (append_instance): its data is held and uploaded once.
    std::vector<std::pair<const Job::Source::Model*, int>> placed;  // model, its part
    for (std::size_t i = 0; i < job.source.models.size(); ++i) {
        const Job::Source::Model& m = job.source.models[i];
        if (!m.visible) continue;
        const auto same = std::find_if(placed.begin(), placed.end(), [&](const auto& p) {
            return p.first->path == m.path && p.first->scene == m.scene && p.first->materials == m.materials;
        });
        if (same != placed.end()) {
            append_instance(merged, same->second, m.transform);
            continue;
        }
        Job one;
        one.source.model = m.path;
        one.source.scene = m.scene;
        one.source.allow_external_files = job.source.allow_external_files;
        one.source.pose_skins = job.source.pose_skins;
        one.source.sg_textures = job.source.sg_textures;
        one.source.max_memory_mib = job.source.max_memory_mib;
        one.source.animation = job.source.animation;
        one.source.disabled = job.source.disabled;
        Scene scene = load_scene(one, diag, keep);
        const std::string name = m.path.empty() ? std::string("demo") : m.path;
        for (const auto& o : m.materials) {
            if (o.index) {
                if (*o.index < 0 || *o.index >= int(scene.materials.size()))
                    throw Error(name, "material " + std::to_string(*o.index),
                                "the model has " + std::to_string(scene.materials.size()) + " materials");
                apply_override(scene.materials[std::size_t(*o.index)], o);
            } else {
                bool found = false;
                for (Material& mat : scene.materials)
                    if (!o.name || mat.name == *o.name) {
                        apply_override(mat, o);
                        found = true;
                    }
                if (o.name && !found) diag.warn(name, "material '" + *o.name + "'", "no material of this name; override ignored");
            }
        }
        placed.emplace_back(&m, append_model(merged, std::move(scene), m.transform, m.scene));
    }
    return merged;
}

}  // namespace fresnel
