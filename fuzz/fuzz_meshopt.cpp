// libFuzzer target: EXT_meshopt_compression. Bytes 0-3 choose mode, filter, byteStride and
// count; the rest is the compressed stream of one bufferView, decoded through the loader.
#include "fuzz_glb.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 4) return 0;
    static const char* modes[] = {"ATTRIBUTES", "TRIANGLES", "INDICES"};
    static const char* filters[] = {"NONE", "OCTAHEDRAL", "QUATERNION", "EXPONENTIAL"};
    std::string mode = modes[data[0] % 3], filter = filters[data[1] % 4];
    std::size_t stride = mode == "ATTRIBUTES" ? std::size_t(data[2] % 64 + 1) * 4 : (data[2] & 1 ? 4 : 2);
    std::size_t count = std::size_t(data[3]) * 3 + 3;
    using nlohmann::json;
    json j = {{"asset", {{"version", "2.0"}}},
              {"extensionsUsed", {"EXT_meshopt_compression", "KHR_mesh_quantization"}},
              {"buffers", {{{"byteLength", size}},
                           {{"byteLength", count * stride + 36},
                            {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}}},
              {"scenes", {{{"nodes", {0}}}}},
              {"nodes", {{{"mesh", 0}}}}};
    json view = {{"buffer", 1}, {"byteLength", count * stride},
                 {"extensions", {{"EXT_meshopt_compression", {{"buffer", 0}, {"byteOffset", 4}, {"byteLength", size - 4},
                                                              {"byteStride", stride}, {"count", count}, {"mode", mode},
                                                              {"filter", filter}}}}}};
    json prim;
    if (mode == "ATTRIBUTES") {
        view["byteStride"] = stride;
        j["bufferViews"] = {view};
        int ctype = stride >= 12 ? 5126 : stride >= 6 ? 5123 : 5121;
        j["accessors"] = {{{"bufferView", 0}, {"componentType", ctype}, {"count", count}, {"type", "VEC3"}}};
        prim = {{"attributes", {{"POSITION", 0}}}};
    } else {
        // Indices into three plain vertices (the last 36 bytes of the fallback buffer are not used).
        j["bufferViews"] = {view};
        j["accessors"] = {{{"bufferView", 0}, {"componentType", stride == 2 ? 5123 : 5125}, {"count", count}, {"type", "SCALAR"}},
                          {{"componentType", 5126}, {"count", 3}, {"type", "VEC3"}}};
        prim = {{"attributes", {{"POSITION", 1}}}, {"indices", 0}};
    }
    j["meshes"] = {{{"primitives", {prim}}}};
    // BIN: 4 bytes of header (unused) then the stream, so byteOffset 4 is the stream.
    fresnel::fuzz::load_glb(j, data, size);
    return 0;
}
