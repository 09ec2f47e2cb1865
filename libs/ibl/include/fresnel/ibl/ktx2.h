#pragma once
// A minimal KTX 2.0 writer and reader for what fresnel stores: uncompressed
// VK_FORMAT_R16G16B16A16_SFLOAT images, 2D or cube, with mip levels.
// (Khronos KTX 2.0 specification: header, level index, basic data format descriptor,
// key/value data; levels stored smallest first, 8-byte aligned.)
#include <filesystem>
#include <vector>

#include "fresnel/ibl/cubemap.h"

namespace fresnel::ibl {

// Writes a cube map (all levels) as RGBA16F.
void write_ktx2_cube(const std::filesystem::path& path, const Cubemap& cube);
// Writes a 2D RGBA float image as RGBA16F with one level.
void write_ktx2_2d(const std::filesystem::path& path, const ImageF& image);

// Reads files written by the functions above, and any cube or 2D KTX2 that fresnel/core/ktx2.h
// decodes (RGBA16F/32F, UASTC HDR, ...). Throws fresnel::Error naming the file and byte offset on
// bad input.
Cubemap read_ktx2_cube(const std::filesystem::path& path);
ImageF read_ktx2_2d(const std::filesystem::path& path);

}  // namespace fresnel::ibl
