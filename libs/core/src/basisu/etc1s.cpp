// ETC1S with BasisLZ supercompression (KHR_texture_basisu): KTX2 global data and slices to RGBA8.
//
// Written from the KTX 2.0 specification (section "BasisLZ Global Data" and the appendix
// "BasisLZ/ETC1S Bitstream Specification") and the Basis Universal ".basis File Format and ETC1S
// Texture Video Specification"; "basis §N" below names that document's sections.
//
// Two stages. The constructor decodes what every image shares: the endpoint codebook (a 5:5:5
// base colour and a 3-bit intensity table per entry, §7), the selector codebook (4x4 texels of
// 2 bits, §8) and the four Huffman models the slices are coded with (§9). transcode() then walks
// one slice's blocks (§10.3): each block gets an endpoint index (predicted from its left, upper or
// upper-left neighbour, or a delta from the previous block) and a selector index (a codebook
// entry or a slot of the approximate move-to-front history, with runs), and the pair is expanded
// as the ETC1 differential block it stands for, both subblocks sharing one colour.
//
// Hostile input: every read is bounds-checked (a bit read past a section's end is an error, not
// a zero), Huffman codes must be complete (RFC 1951 style; a lone symbol excepted, as the
// reference allows), every index is checked against its codebook and every run against the
// blocks left. Allocations are bounded by the 16-bit codebook sizes, 14-bit table sizes, the
// 13-bit history size and the image width. Texture video P-frames are rejected.
#include "fresnel/core/basisu.h"

#include <algorithm>
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "fresnel/core/error.h"

namespace fresnel::basisu {
namespace {

// Thrown by the bit-level decoders; the caller turns it into a fresnel::Error naming the place.
struct Corrupt {
    std::string reason;
};

// Reads bits least significant first within each byte (basis §6: codes are stored LSB to MSB).
class BitReader {
public:
    explicit BitReader(std::span<const std::uint8_t> data) : data_(data) {}

    std::uint32_t bit() {
        if (pos_ >= data_.size() * 8) throw Corrupt{"the data ends in the middle of a value"};
        const std::uint32_t b = (data_[pos_ >> 3] >> (pos_ & 7)) & 1u;
        ++pos_;
        return b;
    }
    // `n` (at most 16) bits, the first read being the least significant.
    std::uint32_t bits(int n) {
        std::uint32_t v = 0;
        for (int i = 0; i < n; ++i) v |= bit() << i;
        return v;
    }
    std::size_t byte_pos() const { return pos_ / 8; }

private:
    std::span<const std::uint8_t> data_;
    std::size_t pos_ = 0;
};

// A canonical Huffman code (RFC 1951 section 3.2.2), decoded a bit at a time: the first bit read
// is the code's most significant, as in Deflate.
class Huffman {
public:
    static constexpr int kMaxLength = 16;

    // `lengths`: one code length (0 = unused, at most 16) per symbol.
    void build(const std::vector<std::uint8_t>& lengths) {
        count_.fill(0);
        for (auto l : lengths) ++count_[l];
        count_[0] = 0;
        std::size_t used = 0;
        long long left = 1;  // code space left at the current length
        for (int len = 1; len <= kMaxLength; ++len) {
            used += count_[len];
            left = left * 2 - count_[len];
            if (left < 0) throw Corrupt{"a Huffman table's code lengths are oversubscribed"};
        }
        if (left > 0 && used > 1) throw Corrupt{"a Huffman table's code lengths are incomplete"};
        std::array<std::size_t, kMaxLength + 2> offset{};
        for (int len = 1; len <= kMaxLength; ++len) offset[len + 1] = offset[len] + count_[len];
        symbols_.assign(used, 0);
        for (std::size_t s = 0; s < lengths.size(); ++s)
            if (lengths[s]) symbols_[offset[lengths[s]]++] = static_cast<std::uint16_t>(s);
    }

