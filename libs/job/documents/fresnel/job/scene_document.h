#pragma once
// Scene files as parsed JSON documents (nlohmann::json), for callers that build or patch
// documents before reading them (batch: a job line's keys over a scene file, sweeps by JSON
// pointer). The target fresnel::job_json offers this header and links nlohmann_json; the job
// library itself keeps nlohmann_json private (fresnel/job/scene_file.h speaks text).
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "fresnel/job/scene_file.h"

namespace fresnel {

// parse_scene_text on a document already parsed.
SceneFile parse_scene_document(const nlohmann::json& doc, const std::string& name,
                               const std::filesystem::path& base_dir, const Job& defaults, Diagnostics& diag,
                               const SceneFileOptions& options = {}, const std::vector<std::string>& ignore = {});

// Parses JSON text with the options' size and depth limits; throws fresnel::Error (name,
// "byte N", reason). For job lists and other JSON the scene-file rules apply to.
nlohmann::json parse_json_limited(std::string_view text, const std::string& name, const SceneFileOptions& options = {});

// scene_text's document.
nlohmann::json scene_document(const Job& job, const std::filesystem::path& base_dir,
                              const std::optional<std::filesystem::path>& output = {},
                              SceneDocumentReport* report = nullptr);

}  // namespace fresnel
