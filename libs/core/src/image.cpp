#include "fresnel/core/image.h"

// The web build (Emscripten) has no OpenEXR and no libjpeg-turbo (Debian builds neither for
// WebAssembly): FRESNEL_NO_OPENEXR makes EXR a clear error naming the feature, and JPEG goes
// through stb_image (FRESNEL_NO_TURBOJPEG).
#ifndef FRESNEL_NO_OPENEXR
#include <ImathBox.h>
#include <OpenEXR/ImfArray.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfRgbaFile.h>
#endif
#include <stb_image.h>
#include <stb_image_write.h>
#ifndef FRESNEL_NO_TURBOJPEG
#include <turbojpeg.h>
#endif

#include <cstring>
#include <fstream>

#include "fresnel/core/atomic_file.h"
#include "fresnel/core/error.h"
#include "fresnel/core/ktx2.h"
#include "radiance_hdr.h"

namespace fresnel {
namespace fs = std::filesystem;

std::vector<std::uint8_t> read_file_bytes(const fs::path& path, std::size_t max_bytes) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) throw Error(path.string(), "", "not a readable file");
    auto size = fs::file_size(path, ec);
    if (ec) throw Error(path.string(), "", "cannot read file size: " + ec.message());
    if (size > max_bytes)
        throw Error(path.string(), "", "file is " + std::to_string(size) + " bytes, over the limit of " +
                                           std::to_string(max_bytes));
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path.string(), "", "cannot open file");
    std::vector<std::uint8_t> data(size);
    if (size && !in.read(reinterpret_cast<char*>(data.data()), std::streamsize(size)))
        throw Error(path.string(), "", "read failed");
    return data;
}

namespace {
void check_size(const std::string& name, long long w, long long h, int bytes_per_pixel, const ImageLimits& limits,
                const std::string& where = "") {
    if (w <= 0 || h <= 0) throw Error(name, where, "image has no pixels");
    if (w > limits.max_dimension || h > limits.max_dimension)
        throw Error(name, where, "image is " + std::to_string(w) + "x" + std::to_string(h) +
                                  ", over the size limit of " + std::to_string(limits.max_dimension) + " pixels per side");
    unsigned long long bytes = static_cast<unsigned long long>(w) * h * bytes_per_pixel;
    if (bytes > limits.max_decoded_bytes)
        throw Error(name, where, "image would decode to " + std::to_string(bytes) + " bytes, over the limit of " +
                                  std::to_string(limits.max_decoded_bytes));
}
}  // namespace

bool peek_image_size(std::span<const std::uint8_t> bytes, int& width, int& height) {
    if (bytes.size() > std::size_t(INT32_MAX)) return false;
    if (ktx2::is_ktx2(bytes)) {
        try {
            const ImageLimits any{INT32_MAX, SIZE_MAX};
            const ktx2::Header h = ktx2::read_header(bytes, "", any);
            width = h.width;
            height = h.height;
            return true;
        } catch (const Error&) {
            return false;
        }
    }
    // PNG: read IHDR ourselves. stb refuses to even report the size of images whose
    // decoded size passes 1 GiB, and we want to name the size and our limit instead.
    static const std::uint8_t png_sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    if (bytes.size() >= 24 && std::memcmp(bytes.data(), png_sig, 8) == 0 && std::memcmp(bytes.data() + 12, "IHDR", 4) == 0) {
        auto be32 = [&](std::size_t at) {
            return (std::uint32_t(bytes[at]) << 24) | (std::uint32_t(bytes[at + 1]) << 16) |
                   (std::uint32_t(bytes[at + 2]) << 8) | std::uint32_t(bytes[at + 3]);
        };
        std::uint32_t w = be32(16), h = be32(20);
        if (w == 0 || h == 0 || w > 0x7FFFFFFF || h > 0x7FFFFFFF) return false;
        width = int(w);
        height = int(h);
        return true;
    }
    int comp = 0;
    return stbi_info_from_memory(bytes.data(), int(bytes.size()), &width, &height, &comp) != 0;
}

