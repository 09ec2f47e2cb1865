#include "radiance_hdr.h"

#include <array>
#include <cmath>
#include <cstring>
#include <string_view>
#include <vector>

#include "fresnel/core/error.h"

namespace fresnel::detail {
namespace {

constexpr std::size_t kMaxHeaderBytes = 64 * 1024;  // real headers are a few hundred bytes

struct Header {
    int width = 0, height = 0;
    bool flip_y = false;  // "+Y": the first scanline in the file is the bottom row
    bool flip_x = false;  // "-X": each scanline runs right to left
    std::size_t data_offset = 0;
};

std::string at_byte(std::size_t pos) { return "byte " + std::to_string(pos); }

// Parses everything up to the first scanline. Returns an empty string on success,
// otherwise the reason (and `fault` the byte offset it refers to).
std::string parse_header(std::span<const std::uint8_t> b, Header& h, std::size_t& fault) {
    fault = 0;
    if (b.size() < 2 || b[0] != '#' || b[1] != '?') return "not a Radiance .hdr file (no '#?' signature)";
    std::size_t pos = 0;
    auto next_line = [&](std::string_view& line) {
        std::size_t start = pos;
        while (pos < b.size() && b[pos] != '\n') {
            if (pos - start > kMaxHeaderBytes) return false;
            ++pos;
        }
        if (pos >= b.size()) return false;
        line = std::string_view(reinterpret_cast<const char*>(b.data()) + start, pos - start);
        ++pos;  // the '\n'
        return true;
    };
    std::string_view line;
    if (!next_line(line)) return "header has no end of line";
    // Header variables up to the first empty line.
    for (;;) {
        fault = pos;
        if (pos > kMaxHeaderBytes) return "header is longer than " + std::to_string(kMaxHeaderBytes) + " bytes";
        if (!next_line(line)) return "header does not end (no empty line before the resolution)";
        if (line.empty()) break;
        if (line.starts_with("FORMAT=")) {
            std::string_view fmt = line.substr(7);
            while (!fmt.empty() && (fmt.back() == ' ' || fmt.back() == '\r')) fmt.remove_suffix(1);
            if (fmt == "32-bit_rle_xyze") return "XYZE pixels are not supported (only FORMAT=32-bit_rle_rgbe)";
            if (fmt != "32-bit_rle_rgbe") return "unknown pixel format '" + std::string(fmt.substr(0, 40)) + "'";
        }
    }
    fault = pos;
    if (!next_line(line)) return "missing resolution line";
    // Resolution: "-Y H +X W" (the usual), or any Y-major combination of signs.
    char ysign = 0, xsign = 0;
    long long hh = 0, ww = 0;
    std::size_t i = 0;
    auto skip_spaces = [&] {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    };
    auto axis = [&](char want, char& sign) {
        skip_spaces();
        if (i + 1 >= line.size() || (line[i] != '-' && line[i] != '+') || line[i + 1] != want) return false;
        sign = line[i];
        i += 2;
        return true;
    };
    auto number = [&](long long& v) {
        skip_spaces();
        std::size_t start = i;
        while (i < line.size() && line[i] >= '0' && line[i] <= '9' && i - start < 10) v = v * 10 + (line[i++] - '0');
        return i > start && (i >= line.size() || line[i] < '0' || line[i] > '9');
    };
    if (!axis('Y', ysign) || !number(hh) || !axis('X', xsign) || !number(ww)) {
        if (!line.empty() && (line[0] == '-' || line[0] == '+') && line.size() > 1 && line[1] == 'X')
            return "column-major (X first) orientation is not supported";
        return "bad resolution line '" + std::string(line.substr(0, 40)) + "' (expected '-Y HEIGHT +X WIDTH')";
    }
    if (hh <= 0 || ww <= 0) return "image has no pixels";
    if (hh > 0x7FFFFFFF || ww > 0x7FFFFFFF) return "image size is out of range";
    h.width = int(ww);
    h.height = int(hh);
    h.flip_y = ysign == '+';
    h.flip_x = xsign == '-';
    h.data_offset = pos;
    return {};
}

}  // namespace

bool radiance_info(std::span<const std::uint8_t> bytes, int& width, int& height, std::string& why) {
    Header h;
    std::size_t fault = 0;
    why = parse_header(bytes, h, fault);
    if (!why.empty()) return false;
    width = h.width;
    height = h.height;
    return true;
}

ImageF decode_radiance(std::span<const std::uint8_t> b, const std::string& name, const ImageLimits& limits) {
    Header h;
    std::size_t fault = 0;
    if (std::string why = parse_header(b, h, fault); !why.empty()) throw Error(name, at_byte(fault), why);
    if (h.width > limits.max_dimension || h.height > limits.max_dimension)
        throw Error(name, "", "image is " + std::to_string(h.width) + "x" + std::to_string(h.height) +
                                  ", over the size limit of " + std::to_string(limits.max_dimension) + " pixels per side");
    const unsigned long long decoded = 16ull * unsigned(h.width) * unsigned(h.height);
    if (decoded > limits.max_decoded_bytes)
        throw Error(name, "", "image would decode to " + std::to_string(decoded) + " bytes, over the limit of " +
                                  std::to_string(limits.max_decoded_bytes));
    // Every scanline takes at least 4 bytes of file (one pixel, or the run-length
    // header), so a file far too short for its claimed height is refused before the
    // output is allocated.
    if ((b.size() - h.data_offset) / 4 < std::size_t(h.height))
        throw Error(name, at_byte(b.size()), "file ends before the pixel data for " + std::to_string(h.width) + "x" +
                                                 std::to_string(h.height) + " pixels");

    // Scale for each exponent byte: value = mantissa * 2^(e - 128 - 8); e = 0 is black.
    std::array<float, 256> scale{};
    for (int e = 1; e < 256; ++e) scale[std::size_t(e)] = std::ldexp(1.0f, e - 136);

    const int W = h.width;
    ImageF img(W, h.height);
    std::vector<std::uint8_t> rgbe(std::size_t(W) * 4);  // one scanline, interleaved
    std::vector<std::uint8_t> planes(std::size_t(W) * 4);  // one scanline, channel-planar
    std::size_t pos = h.data_offset;
    auto truncated = [&](int row) {
        return Error(name, at_byte(pos), "file ends inside scanline " + std::to_string(row) + " of " + std::to_string(h.height));
    };

    for (int row = 0; row < h.height; ++row) {
        const bool adaptive_rle = W >= 8 && W <= 0x7FFF && pos + 4 <= b.size() && b[pos] == 2 && b[pos + 1] == 2 &&
                                  (b[pos + 2] & 0x80) == 0;
        if (adaptive_rle) {
            const int len = (int(b[pos + 2]) << 8) | b[pos + 3];
            if (len != W)
                throw Error(name, at_byte(pos), "scanline " + std::to_string(row) + " says it has " + std::to_string(len) +
                                                    " pixels, the image is " + std::to_string(W) + " wide");
            pos += 4;
            for (int ch = 0; ch < 4; ++ch) {
                std::uint8_t* plane = planes.data() + std::size_t(ch) * W;
                int x = 0;
                while (x < W) {
                    if (pos >= b.size()) throw truncated(row);
                    const std::size_t record = pos;
                    int count = b[pos++];
                    if (count > 128) {  // a run: one value repeated
                        count -= 128;
                        if (count > W - x)
                            throw Error(name, at_byte(record), "run of " + std::to_string(count) + " overflows scanline " + std::to_string(row));
                        if (pos >= b.size()) throw truncated(row);
                        std::memset(plane + x, b[pos++], std::size_t(count));
                    } else {  // literal bytes
                        if (count == 0)
                            throw Error(name, at_byte(record), "run-length record of length 0 in scanline " + std::to_string(row));
                        if (count > W - x)
                            throw Error(name, at_byte(record), "literal run of " + std::to_string(count) + " overflows scanline " + std::to_string(row));
                        if (b.size() - pos < std::size_t(count)) throw truncated(row);
                        std::memcpy(plane + x, b.data() + pos, std::size_t(count));
                        pos += std::size_t(count);
                    }
                    x += count;
                }
            }
            for (int x = 0; x < W; ++x)
                for (int ch = 0; ch < 4; ++ch) rgbe[std::size_t(x) * 4 + ch] = planes[std::size_t(ch) * W + x];
        } else {
            // Flat RGBE quads, with the old run-length form: (1,1,1,n) repeats the previous
            // pixel n times, n shifted left by 8 bits for each consecutive repeat record.
            int x = 0, shift = 0;
            while (x < W) {
                if (b.size() - pos < 4) throw truncated(row);
                const std::uint8_t* q = b.data() + pos;
                if (q[0] == 1 && q[1] == 1 && q[2] == 1) {
                    if (x == 0) throw Error(name, at_byte(pos), "repeat record with no pixel before it in scanline " + std::to_string(row));
                    if (shift > 16) throw Error(name, at_byte(pos), "too many consecutive repeat records in scanline " + std::to_string(row));
                    const long long count = (long long)q[3] << shift;
                    if (count > W - x)
                        throw Error(name, at_byte(pos), "repeat of " + std::to_string(count) + " overflows scanline " + std::to_string(row));
                    for (long long k = 0; k < count; ++k, ++x) std::memcpy(&rgbe[std::size_t(x) * 4], &rgbe[std::size_t(x - 1) * 4], 4);
                    shift += 8;
                } else {
                    std::memcpy(&rgbe[std::size_t(x) * 4], q, 4);
                    ++x;
                    shift = 0;
                }
                pos += 4;
            }
        }
        const int out_row = h.flip_y ? h.height - 1 - row : row;
        float* out = img.pixels.data() + std::size_t(out_row) * W * 4;
        for (int x = 0; x < W; ++x) {
            const std::uint8_t* p = &rgbe[std::size_t(x) * 4];
            const float s = scale[p[3]];
            float* o = out + std::size_t(h.flip_x ? W - 1 - x : x) * 4;
            o[0] = float(p[0]) * s;
            o[1] = float(p[1]) * s;
            o[2] = float(p[2]) * s;
            o[3] = 1.0f;
        }
    }
    return img;
}

}  // namespace fresnel::detail
