// libFuzzer target: KHR_draco_mesh_compression. Bytes 0-1 give the accessors' vertex count
// and which attributes (NORMAL, TEXCOORD_0) the extension names; the rest is the Draco
// stream, decoded through the loader.
#include "fuzz_glb.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 4) return 0;
    std::size_t points = std::size_t(data[0]) * 4 + 3;
    using nlohmann::json;
    json accessors = {{{"componentType", 5126}, {"count", points}, {"type", "VEC3"}},
                      {{"componentType", 5125}, {"count", std::size_t(data[2]) * 3 + 3}, {"type", "SCALAR"}}};
    json attrs = {{"POSITION", 0}}, ids = {{"POSITION", data[3] & 3}};
    if (data[1] & 1) {
        accessors.push_back({{"componentType", 5126}, {"count", points}, {"type", "VEC3"}});
        attrs["NORMAL"] = accessors.size() - 1;
        ids["NORMAL"] = (data[3] >> 2) & 3;
    }
    if (data[1] & 2) {
        accessors.push_back({{"componentType", data[1] & 4 ? 5123 : 5126}, {"normalized", bool(data[1] & 4)},
                             {"count", points}, {"type", "VEC2"}});
        attrs["TEXCOORD_0"] = accessors.size() - 1;
        ids["TEXCOORD_0"] = (data[3] >> 4) & 3;
    }
    json j = {{"asset", {{"version", "2.0"}}},
              {"extensionsUsed", {"KHR_draco_mesh_compression"}},
              {"extensionsRequired", {"KHR_draco_mesh_compression"}},
              {"buffers", {{{"byteLength", size}}}},
              {"bufferViews", {{{"buffer", 0}, {"byteOffset", 4}, {"byteLength", size - 4}}}},
              {"accessors", accessors},
              {"meshes", {{{"primitives", {{{"attributes", attrs}, {"indices", 1},
                                             {"extensions", {{"KHR_draco_mesh_compression",
                                                              {{"bufferView", 0}, {"attributes", ids}}}}}}}}}}},
              {"scenes", {{{"nodes", {0}}}}},
              {"nodes", {{{"mesh", 0}}}}};
    fresnel::fuzz::load_glb(j, data, size);
    return 0;
}