namespace {
bool is_exr(std::span<const std::uint8_t> bytes);
bool is_radiance_hdr(std::span<const std::uint8_t> bytes);

std::uint32_t le_bits(std::span<const std::uint8_t> b, std::size_t at, int n) {
    std::uint32_t v = 0;
    for (int i = n - 1; i >= 0; --i) v = (v << 8) | b[at + std::size_t(i)];
    return v;
}

// WebP's canvas size (RFC 9649): the extended header (VP8X), or a lossless (VP8L) or lossy
// (VP8) bitstream's own.
bool peek_webp_size(std::span<const std::uint8_t> b, int& width, int& height) {
    if (b.size() < 30) return false;
    if (std::memcmp(b.data() + 12, "VP8X", 4) == 0) {
        width = int(le_bits(b, 24, 3)) + 1, height = int(le_bits(b, 27, 3)) + 1;
    } else if (std::memcmp(b.data() + 12, "VP8L", 4) == 0 && b[20] == 0x2F) {
        const std::uint32_t bits = le_bits(b, 21, 4);
        width = int(bits & 0x3FFF) + 1, height = int((bits >> 14) & 0x3FFF) + 1;
    } else if (std::memcmp(b.data() + 12, "VP8 ", 4) == 0 && b[23] == 0x9D && b[24] == 0x01 && b[25] == 0x2A) {
        width = int(le_bits(b, 26, 2) & 0x3FFF), height = int(le_bits(b, 28, 2) & 0x3FFF);
    } else {
        return false;
    }
    return width > 0 && height > 0;
}

std::string ktx2_format(const ktx2::Header& h) {
    std::string f = "KTX2 ";
    switch (h.encoding) {
        case ktx2::Encoding::Etc1s: f += "ETC1S"; break;
        case ktx2::Encoding::Uastc: f += "UASTC"; break;
        case ktx2::Encoding::UastcHdr: f += "UASTC HDR"; break;
        case ktx2::Encoding::Rgba8: f += h.channels == 4 ? "RGBA8" : "RGB8"; break;
        case ktx2::Encoding::Rgba16f: f += h.channels == 4 ? "RGBA16F" : "RGB16F"; break;
        case ktx2::Encoding::Rgba32f: f += h.channels == 4 ? "RGBA32F" : "RGB32F"; break;
    }
    if (h.supercompression == ktx2::Supercompression::Zstandard) f += " (Zstandard)";
    if (h.supercompression == ktx2::Supercompression::Zlib) f += " (zlib)";
    if (h.levels > 1) f += ", " + std::to_string(h.levels) + " levels";
    return f;
}
}  // namespace

ImageHeader peek_image_header(std::span<const std::uint8_t> bytes) {
    ImageHeader h;
    auto starts = [&](const char* magic, std::size_t n) { return bytes.size() >= n && std::memcmp(bytes.data(), magic, n) == 0; };
    if (ktx2::is_ktx2(bytes)) {
        h.format = "KTX2";
        try {
            const ktx2::Header k = ktx2::read_header(bytes, "", ImageLimits{INT32_MAX, SIZE_MAX});
            h.format = ktx2_format(k);
            h.width = k.width, h.height = k.height;
        } catch (const Error&) {
            h.format = "KTX2 (damaged header)";
        }
        return h;
    }
    if (starts("RIFF", 4) && bytes.size() >= 12 && std::memcmp(bytes.data() + 8, "WEBP", 4) == 0) {
        h.format = "WebP";
        if (!peek_webp_size(bytes, h.width, h.height)) h.width = h.height = 0;
        return h;
    }
    if (starts("\x89PNG", 4)) h.format = "PNG";
    else if (starts("\xFF\xD8\xFF", 3)) h.format = "JPEG";
    else if (starts("GIF8", 4)) h.format = "GIF";
    else if (starts("BM", 2)) h.format = "BMP";
    else if (is_exr(bytes)) h.format = "OpenEXR";
    else if (is_radiance_hdr(bytes)) h.format = "Radiance HDR";
    else return h;
    if (h.format == "OpenEXR" || !peek_image_size(bytes, h.width, h.height)) h.width = h.height = 0;
    return h;
}

