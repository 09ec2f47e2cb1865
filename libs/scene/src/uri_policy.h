#pragma once
// Where a glTF URI may point: data URIs, and relative paths inside the model's
// folder. Anything else (absolute paths, ".." escapes, scheme://) is refused
// unless external files are allowed; network URIs are refused always.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace fresnel::gltf {

bool is_data_uri(const std::string& uri);

// Decodes "data:[mime][;base64],payload". Returns nullopt with `error` set on bad input.
std::optional<std::vector<std::uint8_t>> decode_data_uri(const std::string& uri, std::size_t max_bytes,
                                                         std::string& mime, std::string& error);

// Percent-decodes a URI path ("%20" -> " ").
std::string percent_decode(const std::string& s);

// Resolves a non-data URI to a file path, or returns nullopt with `error` naming the reason.
std::optional<std::filesystem::path> resolve_uri(const std::string& uri, const std::filesystem::path& base_dir,
                                                 bool allow_external, std::string& error);

// Resolves a file path written in a model file that is not a URI (OBJ's mtllib, MTL's
// texture maps: no percent-decoding, '\\' taken as '/'), relative to `base_dir`; the result
// must stay inside `root_dir` (the model's folder) unless external files are allowed.
// Schemes (http:, file:, ...) are refused always; absolute paths unless allowed.
std::optional<std::filesystem::path> resolve_model_path(const std::string& path, const std::filesystem::path& base_dir,
                                                        const std::filesystem::path& root_dir, bool allow_external,
                                                        std::string& error);

}  // namespace fresnel::gltf
