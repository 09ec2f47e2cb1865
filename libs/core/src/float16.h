#pragma once
// (Not "half.h": OpenEXR includes Imath's half.h by that name.)
// IEEE 754 half-precision (FP16) to float, exactly: every FP16 value is a float. Shared by the
// KTX2 reader (16-bit float formats) and the ASTC HDR decoder.
#include <cstdint>
#include <cstring>

namespace fresnel::detail {

inline float half_to_float(std::uint16_t h) {
    const std::uint32_t sign = std::uint32_t(h & 0x8000) << 16, exp = (h >> 10) & 0x1F, man = h & 0x3FF;
    if (exp == 0) {
        const float v = float(man) * 0x1p-24f;  // zero or subnormal
        return sign ? -v : v;
    }
    const std::uint32_t bits = exp == 0x1F ? (sign | 0x7F800000u | man << 13)  // infinity, NaN
                                           : (sign | (exp + 112) << 23 | man << 13);
    float f;
    std::memcpy(&f, &bits, sizeof f);  // (std::bit_cast: not in the web build's libc++)
    return f;
}

}  // namespace fresnel::detail
