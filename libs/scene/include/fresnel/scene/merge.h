#pragma once
// Several models in one scene: each model's scene graph goes under a root node of its own
// that carries the model's transform, so a composition of models renders, frames (camera
// convention) and lights as one scene. Used by jobs with several models (scene files).
#include <glm/mat4x4.hpp>

#include "fresnel/scene/scene.h"

namespace fresnel {

// An empty scene with one (empty) scene graph, ready for append_model.
Scene make_composite_scene(std::string source);

// Moves scene `scene_index` of `model` (-1: its default scene) into scene 0 of `dst`, under a
// new root node whose local matrix is `transform`. Every index (meshes, materials, textures,
// images, cameras, lights, nodes) is offset; `dst.parts` gains the model's entry. Returns its
// index in `dst.parts`. Throws fresnel::Error when `scene_index` does not exist.
int append_model(Scene& dst, Scene model, const glm::mat4& transform, int scene_index = -1);

// Places part `part` of `dst` again, at `transform`: its nodes are copied under a new root
// node and refer to the same meshes, materials, textures, images, cameras and lights, so a
// model placed N times costs its nodes N times and its data once (and the renderer uploads
// its meshes and textures once). The new part's entry names the same materials and cameras.
// Returns its index in `dst.parts`.
int append_instance(Scene& dst, int part, const glm::mat4& transform);

}  // namespace fresnel