namespace {
// Baseline and progressive 8-bit JPEG (YCbCr or greyscale) through libjpeg-turbo, about
// three times faster than stb_image: the header is read and the size checked first,
// then the pixels are decoded straight into the image. Returns false for what this
// path does not take (CMYK, 12-bit, damaged headers...), which stb_image then reads
// or rejects with its own message.
bool decode_jpeg_turbo(std::span<const std::uint8_t> bytes, const std::string& name, const ImageLimits& limits,
                       Image8& out) {
#ifdef FRESNEL_NO_TURBOJPEG
    (void)bytes, (void)name, (void)limits, (void)out;
    return false;
#else
    if (bytes.size() < 3 || bytes[0] != 0xFF || bytes[1] != 0xD8 || bytes[2] != 0xFF) return false;
    tjhandle tj = tjInitDecompress();
    if (!tj) return false;
    struct Close {
        tjhandle h;
        ~Close() { tjDestroy(h); }
    } close{tj};
    int w = 0, h = 0, subsampling = 0, colorspace = 0;
    if (tjDecompressHeader3(tj, bytes.data(), static_cast<unsigned long>(bytes.size()), &w, &h, &subsampling,
                            &colorspace) != 0)
        return false;
    if (colorspace != TJCS_YCbCr && colorspace != TJCS_GRAY && colorspace != TJCS_RGB) return false;
    check_size(name, w, h, 4, limits);
    Image8 img(w, h, 4);
    if (tjDecompress2(tj, bytes.data(), static_cast<unsigned long>(bytes.size()), img.pixels.data(), w, w * 4, h,
                      TJPF_RGBA, 0) != 0)
        return false;  // errors and warnings (a truncated stream...) go to stb_image, as before
    out = std::move(img);
    return true;
#endif
}
}  // namespace

namespace {
// The formats stb_image reads here besides PNG, JPEG and GIF (TGA, BMP) store their
// pixels raw or run-length encoded, at most 128 pixels a byte; stb_image reads zeros past the
// end of the data, so without this a 19-byte TGA header would become a 4212x3963 texture.
void check_plausible_size(std::span<const std::uint8_t> bytes, const std::string& name, int w, int h) {
    auto starts = [&](const char* magic, std::size_t n) {
        return bytes.size() >= n && std::memcmp(bytes.data(), magic, n) == 0;
    };
    if (starts("\x89PNG", 4) || starts("\xFF\xD8", 2) || starts("GIF8", 4)) return;  // compressed streams
    const std::uint64_t pixels = std::uint64_t(w) * std::uint64_t(h);
    if (pixels > std::uint64_t(bytes.size()) * 128)
        throw Error(name, "", "the image declares " + std::to_string(w) + "x" + std::to_string(h) + " pixels in " +
                                  std::to_string(bytes.size()) + " bytes of uncompressed or run-length data: "
                                  "truncated, or not an image");
}
}  // namespace

Image8 decode_image8(std::span<const std::uint8_t> bytes, const std::string& name, const ImageLimits& limits) {
    if (bytes.empty()) throw Error(name, "", "image data is empty");
    if (bytes.size() > std::size_t(INT32_MAX)) throw Error(name, "", "image data is too large");
    if (ktx2::is_ktx2(bytes)) return ktx2::decode8(bytes, name, limits);
    if (Image8 jpeg; decode_jpeg_turbo(bytes, name, limits, jpeg)) return jpeg;
    int w = 0, h = 0;
    if (!peek_image_size(bytes, w, h))
        throw Error(name, "", std::string("not a decodable image: ") + (stbi_failure_reason() ? stbi_failure_reason() : "unknown format"));
    check_size(name, w, h, 4, limits);
    check_plausible_size(bytes, name, w, h);
    int comp = 0;
    stbi_uc* px = stbi_load_from_memory(bytes.data(), int(bytes.size()), &w, &h, &comp, 4);
    if (!px) throw Error(name, "", std::string("image decoding failed: ") + (stbi_failure_reason() ? stbi_failure_reason() : "?"));
    Image8 img(w, h, 4);
    std::memcpy(img.pixels.data(), px, img.pixels.size());
    stbi_image_free(px);
    return img;
}

