#pragma once
// EXT_meshopt_compression: bufferViews whose bytes are meshoptimizer-encoded in another
// buffer. Each such view is decoded once, before any accessor reads it, into a buffer of
// its own, and the view is pointed at it, so accessors and images read it as any view.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "json_reader.h"

namespace fresnel::gltf {

// Decodes every bufferView of `doc` that carries EXT_meshopt_compression, appending the
// decoded bytes to `buffers` and rewriting the view's buffer/byteOffset. Every size is
// checked before allocating: the decoded size (count x byteStride) must fit the view's
// byteLength and `max_bytes`; `account(bytes, pointer)` is called before each allocation
// (it throws past the loader's total limit). Throws fresnel::Error naming the view.
void decode_meshopt_views(const JsonReader& r, json& doc, std::vector<std::vector<std::uint8_t>>& buffers,
                          std::size_t max_bytes, const std::function<void(std::size_t, const std::string&)>& account);

// True when buffer `index` is only a fallback placeholder of EXT_meshopt_compression.
bool is_meshopt_fallback_buffer(const JsonReader& r, const json& buffer);

}  // namespace fresnel::gltf
