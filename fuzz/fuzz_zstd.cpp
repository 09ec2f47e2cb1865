// libFuzzer target: our Zstandard decoder (libs/core/src/zstd_decoder.cpp, the web build's). The
// first three bytes give the output size (up to 16 MiB), the rest is the stream.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "../libs/core/src/zstd_decoder.h"
#include "fresnel/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 3) return 0;
    const std::size_t out = std::size_t(data[0]) | std::size_t(data[1]) << 8 | std::size_t(data[2]) << 16;
    std::vector<std::uint8_t> dst(out);
    try {
        fresnel::detail::zstd_decompress({data + 3, size - 3}, dst, "fuzz");
    } catch (const fresnel::Error&) {
    }
    return 0;
}
