#pragma once
// Parts of a file a job can turn off (Job::Source::disabled; the setting `disable`, --disable),
// as the Khronos Sample Viewer's switches: skinning (skinned meshes stay in their bind pose),
// morphing (morph targets dropped), occlusion (occlusion textures unread), and each material
// extension of the material property registry (fresnel/material/properties.h: its block removed
// from every material, as if the file had not used it). Applied when the scene loads
// (load_scene), so every front end — render, trace, batch, the viewer, the page, Python — shows
// the same picture for the same list. Image-based light, punctual lights and shadows are
// settings of their own (environment, sceneLights, render.shadows).
#include <string>
#include <string_view>
#include <vector>

#include "fresnel/scene/scene.h"

namespace fresnel {

// Every feature name, in order: skinning, morphing, occlusion, then the material extensions.
const std::vector<std::string>& feature_names();

// `name` as a feature name (an extension also by its short name: clearcoat is
// KHR_materials_clearcoat); "" when it names none.
std::string feature_name(std::string_view name);

// The features `scene` holds, in feature_names() order (what a viewer's switches offer): skins,
// morph targets, occlusion textures, and the material extensions the file uses (extensionsUsed)
// or its materials hold.
std::vector<std::string> scene_features(const Scene& scene);

// Turns `features` (feature names) off in `scene`.
void disable_features(Scene& scene, const std::vector<std::string>& features);

}  // namespace fresnel
