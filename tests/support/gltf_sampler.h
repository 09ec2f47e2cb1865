#pragma once
// Tests describe samplers as glTF files do, by the numeric codes of the glTF 2.0 specification
// (NEAREST 9728, LINEAR 9729, NEAREST_MIPMAP_NEAREST 9984 ... LINEAR_MIPMAP_LINEAR 9987; REPEAT
// 10497, CLAMP_TO_EDGE 33071, MIRRORED_REPEAT 33648): the library's sampler is typed
// (fresnel/core/sampler.h), and only the glTF loader reads the codes.
#include "fresnel/material/texture.h"

namespace fresnel::test {

inline TextureSampler sampler_from_gltf(int mag_filter, int min_filter, int wrap_s, int wrap_t) {
    TextureSampler s;
    s.mag_filter = mag_filter == 9728 ? TextureFilter::Nearest : TextureFilter::Linear;
    switch (min_filter) {
        case 9728: s.min_filter = TextureFilter::Nearest; s.mip_filter = MipFilter::None; break;
        case 9729: s.min_filter = TextureFilter::Linear; s.mip_filter = MipFilter::None; break;
        case 9984: s.min_filter = TextureFilter::Nearest; s.mip_filter = MipFilter::Nearest; break;
        case 9985: s.min_filter = TextureFilter::Linear; s.mip_filter = MipFilter::Nearest; break;
        case 9986: s.min_filter = TextureFilter::Nearest; s.mip_filter = MipFilter::Linear; break;
        default: s.min_filter = TextureFilter::Linear; s.mip_filter = MipFilter::Linear; break;
    }
    auto wrap = [](int w) {
        return w == 33071 ? TextureWrap::ClampToEdge : w == 33648 ? TextureWrap::MirroredRepeat : TextureWrap::Repeat;
    };
    s.wrap_s = wrap(wrap_s);
    s.wrap_t = wrap(wrap_t);
    return s;
}

}  // namespace fresnel::test