Image8 read_image8(const fs::path& path, const ImageLimits& limits) {
    auto bytes = read_file_bytes(path, limits.max_decoded_bytes);
    return decode_image8(bytes, path.string(), limits);
}

namespace {
ImageF decode_hdr(std::span<const std::uint8_t> bytes, const std::string& name, const ImageLimits& limits) {
    return detail::decode_radiance(bytes, name, limits);
}

#ifndef FRESNEL_NO_OPENEXR
// OpenEXR reads through this stream so that EXR data in memory is never written to disk.
class MemoryStream final : public Imf::IStream {
public:
    MemoryStream(std::span<const std::uint8_t> bytes, const std::string& name) : Imf::IStream(name.c_str()), bytes_(bytes) {}
    bool isMemoryMapped() const override { return false; }
    bool read(char c[], int n) override {
        if (n < 0 || pos_ + std::uint64_t(n) > bytes_.size()) throw std::runtime_error("unexpected end of file");
        std::memcpy(c, bytes_.data() + pos_, std::size_t(n));
        pos_ += std::uint64_t(n);
        return pos_ < bytes_.size();
    }
    std::uint64_t tellg() override { return pos_; }
    void seekg(std::uint64_t pos) override {
        if (pos > bytes_.size()) throw std::runtime_error("seek past the end of the file");
        pos_ = pos;
    }
    void clear() override {}

private:
    std::span<const std::uint8_t> bytes_;
    std::uint64_t pos_ = 0;
};

// Little-endian int32 at `at` (the caller has checked that 4 bytes are there).
std::int32_t le_i32(std::span<const std::uint8_t> b, std::size_t at) {
    return std::int32_t(std::uint32_t(b[at]) | (std::uint32_t(b[at + 1]) << 8) | (std::uint32_t(b[at + 2]) << 16) |
                        (std::uint32_t(b[at + 3]) << 24));
}

// Whether an attribute value of OpenEXR type `type` has exactly the structure its
// declared bytes allow. Types of fixed size must match it; variable ones are walked.
// Unknown types are read by OpenEXR as opaque bytes (declared size), which is safe.
bool exr_attribute_fits(const std::string& type, std::span<const std::uint8_t> v, std::size_t max_name) {
    static const std::pair<const char*, std::size_t> fixed[] = {
        {"box2i", 16}, {"box2f", 16}, {"v2i", 8}, {"v2f", 8}, {"v2d", 16}, {"v3i", 12}, {"v3f", 12}, {"v3d", 24},
        {"int", 4}, {"float", 4}, {"double", 8}, {"compression", 1}, {"lineOrder", 1}, {"envmap", 1},
        {"deepImageState", 1}, {"tiledesc", 9}, {"rational", 8}, {"timecode", 8}, {"keycode", 28},
        {"chromaticities", 32}, {"m33f", 36}, {"m44f", 64}, {"m33d", 72}, {"m44d", 128}};
    for (const auto& [t, n] : fixed)
        if (type == t) return v.size() == n;
    if (type == "chlist") {  // (name\0, 16 bytes)* then \0
        std::size_t p = 0;
        for (;;) {
            std::size_t start = p;
            while (p < v.size() && v[p] != 0) {
                if (p - start >= max_name) return false;
                ++p;
            }
            if (p >= v.size()) return false;
            if (p++ == start) return p == v.size();
            if (v.size() - p < 16) return false;
            p += 16;
        }
    }
    if (type == "stringvector") {  // (int32 length, bytes)* filling the value exactly
        std::size_t p = 0;
        while (p < v.size()) {
            if (v.size() - p < 4) return false;
            std::int32_t n = le_i32(v, p);
            p += 4;
            if (n < 0 || std::size_t(n) > v.size() - p) return false;
            p += std::size_t(n);
        }
        return true;
    }
    if (type == "floatvector") return v.size() % 4 == 0;
    if (type == "preview") {  // uint32 width, height, then RGBA8 pixels
        if (v.size() < 8) return false;
        unsigned long long w = std::uint32_t(le_i32(v, 0)), h = std::uint32_t(le_i32(v, 4));
        return 8 + 4 * w * h == v.size();
    }
    return true;  // string (read by size), idmanifest (sized), unknown types (opaque)
}

// Walks the EXR header attributes (name, type, int32 size, value) and checks that every
// declared size fits in the file, before OpenEXR sees it: OpenEXR 3.1 resizes a string
// attribute to its declared size (up to 2 GiB) before reading it, so a 1 KiB file could
// make it allocate and clear gigabytes (found by fuzz_exr; kept in fuzz/regressions/exr).
void check_exr_header(std::span<const std::uint8_t> b, const std::string& name, const ImageLimits& limits) {
    if (b.size() < 8) throw Error(name, "", "file too short for an OpenEXR header");
    const std::uint32_t flags = std::uint32_t(b[5]) | (std::uint32_t(b[6]) << 8) | (std::uint32_t(b[7]) << 16);
    const bool multipart = flags & 0x1000;
    const std::size_t max_name = (flags & 0x400) ? 255 : 31;
    std::size_t pos = 8;
    auto read_name = [&](const char* what) {
        const std::size_t start = pos;
        while (pos < b.size() && b[pos] != 0) {
            if (pos - start >= max_name)
                throw Error(name, "byte " + std::to_string(start), std::string(what) + " name is longer than " +
                                                                       std::to_string(max_name) + " characters");
            ++pos;
        }
        if (pos >= b.size()) throw Error(name, "byte " + std::to_string(start), "file ends inside the header");
        return std::string(reinterpret_cast<const char*>(b.data()) + start, pos++ - start);
    };
    for (int part = 0;; ++part) {
        if (part > 0) {  // multi-part files end the header list with an empty header
            if (pos >= b.size()) throw Error(name, "byte " + std::to_string(pos), "file ends inside the header");
            if (b[pos] == 0) break;
        }
        for (int attributes = 0;; ++attributes) {
            if (attributes > 10000) throw Error(name, "byte " + std::to_string(pos), "more than 10000 header attributes");
            const std::size_t at = pos;
            std::string attr = read_name("attribute");
            if (attr.empty()) break;
            std::string type = read_name("attribute type");
            if (b.size() - pos < 4) throw Error(name, "byte " + std::to_string(pos), "file ends inside the header");
            const std::int32_t size = le_i32(b, pos);
            pos += 4;
            if (size < 0 || std::size_t(size) > b.size() - pos)
                throw Error(name, "byte " + std::to_string(at),
                            "header attribute '" + attr + "' claims " + std::to_string(size) + " bytes, but " +
                                std::to_string(b.size() - pos) + " remain in the file");
            // OpenEXR reads attributes of known types by their structure, not by the declared
            // size, and sizes some buffers from values inside them: the structure has to fill
            // exactly the declared bytes, or the two readings of the header part ways.
            if (!exr_attribute_fits(type, b.subspan(pos, std::size_t(size)), max_name))
                throw Error(name, "byte " + std::to_string(at),
                            "header attribute '" + attr + "' of type " + type + " does not fit its " +
                                std::to_string(size) + " bytes");
            // The data window decides the size of OpenEXR's own tables and buffers: check it
            // against our limits before OpenEXR allocates them.
            if (attr == "dataWindow" && type == "box2i" && size == 16) {
                long long w = (long long)le_i32(b, pos + 8) - le_i32(b, pos) + 1, h = (long long)le_i32(b, pos + 12) - le_i32(b, pos + 4) + 1;
                check_size(name, w, h, 16, limits, "byte " + std::to_string(at) + " (dataWindow)");
            }
            pos += std::size_t(size);
        }
        if (!multipart) break;
        if (part > 1000) throw Error(name, "byte " + std::to_string(pos), "more than 1000 parts");
    }
}

ImageF decode_exr(std::span<const std::uint8_t> bytes, const std::string& name, const ImageLimits& limits) {
    check_exr_header(bytes, name, limits);
    try {
        MemoryStream stream(bytes, name);
        Imf::InputFile file(stream);
        const Imath::Box2i dw = file.header().dataWindow();
        long long w = (long long)dw.max.x - dw.min.x + 1, h = (long long)dw.max.y - dw.min.y + 1;
        check_size(name, w, h, 16, limits);
        ImageF img{static_cast<int>(w), static_cast<int>(h)};
        const auto& channels = file.header().channels();
        Imf::FrameBuffer fb;
        const char* names[4] = {"R", "G", "B", "A"};
        char* base = reinterpret_cast<char*>(img.pixels.data()) -
                     (std::ptrdiff_t(dw.min.x) + std::ptrdiff_t(dw.min.y) * w) * 4 * std::ptrdiff_t(sizeof(float));
        bool any = false;
        for (int c = 0; c < 4; ++c) {
            bool present = channels.findChannel(names[c]) != nullptr;
            any = any || (c < 3 && present);
            // Missing channels are filled: RGB with 0 (Y-only files get R=G=B below), alpha with 1.
            fb.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), 4 * sizeof(float),
                                           4 * sizeof(float) * std::size_t(w), 1, 1, c == 3 ? 1.0 : 0.0));
        }
        if (!any && channels.findChannel("Y")) {
            fb.insert("Y", Imf::Slice(Imf::FLOAT, base, 4 * sizeof(float), 4 * sizeof(float) * std::size_t(w)));
        } else if (!any) {
            throw Error(name, "", "EXR has no R, G, B or Y channel");
        }
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        if (!any)
            for (std::size_t i = 0; i < img.pixels.size(); i += 4) img.pixels[i + 1] = img.pixels[i + 2] = img.pixels[i];
        return img;
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(name, "", std::string("cannot read OpenEXR data: ") + e.what());
    }
}
#else
constexpr const char* kNoOpenExr =
    "OpenEXR is not available in this build (the web build has no OpenEXR: Debian has no WebAssembly build of it); "
    "use a Radiance .hdr file";
