// libFuzzer target: EXT_texture_webp. The input is the image of a texture that only
// EXT_texture_webp names, decoded through the loader.
#include "fuzz_glb.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    using nlohmann::json;
    json j = {{"asset", {{"version", "2.0"}}},
              {"extensionsUsed", {"EXT_texture_webp"}},
              {"extensionsRequired", {"EXT_texture_webp"}},
              {"buffers", {{{"byteLength", size}}}},
              {"bufferViews", {{{"buffer", 0}, {"byteLength", size}}}},
              {"images", {{{"bufferView", 0}, {"mimeType", "image/webp"}}}},
              {"textures", {{{"extensions", {{"EXT_texture_webp", {{"source", 0}}}}}}}},
              {"materials", {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}}}};
    fresnel::fuzz::load_glb(j, data, size);
    return 0;
}
