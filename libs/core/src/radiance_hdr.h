#pragma once
// Radiance RGBE (.hdr) decoding, our own: stb_image's decoder loops forever on a
// run-length record whose count byte is 0 (found by fuzz_hdr; the input is kept in
// fuzz/regressions/hdr), so every byte of the file is checked here instead.

#include <cstdint>
#include <span>
#include <string>

#include "fresnel/core/image.h"

namespace fresnel::detail {

// Reads the header and the resolution line only. Returns false when the bytes are not
// a Radiance file we can read (the reason goes to `why`).
bool radiance_info(std::span<const std::uint8_t> bytes, int& width, int& height, std::string& why);

// Decodes the whole image into linear RGBA floats (alpha 1), rows top to bottom.
// Supports the header orientations -Y/+Y with +X/-X, flat pixels, the old run-length
// encoding (1,1,1,n repeat records) and the adaptive run-length encoding. Throws
// fresnel::Error naming `name` and the byte offset of the fault.
ImageF decode_radiance(std::span<const std::uint8_t> bytes, const std::string& name, const ImageLimits& limits);

}  // namespace fresnel::detail
