#pragma once
// Posing a scene: its animations applied at a time t, then morph targets and skins evaluated
// on the CPU (the reference any GPU path is checked against).
//
// The rest pose (no animation) is what the loader produces and stays untouched: these
// functions are only used when a time is asked for.
#include <span>
#include <vector>

#include <glm/mat4x4.hpp>

#include "fresnel/scene/animation.h"
#include "fresnel/scene/scene.h"

namespace fresnel {

// Applies animation `index` of the scene (-1: all of them, in order) at time t (seconds;
// each sampler clamps to its first and last keyframes): the targeted nodes' translation,
// rotation, scale (and so `local`) and morph weights (Node::weights, one per target of the
// node's mesh: a sampler with fewer values leaves the others at the mesh's weights). Throws
// fresnel::Error (file: scene.source) when `index` is out of range.
void animate(Scene& scene, int index, float t);

// The local matrix of a node's TRS: T * R * S.
glm::mat4 trs_matrix(const glm::vec3& translation, const glm::quat& rotation, const glm::vec3& scale);

// Moves a primitive from the morph weights it holds (Primitive::applied_weights) to
// `weights` (missing entries count as 0): positions, normals and tangents get
// sum_k (weights[k] - applied[k]) * target_k; normals and tangents are renormalised and
// generated flat normals are generated again. Sets applied_weights to `weights`.
void apply_morph_weights(Primitive& p, std::span<const float> weights);

// Poses every mesh of the scene on the CPU at its nodes' current state: morph targets at the
// node's weights (Node::weights, else the mesh's) where they differ from the loaded ones, then
// skins by joint matrices (world[joint] * inverse bind). Each node whose mesh changes gets a
// copy of its own; skinned copies are in world space (Node::world_space_mesh). Nodes already
// posed in world space (GltfLoadOptions::pose_skins) are left alone.
void pose_meshes(Scene& scene);

// `rest` with animation `index` (-1: all) at time t and its meshes posed (animate, then
// pose_meshes).
Scene animated_scene(const Scene& rest, int index, float t);

}  // namespace fresnel