    std::uint32_t decode(BitReader& r) const {
        if (symbols_.empty()) throw Corrupt{"a symbol is coded with an empty Huffman table"};
        std::uint32_t code = 0, first = 0, index = 0;
        for (int len = 1; len <= kMaxLength; ++len) {
            code |= r.bit();
            const std::uint32_t n = count_[len];
            if (code - first < n) return symbols_[index + code - first];
            index += n;
            first = (first + n) << 1;
            code <<= 1;
        }
        throw Corrupt{"a Huffman code matches no symbol"};  // only possible in a lone-symbol table
    }

private:
    std::array<std::uint32_t, kMaxLength + 1> count_{};
    std::vector<std::uint16_t> symbols_;  // ordered by code
};

// basis §6 (KTX "Compressed Huffman Tables"): a table's code lengths, themselves RLE and Huffman
// coded as in Deflate's dynamic blocks.
Huffman read_huffman(BitReader& r) {
    static constexpr std::uint8_t kOrder[21] = {17, 18, 19, 20, 0, 8,  7, 9,  6, 10, 5,
                                                11, 4,  12, 3,  13, 2, 14, 1, 15, 16};
    Huffman table;
    const std::uint32_t total = r.bits(14);
    if (total == 0) return table;  // an empty table; only an error if a symbol is read from it
    const std::uint32_t n = r.bits(5);
    if (n < 1 || n > 21) throw Corrupt{"a Huffman table has " + std::to_string(n) + " code length codes (1-21)"};
    std::vector<std::uint8_t> cl(21, 0);
    for (std::uint32_t i = 0; i < n; ++i) cl[kOrder[i]] = static_cast<std::uint8_t>(r.bits(3));
    Huffman cl_code;
    cl_code.build(cl);

    std::vector<std::uint8_t> lengths(total, 0);
    std::uint32_t cur = 0;
    while (cur < total) {
        const std::uint32_t sym = cl_code.decode(r);
        if (sym <= 16) {
            lengths[cur++] = static_cast<std::uint8_t>(sym);
            continue;
        }
        // 17, 18: runs of zero lengths (3-10, 11-138); 19, 20: repeats of the last length (3-6, 7-134).
        const std::uint32_t run = sym == 17   ? r.bits(3) + 3
                                  : sym == 18 ? r.bits(7) + 11
                                  : sym == 19 ? r.bits(2) + 3
                                              : r.bits(7) + 7;
        std::uint8_t value = 0;
        if (sym >= 19) {
            if (cur == 0 || lengths[cur - 1] == 0)
                throw Corrupt{"a Huffman code length repeat has no length to repeat"};
            value = lengths[cur - 1];
        }
        if (run > total - cur) throw Corrupt{"a Huffman code length run passes the table's end"};
        std::fill_n(lengths.begin() + cur, run, value);
        cur += run;
    }
    table.build(lengths);
    return table;
}

// basis §10.2: a count sent in chunks of `chunk` bits, each followed by a "more" bit.
std::uint64_t read_vlc(BitReader& r, int chunk) {
    std::uint64_t v = 0;
    for (int shift = 0;; shift += chunk) {
        const std::uint32_t s = r.bits(chunk + 1);
        v |= static_cast<std::uint64_t>(s & ((1u << chunk) - 1)) << shift;
        if (!(s >> chunk)) return v;
        if (shift + chunk >= 32) throw Corrupt{"a run length is longer than 32 bits"};
    }
}

// One endpoint codebook entry: the ETC1 differential base colour (5 bits per channel; the
// delta is always 0) and the intensity table index both subblocks use.
struct Endpoint {
    std::array<std::uint8_t, 3> color5;
    std::uint8_t inten;
};

// KTX "ETC1S Endpoint Codebooks" (basis §7): DPCM-coded intensities and colours.
std::vector<Endpoint> read_endpoints(BitReader& r, std::uint32_t count) {
    Huffman color[3];
    for (auto& c : color) c = read_huffman(r);  // for previous values 0-9, 10-21, 22-31
    const Huffman inten = read_huffman(r);
    const bool grayscale = r.bit() != 0;
    std::vector<Endpoint> out(count);
    std::uint32_t prev_inten = 0;
    std::array<std::uint32_t, 3> prev = {16, 16, 16};
    for (auto& e : out) {
        prev_inten = (prev_inten + inten.decode(r)) & 7;
        e.inten = static_cast<std::uint8_t>(prev_inten);
        for (int c = 0; c < (grayscale ? 1 : 3); ++c) {
            const Huffman& model = color[prev[c] <= 9 ? 0 : prev[c] <= 21 ? 1 : 2];
            prev[c] = (prev[c] + model.decode(r)) & 31;
        }
        for (int c = 0; c < 3; ++c) e.color5[c] = static_cast<std::uint8_t>(prev[grayscale ? 0 : c]);
    }
    return out;
}

// KTX "ETC1S Selector Codebooks" (basis §8): 16 2-bit selectors per entry, row y in byte y of
// the packed value, texel x in bits 2x..2x+1 of its row; raw or XOR-delta coded per byte.
std::vector<std::uint32_t> read_selectors(BitReader& r, std::uint32_t count) {
    if (r.bits(2) != 0) throw Corrupt{"the reserved bits are not zero (global selector codebooks are not supported)"};
    const bool raw = r.bit() != 0;
    Huffman delta;
    if (!raw) delta = read_huffman(r);
    std::vector<std::uint32_t> out(count);
    std::array<std::uint32_t, 4> prev{};
    for (std::uint32_t i = 0; i < count; ++i) {
        std::uint32_t packed = 0;
        for (int j = 0; j < 4; ++j) {
            std::uint32_t byte = raw || i == 0 ? r.bits(8) : delta.decode(r);
            if (byte > 255) throw Corrupt{"a selector delta is over 255"};
            if (!raw && i > 0) byte ^= prev[j];
            prev[j] = byte;
            packed |= byte << (8 * j);
        }
        out[i] = packed;
    }
    return out;
}

// The ETC1 intensity modifier table (Khronos Data Format, ETC1), its columns in selector order:
// basis selector 0..3 stands for -b, -a, +a, +b (ETC1 pixel indices 3, 2, 0, 1).
constexpr int kIntensity[8][4] = {{-8, -2, 2, 8},       {-17, -5, 5, 17},     {-29, -9, 9, 29},
                                  {-42, -13, 13, 42},   {-60, -18, 18, 60},   {-80, -24, 24, 80},
                                  {-106, -33, 33, 106}, {-183, -47, 47, 183}};

// Writes one block's visible texels: its RGB (alpha 255), or for an alpha slice its green into A.
void write_block(std::uint8_t* rgba, int width, int height, std::uint32_t bx, std::uint32_t by, const Endpoint& e,
                 std::uint32_t selectors, bool alpha) {
    std::uint8_t colors[4][3];
    for (int s = 0; s < 4; ++s)
        for (int c = 0; c < 3; ++c) {
            const int base = (e.color5[c] << 3) | (e.color5[c] >> 2);  // 5 to 8 bits, as ETC1 expands
            colors[s][c] = static_cast<std::uint8_t>(std::clamp(base + kIntensity[e.inten][s], 0, 255));
        }
    const int w = std::min(4, width - static_cast<int>(bx * 4)), h = std::min(4, height - static_cast<int>(by * 4));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::uint8_t* c = colors[(selectors >> (8 * y + 2 * x)) & 3];
            std::uint8_t* p = rgba + ((static_cast<std::size_t>(by) * 4 + y) * width + bx * 4 + x) * 4;
            if (alpha) {
                p[3] = c[1];
            } else {
                p[0] = c[0], p[1] = c[1], p[2] = c[2], p[3] = 255;
            }
        }
}

// KTX "BasisLZ Global Data": one image descriptor.
struct ImageDesc {
    std::uint32_t flags, rgb_offset, rgb_length, alpha_offset, alpha_length;
};
constexpr std::uint32_t kPFrame = 0x02;  // imageFlags: a texture video P-frame

std::uint32_t read_le(std::span<const std::uint8_t> d, std::size_t at, int bytes) {
    std::uint32_t v = 0;
    for (int i = 0; i < bytes; ++i) v |= static_cast<std::uint32_t>(d[at + i]) << (8 * i);
    return v;
}

}  // namespace

