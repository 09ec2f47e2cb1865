// `fresnel render [MODEL] -o OUT ...`: headless rendering to PNG, EXR or HDR.
// Every option is documented where it is declared: here, or in cli_common.cpp for the
// flags render shares with trace; README.md's CLI reference is the output of
// `fresnel render --help`.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli_common.h"
#include "commands.h"
#include "fresnel/gpu/context.h"
#include "fresnel/ibl/environment.h"
#include "fresnel/render/job.h"
#include "fresnel/render/renderer.h"
#include "progress.h"

namespace fresnel::cli {
namespace {

// render's own flags; the Job's are JobOptions (cli_common.h), shared with `trace`.
struct RenderOptions : JobOptions {
    int msaa = 4;
    float anisotropy = 16;
    std::string debug = "none";
    bool gl_debug = false;
    std::string gl = "gl33";
    bool no_cache = false;
    bool no_energy_compensation = false;
    int env_samples = 1024;
    int env_size = 256;
};

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

// The job the flags describe: the shared flags (job_from_options), then render's own.
std::optional<Job> render_job(const RenderOptions& o) {
    std::optional<Job> job = job_from_options(o);
    if (!job) return job;
    auto debug = parse_debug_channel(o.debug);
    if (!debug) {
        print_error("--debug: unknown channel '" + o.debug + "'");
        return std::nullopt;
    }
    Job::Output& out = job->output;
    out.debug = *debug;
    out.msaa = o.msaa;
    out.anisotropy = o.anisotropy;
    out.energy_compensation = !o.no_energy_compensation;
    Job::Environment& env = job->environment;
    env.bake_samples = o.env_samples;
    env.bake_size = o.env_size;
    env.use_cache = !o.no_cache;
    return job;
}

int run_render(const RenderOptions& o) {
    auto t_start = Clock::now();
    std::optional<Job> parsed = render_job(o);  // usage checks first (exit 2), before touching files
    if (!parsed) return kExitUsage;
    const Job& job = *parsed;

    // Scene, then the rules of README.md's "Lighting rules" (libs/render/job.h).
    Diagnostics diag;
    auto t_load = Clock::now();
    Scene scene = load_scene(job, diag);
    double load_ms = ms_since(t_load);
    print_warnings(diag);
    ResolvedJob resolved = resolve(job, scene);
    std::string label = "baking " + (resolved.environment ? resolved.environment->describe() : std::string());
    ProgressBar bar(label);
    JobLighting lighting = load_lighting(resolved, [&](double f) { bar.update(f); });
    bar.finish();

    // GPU.
    auto t_gpu = Clock::now();
    gpu::ContextOptions co;
#ifndef NDEBUG
    co.debug = true;  // debug builds always report KHR_debug messages
#else
    co.debug = o.gl_debug;
#endif
    co.api = o.gl == "es3" ? gpu::Api::OpenGLES30 : gpu::Api::OpenGL33;
    co.log = [](const std::string& m) { std::fprintf(stderr, "fresnel: %s\n", m.c_str()); };
    auto context = gpu::create_headless_context(co);
    Renderer renderer(*context);
    renderer.set_scene(scene, resolved.scene_index);
    double upload_ms = ms_since(t_gpu);

    RenderSettings rs = lighting.settings(resolved);
    auto t_frame = Clock::now();
    FrameStats stats;
    ImageF image = renderer.render(resolved.camera, resolved.lights, rs, &stats);
    double frame_ms = ms_since(t_frame);
    if (!stats.gl_errors.empty()) throw Error("OpenGL", "", "the frame raised " + stats.gl_errors);

    write_output(o.output, image, resolved.transparent());

    if (o.json) {
        const CameraSetup& camera = resolved.camera;
        const auto& environment = lighting.environment;
        nlohmann::json j;
        j["output"] = o.output;
        j["model"] = o.model.empty() ? "(demo)" : o.model;
        j["width"] = rs.width;
        j["height"] = rs.height;
        j["renderer"] = context->renderer();
        j["gl_version"] = context->version();
        j["gl_api"] = gpu::api_name(context->api());
        j["load_ms"] = load_ms;
        j["upload_ms"] = upload_ms;
        j["frame_ms"] = frame_ms;
        j["total_ms"] = ms_since(t_start);
        j["draw_calls"] = stats.draw_calls;
        j["triangles"] = stats.triangles;
        j["programs"] = renderer.program_count();
        j["lights"] = resolved.lights.size();
        j["default_lights"] = resolved.default_lights;
        j["environment"] = environment ? environment->source : "none";
        j["environment_ms"] = lighting.environment_ms;
        j["environment_cached"] = environment ? environment->from_cache : false;
        j["camera"] = {{"eye", {camera.eye.x, camera.eye.y, camera.eye.z}},
                       {"target", {camera.target.x, camera.target.y, camera.target.z}},
                       {"znear", camera.znear}, {"zfar", camera.zfar}, {"yfov_deg", camera.yfov_deg}};
        j["warnings"] = diag.lines();
        std::printf("%s\n", j.dump().c_str());
    }
    return kExitOk;
}

}  // namespace

Runner add_render_command(CLI::App& app) {
    auto o = std::make_shared<RenderOptions>();
    CLI::App* cmd = app.add_subcommand("render", "Render a glTF model (or the built-in demo) to an image, headless");
    add_view_options(cmd, *o);
    cmd->add_option("--env-samples", o->env_samples, "GGX samples per texel when baking")->capture_default_str()
        ->check(CLI::Range(1, 65536));
    cmd->add_option("--env-size", o->env_size, "Specular cube face size when baking (power of two)")
        ->capture_default_str();
    cmd->add_flag("--no-cache", o->no_cache, "Neither read nor write $XDG_CACHE_HOME/fresnel: bake the environment and the BRDF table again");
    cmd->add_flag("--no-energy-compensation", o->no_energy_compensation,
                  "Single-scattering specular only (no multiple-scattering compensation of punctual lights)");
    add_light_options(cmd, *o);
    cmd->add_option("--msaa", o->msaa, "MSAA samples (1 = off)")->capture_default_str()->check(CLI::Range(1, 16));
    cmd->add_option("--anisotropy", o->anisotropy,
                    "Anisotropic filtering of the detail maps (base colour, metallic-roughness, normal, specular "
                    "colour, clearcoat normal) with trilinear samplers, 1 = off. 16 matches the Khronos Sample "
                    "Viewer's images best; on software rasterisers each level above 1 costs frame time")
        ->capture_default_str()->check(CLI::Range(1.0f, 16.0f));
    cmd->add_option("--debug", o->debug,
                    "Show a channel instead of shading: basecolor metallic roughness normal geometry-normal tangent "
                    "bitangent occlusion emissive alpha uv0 uv1 D G F diffuse specular irradiance prefiltered ibl-diffuse "
                    "ibl-specular (NaN/Inf show as magenta)")
        ->capture_default_str();
    cmd->add_flag("--json", o->json, "Print timings, camera and counts as one JSON line");
    add_file_options(cmd, *o);
    cmd->add_flag("--gl-debug", o->gl_debug, "Request a debug GL context and print KHR_debug messages");
    cmd->add_option("--gl", o->gl, "Graphics API: gl33 (OpenGL 3.3 core) or es3 (OpenGL ES 3.0; same pictures)")
        ->capture_default_str()
        ->check(CLI::IsMember({"gl33", "es3"}));
    add_pose_options(cmd, *o);
    return [o] { return run_render(*o); };
}

}  // namespace fresnel::cli
