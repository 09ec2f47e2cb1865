// `fresnel render [MODEL] -o OUT ...`: headless rendering to PNG, EXR or HDR.
// Every option is documented here, where it is declared; README.md's CLI
// reference is the output of `fresnel render --help`.
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
#include "job_flags.h"
#include "progress.h"

namespace fresnel::cli {
namespace {

struct RenderOptions {
    std::shared_ptr<JobFlags> job = std::make_shared<JobFlags>();
    std::string output;
    bool json = false;
};

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

std::string lower_extension(const std::string& path) {
    std::string e = std::filesystem::path(path).extension().string();
    for (auto& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

int run_render(const RenderOptions& ro) {
    auto t_start = Clock::now();
    const JobFlags& o = *ro.job;
    std::optional<Job> parsed = job_from_flags(o, &ro.output);  // usage checks first (exit 2), before touching files
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
    gpu::ContextOptions co = context_options(o);
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

    std::string ext = lower_extension(ro.output);
    if (ext == ".png") write_png(ro.output, to_image8(image, resolved.transparent()));
    else if (ext == ".exr") write_exr(ro.output, image);
    else write_hdr(ro.output, image);

    if (ro.json) {
        const CameraSetup& camera = resolved.camera;
        const auto& environment = lighting.environment;
        nlohmann::json j;
        j["output"] = ro.output;
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
    cmd->add_option("model", o->job->model, "glTF 2.0 file (.gltf/.glb); omitted: the built-in demo (7x7 spheres)");
    cmd->add_option("-o,--output", o->output,
                    "Output image: .png (8-bit, display-encoded), .exr/.hdr (linear float after exposure and tone map)")
        ->required();
    add_job_flags(cmd, o->job, "Image size WxH");
    cmd->add_flag("--json", o->json, "Print timings, camera and counts as one JSON line");
    add_input_flags(cmd, o->job);
    return [o] { return run_render(*o); };
}

}  // namespace fresnel::cli
