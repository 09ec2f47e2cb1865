// Zstandard decoding after RFC 8878, written from the specification. Layout of this file, in
// the order the format nests: byte and bit readers, XXH64, FSE tables (RFC 8878 4.1),
// Huffman tables (4.2), then the Decoder: frames (3.1.1), blocks (3.1.1.2), literals
// (3.1.1.3.1), sequences (3.1.1.3.2) and their execution (3.1.1.4, 3.1.1.5).
#include "zstd_decoder.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <memory>
#include <vector>

#include "fresnel/core/error.h"

namespace fresnel::detail {
namespace {

constexpr std::size_t kMaxBlock = std::size_t(128) * 1024;  // Block_Maximum_Size's upper bound
constexpr std::uint32_t kFrameMagic = 0xFD2FB528u;
constexpr std::uint32_t kSkippableMagic = 0x184D2A50u;  // low 4 bits free
constexpr unsigned kMaxWindowLog = 31;                  // libzstd's limit on 64-bit hosts
constexpr unsigned kMaxHuffmanBits = 11;

// ---------------------------------------------------------------- little-endian loads

std::uint32_t le16(const std::uint8_t* p) { return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8; }
std::uint32_t le24(const std::uint8_t* p) { return le16(p) | std::uint32_t(p[2]) << 16; }
std::uint32_t le32(const std::uint8_t* p) { return le24(p) | std::uint32_t(p[3]) << 24; }

std::uint64_t load64(const std::uint8_t* p) {
    if constexpr (std::endian::native == std::endian::little) {
        std::uint64_t v;
        std::memcpy(&v, p, 8);
        return v;
    } else {
        std::uint64_t v = 0;
        for (int i = 7; i >= 0; --i) v = v << 8 | p[i];
        return v;
    }
}

// `n` < 8 bytes, little-endian, the rest zero.
std::uint64_t load_tail(const std::uint8_t* p, std::size_t n) {
    std::uint64_t v = 0;
    for (std::size_t i = n; i-- > 0;) v = v << 8 | p[i];
    return v;
}

// memcpy / memset that take an empty range at a null pointer (an empty dst has one).
void copy_bytes(std::uint8_t* to, const std::uint8_t* from, std::size_t n) {
    if (n > 0) std::memcpy(to, from, n);
}
void fill_bytes(std::uint8_t* to, std::uint8_t value, std::size_t n) {
    if (n > 0) std::memset(to, value, n);
}

std::uint64_t low_bits(std::uint64_t v, unsigned n) { return n >= 64 ? v : v & ((std::uint64_t(1) << n) - 1); }

// ---------------------------------------------------------------- bit readers

// A bitstream read backwards (RFC 8878 4.1, 4.2.2): from the highest bit below the end marker (the
// top set bit of the last byte) down to bit 0 of the first byte. `pos` counts the bits not yet
// read; reading past bit 0 yields zeros and drives pos negative, which the callers treat as
// corruption (or, for Huffman weights, as the end). Never reads outside [data, data + size).
struct BackBits {
    const std::uint8_t* data = nullptr;
    std::size_t size = 0;
    std::int64_t pos = 0;

    // The next n bits (1 <= n <= 56) without consuming them.
    std::uint64_t peek(unsigned n) const {
        const std::int64_t lo = pos - std::int64_t(n);
        if (lo >= 0) {
            const std::size_t byte = std::size_t(lo) >> 3;
            const std::uint64_t w = byte + 8 <= size ? load64(data + byte) : load_tail(data + byte, size - byte);
            return low_bits(w >> (lo & 7), n);
        }
        if (pos <= 0) return 0;
        // pos < n <= 56: the bits left all lie in the first 7 bytes; zeros fill in below bit 0.
        const std::uint64_t w = load_tail(data, std::min<std::size_t>(size, 7));
        return low_bits(w, unsigned(pos)) << (n - unsigned(pos));
    }
    std::uint64_t read(unsigned n) {
        if (n == 0) return 0;
        const std::uint64_t v = peek(n);
        pos -= n;
        return v;
    }
};

// A bitstream read forwards from bit 0 of the first byte (FSE table descriptions, RFC 8878
// 4.1.1). Past the end it yields zeros and sets `overrun`.
struct ForwardBits {
    const std::uint8_t* data;
    std::size_t size;
    std::size_t pos = 0;  // bits consumed
    bool overrun = false;

