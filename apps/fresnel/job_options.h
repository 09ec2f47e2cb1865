#pragma once
// The flags that describe a render job, shared by `render` and `trace` (the job), `view` (the
// first frame) and `batch` (every job's defaults), and how they become a fresnel::Job. They
// are declared and documented once, in job_options.cpp (add_job_flags).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
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
    std::optional<float> time;       // render --time: seconds on the animations' timeline
    std::optional<int> animation;    // render --animation: which one (default: all)
    std::optional<int> frames;       // render --frames: numbered images from --time
    std::string posing = "gpu";      // render --posing: skins and morph targets on the gpu or the cpu
    std::string size = "1024x768";
    float yaw = 0, pitch = 0;
    std::optional<float> distance;
    float fov = 45.0f;
    std::string target;  // --target X,Y,Z; empty = the bounds' centre
    std::optional<int> camera;
    int scene = -1;
    std::string tonemap = "neutral";
    float exposure = 0;
    std::string encoding = "srgb";
    std::string background;
    std::vector<std::string> lights;
    bool no_scene_lights = false;
    int msaa = 0;  // 0: not given (4, or 1 with --shading ogl1 / ogl1-pixel)
    float anisotropy = kDefaultAnisotropy;
    std::string debug = "none";
    bool json = false;
    bool allow_external = false;
    bool gl_debug = false;
    std::string gl = "gl33";
    bool pose_skins = false;
    std::string obj_normals = "auto";
    std::string variant;  // KHR_materials_variants name; empty = the default materials
    std::string env;
    bool env_given = false;
    float env_rotation = 0;
    float env_intensity = 1;
    bool no_ibl = false;
    bool no_cache = false;
    bool no_energy_compensation = false;
    int env_samples = 1024;
    int env_size = 256;
    std::string brdf;              // --brdf D=...,G=...,F=...,diffuse=... (empty: glTF's terms)
    std::string shading = "auto";  // --shading, --ambient, --fog, --fog-color (legacy models)
    std::string ambient;
    std::string fog;
    std::string fog_color;
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
// malformed --env throws fresnel::Error (exit 1).
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

// Writes a rendered frame to `path` (.png 8-bit, .exr, .hdr) atomically: into a temporary
// file in the same folder, renamed over `path` when complete. Throws fresnel::Error.
void write_image_atomically(const std::string& path, const ImageF& image, bool transparent);
// The same for an 8-bit image already quantised (Renderer::render8), to a .png path.
void write_png_atomically(const std::string& path, const Image8& image);


}  // namespace fresnel::cli
