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
// about twice as fast (a 512^2 frame: 12 ms against ~25 ms). Large images are compressed in
// parallel as pigz does: the data in one part per hardware thread, each a raw deflate stream
// primed with the 32 KiB before it (deflateSetDictionary), ended with a sync flush but the last;
// the parts concatenated make one zlib stream (header, blocks, Adler-32 of all the data).
#ifndef FRESNEL_NO_ZLIB  // the web build: stb's own deflate (Emscripten's zlib is a port it would download)
#include <zlib.h>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "fresnel/core/parallel.h"

namespace {
// Raw deflate of data[begin, end) after `dictionary`, flushed to a byte boundary (or finished).
bool deflate_part(const unsigned char* data, std::size_t begin, std::size_t end, std::size_t dictionary, bool last,
                  std::vector<unsigned char>& out) {
    z_stream s{};
    if (deflateInit2(&s, 6, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK) return false;
    bool ok = dictionary == 0 ||
              deflateSetDictionary(&s, data + begin - dictionary, uInt(dictionary)) == Z_OK;
    // deflateBound covers one deflate call on this input; a sync flush adds at most 5 bytes.
    out.resize(deflateBound(&s, uLong(end - begin)) + 64);
    s.next_in = const_cast<unsigned char*>(data + begin);
    s.avail_in = uInt(end - begin);
    s.next_out = out.data();
    s.avail_out = uInt(out.size());
    if (ok) {
        const int rc = deflate(&s, last ? Z_FINISH : Z_SYNC_FLUSH);
        ok = last ? rc == Z_STREAM_END : rc == Z_OK && s.avail_in == 0 && s.avail_out > 0;
    }
    out.resize(s.total_out);
    deflateEnd(&s);
    return ok;
}
}  // namespace

static unsigned char* fresnel_png_deflate(unsigned char* data, int length, int* out_length, int /*quality*/) {
    const std::size_t n = std::size_t(length);
    constexpr std::size_t kMinPart = 256u << 10, kWindow = 32u << 10;
    const std::size_t parts = std::max<std::size_t>(1, std::min<std::size_t>(std::thread::hardware_concurrency(), n / kMinPart));
    std::vector<std::vector<unsigned char>> out(parts);
    std::vector<char> ok(parts, 0);
    fresnel::parallel_for(parts, [&](std::size_t i) {
        const std::size_t begin = n * i / parts, end = n * (i + 1) / parts;
        ok[i] = deflate_part(data, begin, end, std::min(begin, kWindow), i + 1 == parts, out[i]) ? 1 : 0;
    });
    std::size_t total = 2 + 4;
    for (std::size_t i = 0; i < parts; ++i) {
        if (!ok[i]) return nullptr;
        total += out[i].size();
    }
    auto* z = static_cast<unsigned char*>(std::malloc(total));  // stb frees it with STBIW_FREE (free)
    if (!z) return nullptr;
    std::size_t at = 0;
    z[at++] = 0x78;  // deflate, 32 KiB window
    z[at++] = 0x9C;  // default level; (0x78 << 8 | 0x9C) % 31 == 0
    for (const auto& part : out) {
        std::memcpy(z + at, part.data(), part.size());
        at += part.size();
    }
    const uLong adler = adler32(adler32(0L, Z_NULL, 0), data, uInt(n));
    for (int shift = 24; shift >= 0; shift -= 8) z[at++] = static_cast<unsigned char>((adler >> shift) & 0xFF);
    *out_length = int(at);
    return z;
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