    std::uint32_t peek(unsigned n) const {  // n <= 24
        std::uint32_t v = 0;
        for (unsigned got = 0; got < n;) {
            const std::size_t byte = (pos + got) >> 3;
            const unsigned shift = unsigned(pos + got) & 7;
            const unsigned take = std::min(8 - shift, n - got);
            const std::uint32_t b = byte < size ? data[byte] : 0;
            v |= ((b >> shift) & ((1u << take) - 1)) << got;
            got += take;
        }
        return v;
    }
    void skip(unsigned n) {
        pos += n;
        if (pos > size * 8) overrun = true;
    }
    std::uint32_t read(unsigned n) {
        const std::uint32_t v = peek(n);
        skip(n);
        return v;
    }
    std::size_t bytes_used() const { return (pos + 7) / 8; }
};

// ---------------------------------------------------------------- XXH64 (seed 0)

constexpr std::uint64_t kP1 = 0x9E3779B185EBCA87ull, kP2 = 0xC2B2AE3D27D4EB4Full, kP3 = 0x165667B19E3779F9ull,
                        kP4 = 0x85EBCA77C2B2AE63ull, kP5 = 0x27D4EB2F165667C5ull;

std::uint64_t xxh_round(std::uint64_t acc, std::uint64_t lane) { return std::rotl(acc + lane * kP2, 31) * kP1; }

std::uint64_t xxh_merge(std::uint64_t h, std::uint64_t acc) { return (h ^ xxh_round(0, acc)) * kP1 + kP4; }

std::uint64_t xxh64(const std::uint8_t* p, std::size_t n) {
    const std::uint8_t* const end = p + n;
    std::uint64_t h;
    if (n >= 32) {
        std::uint64_t a = kP1 + kP2, b = kP2, c = 0, d = 0 - kP1;
        for (; end - p >= 32; p += 32) {
            a = xxh_round(a, load64(p));
            b = xxh_round(b, load64(p + 8));
            c = xxh_round(c, load64(p + 16));
            d = xxh_round(d, load64(p + 24));
        }
        h = std::rotl(a, 1) + std::rotl(b, 7) + std::rotl(c, 12) + std::rotl(d, 18);
        h = xxh_merge(xxh_merge(xxh_merge(xxh_merge(h, a), b), c), d);
    } else {
        h = kP5;
    }
    h += n;
    for (; end - p >= 8; p += 8) h = std::rotl(h ^ xxh_round(0, load64(p)), 27) * kP1 + kP4;
    if (end - p >= 4) {
        h = std::rotl(h ^ std::uint64_t(le32(p)) * kP1, 23) * kP2 + kP3;
        p += 4;
    }
    for (; p < end; ++p) h = std::rotl(h ^ *p * kP5, 11) * kP1;
    h ^= h >> 33;
    h *= kP2;
    h ^= h >> 29;
    h *= kP3;
    return h ^ (h >> 32);
}

// ---------------------------------------------------------------- FSE (RFC 8878 4.1)

// One state of an FSE decoding table: the symbol it decodes, and the next state,
// `base` + the next `bits` bits of the stream.
struct FseCell {
    std::uint16_t base;
    std::uint8_t bits;
    std::uint8_t symbol;
};

// Builds the decoding table of 2^log states from normalized probabilities (-1: "less than 1")
// of symbols 0..count-1, which must sum to 2^log. False when the spread does not come round.
bool build_fse(const std::int16_t* prob, unsigned count, unsigned log, FseCell* cells) {
    const std::uint32_t size = 1u << log, mask = size - 1;
    std::array<std::uint16_t, 256> next{};
    std::uint32_t high = size - 1;  // "less than 1" symbols take the last cells, one each
    for (unsigned s = 0; s < count; ++s) {
        if (prob[s] == -1) {
            cells[high--].symbol = std::uint8_t(s);
            next[s] = 1;
        } else {
            next[s] = std::uint16_t(std::max<int>(prob[s], 0));
        }
    }
    const std::uint32_t step = (size >> 1) + (size >> 3) + 3;
    std::uint32_t pos = 0;
    for (unsigned s = 0; s < count; ++s)
        for (int i = 0; i < prob[s]; ++i) {
            cells[pos].symbol = std::uint8_t(s);
            do pos = (pos + step) & mask;
            while (pos > high);
        }
    if (pos != 0) return false;
    for (std::uint32_t u = 0; u < size; ++u) {
        const std::uint32_t state = next[cells[u].symbol]++;
        const unsigned bits = log - (unsigned(std::bit_width(state)) - 1);
        cells[u].bits = std::uint8_t(bits);
        cells[u].base = std::uint16_t((state << bits) - size);
    }
    return true;
}

// ---------------------------------------------------------------- sequence tables (3.1.1.3.2)

// A sequence decoding state with its symbol already turned into a value: the length or offset
// value is `value` + the next `extra` bits.
struct SeqCell {
    std::uint32_t value;
    std::uint16_t base;
    std::uint8_t bits;
    std::uint8_t extra;
};

struct SeqTable {
    unsigned log = 0;
    std::array<SeqCell, 512> cells{};
};

enum SeqKind { kLiteralLengths = 0, kOffsets = 1, kMatchLengths = 2 };

constexpr std::array<std::int16_t, 36> kLLDefault = {4, 3, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 1, 1, 1, 2, 2,
                                                     2, 2, 2, 2, 2, 2, 2, 3, 2, 1, 1, 1, 1, 1, -1, -1, -1, -1};
constexpr std::array<std::int16_t, 53> kMLDefault = {1, 4, 3, 2, 2, 2, 2, 2, 2, 1, 1, 1, 1, 1, 1, 1, 1, 1,
                                                     1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1,
                                                     1, 1, 1, 1, 1, 1, 1, 1, 1, 1, -1, -1, -1, -1, -1, -1, -1};
constexpr std::array<std::int16_t, 29> kOFDefault = {1, 1, 1, 1, 1, 1, 2, 2, 2, 1, 1, 1, 1, 1, 1,
                                                     1, 1, 1, 1, 1, 1, 1, 1, 1, -1, -1, -1, -1, -1};
constexpr std::array<std::uint32_t, 36> kLLBase = {0,  1,  2,  3,  4,  5,   6,   7,   8,   9,    10,   11,
                                                   12, 13, 14, 15, 16, 18,  20,  22,  24,  28,   32,   40,
                                                   48, 64, 128, 256, 512, 1024, 2048, 4096, 8192, 16384, 32768, 65536};
constexpr std::array<std::uint8_t, 36> kLLExtra = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,  0,  0,  1,  1,
                                                   1, 1, 2, 2, 3, 3, 4, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};
constexpr std::array<std::uint32_t, 53> kMLBase = {
    3,  4,  5,  6,  7,  8,  9,  10, 11, 12, 13,  14,  15,  16,  17,   18,   19,   20,    21,    22,    23,   24,
    25, 26, 27, 28, 29, 30, 31, 32, 33, 34, 35,  37,  39,  41,  43,   47,   51,   59,    67,    83,    99,   131,
    259, 515, 1027, 2051, 4099, 8195, 16387, 32771, 65539};
constexpr std::array<std::uint8_t, 53> kMLExtra = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,  0,  0,  0,
                                                   0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1,  1,  1,  1,
                                                   2, 2, 3, 3, 4, 4, 5, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};

