#include "webp_decoder.h"

#include <cstring>
#include <webp/decode.h>

#include "fresnel/core/error.h"

namespace fresnel::gltf {

bool is_webp(std::span<const std::uint8_t> bytes) {
    return bytes.size() >= 12 && std::memcmp(bytes.data(), "RIFF", 4) == 0 && std::memcmp(bytes.data() + 8, "WEBP", 4) == 0;
}

Image8 decode_webp(std::span<const std::uint8_t> bytes, const std::string& name, const ImageLimits& limits) {
    auto fail = [&](const std::string& what) -> void { throw Error(name, "", "EXT_texture_webp: " + what); };
    WebPBitstreamFeatures features;
    VP8StatusCode status = WebPGetFeatures(bytes.data(), bytes.size(), &features);
    if (status != VP8_STATUS_OK) fail("not a readable WebP image (libwebp status " + std::to_string(int(status)) + ")");
    if (features.has_animation) fail("animated WebP is not a texture");
    int w = features.width, h = features.height;
    if (w <= 0 || h <= 0 || w > limits.max_dimension || h > limits.max_dimension)
        fail(std::to_string(w) + "x" + std::to_string(h) + " is outside 1.." + std::to_string(limits.max_dimension) +
             " per side");
    std::size_t size = std::size_t(w) * std::size_t(h) * 4;
    if (size > limits.max_decoded_bytes)
        fail(std::to_string(w) + "x" + std::to_string(h) + " decodes to " + std::to_string(size) +
             " bytes, over the limit of " + std::to_string(limits.max_decoded_bytes));
    Image8 img(w, h, 4);
    if (!WebPDecodeRGBAInto(bytes.data(), bytes.size(), img.pixels.data(), img.pixels.size(), w * 4))
        fail("the image data is corrupt or truncated");
    return img;
}

}  // namespace fresnel::gltf
