#pragma once
// Mip chains of 8-bit RGBA images, built on the CPU (in parallel, before upload) so the
// GPU driver never has to: on Mesa's llvmpipe glGenerateMipmap of five 2048^2 maps
// took ~400 ms of DamagedHelmet's first frame.
//
// Each level is made from the one above it exactly as a linear-filtered blit does
// (what Mesa's glGenerateMipmap runs): the destination texel centre maps to the source,
// which is read bilinearly with clamp-to-edge. For even sizes that is the 2x2 box
// average. sRGB images are filtered in linear light (decoded per texel, encoded with
// rounding), alpha always linearly.
#include <vector>

#include "fresnel/core/image.h"

namespace fresnel {

// Number of levels of a full chain for a width x height image (1 for 1x1).
int mip_level_count(int width, int height);

// The next level: max(1, w/2) x max(1, h/2). The image must be RGBA (4 channels).
Image8 downsample_half(const Image8& level, bool srgb);

// Levels 1 .. n-1 of the full chain below `level0` (level 0 itself is not copied).
std::vector<Image8> build_mip_chain(const Image8& level0, bool srgb);

}  // namespace fresnel