constexpr unsigned kSeqMaxSymbol[3] = {35, 31, 52};
constexpr unsigned kSeqMaxLog[3] = {9, 8, 9};
constexpr const char* kSeqName[3] = {"literal lengths", "offsets", "match lengths"};

void to_seq_table(SeqKind kind, const FseCell* cells, unsigned log, SeqTable& t) {
    t.log = log;
    for (std::size_t u = 0; u < (std::size_t(1) << log); ++u) {
        const FseCell c = cells[u];
        SeqCell& o = t.cells[u];
        o.base = c.base;
        o.bits = c.bits;
        switch (kind) {
            case kLiteralLengths: o.value = kLLBase[c.symbol], o.extra = kLLExtra[c.symbol]; break;
            case kMatchLengths: o.value = kMLBase[c.symbol], o.extra = kMLExtra[c.symbol]; break;
            case kOffsets: o.value = std::uint32_t(1) << c.symbol, o.extra = c.symbol; break;
        }
    }
}

void copy_match(std::uint8_t* out, std::size_t offset, std::size_t length) {
    const std::uint8_t* from = out - offset;
    if (offset >= length) {
        std::memcpy(out, from, length);
    } else if (offset == 1) {
        std::memset(out, *from, length);
    } else {
        // Overlapping: the copy repeats the last `offset` bytes. Chunks of 8 never overlap
        // themselves once offset >= 8.
        if (offset >= 8)
            for (; length >= 8; length -= 8, out += 8, from += 8) std::memcpy(out, from, 8);
        for (; length > 0; --length) *out++ = *from++;
    }
}

// ---------------------------------------------------------------- the decoder

struct HufCell {
    std::uint8_t symbol;
    std::uint8_t bits;
};

class Decoder {
public:
    Decoder(std::span<const std::uint8_t> src, std::span<std::uint8_t> dst, const std::string& name,
            std::uint64_t src_offset)
        : src_(src), name_(name), src_offset_(src_offset), out_(dst.data()), dst_begin_(dst.data()),
          dst_end_(dst.data() + dst.size()) {
        FseCell cells[64];
        build_fse(kLLDefault.data(), unsigned(kLLDefault.size()), 6, cells);
        to_seq_table(kLiteralLengths, cells, 6, predefined_[kLiteralLengths]);
        build_fse(kOFDefault.data(), unsigned(kOFDefault.size()), 5, cells);
        to_seq_table(kOffsets, cells, 5, predefined_[kOffsets]);
        build_fse(kMLDefault.data(), unsigned(kMLDefault.size()), 6, cells);
        to_seq_table(kMatchLengths, cells, 6, predefined_[kMatchLengths]);
    }

