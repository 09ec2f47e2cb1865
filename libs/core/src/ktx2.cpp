#include "fresnel/core/ktx2.h"

// The web build has neither libzstd nor zlib (FRESNEL_NO_ZSTD, FRESNEL_NO_ZLIB): Zstandard goes
// through our own decoder there (zstd_decoder.h), zlib-supercompressed files are an error naming it.
#ifndef FRESNEL_NO_ZSTD
#include <zstd.h>
#endif
#ifndef FRESNEL_NO_ZLIB
#include <zlib.h>
#endif

#include <algorithm>
#include <bit>
#include <cstring>
#include <optional>

#include "fresnel/core/basisu.h"
#include "fresnel/core/error.h"
#include "float16.h"
#include "zstd_decoder.h"

namespace fresnel::ktx2 {
namespace {

constexpr std::uint8_t kIdentifier[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};

// Data format descriptor colour models of the Basis Universal formats (Khronos Data Format spec).
constexpr std::uint8_t kModelEtc1s = 163, kModelUastc = 166, kModelUastcHdr4x4 = 167;
// Channel ids: ETC1S's alpha slice (AAA), UASTC's RGBA.
constexpr std::uint8_t kChannelEtc1sAaa = 15, kChannelUastcRgba = 3;

std::string byte_at(std::uint64_t at) { return "byte " + std::to_string(at); }

struct Reader {
    std::span<const std::uint8_t> bytes;
    const std::string& name;
    std::uint64_t get(std::uint64_t at, int n) const {
        if (at > bytes.size() || std::uint64_t(n) > bytes.size() - at)
            throw Error(name, byte_at(at), "unexpected end of file");
        std::uint64_t v = 0;
        for (int i = n - 1; i >= 0; --i) v = (v << 8) | bytes[std::size_t(at) + std::size_t(i)];
        return v;
    }
    std::uint32_t u32(std::uint64_t at) const { return std::uint32_t(get(at, 4)); }
    std::uint64_t u64(std::uint64_t at) const { return get(at, 8); }
    // Checks that [offset, offset + length) lies inside the file; `what` names it.
    void range(std::uint64_t offset, std::uint64_t length, std::uint64_t field, const std::string& what) const {
        if (offset > bytes.size() || length > bytes.size() - offset)
            throw Error(name, byte_at(field), what + " (" + std::to_string(length) + " bytes at " + std::to_string(offset) +
                                                  ") lies outside the file's " + std::to_string(bytes.size()) + " bytes");
    }
};

struct RawFormat {
    Encoding encoding;
    int channels;
    bool srgb;
    int bytes_per_pixel;
};

std::optional<RawFormat> raw_format(std::uint32_t vk) {
    switch (vk) {
        case 23: return RawFormat{Encoding::Rgba8, 3, false, 3};    // R8G8B8_UNORM
        case 29: return RawFormat{Encoding::Rgba8, 3, true, 3};     // R8G8B8_SRGB
        case 37: return RawFormat{Encoding::Rgba8, 4, false, 4};    // R8G8B8A8_UNORM
        case 43: return RawFormat{Encoding::Rgba8, 4, true, 4};     // R8G8B8A8_SRGB
        case 90: return RawFormat{Encoding::Rgba16f, 3, false, 6};  // R16G16B16_SFLOAT
        case 97: return RawFormat{Encoding::Rgba16f, 4, false, 8};  // R16G16B16A16_SFLOAT
        case 106: return RawFormat{Encoding::Rgba32f, 3, false, 12};  // R32G32B32_SFLOAT
        case 109: return RawFormat{Encoding::Rgba32f, 4, false, 16};  // R32G32B32A32_SFLOAT
        default: return std::nullopt;
    }
}

int level_size(int size, int level) { return std::max(1, size >> level); }

// The bytes one image of `level` holds after supercompression is undone (0: set by BasisLZ's
// own image descriptors).
std::uint64_t image_bytes(const Header& h, int level) {
    const std::uint64_t w = std::uint64_t(level_size(h.width, level)), ht = std::uint64_t(level_size(h.height, level));
    switch (h.encoding) {
        case Encoding::Etc1s: return 0;
        case Encoding::Uastc:
        case Encoding::UastcHdr: return ((w + 3) / 4) * ((ht + 3) / 4) * 16;
        default: return w * ht * std::uint64_t(raw_format(h.vk_format)->bytes_per_pixel);
    }
}

void check_limits(const std::string& name, int w, int h, std::uint64_t bytes_per_pixel, const ImageLimits& limits) {
    if (w > limits.max_dimension || h > limits.max_dimension)
        throw Error(name, byte_at(20), "image is " + std::to_string(w) + "x" + std::to_string(h) +
                                           ", over the size limit of " + std::to_string(limits.max_dimension) +
                                           " pixels per side");
    const std::uint64_t bytes = std::uint64_t(w) * std::uint64_t(h) * bytes_per_pixel;
    if (bytes > limits.max_decoded_bytes)
        throw Error(name, byte_at(20), "image would decode to " + std::to_string(bytes) + " bytes, over the limit of " +
                                           std::to_string(limits.max_decoded_bytes));
}

// The level's bytes with supercompression undone: the file's own bytes, or a buffer exactly the
// size the header promised (a stream that inflates to more or less is an error).
std::span<const std::uint8_t> level_data(const Header& h, std::span<const std::uint8_t> bytes, int level,
                                         const std::string& name, std::vector<std::uint8_t>& storage) {
    const Level& lv = h.level_index[std::size_t(level)];
    const std::span<const std::uint8_t> stored = bytes.subspan(std::size_t(lv.offset), std::size_t(lv.length));
    const std::string where = byte_at(80 + std::uint64_t(level) * 24);
    if (h.supercompression == Supercompression::None || h.supercompression == Supercompression::BasisLZ) return stored;
    storage.assign(std::size_t(lv.uncompressed_length), 0);
    if (h.supercompression == Supercompression::Zstandard) {
#ifdef FRESNEL_NO_ZSTD
        // The web build: our own decoder (zstd_decoder.h), held to libzstd by its test.
        detail::zstd_decompress(stored, storage, name, lv.offset);
#else
        const unsigned long long declared = ZSTD_getFrameContentSize(stored.data(), stored.size());
        if (declared == ZSTD_CONTENTSIZE_ERROR)
            throw Error(name, where, "level " + std::to_string(level) + " is not a Zstandard stream");
        if (declared != ZSTD_CONTENTSIZE_UNKNOWN && declared != lv.uncompressed_length)
            throw Error(name, where, "level " + std::to_string(level) + "'s Zstandard stream holds " +
                                         std::to_string(declared) + " bytes, the level index says " +
                                         std::to_string(lv.uncompressed_length));
        const std::size_t n = ZSTD_decompress(storage.data(), storage.size(), stored.data(), stored.size());
        if (ZSTD_isError(n))
            throw Error(name, where, "level " + std::to_string(level) + ": Zstandard: " + ZSTD_getErrorName(n));
        if (n != storage.size())
            throw Error(name, where, "level " + std::to_string(level) + "'s Zstandard stream holds " +
                                         std::to_string(n) + " bytes, the level index says " + std::to_string(storage.size()));
#endif
    } else {
#ifdef FRESNEL_NO_ZLIB
        throw Error(name, where, "zlib-supercompressed KTX2 is not supported in this build (no zlib)");
#else
        uLongf n = uLongf(storage.size());
        const int rc = uncompress(storage.data(), &n, stored.data(), uLong(stored.size()));
        if (rc != Z_OK || n != storage.size())
            throw Error(name, where, "level " + std::to_string(level) + ": the zlib stream does not inflate to the " +
                                         std::to_string(storage.size()) + " bytes the level index says");
#endif
    }
    return storage;
}

struct Pixels {
    Image8 ldr;
    ImageF hdr;
    bool is_hdr = false;
};

// Decodes image `index` (layer * faces + face) of `level`.
class Decoder {
public:
    Decoder(std::span<const std::uint8_t> bytes, const std::string& name, const ImageLimits& limits)
        : bytes_(bytes), name_(name), header_(read_header(bytes, name, limits)) {
        if (header_.encoding == Encoding::Etc1s) {
            const auto images = std::uint32_t(header_.levels * header_.layers * header_.faces);
            etc1s_.emplace(header_.global_data, images, name);
        }
    }
    const Header& header() const { return header_; }

