#pragma once
// SplitMix64 (Steele, Lea and Flood 2014): a 64-bit hash that seeds the tracer's per-sample
// random streams and the occlusion bake's per-vertex rotations.
#include <cstdint>

namespace fresnel::trace {

inline std::uint64_t splitmix64(std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

}  // namespace fresnel::trace