    void run() {
        const std::uint8_t* p = src_.data();
        const std::uint8_t* const end = p + src_.size();
        if (p == end) fail(p, "no frame (the data is empty)");
        while (p < end) {
            if (end - p < 4) fail(p, "truncated frame (" + std::to_string(end - p) + " bytes after the last frame)");
            const std::uint32_t magic = le32(p);
            if ((magic & 0xFFFFFFF0u) == kSkippableMagic) {
                if (end - p < 8) fail(p, "truncated skippable frame header");
                const std::uint32_t size = le32(p + 4);
                if (size > std::size_t(end - p) - 8) fail(p, "skippable frame runs past the end of the data");
                p += 8 + std::size_t(size);
                continue;
            }
            if (magic != kFrameMagic) fail(p, "not a Zstandard frame (bad magic number)");
            p = frame(p, end);
        }
        if (out_ != dst_end_)
            fail(end, "the data inflates to " + std::to_string(out_ - dst_begin_) + " bytes, " +
                          std::to_string(dst_end_ - dst_begin_) + " were expected");
    }

private:
    [[noreturn]] void fail(const std::uint8_t* at, const std::string& what) const {
        throw Error(name_, "byte " + std::to_string(src_offset_ + std::uint64_t(at - src_.data())), "Zstandard: " + what);
    }
    [[noreturn]] void too_long(const std::uint8_t* at, const std::uint8_t* limit) const {
        if (limit == dst_end_)
            fail(at, "the data inflates to more than the " + std::to_string(dst_end_ - dst_begin_) + " bytes expected");
        fail(at, "block inflates to more than its maximum of " + std::to_string(block_max_) + " bytes");
    }

    BackBits back_bits(const std::uint8_t* begin, const std::uint8_t* end, const char* what) const {
        if (begin >= end) fail(begin, std::string(what) + " is empty");
        const std::uint8_t last = end[-1];
        if (last == 0) fail(end - 1, std::string(what) + " lacks its end marker");
        BackBits b;
        b.data = begin;
        b.size = std::size_t(end - begin);
        b.pos = std::int64_t(b.size - 1) * 8 + std::bit_width(unsigned(last)) - 1;
        return b;
    }

    // -------------------------------------------------------- frames and blocks

    const std::uint8_t* frame(const std::uint8_t* p, const std::uint8_t* end) {
        const std::uint8_t* const start = p;
        p += 4;
        if (p == end) fail(start, "truncated frame header");
        const unsigned desc = *p++;
        const unsigned fcs_flag = desc >> 6;
        const bool single_segment = desc & 0x20;
        const bool has_checksum = desc & 0x04;
        if (desc & 0x08) fail(start + 4, "reserved bit set in the frame header");
        const std::size_t dict_bytes = std::array<std::size_t, 4>{0, 1, 2, 4}[desc & 3];
        const std::size_t fcs_bytes = fcs_flag == 0 ? (single_segment ? 1 : 0) : std::size_t(1) << fcs_flag;
        if ((single_segment ? 0 : 1) + dict_bytes + fcs_bytes > std::size_t(end - p))
            fail(start, "truncated frame header");
        std::uint64_t window = 0;
        if (!single_segment) {
            const unsigned wd = *p++;
            const unsigned log = 10 + (wd >> 3);
            if (log > kMaxWindowLog)
                fail(start + 5, "window of 2^" + std::to_string(log) + " bytes is over the limit of 2^" +
                                    std::to_string(kMaxWindowLog));
            window = (std::uint64_t(1) << log) + (std::uint64_t(1) << (log - 3)) * (wd & 7);
        }
        std::uint64_t dict_id = 0;
        for (std::size_t i = 0; i < dict_bytes; ++i) dict_id |= std::uint64_t(p[i]) << (8 * i);
        p += dict_bytes;
        if (dict_id != 0)
            fail(start, "frame needs dictionary " + std::to_string(dict_id) + " (dictionaries are not supported)");
        std::uint64_t content_size = 0;
        for (std::size_t i = 0; i < fcs_bytes; ++i) content_size |= std::uint64_t(p[i]) << (8 * i);
        p += fcs_bytes;
        if (fcs_bytes == 2) content_size += 256;
        const bool size_known = fcs_bytes != 0;
        if (single_segment) window = content_size;
        const std::size_t room = std::size_t(dst_end_ - out_);
        if (size_known && content_size > room)
            fail(start, "frame holds " + std::to_string(content_size) + " bytes, more than the " +
                            std::to_string(room) + " left to fill");
        block_max_ = std::size_t(std::min<std::uint64_t>(window, kMaxBlock));

        // Each frame starts afresh: no tables, no Huffman tree, the initial repeat offsets.
        frame_start_ = out_;
        have_huffman_ = false;
        active_ = {nullptr, nullptr, nullptr};
        rep_ = {1, 4, 8};

        for (bool last = false; !last;) {
            if (end - p < 3) fail(p, "truncated block header");
            const std::uint8_t* const block = p;
            const std::uint32_t header = le24(p);
            p += 3;
            last = header & 1;
            const unsigned type = (header >> 1) & 3;
            const std::size_t size = header >> 3;
            if (type == 3) fail(block, "reserved block type");
            if (size > block_max_)
                fail(block, "block of " + std::to_string(size) + " bytes is over the maximum of " +
                                std::to_string(block_max_));
            const std::size_t stored = type == 1 ? 1 : size;
            if (stored > std::size_t(end - p)) fail(block, "truncated block");
            if (type == 2) {
                compressed_block(p, p + size);
            } else {
                if (size > std::size_t(dst_end_ - out_)) too_long(block, dst_end_);
                if (type == 0)
                    copy_bytes(out_, p, size);
                else
                    fill_bytes(out_, *p, size);
                out_ += size;
            }
            p += stored;
        }
        const std::size_t produced = std::size_t(out_ - frame_start_);
        if (size_known && produced != content_size)
            fail(start, "frame inflates to " + std::to_string(produced) + " bytes, its header says " +
                            std::to_string(content_size));
        if (has_checksum) {
            if (end - p < 4) fail(p, "truncated content checksum");
            if (le32(p) != std::uint32_t(xxh64(frame_start_, produced))) fail(p, "content checksum mismatch");
            p += 4;
        }
        return p;
    }

