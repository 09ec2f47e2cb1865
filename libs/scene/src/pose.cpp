#include "fresnel/scene/pose.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "fresnel/core/error.h"
#include "fresnel/scene/mesh_ops.h"

namespace fresnel {

namespace {

glm::vec3 normalised_or(const glm::vec3& v, const glm::vec3& fallback) {
    float len = glm::length(v);
    return len > 1e-20f && std::isfinite(len) ? v / len : fallback;
}

void animate_one(Scene& scene, const Animation& a, float t) {
    for (const auto& c : a.channels) {
        if (c.sampler < 0 || std::size_t(c.sampler) >= a.samplers.size()) continue;
        const AnimationSampler& s = a.samplers[std::size_t(c.sampler)];
        if (!s.consistent()) continue;
        if (c.path == AnimationPath::Pointer) {  // KHR_animation_pointer: values interpolated linearly
            write_animation_pointer(scene, c.pointer, sample(s, t));
            continue;
        }
        if (c.node < 0 || std::size_t(c.node) >= scene.nodes.size()) continue;
        Node& n = scene.nodes[std::size_t(c.node)];
        switch (c.path) {
            case AnimationPath::Translation:
            case AnimationPath::Scale: {
                if (s.width != 3 || !n.has_trs) break;
                float v[3];
                sample(s, t, v);
                (c.path == AnimationPath::Translation ? n.translation : n.scale) = glm::vec3(v[0], v[1], v[2]);
                n.local = trs_matrix(n.translation, n.rotation, n.scale);
                break;
            }
            case AnimationPath::Rotation:
                if (s.width != 4 || !n.has_trs) break;
                n.rotation = sample_rotation(s, t);
                n.local = trs_matrix(n.translation, n.rotation, n.scale);
                break;
            case AnimationPath::Weights: {
                if (n.mesh < 0 || std::size_t(n.mesh) >= scene.meshes.size()) break;
                const Mesh& m = scene.meshes[std::size_t(n.mesh)];
                std::size_t targets = m.weights.size();
                for (const auto& p : m.primitives) targets = std::max(targets, p.targets.size());
                if (n.weights.empty()) n.weights = m.weights;
                n.weights.resize(targets, 0.0f);
                std::vector<float> v = sample(s, t);
                for (std::size_t k = 0; k < v.size() && k < targets; ++k) n.weights[k] = v[k];
                break;
            }
            case AnimationPath::Pointer: break;  // handled above
        }
    }
}

}  // namespace

glm::mat4 trs_matrix(const glm::vec3& translation, const glm::quat& rotation, const glm::vec3& scale) {
    return glm::translate(glm::mat4(1.0f), translation) * glm::mat4_cast(rotation) * glm::scale(glm::mat4(1.0f), scale);
}

void animate(Scene& scene, int index, float t) {
    if (index >= int(scene.animations.size()) || index < -1)
        throw Error(scene.source, "--animation " + std::to_string(index),
                    "the file has " + std::to_string(scene.animations.size()) + " animations");
    if (scene.framing.empty()) keep_framing(scene);
    if (index >= 0) {
        animate_one(scene, scene.animations[std::size_t(index)], t);
        return;
    }
    for (const auto& a : scene.animations) animate_one(scene, a, t);
}

void apply_morph_weights(Primitive& p, std::span<const float> weights) {
    bool changed = false;
    for (std::size_t k = 0; k < p.targets.size(); ++k) {
        float w = k < weights.size() ? weights[k] : 0.0f;
        float w0 = k < p.applied_weights.size() ? p.applied_weights[k] : 0.0f;
        float dw = w - w0;
        if (dw == 0.0f || !std::isfinite(dw)) continue;
        changed = true;
        const MorphTarget& mt = p.targets[k];
        for (std::size_t i = 0; i < mt.positions.size() && i < p.positions.size(); ++i) p.positions[i] += dw * mt.positions[i];
        for (std::size_t i = 0; i < mt.normals.size() && i < p.normals.size(); ++i) p.normals[i] += dw * mt.normals[i];
        for (std::size_t i = 0; i < mt.tangents.size() && i < p.tangents.size(); ++i)
            p.tangents[i] += glm::vec4(dw * mt.tangents[i], 0.0f);
    }
    p.applied_weights.assign(p.targets.size(), 0.0f);
    for (std::size_t k = 0; k < p.targets.size() && k < weights.size(); ++k) p.applied_weights[k] = weights[k];
    if (!changed) return;
    for (auto& n : p.normals) n = normalised_or(n, glm::vec3(0, 0, 1));
    for (auto& t : p.tangents) t = glm::vec4(normalised_or(glm::vec3(t), glm::vec3(1, 0, 0)), t.w);
    if (p.generated_normals && p.topology == Topology::Triangles && p.indices.empty()) {
        for (std::size_t v = 0; v + 2 < p.positions.size() && v + 2 < p.normals.size(); v += 3) {
            glm::vec3 f = normalised_or(glm::cross(p.positions[v + 1] - p.positions[v], p.positions[v + 2] - p.positions[v]),
                                        glm::vec3(0, 0, 1));
            p.normals[v] = p.normals[v + 1] = p.normals[v + 2] = f;
        }
    }
}

void pose_meshes(Scene& scene) {
    SkinMatrices posed;
    fresnel::skin_matrices(scene.nodes, scene.skins, posed);
    const std::vector<glm::mat4>& world = posed.world;
    const std::vector<std::vector<glm::mat4>>& skin_matrices = posed.skins;
    std::size_t mesh_count = scene.meshes.size();  // copies are appended after the originals
    for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
        Node& node = scene.nodes[i];
        if (node.mesh < 0 || std::size_t(node.mesh) >= mesh_count || node.world_space_mesh) continue;
        const Mesh& mesh = scene.meshes[std::size_t(node.mesh)];
        const std::vector<float>& weights = node.weights.empty() ? mesh.weights : node.weights;
        bool morph = false, skinned = false;
        const std::vector<glm::mat4>* mats = nullptr;
        if (node.skin >= 0 && std::size_t(node.skin) < skin_matrices.size() && !skin_matrices[std::size_t(node.skin)].empty())
            mats = &skin_matrices[std::size_t(node.skin)];
        for (const auto& p : mesh.primitives) {
            for (std::size_t k = 0; k < p.targets.size(); ++k) {
                float w = k < weights.size() ? weights[k] : 0.0f;
                float w0 = k < p.applied_weights.size() ? p.applied_weights[k] : 0.0f;
                morph = morph || w != w0;
            }
            skinned = skinned || (mats && !p.joints.empty());
        }
        if (!morph && !skinned) continue;
        Mesh posed = mesh;
        for (auto& p : posed.primitives) {
            if (morph) apply_morph_weights(p, weights);
            // A primitive without joints follows the node; weights act normalised, as on the GPU.
            if (skinned) pose_skinned(p, *mats, world[i], SkinWeights::Homogeneous);
        }
        scene.meshes.push_back(std::move(posed));
        node.mesh = int(scene.meshes.size()) - 1;
        node.world_space_mesh = skinned;
    }
}