struct Etc1sTranscoder::Impl {
    std::string name;
    std::vector<ImageDesc> images;
    std::vector<Endpoint> endpoints;
    std::vector<std::uint32_t> selectors;
    // basis §9 (KTX "ETC1S Slice Huffman Tables").
    Huffman endpoint_pred, endpoint_delta, selector, selector_rle;
    std::uint32_t history_size = 0;

    void decode_slice(std::span<const std::uint8_t> data, int width, int height, std::uint8_t* rgba, bool alpha,
                      const std::string& place) const;
};

// basis §10.3 (KTX "ETC1S Slice Block Decoding"), for I-frames.
void Etc1sTranscoder::Impl::decode_slice(std::span<const std::uint8_t> data, int width, int height, std::uint8_t* rgba,
                                         bool alpha, const std::string& place) const {
    constexpr std::uint32_t kPredRepeat = 256;  // endpoint prediction symbol: repeat the last symbol
    constexpr std::uint32_t kRleLong = 63;      // selector run symbol: the run length follows as a VLC
    const std::uint32_t bw = (static_cast<std::uint32_t>(width) + 3) / 4;
    const std::uint32_t bh = (static_cast<std::uint32_t>(height) + 3) / 4;
    const std::uint64_t blocks = std::uint64_t{bw} * bh, groups = std::uint64_t{(bw + 1) / 2} * ((bh + 1) / 2);
    const std::uint32_t n_endpoints = static_cast<std::uint32_t>(endpoints.size());
    const std::uint32_t n_selectors = static_cast<std::uint32_t>(selectors.size());
    const std::uint32_t rle_symbol = n_selectors + history_size;

    BitReader r(data);
    std::vector<std::uint32_t> above(bw), current(bw);  // endpoint indices of the previous and this row
    std::vector<std::uint8_t> odd_row_preds((bw + 1) / 2);  // the upper 4 bits of each even row's symbol
    std::vector<std::uint32_t> history(history_size);   // approximate move-to-front (basis §10.1)
    std::size_t rover = history_size / 2;
    std::uint32_t preds = 0, prev_pred_symbol = 0, prev_endpoint = 0;
    std::uint64_t pred_repeat = 0, selector_run = 0, group = 0;
    std::uint32_t x = 0, y = 0;
    try {
        for (y = 0; y < bh; ++y) {
            for (x = 0; x < bw; ++x) {
                // One symbol gives 2-bit endpoint predictions for a 2x2 group of blocks: the low
                // 4 bits for this (even) row, the high 4 bits kept for the odd row below.
                if ((x & 1) == 0) {
                    if ((y & 1) == 0) {
                        ++group;
                        if (pred_repeat > 0) {
                            --pred_repeat;
                            preds = prev_pred_symbol;
                        } else {
                            preds = endpoint_pred.decode(r);
                            if (preds == kPredRepeat) {
                                pred_repeat = read_vlc(r, 4) + 3 - 1;
                                if (pred_repeat > groups - group)
                                    throw Corrupt{"an endpoint prediction run passes the slice's end"};
                                preds = prev_pred_symbol;
                            } else if (preds > kPredRepeat) {
                                throw Corrupt{"endpoint prediction symbol " + std::to_string(preds) + " is over 256"};
                            } else {
                                prev_pred_symbol = preds;
                            }
                        }
                        odd_row_preds[x >> 1] = static_cast<std::uint8_t>(preds >> 4);
                    } else {
                        preds = odd_row_preds[x >> 1];
                    }
                }
                const std::uint32_t pred = preds & 3;
                preds >>= 2;

                std::uint32_t endpoint = 0;
                if (pred == 3) {  // a delta from the previous block's index, wrapping once
                    endpoint = endpoint_delta.decode(r) + prev_endpoint;
                    if (endpoint >= n_endpoints) endpoint -= n_endpoints;
                    if (endpoint >= n_endpoints) throw Corrupt{"endpoint index out of the codebook's range"};
                } else if ((pred != 1 && x == 0) || (pred != 0 && y == 0)) {
                    throw Corrupt{"an endpoint is predicted from a block outside the image"};
                } else {
                    endpoint = pred == 0 ? prev_endpoint : pred == 1 ? above[x] : above[x - 1];
                }
                current[x] = prev_endpoint = endpoint;

                std::uint32_t symbol = n_selectors;  // inside a run: history slot 0
                if (selector_run > 0) {
                    --selector_run;
                } else {
                    symbol = selector.decode(r);
                    if (symbol == rle_symbol) {
                        const std::uint32_t run_symbol = selector_rle.decode(r);
                        const std::uint64_t run = (run_symbol == kRleLong ? read_vlc(r, 7) : run_symbol) + 3;
                        if (run > blocks - (std::uint64_t{y} * bw + x))
                            throw Corrupt{"a selector run passes the slice's end"};
                        selector_run = run - 1;
                        symbol = n_selectors;
                    }
                }
                std::uint32_t sel = symbol;
                if (symbol >= n_selectors) {  // a history slot; a used slot moves halfway to the front
                    const std::uint32_t slot = symbol - n_selectors;
                    if (slot >= history.size()) throw Corrupt{"selector history slot out of range"};
                    sel = history[slot];
                    if (slot) std::swap(history[slot / 2], history[slot]);
                } else if (!history.empty()) {  // a new entry overwrites the rover's place, in the back half
                    history[rover] = sel;
                    if (++rover == history.size()) rover = history.size() / 2;
                }
                write_block(rgba, width, height, x, y, endpoints[endpoint], selectors[sel], alpha);
            }
            std::swap(above, current);
        }
    } catch (const Corrupt& c) {
        throw Error(name, place + " block (" + std::to_string(x) + ", " + std::to_string(y) + ")", c.reason);
    }
}

