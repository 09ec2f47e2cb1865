#include "fresnel/scene/scene_textures.h"

#include <algorithm>
#include <utility>

#include "fresnel/core/parallel.h"
#include "fresnel/material/evaluate.h"

namespace fresnel {

SceneTextures::SceneTextures(const Scene& scene) {
    std::vector<std::pair<int, bool>> wanted;
    for (const Material& m : scene.materials)
        for (int i = 0; i < kMaterialMapCount; ++i) {
            auto map = MaterialMap(i);
            const TextureSlot* slot = material_map(m, map);
            if (!slot || !slot->valid()) continue;
            wanted.emplace_back(slot->texture, map_srgb(m, map));
        }
    std::sort(wanted.begin(), wanted.end());
    wanted.erase(std::unique(wanted.begin(), wanted.end()), wanted.end());
    textures_.resize(scene.textures.size() * 2);
    parallel_for(wanted.size(), [&](std::size_t k) {
        auto [t, srgb] = wanted[k];
        if (t < 0 || t >= int(scene.textures.size())) return;
        const Texture& tex = scene.textures[std::size_t(t)];
        if (tex.image < 0 || tex.image >= int(scene.images.size()) || !scene.images[std::size_t(tex.image)].valid())
            return;
        TextureSampler s;
        s.mag_filter = tex.sampler.mag_filter;
        s.min_filter = tex.sampler.min_filter;
        s.mip_filter = MipFilter::Linear;
        s.wrap_s = tex.sampler.wrap_s;
        s.wrap_t = tex.sampler.wrap_t;
        textures_[std::size_t(t) * 2 + (srgb ? 1 : 0)] =
            std::make_unique<SampledTexture>(scene.images[std::size_t(tex.image)].pixels, s, srgb);
    });
}

const SampledTexture* SceneTextures::get(int texture, bool srgb) const {
    std::size_t i = std::size_t(texture) * 2 + (srgb ? 1 : 0);
    return texture >= 0 && i < textures_.size() ? textures_[i].get() : nullptr;
}

}  // namespace fresnel
