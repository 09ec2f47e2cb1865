// libFuzzer target: float image decoding (exr path of decode_image_float) with size limits.
#include <cstdint>
#include <cstddef>
#include <vector>

#include "fresnel/core/error.h"
#include "fresnel/core/image.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fresnel::ImageLimits limits;
    limits.max_decoded_bytes = 64u << 20;
    // Force the exr decoder by the magic bytes, so the fuzzer spends its time inside it.
    std::vector<std::uint8_t> bytes({0x76, 0x2f, 0x31, 0x01});
    bytes.insert(bytes.end(), data, data + size);
    try {
        (void)fresnel::decode_image_float(bytes, "fuzz", limits);
    } catch (const fresnel::Error&) {
    }
    return 0;
}
