#pragma once
// Shader sources embedded at build time from the files in shaders/.
#include <string_view>
#include <vector>

namespace fresnel::shaders {
// The source of `name` (e.g. "brdf.glsl"), or an empty view when there is no such file.
std::string_view find(std::string_view name);
std::vector<std::string_view> names();
}  // namespace fresnel::shaders
