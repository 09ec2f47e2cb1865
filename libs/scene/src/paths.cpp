#include "fresnel/scene/paths.h"

#include "uri_policy.h"

namespace fresnel {

std::optional<std::filesystem::path> resolve_relative_path(const std::string& uri, const std::filesystem::path& base_dir,
                                                           bool allow_external, std::string& error) {
    if (gltf::is_data_uri(uri)) {
        error = "'data:' URIs name no file";
        return std::nullopt;
    }
    auto path = gltf::resolve_uri(uri, base_dir, allow_external, error);
    // The glTF loader's wording names the model; here the folder is the naming file's.
    for (auto at = error.find("the model's folder"); at != std::string::npos; at = error.find("the model's folder"))
        error.replace(at, 18, "the file's folder");
    return path;
}

}  // namespace fresnel
