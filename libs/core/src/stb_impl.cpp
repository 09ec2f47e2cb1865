// Compiles the stb_image / stb_image_write implementations from Debian's libstb-dev
// headers into this library, so that sanitizer and fuzzing builds instrument them.
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
// Size limits are ours (ImageLimits, checked from the header before decoding), not stb's.
#define STBI_FAILURE_USERMSG
// Only the formats models bring (PNG, JPEG; BMP, TGA and GIF in OBJ/MTL material libraries; HDR):
// Debian's stb_image 2.27's 16-bit PNM path overflows its buffer on a truncated file
// (fuzz_webp, fuzz/regressions/webp/pnm-16-bit-truncated), and PSD and PIC are no texture formats.
#define STBI_NO_PNM
#define STBI_NO_PSD
#define STBI_NO_PIC
// PNG deflate through zlib (level 6): as small as stb's own compressor at its level 8, and
// about twice as fast (a 512^2 frame: 12 ms against ~25 ms).
#ifndef FRESNEL_NO_ZLIB  // the web build: stb's own deflate (Emscripten's zlib is a port it would download)
#include <zlib.h>
#include <cstdlib>
static unsigned char* fresnel_png_deflate(unsigned char* data, int length, int* out_length, int /*quality*/) {
    uLongf size = compressBound(uLong(length));
    auto* out = static_cast<unsigned char*>(std::malloc(size));  // stb frees it with STBIW_FREE (free)
    if (!out) return nullptr;
    if (compress2(out, &size, data, uLong(length), 6) != Z_OK) {
        std::free(out);
        return nullptr;
    }
    *out_length = int(size);
    return out;
}
#define STBIW_ZLIB_COMPRESS fresnel_png_deflate
#endif
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#include <stb_image.h>
#include <stb_image_write.h>
#pragma GCC diagnostic pop
