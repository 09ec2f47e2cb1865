#pragma once
// A scene's textures as fresnel::evaluate reads them on the CPU: every (texture, colour space)
// that one of the scene's materials reads, decoded once with its mip chain (in parallel), with
// the texture's sampler (trilinear between levels). The path tracer and the Python module's
// evaluate() read materials through it.
#include <memory>
#include <vector>

#include "fresnel/material/texture.h"
#include "fresnel/scene/scene.h"

namespace fresnel {

class SceneTextures final : public TextureSource {
public:
    explicit SceneTextures(const Scene& scene);
    const SampledTexture* get(int texture, bool srgb) const override;

private:
    std::vector<std::unique_ptr<SampledTexture>> textures_;  // 2 per texture: linear, sRGB
};

}  // namespace fresnel