Etc1sTranscoder::Etc1sTranscoder(std::span<const std::uint8_t> global_data, std::uint32_t image_count, std::string name)
    : impl_(std::make_unique<Impl>()) {
    Impl& m = *impl_;
    m.name = std::move(name);
    const auto g = global_data;
    constexpr std::size_t kHeader = 20, kDesc = 20;
    if (g.size() < kHeader)
        throw Error(m.name, "byte 0",
                    "BasisLZ global data of " + std::to_string(g.size()) + " bytes is shorter than its 20-byte header");
    const std::uint32_t n_endpoints = read_le(g, 0, 2), n_selectors = read_le(g, 2, 2);
    const std::uint64_t sizes[4] = {read_le(g, 4, 4), read_le(g, 8, 4), read_le(g, 12, 4), read_le(g, 16, 4)};
    std::uint64_t start[5] = {kHeader + std::uint64_t{kDesc} * image_count};
    for (int i = 0; i < 4; ++i) start[i + 1] = start[i] + sizes[i];
    if (start[4] > g.size())
        throw Error(m.name, "byte 4", "BasisLZ global data needs " + std::to_string(start[4]) + " bytes for " +
                                          std::to_string(image_count) + " images and its sections, but has " +
                                          std::to_string(g.size()));
    if (n_endpoints == 0 || n_selectors == 0) throw Error(m.name, "byte 0", "an ETC1S codebook is empty");

    m.images.resize(image_count);
    for (std::uint32_t i = 0; i < image_count; ++i) {
        const std::size_t at = kHeader + std::size_t{kDesc} * i;
        m.images[i] = {read_le(g, at, 4), read_le(g, at + 4, 4), read_le(g, at + 8, 4), read_le(g, at + 12, 4),
                       read_le(g, at + 16, 4)};
    }

    // Each section's bit stream; a failure names the byte of the global data where it happened.
    auto section = [&](int index, const char* what, auto&& decode) {
        BitReader r(g.subspan(start[index], sizes[index]));
        try {
            decode(r);
        } catch (const Corrupt& c) {
            throw Error(m.name, "byte " + std::to_string(start[index] + r.byte_pos()),
                        std::string(what) + ": " + c.reason);
        }
    };
    section(0, "endpoint codebook", [&](BitReader& r) { m.endpoints = read_endpoints(r, n_endpoints); });
    section(1, "selector codebook", [&](BitReader& r) { m.selectors = read_selectors(r, n_selectors); });
    section(2, "slice Huffman tables", [&](BitReader& r) {
        m.endpoint_pred = read_huffman(r);
        m.endpoint_delta = read_huffman(r);
        m.selector = read_huffman(r);
        m.selector_rle = read_huffman(r);
        m.history_size = r.bits(13);
    });
}

