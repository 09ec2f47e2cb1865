#pragma once
// The EXT_meshopt_compression filters (OCTAHEDRAL, QUATERNION, EXPONENTIAL), decoded in
// place as the extension's reference decoder writes them (meshoptimizer's
// js/meshopt_decoder_reference.js: double precision, results rounded half up, stored with
// the wrap of a JavaScript typed array). Decoders may round differently (Debian's
// meshoptimizer 0.18 moves 0.2 % of 8-bit normal components one step from the reference),
// so fresnel owns these few lines to decode every file the same way on every machine and
// in the browser build. Hostile values (a zero octahedral scale, an out-of-range quaternion
// scale) give NaN or huge numbers, which store as the reference stores them: never UB.
#include <cstddef>
#include <cstdint>

namespace fresnel::gltf {

// `data` holds `count` elements of `stride` bytes; the caller has checked the stride rules
// (OCTAHEDRAL 4 or 8, QUATERNION 8, EXPONENTIAL a multiple of 4).
void meshopt_filter_octahedral(std::uint8_t* data, std::size_t count, std::size_t stride);
void meshopt_filter_quaternion(std::uint8_t* data, std::size_t count, std::size_t stride);
void meshopt_filter_exponential(std::uint8_t* data, std::size_t count, std::size_t stride);

}  // namespace fresnel::gltf