    void compressed_block(const std::uint8_t* p, const std::uint8_t* end) {
        const std::size_t room = std::min(block_max_, std::size_t(dst_end_ - out_));
        p = literals(p, end);
        sequences(p, end, out_ + room);
    }

    // -------------------------------------------------------- literals (3.1.1.3.1)

    std::uint8_t* literal_buffer() {
        if (literal_buffer_.empty()) literal_buffer_.resize(kMaxBlock);
        return literal_buffer_.data();
    }

    const std::uint8_t* literals(const std::uint8_t* p, const std::uint8_t* end) {
        const std::uint8_t* const start = p;
        if (p == end) fail(p, "empty compressed block");
        const unsigned type = p[0] & 3, format = (p[0] >> 2) & 3;
        if (type < 2) {  // raw or RLE
            std::size_t header = 1, size = p[0] >> 3;
            if (format == 1) header = 2;
            if (format == 3) header = 3;
            if (header > std::size_t(end - p)) fail(start, "truncated literals header");
            if (format == 1) size = (p[0] >> 4) | std::size_t(p[1]) << 4;
            if (format == 3) size = (p[0] >> 4) | std::size_t(p[1]) << 4 | std::size_t(p[2]) << 12;
            if (size > block_max_) fail(start, "more literals than a block may hold");
            p += header;
            if (type == 0) {
                if (size > std::size_t(end - p)) fail(start, "raw literals run past the end of the block");
                literals_ = p;
                literal_count_ = size;
                return p + size;
            }
            if (p == end) fail(start, "truncated RLE literals");
            std::uint8_t* buffer = literal_buffer();
            fill_bytes(buffer, *p, size);
            literals_ = buffer;
            literal_count_ = size;
            return p + 1;
        }
        // Huffman-coded, with a tree (2) or the previous block's (3, treeless).
        const unsigned header = format < 2 ? 3 : format + 2, field = format < 2 ? 10 : 4 * format + 6;
        const bool four_streams = format != 0;
        if (header > std::size_t(end - p)) fail(start, "truncated literals header");
        std::uint64_t h = 0;
        for (unsigned i = 0; i < header; ++i) h |= std::uint64_t(p[i]) << (8 * i);
        const std::size_t size = std::size_t(low_bits(h >> 4, field));
        const std::size_t compressed = std::size_t(low_bits(h >> (4 + field), field));
        if (size > block_max_) fail(start, "more literals than a block may hold");
        p += header;
        if (compressed > std::size_t(end - p)) fail(start, "compressed literals run past the end of the block");
        const std::uint8_t* const stop = p + compressed;
        if (type == 2)
            p = huffman_tree(p, stop);
        else if (!have_huffman_)
            fail(start, "treeless literals with no earlier Huffman tree in the frame");
        std::uint8_t* out = literal_buffer();
        if (!four_streams) {
            huffman_streams<1>({HuffmanLane{p, stop, out, size}});
        } else {
            if (stop - p < 6) fail(p, "truncated Huffman jump table");
            const std::size_t s1 = le16(p), s2 = le16(p + 2), s3 = le16(p + 4);
            p += 6;
            if (s1 + s2 + s3 > std::size_t(stop - p)) fail(p - 6, "Huffman jump table points past the literals");
            const std::size_t quarter = (size + 3) / 4;
            if (3 * quarter > size) fail(start, "too few literals (" + std::to_string(size) + ") for four streams");
            const std::uint8_t* const a = p + s1;
            const std::uint8_t* const b = a + s2;
            const std::uint8_t* const c = b + s3;
            huffman_streams<4>({HuffmanLane{p, a, out, quarter}, HuffmanLane{a, b, out + quarter, quarter},
                                HuffmanLane{b, c, out + 2 * quarter, quarter},
                                HuffmanLane{c, stop, out + 3 * quarter, size - 3 * quarter}});
        }
        literals_ = out;
        literal_count_ = size;
        return stop;
    }

