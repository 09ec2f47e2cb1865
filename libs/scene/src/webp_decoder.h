#pragma once
// EXT_texture_webp: WebP images (lossy, lossless, with alpha) decoded by libwebp.
#include <cstdint>
#include <span>
#include <string>

#include "fresnel/core/image.h"

namespace fresnel::gltf {

// "RIFF....WEBP": the container every WebP file starts with.
bool is_webp(std::span<const std::uint8_t> bytes);

// Decodes to RGBA8. The header's size is checked against `limits` before the pixels are
// allocated. Throws fresnel::Error(name, "", "EXT_texture_webp: ...").
Image8 decode_webp(std::span<const std::uint8_t> bytes, const std::string& name, const ImageLimits& limits);

}  // namespace fresnel::gltf
