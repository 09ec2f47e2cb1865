// `fresnel trace [MODEL] -o OUT ...`: the CPU path tracer (libs/trace), the ground truth for
// `render`. It takes render's models and scene files and its flags for the camera,
// environment, lights, tone mapping and background (job_options.h), so the same command line
// describes the same scene; every option is documented where it is declared; README.md's CLI
// reference is `fresnel trace --help`.
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <thread>

#include "fresnel/core/atomic_file.h"
#include "cli_common.h"
#include "commands.h"
#include "fresnel/ibl/bake.h"
#include "fresnel/ibl/environment.h"
#include "fresnel/job/job.h"
#include "fresnel/trace/job_inputs.h"
#include "fresnel/trace/tracer.h"
#include "job_options.h"
#include "progress.h"

namespace fresnel::cli {
namespace {

struct TraceOptions : RenderOptions {
    int spp = 64;
    int max_bounces = 16;
    double time_limit = 0;
    std::uint64_t seed = 0;
    unsigned threads = 0;
    bool no_env_visibility = false;
};


int run_trace(const TraceOptions& o, const CLI::App* cmd) {
    auto t_start = Clock::now();
    // Ctrl+C ends the trace after the pass in progress (at least one) and writes what was traced;
    // a second Ctrl+C quits at once.
    InterruptGuard interrupt;
    Diagnostics diag;
    std::string output;
    std::optional<Job> parsed = job_from_command(o, cmd, diag, output);  // usage checks first (exit 2)
    if (!parsed) return kExitUsage;
    std::string ext = lower_extension(output);
    if (ext != ".png" && ext != ".exr" && ext != ".hdr") {
        print_error("-o: output must end in .png, .exr or .hdr: '" + output + "'");
        return kExitUsage;
    }
    parsed->output.float_output = ext == ".exr" || ext == ".hdr";
    const Job& job = *parsed;
    check_writable(output);  // before the trace, whose result would be lost

    auto t_load = Clock::now();
    Scene scene = load_scene(job, diag);
    double load_ms = ms_since(t_load);
    // The same rules as render: camera, lights, environment, background (libs/render/job.h).
    ResolvedJob resolved = resolve(job, scene, &diag);
    print_warnings(diag);
    const RenderSettings& rs = resolved.settings;

    auto t_env = Clock::now();
    trace::JobInputs inputs = trace::load_job_inputs(resolved);  // the environment, the BRDF table
    double env_ms = ms_since(t_env);

    auto t_build = Clock::now();
    trace::TraceScene tscene(scene, resolved.instances, trace::TraceSceneOptions{rs.instancing});
    double build_ms = ms_since(t_build);

    trace::TraceSettings ts;
    ts.samples = o.spp;
    ts.max_bounces = o.max_bounces;
    ts.time_limit_s = o.time_limit;
    ts.seed = o.seed;
    ts.threads = o.threads;
    ts.env_visibility = !o.no_env_visibility;
    ts = inputs.settings(resolved, ts);
    ts.stop = &interrupt.requested();

    trace::TraceStats stats;
    ImageF radiance;
    {
        ProgressBar bar("tracing", true);
        radiance = trace::trace_image(tscene, resolved.camera, resolved.lights, inputs.light(), ts,
                                      &stats, [&](double f) { bar.update(f); });
    }
    ImageF image = trace::to_output(radiance, rs);
    write_image(output, image, resolved.transparent());
    if (stats.stopped)
        std::fprintf(stderr, "fresnel: trace: interrupted: %s has %d of %d samples per pixel\n", output.c_str(),
                     stats.samples, o.spp);

    if (o.json) {
        const CameraSetup& camera = resolved.camera;
        double seconds = stats.trace_ms / 1000.0;
        nlohmann::json j;
        j["output"] = output;
        if (o.models.size() == 1) j["model"] = o.models[0];
        else if (o.models.empty()) j["model"] = "(demo)";
        else j["model"] = o.models;
        j["width"] = rs.width;
        j["height"] = rs.height;
        j["renderer"] = "fresnel trace (CPU, Embree 3)";
        j["threads"] = o.threads ? o.threads : std::max(1u, std::thread::hardware_concurrency());
        j["spp"] = stats.samples;
        j["spp_requested"] = o.spp;
        j["time_limited"] = stats.time_limited;
        j["interrupted"] = stats.stopped;
        j["max_bounces"] = o.max_bounces;
        j["energy_compensation"] = rs.energy_compensation;
        j["env_visibility"] = !o.no_env_visibility;
        j["seed"] = o.seed;
        j["camera_paths"] = stats.camera_paths;
        j["rays"] = stats.rays;
        j["msamples_per_s"] = seconds > 0 ? double(stats.camera_paths) / seconds / 1e6 : 0.0;
        j["mpaths_per_s"] = j["msamples_per_s"];
        j["mrays_per_s"] = seconds > 0 ? double(stats.rays) / seconds / 1e6 : 0.0;
        j["load_ms"] = load_ms;
        j["environment_ms"] = env_ms;
        j["build_ms"] = build_ms;
        j["trace_ms"] = stats.trace_ms;
        j["total_ms"] = ms_since(t_start);
        j["triangles"] = tscene.triangle_count();
        j["stored_triangles"] = tscene.stored_triangle_count();  // a mesh placed several times once
        j["placements"] = tscene.placement_count();             // Embree instances
        j["lights"] = resolved.lights.size();
        j["default_lights"] = resolved.default_lights;
        j["environment"] = resolved.environment ? resolved.environment->describe() : "none";
        j["camera"] = camera_json(camera);
        j["warnings"] = diag.lines();
        std::printf("%s\n", j.dump().c_str());
    }
    return stats.stopped ? kExitInterrupted : kExitOk;
}

}  // namespace

Runner add_trace_command(CLI::App& app) {
    auto o = std::make_shared<TraceOptions>();
    CLI::App* cmd = app.add_subcommand(
        "trace", "Path-trace a glTF model (or the built-in demo) on the CPU: the ground truth for render");
    cmd->footer("Examples:\n"
                "  fresnel trace model.glb -o ref.exr --spp 256 --env sky.hdr # ground truth for render's image\n"
                "  fresnel trace model.glb -o t.png --time-limit 30 --json    # what 30 s reach (Ctrl+C keeps it)\n");
    add_model_and_output(cmd, *o);
    cmd->add_option("--spp", o->spp, "Samples (camera paths) per pixel")->capture_default_str()->check(CLI::Range(1, 1 << 20));
    cmd->add_option("--max-bounces,--bounces", o->max_bounces,
                    "Scattering events per path; 1 = direct light only (punctual lights and one bounce of the "
                    "environment: the rasteriser's light transport)")
        ->capture_default_str()->check(CLI::Range(0, 1024));
    cmd->add_option("--time-limit", o->time_limit,
                    "Stop after the pass during which this many seconds have passed (0 = none); --json reports the "
                    "samples reached")
        ->capture_default_str()->check(CLI::NonNegativeNumber);
    cmd->add_option("--seed", o->seed, "Random seed: the same seed gives the same image")->capture_default_str();
    cmd->add_option("--threads", o->threads, "Worker threads (0 = all cores)")->capture_default_str();
    cmd->add_flag("--no-env-visibility", o->no_env_visibility,
                  "Environment light is never shadowed (as in real-time image-based lighting); punctual lights are");
    cmd->add_flag("--json", o->json, "Print timings, samples, Msamples/s and the camera as one JSON line");
    add_job_flags(cmd, *o, JobFlagSet::Trace);
    return [o, cmd] { return run_trace(*o, cmd); };
}

}  // namespace fresnel::cli
