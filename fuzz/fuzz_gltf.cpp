// libFuzzer target: the glTF/GLB loader on arbitrary bytes (no external files).
#include <cstdint>
#include <cstddef>

#include "fresnel/scene/gltf_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fresnel::Diagnostics diag;
    fresnel::GltfLoadOptions options;
    options.max_vertices = 1 << 20;  // keep single inputs cheap
    options.max_total_bytes = 256u << 20;
    options.image_limits.max_decoded_bytes = 64u << 20;
    options.threads = 1;
    try {
        // A base folder that does not exist: relative URIs resolve to nothing.
        (void)fresnel::load_gltf_from_memory({data, size}, "fuzz.glb", "/nonexistent-fresnel-fuzz", diag, options);
    } catch (const fresnel::Error&) {
    }
    return 0;
}
