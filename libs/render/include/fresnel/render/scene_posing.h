#pragma once
// A scene on a Renderer shown at times of its animations (the viewer's and the web page's
// playback, `fresnel render --frames`): the scene is posed in place (fresnel::ScenePoser) and
// the renderer brought up to date, on the GPU where the scene fits the shaders' limits
// (gpu_animatable: the bind pose uploaded once, then only the nodes move), else on the CPU
// (fresnel/scene/pose.h, the reference: the posed meshes uploaded again).
#include <optional>
#include <utility>

#include "fresnel/render/renderer.h"
#include "fresnel/scene/pose.h"

namespace fresnel {

class ScenePosing {
public:
    ScenePosing() = default;
    // `scene` at rest, just given to the renderer (set_scene); it must outlive this.
    // prefer_gpu false: always the CPU reference.
    void reset(Scene& scene, bool prefer_gpu = true);

    // Shows animation `index` (-1: all) at time `t` (none: the rest pose) when that is not what
    // is shown already: poses the scene and updates `renderer` (update_transforms, or set_scene
    // of scene `scene_index` for CPU posing). Throws as fresnel::animate() does (an index the
    // file lacks); the scene is then back at rest.
    void show(Renderer& renderer, int index, std::optional<float> t, int scene_index);

    // RenderSettings::gpu_animation for the frames drawn now.
    bool gpu_animation() const { return shown_.has_value() && gpu_; }
    // Whether the scene is posed on the GPU (false: on the CPU).
    bool on_gpu() const { return gpu_; }
    bool posed() const { return shown_.has_value(); }
    // The scene's material edits since (a material editor) are kept across poses.
    void keep_materials() { poser_.keep_materials(); }

private:
    Scene* scene_ = nullptr;
    ScenePoser poser_;
    bool gpu_ = false;
    std::optional<std::pair<int, float>> shown_;  // (animation, time); none: the rest pose
};

}  // namespace fresnel
