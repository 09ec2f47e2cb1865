#pragma once
// Scene files (*.fresnel.json): a render job written down, so a look can be versioned,
// shared and reloaded. The format is docs/scene.schema.json (JSON Schema), described in
// docs/scene-file.md; the "fresnel" key holds the format's version (kSceneFileVersion).
//
// A scene file is read *onto* a job: keys present replace the job's values, keys absent
// keep them. So `fresnel render` reads the file onto the default job, then applies the
// flags the user gave; `fresnel batch` reads each job onto the job its flags describe.
//
// The file is hostile input: its size and nesting are capped, every value is type- and
// range-checked (fresnel::Error naming the file and the JSON pointer, e.g.
// "/models/1/translation/2"), paths are relative to the file's folder and may not leave it
// (the URI policy of models, fresnel/scene/paths.h) unless external files are allowed.
// Unknown keys are warnings naming their pointer. Settings (camera.yaw, render.exposure, ...)
// are read through the settings registry, with its ranges and its one error message.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fresnel/core/error.h"
#include "fresnel/job/job.h"

namespace fresnel {

inline constexpr int kSceneFileVersion = 1;

struct SceneFileOptions {
    bool allow_external_files = false;  // paths outside the file's folder (absolute, ..)
    std::size_t max_bytes = std::size_t(16) << 20;
    int max_depth = 64;  // nesting of arrays and objects
    // false: the "fresnel" version key may be absent (inline jobs of a batch job list).
    bool require_version = true;
};

struct SceneFile {
    Job job;
    // "output": the image to write, resolved against the file's folder (as written when
    // external files are allowed and it is absolute).
    std::optional<std::filesystem::path> output;
};

// True for names ending in ".json" (scene files; models are .gltf, .glb, ...).
bool is_scene_file(const std::filesystem::path& path);

// Reads the scene file `path` onto `defaults`. Throws fresnel::Error (file, pointer, reason);
// warnings (unknown keys, ignored values) go to `diag`.
SceneFile load_scene_file(const std::filesystem::path& path, const Job& defaults, Diagnostics& diag,
                          const SceneFileOptions& options = {});

// The same for scene-file text already read: `name` appears in messages, relative paths
// resolve against `base_dir`. `ignore` lists top-level keys the caller handles (no
// unknown-key warning). (fresnel/job/scene_document.h, target fresnel::job_json, has the
// same on parsed nlohmann::json documents, for callers that build documents.)
SceneFile parse_scene_text(std::string_view text, const std::string& name, const std::filesystem::path& base_dir,
                           const Job& defaults, Diagnostics& diag, const SceneFileOptions& options = {},
                           const std::vector<std::string>& ignore = {});

// The other way: `job` as a scene file, every field a scene file holds (the reader
// gives the same job back, floats exactly). Paths are written relative to `base_dir` (the
// folder the file will be in); those outside it are written with "..", or absolute when no
// relative path exists, and listed in `outside` (the reader then needs allow_external_files).
// The settings are written through the settings registry (fresnel/job/settings.h): those
// that differ from the default job's, at their keys' places. `dropped` lists what a scene file
// cannot hold (nothing the registry offers to scene files). `output` is written as "output"
// when given.
struct SceneDocumentReport {
    std::vector<std::string> outside, dropped;
};
// The document as save_scene_file writes it (two-space indents, a final newline).
std::string scene_text(const Job& job, const std::filesystem::path& base_dir,
                       const std::optional<std::filesystem::path>& output = {}, SceneDocumentReport* report = nullptr);

// Writes scene_text(job, the file's folder) to `path` atomically (a temporary file in the
// same folder, flushed, renamed over `path`; a failed write leaves `path` as it was). Files
// outside the folder and dropped fields are warnings in `diag`. Throws fresnel::Error.
void save_scene_file(const std::filesystem::path& path, const Job& job, Diagnostics& diag,
                     const std::optional<std::filesystem::path>& output = {});

}  // namespace fresnel