    // The Huffman tree description (4.2.1): weights, FSE-compressed or 4 bits each, the last one
    // implied. Builds the decoding table; returns the end of the description.
    const std::uint8_t* huffman_tree(const std::uint8_t* p, const std::uint8_t* end) {
        const std::uint8_t* const start = p;
        if (p == end) fail(p, "missing Huffman tree description");
        const unsigned header = *p++;
        std::array<std::uint8_t, 256> weight{};
        std::size_t n = 0;
        if (header < 128) {
            if (header > std::size_t(end - p)) fail(start, "Huffman weights run past the literals");
            const std::uint8_t* const stop = p + header;
            std::array<std::int16_t, 256> prob{};
            unsigned log = 0;
            const std::uint8_t* const bits = fse_description(p, stop, 6, 255, prob.data(), log);
            std::array<FseCell, 64> cells{};
            if (!build_fse(prob.data(), 256, log, cells.data())) fail(p, "invalid FSE table for Huffman weights");
            BackBits br = back_bits(bits, stop, "Huffman weight bitstream");
            // Two interleaved states share the table; when a state update reads past the start of
            // the stream, the other state's symbol is the last one.
            unsigned state[2] = {unsigned(br.read(log)), unsigned(br.read(log))};
            for (int s = 0;; s ^= 1) {
                if (n == 255) fail(start, "more than 255 Huffman weights");
                const FseCell c = cells[state[s]];
                weight[n++] = c.symbol;
                state[s] = c.base + unsigned(br.read(c.bits));
                if (br.pos < 0) {
                    if (n == 255) fail(start, "more than 255 Huffman weights");
                    weight[n++] = cells[state[s ^ 1]].symbol;
                    break;
                }
            }
            p = stop;
        } else {
            n = header - 127;
            if ((n + 1) / 2 > std::size_t(end - p)) fail(start, "Huffman weights run past the literals");
            for (std::size_t i = 0; i < n; ++i) weight[i] = std::uint8_t(i & 1 ? p[i / 2] & 15 : p[i / 2] >> 4);
            p += (n + 1) / 2;
        }
        std::uint32_t total = 0;
        for (std::size_t i = 0; i < n; ++i) {
            if (weight[i] > kMaxHuffmanBits) fail(start, "Huffman weight over 11");
            if (weight[i] > 0) total += 1u << (weight[i] - 1);
        }
        if (total == 0) fail(start, "Huffman weights are all zero");
        const unsigned max_bits = unsigned(std::bit_width(total));
        if (max_bits > kMaxHuffmanBits) fail(start, "Huffman codes longer than 11 bits");
        const std::uint32_t rest = (1u << max_bits) - total;
        if (!std::has_single_bit(rest)) fail(start, "Huffman weights do not form a complete tree");
        weight[n++] = std::uint8_t(std::countr_zero(rest) + 1);
        // Codes go to weights in increasing order, and within a weight to increasing symbols;
        // a symbol of weight w covers 2^(w-1) cells of the 2^max_bits-cell table.
        std::array<std::uint32_t, kMaxHuffmanBits + 2> next{};
        for (std::size_t i = 0; i < n; ++i)
            if (weight[i] > 0) next[weight[i]] += 1u << (weight[i] - 1);
        for (std::uint32_t w = 1, at = 0; w <= max_bits; ++w) {
            const std::uint32_t span = next[w];
            next[w] = at;
            at += span;
        }
        for (std::size_t i = 0; i < n; ++i) {
            const unsigned w = weight[i];
            if (w == 0) continue;
            const HufCell cell{std::uint8_t(i), std::uint8_t(max_bits + 1 - w)};
            std::fill_n(huffman_.begin() + next[w], std::size_t(1) << (w - 1), cell);
            next[w] += 1u << (w - 1);
        }
        huffman_bits_ = max_bits;
        have_huffman_ = true;
        return p;
    }

    // One Huffman-coded stream (4.2.2) of `count` literals.
    struct HuffmanLane {
        const std::uint8_t* begin;
        const std::uint8_t* end;
        std::uint8_t* out;
        std::size_t count;
    };

    // Decodes 1 or 4 streams, interleaved so the 4 dependency chains overlap. Each stream must
    // end exactly where its bits do.
    template <std::size_t N>
    void huffman_streams(const std::array<HuffmanLane, N>& lanes) {
        std::array<BackBits, N> br;
        std::array<std::uint8_t*, N> out;
        std::array<std::size_t, N> done{};
        for (std::size_t l = 0; l < N; ++l) {
            br[l] = back_bits(lanes[l].begin, lanes[l].end, "Huffman stream");
            out[l] = lanes[l].out;
        }
        const unsigned bits = huffman_bits_, drop = 64 - bits;
        const HufCell* const table = huffman_.data();
        // Fast: while each stream has 64 bits and 5 literals left, one load feeds 5 symbols
        // (at least 57 fresh bits, at most 55 used).
        for (;;) {
            bool room = true;
            for (std::size_t l = 0; l < N; ++l) room &= br[l].pos >= 64 && lanes[l].count - done[l] >= 5;
            if (!room) break;
            std::array<std::uint64_t, N> window;
            for (std::size_t l = 0; l < N; ++l) {
                const std::size_t top = (std::size_t(br[l].pos) + 7) >> 3;  // bytes up to the next unread bit
                window[l] = load64(br[l].data + top - 8) << (top * 8 - std::size_t(br[l].pos));
            }
            for (int k = 0; k < 5; ++k)
                for (std::size_t l = 0; l < N; ++l) {
                    const HufCell c = table[window[l] >> drop];
                    out[l][done[l]++] = c.symbol;
                    window[l] <<= c.bits;
                    br[l].pos -= c.bits;
                }
        }
        for (std::size_t l = 0; l < N; ++l) {
            for (std::size_t i = done[l]; i < lanes[l].count; ++i) {
                const HufCell c = table[br[l].peek(bits)];
                lanes[l].out[i] = c.symbol;
                br[l].pos -= c.bits;
            }
            if (br[l].pos != 0)
                fail(lanes[l].begin,
                     br[l].pos < 0 ? "Huffman stream ends before its literals do" : "Huffman stream has bits left over");
        }
    }

