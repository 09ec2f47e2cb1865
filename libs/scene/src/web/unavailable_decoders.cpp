// The web build (Emscripten) has no meshoptimizer, Draco or libwebp: Debian builds none of
// them for WebAssembly. This file stands in for meshopt_decoder.cpp, draco_decoder.cpp and
// webp_decoder.cpp there (libs/scene/CMakeLists.txt), so a file that uses one of these
// extensions fails with an error naming it and its place, never silently.
#include <cstring>

#include "draco_decoder.h"
#include "fresnel/core/error.h"
#include "meshopt_decoder.h"
#include "webp_decoder.h"

namespace fresnel::gltf {

namespace {
std::string unavailable(const char* extension, const char* library) {
    return std::string(extension) + ": not available in the web build (Debian has no WebAssembly build of " + library +
           ")";
}
}  // namespace

bool is_meshopt_fallback_buffer(const JsonReader& r, const json& buffer) {
    const json& ext = r.object(buffer, "extensions", "");
    const json* m = r.find(ext, "EXT_meshopt_compression");
    return m && m->is_object() && m->value("fallback", false) == true;
}

void decode_meshopt_views(const JsonReader& r, json& doc, std::vector<std::vector<std::uint8_t>>&, std::size_t,
                          const std::function<void(std::size_t, const std::string&)>&) {
    if (!doc.is_object()) return;
    auto views = doc.find("bufferViews");
    if (views == doc.end() || !views->is_array()) return;
    for (std::size_t i = 0; i < views->size(); ++i) {
        const json& v = (*views)[i];
        if (!v.is_object()) continue;
        std::string vptr = "/bufferViews/" + std::to_string(i);
        if (r.find(r.object(v, "extensions", vptr), "EXT_meshopt_compression"))
            r.fail(vptr + "/extensions/EXT_meshopt_compression", unavailable("EXT_meshopt_compression", "meshoptimizer"));
    }
}

std::map<int, AccessorData> decode_draco_primitive(const JsonReader& r, const json&, const json&, const std::string& ptr,
                                                   const AccessorDecoder&, std::size_t) {
    r.fail(ptr, unavailable("KHR_draco_mesh_compression", "Draco"));
    return {};
}

bool is_webp(std::span<const std::uint8_t> bytes) {
    return bytes.size() >= 12 && std::memcmp(bytes.data(), "RIFF", 4) == 0 && std::memcmp(bytes.data() + 8, "WEBP", 4) == 0;
}

Image8 decode_webp(std::span<const std::uint8_t>, const std::string& name, const ImageLimits&) {
    throw Error(name, "", unavailable("EXT_texture_webp", "libwebp"));
}

}  // namespace fresnel::gltf
