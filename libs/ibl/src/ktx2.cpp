#include "fresnel/ibl/ktx2.h"

#include <Imath/half.h>

#include <cstring>
#include <fstream>

#include "fresnel/core/atomic_file.h"
#include "fresnel/core/error.h"
#include "fresnel/core/ktx2.h"
#include "fresnel/core/version.h"

namespace fresnel::ibl {
namespace fs = std::filesystem;

namespace {
constexpr std::uint8_t kIdentifier[12] = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
constexpr std::uint32_t kVkR16G16B16A16Sfloat = 97;

struct Writer {
    std::vector<std::uint8_t> out;
    void u8(std::uint8_t v) { out.push_back(v); }
    void u16(std::uint16_t v) { u8(std::uint8_t(v)), u8(std::uint8_t(v >> 8)); }
    void u32(std::uint32_t v) { u16(std::uint16_t(v)), u16(std::uint16_t(v >> 16)); }
    void u64(std::uint64_t v) { u32(std::uint32_t(v)), u32(std::uint32_t(v >> 32)); }
    void put_u64(std::size_t at, std::uint64_t v) {
        for (int i = 0; i < 8; ++i) out[at + std::size_t(i)] = std::uint8_t(v >> (8 * i));
    }
    void put_u32(std::size_t at, std::uint32_t v) {
        for (int i = 0; i < 4; ++i) out[at + std::size_t(i)] = std::uint8_t(v >> (8 * i));
    }
    void align(std::size_t a) {
        while (out.size() % a) out.push_back(0);
    }
};

// Basic data format descriptor for RGBA16F, linear, BT.709 primaries.
void write_dfd(Writer& w) {
    const std::uint32_t block_size = 24 + 16 * 4;
    w.u32(4 + block_size);  // dfdTotalSize
    w.u32(0);               // vendorId 0 (Khronos), descriptorType 0 (basic)
    w.u32(2u | (block_size << 16));  // versionNumber 2, descriptorBlockSize
    w.u8(1);  // colorModel KHR_DF_MODEL_RGBSDA
    w.u8(1);  // colorPrimaries BT709
    w.u8(1);  // transferFunction LINEAR
    w.u8(0);  // flags: straight alpha
    w.u32(0);  // texelBlockDimension 0..3 (1x1x1x1 encoded as 0)
    w.u32(8), w.u32(0);  // bytesPlane0..7: 8 bytes per texel in plane 0
    const std::uint8_t channels[4] = {0, 1, 2, 15};  // R, G, B, A
    for (int c = 0; c < 4; ++c) {
        w.u16(std::uint16_t(c * 16));  // bitOffset
        w.u8(15);                      // bitLength - 1
        w.u8(std::uint8_t(channels[c] | 0x80 | 0x40));  // channel id, FLOAT | SIGNED
        w.u32(0);                      // samplePosition0..3
        w.u32(0xBF800000u);            // sampleLower: -1.0f
        w.u32(0x3F800000u);            // sampleUpper: 1.0f
    }
}

void write_kv(Writer& w, const std::string& key, const std::string& value) {
    std::uint32_t len = std::uint32_t(key.size() + 1 + value.size() + 1);
    w.u32(len);
    for (char c : key) w.u8(std::uint8_t(c));
    w.u8(0);
    for (char c : value) w.u8(std::uint8_t(c));
    w.u8(0);
    w.align(4);
}

// levels[l][face] -> RGBA float data of size (w>>l) x (h>>l)
void write_ktx2(const fs::path& path, int width, int height, int faces,
                const std::vector<std::vector<const float*>>& levels) {
    Writer w;
    for (auto b : kIdentifier) w.u8(b);
    const std::uint32_t level_count = std::uint32_t(levels.size());
    w.u32(kVkR16G16B16A16Sfloat);
    w.u32(2);  // typeSize
    w.u32(std::uint32_t(width));
    w.u32(std::uint32_t(height));
    w.u32(0);  // pixelDepth
    w.u32(0);  // layerCount
    w.u32(std::uint32_t(faces));
    w.u32(level_count);
    w.u32(0);  // supercompressionScheme
    std::size_t index_at = w.out.size();
    for (int i = 0; i < 4; ++i) w.u32(0);  // dfd offset/length, kvd offset/length
    w.u64(0), w.u64(0);                      // sgd offset/length
    std::size_t level_index_at = w.out.size();
    for (std::uint32_t l = 0; l < level_count; ++l) w.u64(0), w.u64(0), w.u64(0);
    std::size_t dfd_at = w.out.size();
    write_dfd(w);
    std::size_t dfd_len = w.out.size() - dfd_at;
    std::size_t kvd_at = w.out.size();
    write_kv(w, "KTXwriter", "fresnel " + std::string(fresnel::version()));
    std::size_t kvd_len = w.out.size() - kvd_at;
    w.put_u32(index_at, std::uint32_t(dfd_at));
    w.put_u32(index_at + 4, std::uint32_t(dfd_len));
    w.put_u32(index_at + 8, std::uint32_t(kvd_at));
    w.put_u32(index_at + 12, std::uint32_t(kvd_len));
    // Level data, smallest level first, each aligned to 8 (lcm of texel size 8 and 4).
    for (int l = int(level_count) - 1; l >= 0; --l) {
        w.align(8);
        std::size_t at = w.out.size();
        int lw = std::max(1, width >> l), lh = std::max(1, height >> l);
        for (int f = 0; f < faces; ++f) {
            const float* src = levels[std::size_t(l)][std::size_t(f)];
            for (std::size_t i = 0; i < std::size_t(lw) * lh * 4; ++i) w.u16(Imath::half(src[i]).bits());
        }
        std::size_t len = w.out.size() - at;
        std::size_t entry = level_index_at + std::size_t(l) * 24;
        w.put_u64(entry, at);
        w.put_u64(entry + 8, len);
        w.put_u64(entry + 16, len);
    }
    write_file_atomically(path, std::span<const std::uint8_t>(w.out));  // whole or absent; throws naming `path`
}

struct Ktx2Image {
    int width = 0, height = 0, faces = 1, levels = 1;
    std::vector<std::vector<std::vector<float>>> data;  // [level][face] RGBA floats
};

// Read through fresnel/core/ktx2.h, the one KTX2 reader: RGBA16F/32F as written above, and the
// other formats it decodes (a UASTC HDR cube map, say).
Ktx2Image read_ktx2(const fs::path& path) {
    const ImageLimits limits{16384, std::size_t(1) << 31};
    const std::vector<std::uint8_t> bytes = read_file_bytes(path, limits.max_decoded_bytes);
    const ktx2::Header h = ktx2::read_header(bytes, path.string(), limits);
    if (h.layers > 1) throw Error(path.string(), "byte 32", "only 2D and cube images without layers are supported");
    Ktx2Image img;
    img.width = h.width;
    img.height = h.height;
    img.faces = h.faces;
    img.levels = h.levels;
    for (int l = 0; l < h.levels; ++l) {
        auto& faces = img.data.emplace_back();
        for (ImageF& f : ktx2::decode_level_float(bytes, l, path.string(), limits)) faces.push_back(std::move(f.pixels));
    }
    return img;
}
}  // namespace

void write_ktx2_cube(const fs::path& path, const Cubemap& cube) {
    std::vector<std::vector<const float*>> levels;
    for (const auto& lv : cube.levels) {
        std::vector<const float*> faces;
        for (const auto& f : lv.faces) faces.push_back(f.data());
        levels.push_back(faces);
    }
    write_ktx2(path, cube.size(), cube.size(), 6, levels);
}

void write_ktx2_2d(const fs::path& path, const ImageF& image) {
    write_ktx2(path, image.width, image.height, 1, {{image.pixels.data()}});
}

Cubemap read_ktx2_cube(const fs::path& path) {
    Ktx2Image img = read_ktx2(path);
    if (img.faces != 6 || img.width != img.height) throw Error(path.string(), "", "not a square cube map");
    Cubemap cube;
    for (int l = 0; l < img.levels; ++l) {
        CubeLevel lv;
        lv.size = std::max(1, img.width >> l);
        for (int f = 0; f < 6; ++f) lv.faces[std::size_t(f)] = std::move(img.data[std::size_t(l)][std::size_t(f)]);
        cube.levels.push_back(std::move(lv));
    }
    return cube;
}

ImageF read_ktx2_2d(const fs::path& path) {
    Ktx2Image img = read_ktx2(path);
    if (img.faces != 1) throw Error(path.string(), "", "not a 2D image");
    ImageF out(img.width, img.height);
    out.pixels = std::move(img.data[0][0]);
    return out;
}

}  // namespace fresnel::ibl
