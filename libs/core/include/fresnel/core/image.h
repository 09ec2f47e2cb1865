#pragma once
// Images in memory and on disk. Decoders treat their input as hostile: the
// header is read first and the size checked against ImageLimits before any
// pixel memory is allocated.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace fresnel {

struct ImageLimits {
    int max_dimension = 16384;                          // per side, pixels
    std::size_t max_decoded_bytes = std::size_t(1) << 30;  // one image, after decoding (1 GiB)
};

// Linear float RGBA, rows top to bottom.
struct ImageF {
    int width = 0, height = 0;
    std::vector<float> pixels;  // width*height*4
    ImageF() = default;
    ImageF(int w, int h) : width(w), height(h), pixels(std::size_t(w) * h * 4, 0.0f) {}
    float* at(int x, int y) { return &pixels[(std::size_t(y) * width + x) * 4]; }
    const float* at(int x, int y) const { return &pixels[(std::size_t(y) * width + x) * 4]; }
};

// 8-bit image with 1..4 channels, rows top to bottom.
struct Image8 {
    int width = 0, height = 0, channels = 4;
    std::vector<std::uint8_t> pixels;
    Image8() = default;
    Image8(int w, int h, int c) : width(w), height(h), channels(c), pixels(std::size_t(w) * h * c, 0) {}
    std::uint8_t* at(int x, int y) { return &pixels[(std::size_t(y) * width + x) * channels]; }
    const std::uint8_t* at(int x, int y) const { return &pixels[(std::size_t(y) * width + x) * channels]; }
};

// Decodes PNG/JPEG (and the other formats stb_image reads) and KTX2 (fresnel/core/ktx2.h: Basis
// Universal ETC1S/UASTC, 8-bit RGB(A)) from memory into
// 8-bit RGBA. `name` is used in error messages. Throws fresnel::Error.
Image8 decode_image8(std::span<const std::uint8_t> bytes, const std::string& name, const ImageLimits& limits = {});

// Reads the dimensions without decoding; false if the header is not understood.
bool peek_image_size(std::span<const std::uint8_t> bytes, int& width, int& height);

// What an encoded image is, from its header alone (fresnel info): its format ("PNG", "JPEG",
// "WebP", "KTX2 UASTC (Zstandard)", "Radiance HDR", ...; "unknown" when not recognised) and its
// size (0 x 0 when the header does not say or is not understood).
struct ImageHeader {
    std::string format = "unknown";
    int width = 0, height = 0;
};
ImageHeader peek_image_header(std::span<const std::uint8_t> bytes);

// Reads an 8-bit image file (PNG, JPEG, ...) into RGBA.
Image8 read_image8(const std::filesystem::path& path, const ImageLimits& limits = {});
// Reads a float image: Radiance .hdr, OpenEXR .exr (RGB(A), any compression OpenEXR
// supports) or an HDR KTX2 (UASTC HDR, 16/32-bit float); any other file is decoded as an 8-bit image, values / 255 (no transfer curve).
ImageF read_image_float(const std::filesystem::path& path, const ImageLimits& limits = {});

// Decodes a float image from memory, by its magic bytes: OpenEXR, Radiance .hdr, KTX2, else 8-bit
// formats as decode_image8, values / 255.
ImageF decode_image_float(std::span<const std::uint8_t> bytes, const std::string& name, const ImageLimits& limits = {});
// Whether `bytes` are an OpenEXR, Radiance HDR or HDR KTX2 file: linear values, where the 8-bit formats
// decode_image_float reads hold display values / 255.
bool is_linear_image(std::span<const std::uint8_t> bytes);

// The encoded bytes of a file (PNG through zlib, Radiance RGBE); throw fresnel::Error.
std::vector<std::uint8_t> encode_png(const Image8& image);
std::vector<std::uint8_t> encode_hdr(const ImageF& image);

// Image files written whole or absent (fresnel/core/atomic_file.h): encoded in memory, written
// to a temporary beside `path` with every write checked, flushed to the disk, then renamed over
// `path`. On any failure (a full disk, a read-only folder) `path` keeps what it held, no
// temporary stays, and the fresnel::Error names `path` and the system's reason.
void write_png(const std::filesystem::path& path, const Image8& image);
void write_hdr(const std::filesystem::path& path, const ImageF& image);
void write_exr(const std::filesystem::path& path, const ImageF& image);  // half-float RGBA, ZIP

// Reads a whole file with a size cap; throws fresnel::Error naming the file.
std::vector<std::uint8_t> read_file_bytes(const std::filesystem::path& path, std::size_t max_bytes);

}  // namespace fresnel
