#include "fresnel/render/scene_posing.h"

namespace fresnel {

void ScenePosing::reset(Scene& scene, bool prefer_gpu) {
    scene_ = &scene;
    poser_ = ScenePoser(scene);
    gpu_ = prefer_gpu && gpu_animatable(scene);
    shown_.reset();
}

void ScenePosing::show(Renderer& renderer, int index, std::optional<float> t, int scene_index) {
    if (!scene_) return;
    std::optional<std::pair<int, float>> want;
    if (t) want = std::pair(index, *t);
    if (want == shown_) return;
    shown_.reset();
    try {
        if (want) poser_.pose(want->first, want->second, !gpu_);
        else poser_.rest();
    } catch (...) {
        poser_.rest();
        if (gpu_) renderer.update_transforms();
        else renderer.set_scene(*scene_, scene_index);
        throw;
    }
    shown_ = want;
    if (gpu_) renderer.update_transforms();
    else renderer.set_scene(*scene_, scene_index);
}

}  // namespace fresnel