Scene animated_scene(const Scene& rest, int index, float t) {
    Scene s = rest;
    animate(s, index, t);
    pose_meshes(s);
    return s;
}

ScenePoser::ScenePoser(Scene& scene) : scene_(&scene), mesh_count_(scene.meshes.size()) {
    nodes_.reserve(scene.nodes.size());
    for (const Node& n : scene.nodes)
        nodes_.push_back({n.local, n.translation, n.scale, n.rotation, n.weights, n.mesh, n.world_space_mesh});
    for (const Animation& a : scene.animations)
        for (const AnimationChannel& c : a.channels) pointers_ = pointers_ || c.path == AnimationPath::Pointer;
    if (pointers_) {
        materials_ = scene.materials;
        lights_ = scene.lights;
        cameras_ = scene.cameras;
    }
}

void ScenePoser::rest() {
    if (!scene_ || !posed_) return;
    Scene& s = *scene_;
    for (std::size_t i = 0; i < nodes_.size() && i < s.nodes.size(); ++i) {
        const NodePose& p = nodes_[i];
        Node& n = s.nodes[i];
        n.local = p.local;
        n.translation = p.translation;
        n.scale = p.scale;
        n.rotation = p.rotation;
        n.weights = p.weights;
        n.mesh = p.mesh;
        n.world_space_mesh = p.world_space_mesh;
    }
    s.meshes.resize(mesh_count_);  // CPU-posed copies
    if (pointers_) {
        s.materials = materials_;
        s.lights = lights_;
        s.cameras = cameras_;
    }
    posed_ = false;
}

void ScenePoser::pose(int index, float t, bool meshes) {
    if (!scene_) return;
    rest();
    animate(*scene_, index, t);
    posed_ = true;
    if (meshes) pose_meshes(*scene_);
}

void ScenePoser::keep_materials() {
    if (scene_ && pointers_) materials_ = scene_->materials;
}

}  // namespace fresnel