    Pixels decode(int level, int index) {
        if (level != cached_level_) {  // each level's supercompression is undone once
            data_ = level_data(header_, bytes_, level, name_, storage_);
            cached_level_ = level;
        }
        const auto data = data_;
        const int w = level_size(header_.width, level), h = level_size(header_.height, level);
        Pixels out;
        if (header_.encoding == Encoding::Etc1s) {
            const auto image = std::uint32_t(level * header_.layers * header_.faces + index);
            out.ldr = Image8(w, h, 4);
            etc1s_->transcode(image, data, w, h, out.ldr.pixels.data());
            return out;
        }
        const std::uint64_t size = image_bytes(header_, level);
        const auto image = data.subspan(std::size_t(size) * std::size_t(index), std::size_t(size));
        const std::string where = name_ + " level " + std::to_string(level) + " image " + std::to_string(index);
        switch (header_.encoding) {
            case Encoding::Uastc:
                out.ldr = Image8(w, h, 4);
                basisu::transcode_uastc(image, w, h, out.ldr.pixels.data(), where);
                break;
            case Encoding::UastcHdr:
                out.is_hdr = true;
                out.hdr = ImageF(w, h);
                basisu::transcode_uastc_hdr(image, w, h, out.hdr.pixels.data(), where);
                break;
            case Encoding::Rgba8: {
                out.ldr = Image8(w, h, 4);
                const int c = header_.channels;
                for (std::size_t p = 0; p < std::size_t(w) * std::size_t(h); ++p) {
                    for (int k = 0; k < 4; ++k) out.ldr.pixels[p * 4 + std::size_t(k)] = k < c ? image[p * std::size_t(c) + std::size_t(k)] : 255;
                }
                break;
            }
            case Encoding::Rgba16f:
            case Encoding::Rgba32f: {
                out.is_hdr = true;
                out.hdr = ImageF(w, h);
                const int c = header_.channels;
                const bool half = header_.encoding == Encoding::Rgba16f;
                for (std::size_t p = 0; p < std::size_t(w) * std::size_t(h); ++p) {
                    for (int k = 0; k < 4; ++k) {
                        float v = 1.0f;
                        if (k < c) {
                            const std::size_t at = (p * std::size_t(c) + std::size_t(k)) * (half ? 2 : 4);
                            if (half) {
                                v = detail::half_to_float(std::uint16_t(image[at] | (image[at + 1] << 8)));
                            } else {
                                std::uint32_t bits = 0;
                                for (int b = 3; b >= 0; --b) bits = (bits << 8) | image[at + std::size_t(b)];
                                std::memcpy(&v, &bits, sizeof v);
                            }
                        }
                        out.hdr.pixels[p * 4 + std::size_t(k)] = v;
                    }
                }
                break;
            }
            case Encoding::Etc1s: break;  // above
        }
        return out;
    }

private:
    std::span<const std::uint8_t> bytes_;
    const std::string& name_;
    Header header_;
    std::optional<basisu::Etc1sTranscoder> etc1s_;
    int cached_level_ = -1;
    std::vector<std::uint8_t> storage_;
    std::span<const std::uint8_t> data_;
};

ImageF to_float(Pixels&& p) {
    if (p.is_hdr) return std::move(p.hdr);
    ImageF out(p.ldr.width, p.ldr.height);
    for (std::size_t i = 0; i < p.ldr.pixels.size(); ++i) out.pixels[i] = p.ldr.pixels[i] / 255.0f;
    return out;
}

}  // namespace

bool is_ktx2(std::span<const std::uint8_t> bytes) {
    return bytes.size() >= 12 && std::memcmp(bytes.data(), kIdentifier, 12) == 0;
}

Header read_header(std::span<const std::uint8_t> bytes, const std::string& name, const ImageLimits& limits) {
    if (!is_ktx2(bytes)) throw Error(name, byte_at(0), "not a KTX 2.0 file");
    const Reader r{bytes, name};
    Header h;
    h.vk_format = r.u32(12);
    const std::uint32_t width = r.u32(20), height = r.u32(24), depth = r.u32(28), layers = r.u32(32),
                        faces = r.u32(36), levels = r.u32(40), scheme = r.u32(44);
    if (width == 0) throw Error(name, byte_at(20), "the image has no pixels (width 0)");
    if (height == 0) throw Error(name, byte_at(24), "1D textures are not supported");
    if (depth > 1) throw Error(name, byte_at(28), "3D textures are not supported");
    if (width > 0x7FFFFFFF || height > 0x7FFFFFFF) throw Error(name, byte_at(20), "image size out of range");
    if (faces != 1 && faces != 6) throw Error(name, byte_at(36), "faceCount is " + std::to_string(faces) + " (1 or 6)");
    if (faces == 6 && width != height) throw Error(name, byte_at(20), "a cube map whose faces are not square");
    h.width = int(width);
    h.height = int(height);
    h.faces = int(faces);
    h.layers = int(std::max<std::uint32_t>(1, layers));
    const int max_levels = std::bit_width(std::max(width, height));
    if (levels > std::uint32_t(max_levels))
        throw Error(name, byte_at(40), "levelCount " + std::to_string(levels) + " is more than a " + std::to_string(width) +
                                           "x" + std::to_string(height) + " image has (" + std::to_string(max_levels) + ")");
    h.levels = int(std::max<std::uint32_t>(1, levels));
    if (scheme > 3) throw Error(name, byte_at(44), "unknown supercompression scheme " + std::to_string(scheme));
    h.supercompression = Supercompression(scheme);

    // Data format descriptor: the colour model, transfer function and channels.
    const std::uint32_t dfd_offset = r.u32(48), dfd_length = r.u32(52);
    r.range(dfd_offset, dfd_length, 48, "the data format descriptor");
    if (dfd_length < 4 + 24) throw Error(name, byte_at(52), "the data format descriptor is too short");
    const std::uint32_t block_size = r.u32(dfd_offset + 8) >> 16;
    if (block_size < 24 || block_size > dfd_length - 4 || (block_size - 24) % 16 != 0)
        throw Error(name, byte_at(dfd_offset + 8), "bad descriptor block size " + std::to_string(block_size));
    const std::uint8_t model = bytes[dfd_offset + 12], transfer = bytes[dfd_offset + 14];
    const int samples = int((block_size - 24) / 16);
    auto channel = [&](int s) { return std::uint8_t(bytes[dfd_offset + 28 + std::size_t(s) * 16 + 3] & 0x0F); };
    h.srgb = transfer == 2;

    if (h.vk_format == 0) {
        if (model == kModelEtc1s) {
            h.encoding = Encoding::Etc1s;
            if (h.supercompression != Supercompression::BasisLZ)
                throw Error(name, byte_at(44), "ETC1S data without BasisLZ supercompression");
            h.has_alpha = samples >= 2 && channel(1) == kChannelEtc1sAaa;
        } else if (model == kModelUastc || model == kModelUastcHdr4x4) {
            h.encoding = model == kModelUastc ? Encoding::Uastc : Encoding::UastcHdr;
            h.has_alpha = model == kModelUastc && samples >= 1 && channel(0) == kChannelUastcRgba;
        } else {
            throw Error(name, byte_at(dfd_offset + 12), "unsupported colour model " + std::to_string(model) +
                                                            " (fresnel reads ETC1S, UASTC and UASTC HDR 4x4)");
        }
    } else if (auto raw = raw_format(h.vk_format)) {
        h.encoding = raw->encoding;
        h.channels = raw->channels;
        h.has_alpha = raw->channels == 4;
        h.srgb = raw->srgb;
    } else {
        throw Error(name, byte_at(12), "unsupported vkFormat " + std::to_string(h.vk_format) +
                                           " (fresnel reads Basis Universal ETC1S/UASTC and RGB(A) 8-bit, 16-bit and "
                                           "32-bit float)");
    }
    if (h.supercompression == Supercompression::BasisLZ && h.encoding != Encoding::Etc1s)
        throw Error(name, byte_at(44), "BasisLZ supercompression of data that is not ETC1S");
    check_limits(name, h.width, h.height, h.hdr() ? 16 : 4, limits);

    const std::uint64_t sgd_offset = r.u64(64), sgd_length = r.u64(72);
    r.range(sgd_offset, sgd_length, 64, "the supercompression global data");
    if (h.encoding == Encoding::Etc1s) {
        if (sgd_length == 0) throw Error(name, byte_at(72), "ETC1S data without BasisLZ global data");
        h.global_data = bytes.subspan(std::size_t(sgd_offset), std::size_t(sgd_length));
    }
    const std::uint32_t kvd_offset = r.u32(56), kvd_length = r.u32(60);
    r.range(kvd_offset, kvd_length, 56, "the key/value data");

    // Level index: every level inside the file, and of the size its dimensions give.
    const std::uint64_t images = std::uint64_t(h.layers) * std::uint64_t(h.faces);
    for (int l = 0; l < h.levels; ++l) {
        const std::uint64_t entry = 80 + std::uint64_t(l) * 24;
        Level lv{r.u64(entry), r.u64(entry + 8), r.u64(entry + 16)};
        r.range(lv.offset, lv.length, entry, "level " + std::to_string(l));
        const std::uint64_t expected = image_bytes(h, l) * images;
        if (h.encoding != Encoding::Etc1s) {
            const std::uint64_t held =
                h.supercompression == Supercompression::None ? lv.length : lv.uncompressed_length;
            if (held != expected)
                throw Error(name, byte_at(entry), "level " + std::to_string(l) + " holds " + std::to_string(held) +
                                                      " bytes; a " + std::to_string(level_size(h.width, l)) + "x" +
                                                      std::to_string(level_size(h.height, l)) + " level of " +
                                                      std::to_string(images) + " image(s) takes " + std::to_string(expected));
            if (expected > limits.max_decoded_bytes)
                throw Error(name, byte_at(entry), "level " + std::to_string(l) + " would take " + std::to_string(expected) +
                                                      " bytes, over the limit of " + std::to_string(limits.max_decoded_bytes));
        }
        h.level_index.push_back(lv);
    }
    return h;
}

Image8 decode8(std::span<const std::uint8_t> bytes, const std::string& name, const ImageLimits& limits) {
    Decoder d(bytes, name, limits);
    if (d.header().hdr())
        throw Error(name, "", "an HDR KTX2 texture where an 8-bit image is expected");
    return std::move(d.decode(0, 0).ldr);
}

ImageF decode_float(std::span<const std::uint8_t> bytes, const std::string& name, const ImageLimits& limits) {
    Decoder d(bytes, name, limits);
    return to_float(d.decode(0, 0));
}

std::vector<ImageF> decode_level_float(std::span<const std::uint8_t> bytes, int level, const std::string& name,
                                       const ImageLimits& limits) {
    Decoder d(bytes, name, limits);
    if (level < 0 || level >= d.header().levels)
        throw Error(name, "", "no level " + std::to_string(level) + " (the file has " + std::to_string(d.header().levels) + ")");
    std::vector<ImageF> out;
    for (int i = 0; i < d.header().layers * d.header().faces; ++i) out.push_back(to_float(d.decode(level, i)));
    return out;
}

}  // namespace fresnel::ktx2
