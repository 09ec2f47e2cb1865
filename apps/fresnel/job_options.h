#pragma once
// The flags that describe a render job, shared by `render` and `trace` (the job), `view` (the
// first frame) and `batch` (every job's defaults), and how they become a fresnel::Job. The
// settings' flags come from the settings registry (fresnel/job/settings.h, add_job_flags);
// the others (--light, --gl, --gl-debug) are declared in job_options.cpp.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "fresnel/job/job.h"

namespace fresnel::cli {

struct RenderOptions {
    std::vector<std::string> models;  // render: glTF files, or one scene file; empty: the demo
    std::string output;
    int turntable = 0;       // render --turntable N
    std::string video;       // render --video FILE.mp4
    int fps = 24;            // render --fps: of --frames and --video
    std::optional<int> frames;       // render --frames: numbered images from --time (the settings' animation.time)
    std::string posing = "gpu";      // render --posing: skins and morph targets on the gpu or the cpu
    // The job settings (fresnel/job/settings.h) as given on the command line: a valued flag's
    // text by the setting's key, a switch (--no-cache, --pose-skins) by its key, a shortcut
    // (--no-ibl) by its flag. A value
    // present before parsing is that command's default (view: render.size 1280x720).
    std::map<std::string, std::string> settings;
    std::map<std::string, bool> switches;
    std::vector<std::string> lights;  // --light SPEC (repeatable): the added lights, not a setting
    bool json = false;
    bool gl_debug = false;
    std::string gl = "gl33";
    // --allow-external-files (the setting allowExternalFiles), which also governs the scene file's paths.
    bool allow_external() const {
        auto it = switches.find("allowExternalFiles");
        return it != switches.end() && it->second;
    }
};

// Which flags apply. Without a command (`cmd` null) every flag does, defaults included: the
// flags alone describe the job. With one, only those the user gave (CLI11's count()): they
// override a scene file.
// A flag the command does not take (JobFlagSet::Trace) counts as not given.
struct GivenFlags {
    const CLI::App* cmd = nullptr;
    bool operator()(const char* name) const { return !cmd || explicitly(name); }
    bool explicitly(const char* name) const {
        const CLI::Option* opt = cmd ? cmd->get_option_no_throw(name) : nullptr;
        return opt && opt->count() > 0;
    }
};

// Which job flags a command takes: all of them (render, batch), or those that describe the
// scene, camera, light and image but not the rasteriser (trace: no --msaa, --anisotropy,
// --debug, --gl, --gl-debug, --env-samples, --env-size, --no-cache, --no-energy-compensation).
enum class JobFlagSet { Raster, Trace };

// Registers the job flags (all of render's but the model, -o, --turntable, --video, --fps and
// --json) on `cmd`.
void add_job_flags(CLI::App* cmd, RenderOptions& o, JobFlagSet set = JobFlagSet::Raster);

// Registers the positional model(s) and -o/--output of a command that renders one job
// (render, trace), with one wording for both.
void add_model_and_output(CLI::App* cmd, RenderOptions& o);

// A resolved camera as the --json reports of render and trace give it.
nlohmann::json camera_json(const CameraSetup& camera);

// `job` with the given flags applied (the output's float/encoded choice is the caller's).
// Usage errors are printed and give nullopt (exit 2), before any file is touched; a
// malformed value of a setting is a usage error too (the registry's message).
std::optional<Job> job_from_options(const RenderOptions& o, Job job, const GivenFlags& given = {});

// The context options the flags ask for (--gl, --gl-debug; debug builds always debug).
struct ContextFlags {
    bool debug = false;
    bool es3 = false;
};
ContextFlags context_flags(const RenderOptions& o);

// The job of a command line (render, trace): a scene file (the one model) read onto the
// default job, then the flags the user gave; or the flags alone for models and the demo.
// `output` is -o, else the scene file's "output". Usage errors are printed and give nullopt
// (exit 2); a bad scene file throws fresnel::Error (exit 1).
// The same without the output rule, read onto `defaults` (the viewer's window size):
// `scene_output` gets the scene file's "output" when there is one.
std::optional<Job> job_from_sources(const RenderOptions& o, const CLI::App* cmd, Diagnostics& diag, const Job& defaults,
                                    std::string* scene_output = nullptr);
std::optional<Job> job_from_command(const RenderOptions& o, const CLI::App* cmd, Diagnostics& diag,
                                    std::string& output);

// Writes a rendered frame to `path` (.png 8-bit, .exr, .hdr), whole or absent as every image
// writer (fresnel/core/image.h). Throws fresnel::Error naming `path` and the reason.
void write_image(const std::string& path, const ImageF& image, bool transparent);


}  // namespace fresnel::cli
