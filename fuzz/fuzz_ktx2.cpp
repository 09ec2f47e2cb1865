// libFuzzer target: KTX2 textures (fresnel/core/ktx2.h): the container, Zstandard and zlib
// supercompression, and the Basis Universal transcoders (ETC1S/BasisLZ, UASTC, UASTC HDR), every
// level of the file, with size limits.
#include <cstddef>
#include <cstdint>

#include "fresnel/core/error.h"
#include "fresnel/core/ktx2.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fresnel::ImageLimits limits;
    limits.max_dimension = 4096;
    limits.max_decoded_bytes = 64u << 20;
    try {
        const fresnel::ktx2::Header h = fresnel::ktx2::read_header({data, size}, "fuzz", limits);
        for (int level = 0; level < h.levels; ++level) (void)fresnel::ktx2::decode_level_float({data, size}, level, "fuzz", limits);
    } catch (const fresnel::Error&) {
    }
    return 0;
}