ImageF decode_exr(std::span<const std::uint8_t>, const std::string& name, const ImageLimits&) {
    throw Error(name, "", kNoOpenExr);
}
#endif

}  // namespace

namespace {
bool is_exr(std::span<const std::uint8_t> bytes) {
    static const std::uint8_t exr_magic[4] = {0x76, 0x2f, 0x31, 0x01};
    return bytes.size() >= 4 && std::memcmp(bytes.data(), exr_magic, 4) == 0;
}
bool is_radiance_hdr(std::span<const std::uint8_t> bytes) { return bytes.size() >= 2 && bytes[0] == '#' && bytes[1] == '?'; }
}  // namespace

bool is_linear_image(std::span<const std::uint8_t> bytes) {
    if (is_exr(bytes) || is_radiance_hdr(bytes)) return true;
    if (!ktx2::is_ktx2(bytes)) return false;
    try {
        return ktx2::read_header(bytes, "", ImageLimits{INT32_MAX, SIZE_MAX}).hdr();
    } catch (const Error&) {
        return false;
    }
}

ImageF decode_image_float(std::span<const std::uint8_t> bytes, const std::string& name, const ImageLimits& limits) {
    if (is_exr(bytes)) return decode_exr(bytes, name, limits);
    if (is_radiance_hdr(bytes)) return decode_hdr(bytes, name, limits);
    if (ktx2::is_ktx2(bytes)) return ktx2::decode_float(bytes, name, limits);
    // 8-bit formats: values / 255 (no transfer curve applied).
    Image8 img = decode_image8(bytes, name, limits);
    ImageF out(img.width, img.height);
    for (std::size_t i = 0; i < img.pixels.size(); ++i) out.pixels[i] = img.pixels[i] / 255.0f;
    return out;
}

