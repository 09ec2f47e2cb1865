#pragma once
// Helpers shared by the subcommands: exit codes, error and warning printing, and the flags
// that describe what to draw (model, camera, environment, lights, tone mapping), which
// `render` and `trace` share so that the same flags give the same Job.
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "fresnel/core/error.h"
#include "fresnel/core/image.h"
#include "fresnel/render/job.h"

namespace fresnel::cli {

// Exit codes: 0 success, 1 bad input, 2 bad usage.
inline constexpr int kExitOk = 0, kExitBadInput = 1, kExitUsage = 2;

// Prints "fresnel: error: FILE: WHERE: WHAT" to stderr.
void print_error(const Error& e);
void print_error(const std::string& message);
// Prints each unique warning once to stderr ("fresnel: warning: ... (xN)"), then a count.
void print_warnings(const Diagnostics& d);

// The flags of a Job that every image-making command takes.
struct JobOptions {
    std::string model;
    std::string output;
    std::string size = "1024x768";
    float yaw = 0, pitch = 0;
    std::optional<float> distance;
    float fov = 45.0f;
    std::optional<int> camera;
    int scene = -1;
    std::string tonemap = "neutral";
    float exposure = 0;
    std::string encoding = "srgb";
    std::string background;
    std::vector<std::string> lights;
    bool no_scene_lights = false;
    bool json = false;
    bool allow_external = false;
    bool pose_skins = false;
    std::string env;
    bool env_given = false;
    float env_rotation = 0;
    float env_intensity = 1;
    bool no_ibl = false;
};

// Registers the flags on `cmd`, in the order `fresnel render --help` lists them; `o` must
// outlive the parse. The model, output, camera, tone mapping, background and environment:
void add_view_options(CLI::App* cmd, JobOptions& o);
// --light, --no-scene-lights:
void add_light_options(CLI::App* cmd, JobOptions& o);
// --allow-external-files:
void add_file_options(CLI::App* cmd, JobOptions& o);
// --pose-skins:
void add_pose_options(CLI::App* cmd, JobOptions& o);

// The job the flags describe. Usage errors are printed and give nullopt (exit 2), before
// any file is touched; a malformed --env throws fresnel::Error (exit 1).
std::optional<Job> job_from_options(const JobOptions& o);

// The lower-case extension of a path (".png").
std::string lower_extension(const std::string& path);
// Writes a frame as `render` does: PNG (8-bit from display-encoded values, RGBA when
// `transparent`), EXR or HDR by the file's extension.
void write_output(const std::string& path, const ImageF& image, bool transparent);

}  // namespace fresnel::cli
