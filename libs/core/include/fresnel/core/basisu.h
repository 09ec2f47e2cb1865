#pragma once
// Basis Universal transcoders for KTX2 textures (KHR_texture_basisu): ETC1S with BasisLZ
// supercompression, UASTC LDR 4x4 and UASTC HDR 4x4, each decoded to plain pixels. Written from
// the specifications (KTX 2.0 section "BasisLZ Global Data"; the Basis Universal "ETC1S texture
// video" and "UASTC texture" specifications; the Khronos Data Format ASTC section for HDR).
//
// Every input is hostile: a transcoder reads only inside the spans it is given, checks every
// count and length against them before allocating, and throws fresnel::Error naming `name` and
// the place (a byte offset, a block) on bad data. Output buffers are the caller's, sized
// width * height * 4 elements. The KTX2 container itself is read by fresnel/core/ktx2.h.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

namespace fresnel::basisu {

// ETC1S: a file's BasisLZ global data (KTX2 supercompressionGlobalData: its endpoint and
// selector codebooks, Huffman tables and one descriptor per image) decoded once, then each image
// transcoded from its level's bytes.
class Etc1sTranscoder {
public:
    // `image_count`: the number of images the global data describes (the KTX2 file's
    // levels x layers x faces, counting each level's layers x faces; KTX2 orders the image
    // descriptors level 0 first, then by layer, then by face).
    Etc1sTranscoder(std::span<const std::uint8_t> global_data, std::uint32_t image_count, std::string name);
    ~Etc1sTranscoder();
    Etc1sTranscoder(Etc1sTranscoder&&) noexcept;
    Etc1sTranscoder& operator=(Etc1sTranscoder&&) noexcept;

    std::uint32_t image_count() const;
    // Whether image `image` has an alpha slice (a second slice whose G channel is alpha).
    bool has_alpha(std::uint32_t image) const;
    // Transcodes image `image` (width x height pixels; its slices' offsets in the global data
    // are relative to the start of `level_data`, the bytes of the level it belongs to) into
    // RGBA8, rows top to bottom. Without an alpha slice, alpha is 255.
    void transcode(std::uint32_t image, std::span<const std::uint8_t> level_data, int width, int height,
                   std::uint8_t* rgba) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// UASTC LDR 4x4: `blocks` holds ceil(width/4) x ceil(height/4) 16-byte blocks in row order
// (a level's bytes after Zstandard, if any, is undone); writes RGBA8, rows top to bottom. A block
// with a reserved mode, an out-of-range pattern or an invalid trit/quint group throws, naming it.
void transcode_uastc(std::span<const std::uint8_t> blocks, int width, int height, std::uint8_t* rgba,
                     const std::string& name);

// UASTC HDR 4x4 (any ASTC 4x4 block, HDR profile): the same layout; writes linear RGBA floats (the
// blocks' half-float values widened exactly). An illegal block decodes to opaque magenta, as the
// ASTC specification allows, and the rest of the image decodes; a span of the wrong size throws.
void transcode_uastc_hdr(std::span<const std::uint8_t> blocks, int width, int height, float* rgba,
                         const std::string& name);

}  // namespace fresnel::basisu
