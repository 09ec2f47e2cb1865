// libFuzzer target: the OBJ loader on arbitrary bytes, and the MTL parser on the same bytes
// (no external files: mtllib and texture paths resolve against a folder that does not exist).
#include <cstdint>
#include <cstddef>
#include <string_view>

#include "fresnel/scene/obj_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fresnel::Diagnostics diag;
    fresnel::ObjLoadOptions options;
    options.max_elements = 1 << 20;  // keep single inputs cheap
    options.max_polygon_vertices = 1 << 16;
    options.triangulation_budget = 1 << 22;
    options.image_limits.max_decoded_bytes = 64u << 20;
    options.threads = 1;
    try {
        (void)fresnel::load_obj_from_memory({data, size}, "fuzz.obj", "/nonexistent-fresnel-fuzz", diag, options);
    } catch (const fresnel::Error&) {
    }
    try {
        (void)fresnel::parse_mtl(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.mtl", diag, 1 << 16);
    } catch (const fresnel::Error&) {
    }
    return 0;
}