    // -------------------------------------------------------- FSE table descriptions (4.1.1)

    // Reads a table description at p (at most `end`): the accuracy log into `log` (at most
    // max_log) and the probabilities of symbols 0..max_symbol into prob (the rest zero).
    // Returns the first byte after it.
    const std::uint8_t* fse_description(const std::uint8_t* p, const std::uint8_t* end, unsigned max_log,
                                        unsigned max_symbol, std::int16_t* prob, unsigned& log) const {
        ForwardBits in{p, std::size_t(end - p)};
        std::fill_n(prob, max_symbol + 1, std::int16_t(0));
        log = in.read(4) + 5;
        if (log > max_log)
            fail(p, "FSE accuracy log " + std::to_string(log) + " is over the maximum of " + std::to_string(max_log));
        std::int32_t remaining = (1 << log) + 1;
        std::int32_t threshold = 1 << log;
        unsigned bits = log + 1;
        unsigned symbol = 0;
        while (remaining > 1) {
            if (in.overrun) break;
            if (symbol > max_symbol) fail(p, "FSE table description has too many symbols");
            // Values 0..remaining take `bits` bits, the smallest ones one bit less.
            const std::int32_t small_limit = 2 * threshold - 1 - remaining;
            std::int32_t value = std::int32_t(in.peek(bits - 1));
            if (value < small_limit) {
                in.skip(bits - 1);
            } else {
                value = std::int32_t(in.read(bits));
                if (value >= threshold) value -= small_limit;
            }
            const std::int32_t probability = value - 1;
            remaining -= probability < 0 ? -probability : probability;
            prob[symbol++] = std::int16_t(probability);
            if (probability == 0) {
                // 2-bit repeat counts of further zero probabilities, 3 meaning "and more".
                for (;;) {
                    const unsigned repeat = in.read(2);
                    symbol += repeat;
                    if (symbol > max_symbol + 1) fail(p, "FSE table description has too many symbols");
                    if (repeat != 3 || in.overrun) break;
                }
            }
            while (remaining < threshold) {
                --bits;
                threshold >>= 1;
            }
        }
        if (in.overrun) fail(p, "truncated FSE table description");
        if (remaining != 1) fail(p, "FSE probabilities do not add up");
        return p + in.bytes_used();
    }

    // -------------------------------------------------------- sequences (3.1.1.3.2)

    const std::uint8_t* sequence_table(SeqKind kind, unsigned mode, const std::uint8_t* p, const std::uint8_t* end) {
        switch (mode) {
            case 0:  // predefined
                active_[kind] = &predefined_[kind];
                return p;
            case 1: {  // RLE: one symbol, no state bits
                if (p == end) fail(p, std::string("truncated RLE table for ") + kSeqName[kind]);
                if (*p > kSeqMaxSymbol[kind]) fail(p, std::string("RLE symbol out of range for ") + kSeqName[kind]);
                const FseCell cell{0, 0, *p};
                to_seq_table(kind, &cell, 0, tables_[kind]);
                active_[kind] = &tables_[kind];
                return p + 1;
            }
            case 2: {  // FSE-compressed
                std::array<std::int16_t, 256> prob{};
                unsigned log = 0;
                const std::uint8_t* const next =
                    fse_description(p, end, kSeqMaxLog[kind], kSeqMaxSymbol[kind], prob.data(), log);
                std::array<FseCell, 512> cells{};
                if (!build_fse(prob.data(), kSeqMaxSymbol[kind] + 1, log, cells.data()))
                    fail(p, std::string("invalid FSE table for ") + kSeqName[kind]);
                to_seq_table(kind, cells.data(), log, tables_[kind]);
                active_[kind] = &tables_[kind];
                return next;
            }
            default:  // repeat
                if (!active_[kind]) fail(p, std::string("repeated table for ") + kSeqName[kind] + " with none before");
                return p;
        }
    }

