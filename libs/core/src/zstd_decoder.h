#pragma once
// A Zstandard decoder (RFC 8878 frames), our own, for the web build: Emscripten has no libzstd,
// and Zstandard-supercompressed KTX2 levels must still load there. The native build keeps
// libzstd; zstd_decoder_test holds this one byte for byte to it.
//
// Supported: Zstandard frames (any number, with skippable frames between them), raw / RLE /
// compressed blocks, raw / RLE / Huffman (1 or 4 streams, treeless) literals, predefined / RLE /
// FSE / repeat sequence tables, repeat offsets, the XXH64 content checksum (verified).
// Not supported: dictionaries (a frame naming Dictionary_ID != 0 is an error) and the legacy
// pre-1.0 formats.
//
// The output is decoded straight into `dst`: matches reach back into it, never past the start of
// their own frame, so no window is ever allocated whatever Window_Size a header claims (beyond
// libzstd's 2 GiB limit it is an error, as there). Memory: one 128 KiB literals buffer and a few
// KiB of tables. Every read of `src` and write of `dst` is bounds-checked.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace fresnel::detail {

// Decodes the Zstandard frame(s) in `src` into exactly `dst.size()` bytes; throws
// fresnel::Error(name, "byte N", "Zstandard: ...") when the data is not valid Zstandard, or
// inflates to more or fewer bytes than dst holds. N is the offset in `src` of the structure at
// fault, plus `src_offset` (pass where src starts in the file to name file offsets).
void zstd_decompress(std::span<const std::uint8_t> src, std::span<std::uint8_t> dst, const std::string& name,
                     std::uint64_t src_offset = 0);

// XXH64 of `data` with seed 0 (the content checksum keeps its low 32 bits); exposed for tests.
std::uint64_t zstd_xxh64(std::span<const std::uint8_t> data);

}  // namespace fresnel::detail
