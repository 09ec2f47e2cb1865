#pragma once
// KTX 2.0 textures (Khronos KTX 2.0 specification): the container read as hostile input, its
// supercompression undone (Zstandard, zlib, BasisLZ) and its first image decoded to pixels:
// Basis Universal ETC1S and UASTC LDR to RGBA8, UASTC HDR and float formats to linear floats,
// and the plain 8-bit, 16-bit-float and 32-bit-float RGB(A) formats. What glTF's
// KHR_texture_basisu and KTX2 environments hold.
//
// decode_image8 / decode_image_float (fresnel/core/image.h) call these when they see the KTX2
// identifier, so every loader takes KTX2 without knowing of it.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "fresnel/core/image.h"

namespace fresnel::ktx2 {

enum class Supercompression : std::uint32_t { None = 0, BasisLZ = 1, Zstandard = 2, Zlib = 3 };

// What a file's pixels are, from its vkFormat and data format descriptor.
enum class Encoding {
    Rgba8,     // VK_FORMAT_R8G8B8(A8)_UNORM / _SRGB
    Rgba16f,   // VK_FORMAT_R16G16B16(A16)_SFLOAT
    Rgba32f,   // VK_FORMAT_R32G32B32(A32)_SFLOAT
    Etc1s,     // vkFormat 0, colour model ETC1S (163), BasisLZ
    Uastc,     // vkFormat 0, colour model UASTC (166)
    UastcHdr,  // vkFormat 0, colour model UASTC HDR 4x4 (167)
};

struct Level {
    std::uint64_t offset = 0, length = 0, uncompressed_length = 0;
};

// The header, index, level index and data format descriptor, checked against the file's size.
struct Header {
    std::uint32_t vk_format = 0;
    int width = 0, height = 0, layers = 1, faces = 1, levels = 1;
    Supercompression supercompression = Supercompression::None;
    Encoding encoding = Encoding::Rgba8;
    int channels = 4;       // for the raw formats: 3 or 4 (Basis formats decode to 4)
    bool has_alpha = false;  // the descriptor names an alpha channel
    bool srgb = false;       // transfer function sRGB
    std::vector<Level> level_index;                     // level 0 first
    std::span<const std::uint8_t> global_data;          // BasisLZ's supercompression global data
    bool hdr() const { return encoding == Encoding::UastcHdr || encoding == Encoding::Rgba16f || encoding == Encoding::Rgba32f; }
};

// Whether `bytes` start with the KTX 2.0 identifier.
bool is_ktx2(std::span<const std::uint8_t> bytes);

// Reads and checks the header (sizes against `limits`, every offset and length against the
// file); throws fresnel::Error naming `name` and the byte.
Header read_header(std::span<const std::uint8_t> bytes, const std::string& name, const ImageLimits& limits = {});

// The first image (level 0, layer 0, face 0). Basis LDR and 8-bit formats as RGBA8; an HDR file
// asked for as 8-bit is an error naming it. decode_float returns linear floats for HDR files and
// value / 255 for 8-bit ones (no transfer curve, as decode_image_float does for PNG).
Image8 decode8(std::span<const std::uint8_t> bytes, const std::string& name, const ImageLimits& limits = {});
ImageF decode_float(std::span<const std::uint8_t> bytes, const std::string& name, const ImageLimits& limits = {});

// Every image of level `level` as linear floats (HDR) or value / 255 (LDR), layer-major then
// face: a KTX2 cube map's six faces, in KTX2's face order (+X, -X, +Y, -Y, +Z, -Z).
std::vector<ImageF> decode_level_float(std::span<const std::uint8_t> bytes, int level, const std::string& name,
                                       const ImageLimits& limits = {});

}  // namespace fresnel::ktx2
