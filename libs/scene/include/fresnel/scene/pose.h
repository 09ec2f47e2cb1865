#pragma once
// Posing a scene: its animations applied at a time t, then morph targets and skins evaluated
// on the CPU (the reference any GPU path is checked against).
//
// The rest pose (no animation) is what the loader produces and stays untouched: these
// functions are only used when a time is asked for.
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/mat4x4.hpp>

#include "fresnel/scene/animation.h"
#include "fresnel/scene/scene.h"

namespace fresnel {

// Applies animation `index` of the scene (-1: all of them, in order) at time t (seconds;
// each sampler clamps to its first and last keyframes): the targeted nodes' translation,
// rotation, scale (and so `local`) and morph weights (Node::weights, one per target of the
// node's mesh: a sampler with fewer values leaves the others at the mesh's weights), and the
// material, light and camera properties of KHR_animation_pointer channels. Throws
// fresnel::Error (file: scene.source) when `index` is out of range.
void animate(Scene& scene, int index, float t);

// KHR_animation_pointer targets fresnel animates (JSON pointers into the glTF document; N is
// an index into the scene's arrays, which follow the file's):
//  - /materials/N/ + the path of every property the material property registry marks
//    animatable (fresnel/material/properties.h; `fresnel settings --materials` lists them:
//    the core factors, normalTexture/scale, occlusionTexture/strength and every extension's
//    factors; a block the material lacks is added with the extension's defaults), and
//    TEXTURE/extensions/KHR_texture_transform/offset | rotation | scale of each texture;
//  - /extensions/KHR_lights_punctual/lights/N/ + color | intensity | range |
//    spot/innerConeAngle | spot/outerConeAngle;
//  - /cameras/N/ + perspective/yfov | znear | zfar | aspectRatio, orthographic/xmag | ymag | znear | zfar.
// (Node translation, rotation, scale and weights become ordinary channels in the loader.)
// The number of floats the property holds (1 to 4), or 0 with `why` set when fresnel does not
// animate it (unknown property, index out of range, a camera of the other type, ...).
int animation_pointer_width(const Scene& scene, std::string_view pointer, std::string* why = nullptr);
// Writes `values` (animation_pointer_width floats) to the property; values are clamped to the
// property's valid range (factors to [0, 1] where the specification bounds them, angles,
// distances and ior to what the shaders accept). False when the pointer names nothing fresnel animates.
bool write_animation_pointer(Scene& scene, std::string_view pointer, std::span<const float> values);

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

// A scene posed again and again in place (a viewer's playback, a sequence of frames) without
// copying it: what animations change (the nodes' transforms, morph weights and meshes, and the
// materials, lights and cameras that KHR_animation_pointer channels reach) is kept as it was at
// construction and put back before each pose; meshes posed on the CPU are appended after the
// loaded ones and dropped again. Anything else (a node's visibility, edits) stays as it is.
class ScenePoser {
public:
    ScenePoser() = default;
    // `scene` at rest; it must outlive the poser (which keeps a pointer to it).
    explicit ScenePoser(Scene& scene);

    // The scene at animation `index` (-1: all of them) at time t: animate(), then with
    // `meshes` pose_meshes() (the CPU reference); without, meshes stay as loaded for the GPU to
    // pose from the nodes (RenderSettings::gpu_animation). Throws as animate() does.
    void pose(int index, float t, bool meshes);
    // Back to the pose at construction.
    void rest();
    // The scene's materials as they are now (edited) become the ones put back before each pose.
    void keep_materials();
    bool posed() const { return posed_; }

private:
    struct NodePose {  // what animate() and pose_meshes() change in a node
        glm::mat4 local{1.0f};
        glm::vec3 translation{0.0f}, scale{1.0f};
        glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
        std::vector<float> weights;
        int mesh = -1;
        bool world_space_mesh = false;
    };
    Scene* scene_ = nullptr;
    std::vector<NodePose> nodes_;
    bool pointers_ = false;  // some channel is a KHR_animation_pointer: materials, lights and cameras are kept too
    std::vector<Material> materials_;
    std::vector<Light> lights_;
    std::vector<Camera> cameras_;
    std::size_t mesh_count_ = 0;
    bool posed_ = false;
};

}  // namespace fresnel