ImageF read_image_float(const fs::path& path, const ImageLimits& limits) {
    auto bytes = read_file_bytes(path, limits.max_decoded_bytes);
    return decode_image_float(bytes, path.string(), limits);
}

namespace {
// stb's writers append to a growing buffer through this callback; nothing reaches a file until
// the bytes are whole, so a short write cannot pass unnoticed (stb ignores fwrite's result).
void append_bytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(context);
    const auto* b = static_cast<const std::uint8_t*>(data);
    out->insert(out->end(), b, b + size);
}
}  // namespace

std::vector<std::uint8_t> encode_png(const Image8& image) {
    std::vector<std::uint8_t> out;
    if (image.width <= 0 || image.height <= 0 || image.channels < 1 || image.channels > 4 ||
        image.pixels.size() != std::size_t(image.width) * image.height * image.channels ||
        !stbi_write_png_to_func(append_bytes, &out, image.width, image.height, image.channels, image.pixels.data(),
                                image.width * image.channels))
        throw Error("", "", "cannot encode a " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                                " image as PNG");
    return out;
}

std::vector<std::uint8_t> encode_hdr(const ImageF& image) {
    // stb writes RGB(A) floats; alpha is dropped by the RGBE format.
    std::vector<std::uint8_t> out;
    if (image.width <= 0 || image.height <= 0 || image.pixels.size() != std::size_t(image.width) * image.height * 4 ||
        !stbi_write_hdr_to_func(append_bytes, &out, image.width, image.height, 4, image.pixels.data()))
        throw Error("", "", "cannot encode a " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                                " image as Radiance HDR");
    return out;
}