    void sequences(const std::uint8_t* p, const std::uint8_t* end, std::uint8_t* const limit) {
        const std::uint8_t* const start = p;
        if (p == end) fail(p, "missing sequences section");
        std::size_t count = p[0];
        if (count == 0) {
            if (end - p != 1) fail(p, "bytes after an empty sequences section");
            p += 1;
        } else {
            if (count < 128) {
                p += 1;
            } else if (count < 255) {
                if (end - p < 2) fail(start, "truncated sequences header");
                count = ((count - 128) << 8) + p[1];
                p += 2;
            } else {
                if (end - p < 3) fail(start, "truncated sequences header");
                count = le16(p + 1) + 0x7F00;
                p += 3;
            }
            if (p == end) fail(start, "truncated sequences header");
            const unsigned modes = *p++;
            if (modes & 3) fail(p - 1, "reserved bits set in the sequence modes");
            p = sequence_table(kLiteralLengths, modes >> 6, p, end);
            p = sequence_table(kOffsets, (modes >> 4) & 3, p, end);
            p = sequence_table(kMatchLengths, (modes >> 2) & 3, p, end);
        }

        std::uint8_t* out = out_;
        const std::uint8_t* lit = literals_;
        const std::uint8_t* const lit_end = literals_ + literal_count_;
        if (count > 0) {
            BackBits br = back_bits(p, end, "sequence bitstream");
            const SeqTable& llt = *active_[kLiteralLengths];
            const SeqTable& oft = *active_[kOffsets];
            const SeqTable& mlt = *active_[kMatchLengths];
            std::size_t ll_state = std::size_t(br.read(llt.log));
            std::size_t of_state = std::size_t(br.read(oft.log));
            std::size_t ml_state = std::size_t(br.read(mlt.log));
            std::array<std::uint64_t, 3> rep = rep_;
            for (std::size_t i = 0; i < count; ++i) {
                const SeqCell lc = llt.cells[ll_state], oc = oft.cells[of_state], mc = mlt.cells[ml_state];
                const std::uint64_t offset_value = oc.value + br.read(oc.extra);
                const std::size_t match = mc.value + std::size_t(br.read(mc.extra));
                const std::size_t literal = lc.value + std::size_t(br.read(lc.extra));
                std::uint64_t offset;
                if (offset_value > 3) {
                    offset = offset_value - 3;
                    rep = {offset, rep[0], rep[1]};
                } else {
                    // Repeat offsets; with no literals before the match, each index shifts by one.
                    const unsigned index = unsigned(offset_value) - (literal == 0 ? 0 : 1);
                    if (index == 0) {
                        offset = rep[0];
                    } else {
                        offset = index == 3 ? rep[0] - 1 : rep[index];
                        if (offset == 0) fail(p, "repeat offset of 0");
                        if (index == 1)
                            rep = {offset, rep[0], rep[2]};
                        else
                            rep = {offset, rep[0], rep[1]};
                    }
                }
                if (i + 1 < count) {
                    ll_state = lc.base + std::size_t(br.read(lc.bits));
                    ml_state = mc.base + std::size_t(br.read(mc.bits));
                    of_state = oc.base + std::size_t(br.read(oc.bits));
                }
                if (literal > std::size_t(lit_end - lit)) fail(p, "sequence takes more literals than the block has");
                if (literal + match > std::size_t(limit - out)) too_long(start, limit);
                copy_bytes(out, lit, literal);
                out += literal;
                lit += literal;
                if (offset > std::uint64_t(out - frame_start_))
                    fail(p, "match offset " + std::to_string(offset) + " reaches before the start of the frame");
                copy_match(out, std::size_t(offset), match);
                out += match;
            }
            if (br.pos != 0)
                fail(p, br.pos < 0 ? "sequence bitstream ends before its sequences do"
                                   : "sequence bitstream has bits left over");
            rep_ = rep;
        }
        const std::size_t rest = std::size_t(lit_end - lit);
        if (rest > std::size_t(limit - out)) too_long(start, limit);
        copy_bytes(out, lit, rest);
        out_ = out + rest;
    }

    std::span<const std::uint8_t> src_;
    const std::string& name_;
    std::uint64_t src_offset_;
    std::uint8_t* out_;
    std::uint8_t* const dst_begin_;
    std::uint8_t* const dst_end_;

    // The current frame.
    std::uint8_t* frame_start_ = nullptr;
    std::size_t block_max_ = 0;
    std::array<std::uint64_t, 3> rep_{};
    bool have_huffman_ = false;
    unsigned huffman_bits_ = 0;
    std::array<HufCell, std::size_t(1) << kMaxHuffmanBits> huffman_{};
    std::array<const SeqTable*, 3> active_{};  // null: no table yet (Repeat_Mode is an error)
    std::array<SeqTable, 3> tables_{};
    std::array<SeqTable, 3> predefined_{};

    // The current block's literals: in src (raw) or literal_buffer_.
    std::vector<std::uint8_t> literal_buffer_;
    const std::uint8_t* literals_ = nullptr;
    std::size_t literal_count_ = 0;
};

}  // namespace

std::uint64_t zstd_xxh64(std::span<const std::uint8_t> data) { return xxh64(data.data(), data.size()); }

void zstd_decompress(std::span<const std::uint8_t> src, std::span<std::uint8_t> dst, const std::string& name,
                     std::uint64_t src_offset) {
    auto decoder = std::make_unique<Decoder>(src, dst, name, src_offset);  // ~30 KiB of tables: not on the stack
    decoder->run();
}

}  // namespace fresnel::detail
