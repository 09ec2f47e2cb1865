#pragma once
// Small pictures of environments for the viewer's presets list, without GL.
#include <string>

#include "fresnel/core/image.h"

namespace fresnel::viewer {

// The picture of an environment preset (State::environment_presets): "studio" (the built-in
// studio), an .hdr/.exr panorama, or a `fresnel bake` folder (its preview of the specular cube's
// sharpest level when the bake wrote previews; none otherwise). Box-filtered to `width` x
// width / 2, exposed so that its mean luminance is 0.18, tone mapped (x / (1 + x)) and
// sRGB-encoded (ibl::panorama_thumbnail): RGB, rows top to bottom. Throws fresnel::Error when the
// file does not read or a baked folder holds no preview.
Image8 environment_thumbnail(const std::string& preset, int width = 96);

}  // namespace fresnel::viewer