namespace {
// `encode`'s bytes written whole or absent; an encoding error names `path`.
template <class Encode>
void write_encoded(const fs::path& path, Encode&& encode) {
    std::vector<std::uint8_t> bytes;
    try {
        bytes = encode();
    } catch (const Error& e) {
        throw Error(path.string(), "", e.reason());
    }
    write_file_atomically(path, std::span<const std::uint8_t>(bytes));
}
}  // namespace

void write_png(const fs::path& path, const Image8& image) {
    write_encoded(path, [&] { return encode_png(image); });
}

void write_hdr(const fs::path& path, const ImageF& image) {
    write_encoded(path, [&] { return encode_hdr(image); });
}

void write_exr(const fs::path& path, const ImageF& image) {
#ifdef FRESNEL_NO_OPENEXR
    (void)image;
    throw Error(path.string(), "", kNoOpenExr);
#else
    // OpenEXR checks its own writes (a full disk throws); the temporary and the rename make the
    // file whole or absent as every other writer's.
    write_file_atomically(path, [&](const fs::path& tmp) {
        try {
            Imf::Header header(image.width, image.height);
            header.compression() = Imf::ZIP_COMPRESSION;
            Imf::RgbaOutputFile file(tmp.string().c_str(), header, Imf::WRITE_RGBA);
            std::vector<Imf::Rgba> px(std::size_t(image.width) * image.height);
            for (std::size_t i = 0; i < px.size(); ++i)
                px[i] = Imf::Rgba(image.pixels[i * 4], image.pixels[i * 4 + 1], image.pixels[i * 4 + 2],
                                  image.pixels[i * 4 + 3]);
            file.setFrameBuffer(px.data(), 1, std::size_t(image.width));
            file.writePixels(image.height);
        } catch (const std::exception& e) {
            // OpenEXR's message names the temporary file: say the file the user asked for.
            std::string why = e.what();
            for (std::size_t at; (at = why.find(tmp.string())) != std::string::npos;)
                why.replace(at, tmp.string().size(), path.string());
            throw Error(path.string(), "", "cannot write OpenEXR: " + why);
        }
    });
#endif
}

}  // namespace fresnel
