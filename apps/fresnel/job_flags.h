#pragma once
// The flags that describe a fresnel::Job (camera, environment, lights, tone mapping,
// output), declared once for every subcommand that renders (`render`, `view`), and the
// way back: the `fresnel render ...` command line of a Job (the viewer's "copy as command
// line"). Every flag is documented here, where it is declared; README.md's CLI reference
// is the output of --help.
#include <CLI/CLI.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fresnel/gpu/context.h"
#include "fresnel/render/job.h"

namespace fresnel::cli {

struct JobFlags {
    std::string model;
    std::string size = "1024x768";
    float yaw = 0, pitch = 0;
    std::optional<float> distance;
    float fov = 45.0f;
    std::string target;  // X,Y,Z; empty = the bounds' centre
    std::optional<int> camera;
    int scene = -1;
    std::string tonemap = "neutral";
    float exposure = 0;
    std::string encoding = "srgb";
    std::string background;
    std::vector<std::string> lights;
    bool no_scene_lights = false;
    int msaa = 4;
    float anisotropy = 16;
    std::string debug = "none";
    bool allow_external = false;
    bool gl_debug = false;
    std::string gl = "gl33";
    bool pose_skins = false;
    std::string env;
    bool env_given = false;
    float env_rotation = 0;
    float env_intensity = 1;
    bool no_ibl = false;
    bool no_cache = false;
    bool no_energy_compensation = false;
    int env_samples = 1024;
    int env_size = 256;
};

// Registers --size ... --debug on `cmd` (in `fresnel render --help`'s order); `size_help`
// describes --size, whose default is flags->size.
void add_job_flags(CLI::App* cmd, const std::shared_ptr<JobFlags>& flags, const std::string& size_help);
// Registers --allow-external-files, --gl-debug, --gl and --pose-skins.
void add_input_flags(CLI::App* cmd, const std::shared_ptr<JobFlags>& flags);

// The job the flags describe. Usage errors are printed and give nullopt (exit 2), before
// any file is touched; a malformed --env throws fresnel::Error (exit 1). `output`, when
// given, is `render -o`'s file: its extension must be .png, .exr or .hdr and picks float output.
std::optional<Job> job_from_flags(const JobFlags& flags, const std::string* output = nullptr);

// The GL context the flags ask for (--gl, --gl-debug; debug builds always debug), logging to stderr.
gpu::ContextOptions context_options(const JobFlags& flags);

// Quotes `s` for a POSIX shell when it needs it ('...').
std::string shell_quote(const std::string& s);

// The `fresnel render` command line that renders `job` to `output`: the job's model, then
// only the flags whose values differ from the defaults (numbers in their shortest exact
// form, so the line parses back to the same job; lights as dir:/point: specs).
std::string render_command_line(const Job& job, const std::string& output);

}  // namespace fresnel::cli
