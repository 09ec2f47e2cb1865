// libFuzzer target: the glTF/GLB loader on arbitrary bytes (no external files), then the
// scene's animations played and posed on the CPU at a few times.
#include <cstdint>
#include <cstddef>

#include "fresnel/scene/gltf_loader.h"
#include "fresnel/scene/pose.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fresnel::Diagnostics diag;
    fresnel::GltfLoadOptions options;
    options.max_vertices = 1 << 20;  // keep single inputs cheap
    options.max_total_bytes = 256u << 20;
    options.image_limits.max_decoded_bytes = 64u << 20;
    options.threads = 1;
    try {
        // A base folder that does not exist: relative URIs resolve to nothing.
        fresnel::Scene scene =
            fresnel::load_gltf_from_memory({data, size}, "fuzz.glb", "/nonexistent-fresnel-fuzz", diag, options);
        for (float t : {-1.0f, 0.37f, 1e9f}) (void)fresnel::animated_scene(scene, -1, t);
    } catch (const fresnel::Error&) {
    }
    return 0;
}
