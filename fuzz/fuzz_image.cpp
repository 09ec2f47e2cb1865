// libFuzzer target: 8-bit image decoding (PNG, JPEG, ...) with size limits.
#include <cstdint>
#include <cstddef>

#include "fresnel/core/error.h"
#include "fresnel/core/image.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fresnel::ImageLimits limits;
    limits.max_decoded_bytes = 64u << 20;
    try {
        (void)fresnel::decode_image8({data, size}, "fuzz", limits);
    } catch (const fresnel::Error&) {
    }
    return 0;
}