Etc1sTranscoder::~Etc1sTranscoder() = default;
Etc1sTranscoder::Etc1sTranscoder(Etc1sTranscoder&&) noexcept = default;
Etc1sTranscoder& Etc1sTranscoder::operator=(Etc1sTranscoder&&) noexcept = default;

std::uint32_t Etc1sTranscoder::image_count() const { return static_cast<std::uint32_t>(impl_->images.size()); }

bool Etc1sTranscoder::has_alpha(std::uint32_t image) const {
    if (image >= impl_->images.size())
        throw Error(impl_->name, "image " + std::to_string(image), "no such image in the BasisLZ global data");
    return impl_->images[image].alpha_length > 0;
}

void Etc1sTranscoder::transcode(std::uint32_t image, std::span<const std::uint8_t> level_data, int width, int height,
                                std::uint8_t* rgba) const {
    const Impl& m = *impl_;
    const std::string place = "image " + std::to_string(image);
    if (image >= m.images.size()) throw Error(m.name, place, "no such image in the BasisLZ global data");
    if (width <= 0 || height <= 0)
        throw Error(m.name, place, "invalid size " + std::to_string(width) + "x" + std::to_string(height));
    const ImageDesc& d = m.images[image];
    if (d.flags & kPFrame) throw Error(m.name, place, "ETC1S texture video (P-frames) is not supported");
    auto slice = [&](std::uint32_t offset, std::uint32_t length, const char* what) {
        if (std::uint64_t{offset} + length > level_data.size())
            throw Error(m.name, place, std::string(what) + " slice (bytes " + std::to_string(offset) + " + " +
                                           std::to_string(length) + ") lies outside the level's " +
                                           std::to_string(level_data.size()) + " bytes");
        return level_data.subspan(offset, length);
    };
    m.decode_slice(slice(d.rgb_offset, d.rgb_length, "RGB"), width, height, rgba, false, place);
    if (d.alpha_length > 0)
        m.decode_slice(slice(d.alpha_offset, d.alpha_length, "alpha"), width, height, rgba, true,
                       place + " alpha slice");
}

}  // namespace fresnel::basisu
