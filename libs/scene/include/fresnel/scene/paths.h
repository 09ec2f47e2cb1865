#pragma once
// The URI policy of models, for other files that name files (scene files, batch job lists):
// relative paths inside `base_dir`; absolute paths and ".." escapes only with `allow_external`;
// never a scheme (http:, file:, ...). The same rules as glTF URIs (percent-decoded).
#include <filesystem>
#include <optional>
#include <string>

namespace fresnel {

// The path `uri` names relative to `base_dir`, or nullopt with `error` saying why it is refused.
std::optional<std::filesystem::path> resolve_relative_path(const std::string& uri, const std::filesystem::path& base_dir,
                                                           bool allow_external, std::string& error);

}  // namespace fresnel
