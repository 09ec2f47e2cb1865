// `fresnel render [MODEL... | SCENE.fresnel.json] -o OUT ...`: headless rendering to PNG, EXR or HDR.
// Every option is documented where it is declared: here, or in job_options.cpp for the job
// flags render shares with batch, trace and view; docs/cli-reference.md is the output of
// `fresnel render --help`.
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>
#include <filesystem>
#include <future>
#include <optional>
#include <nlohmann/json.hpp>
#include <sstream>

#include "fresnel/core/process_memory.h"
#include "fresnel/core/atomic_file.h"
#include "cli_common.h"
#include "commands.h"
#include "fresnel/gpu/context.h"
#include "fresnel/ibl/environment.h"
#include "fresnel/job/job.h"
#include "fresnel/render/renderer.h"
#include "fresnel/render/scene_posing.h"
#include "fresnel/trace/job_inputs.h"
#include "fresnel/job/scene_file.h"
#include "fresnel/scene/pose.h"
#include "command_line.h"
#include "job_options.h"
#include "progress.h"

namespace fresnel::cli {
namespace {


// `i` zero-padded to `width` digits.
std::string padded(long long i, int width) {
    std::string d = std::to_string(i);
    return d.size() < std::size_t(width) ? std::string(std::size_t(width) - d.size(), '0') + d : d;
}

// The frame pattern in OUT: its one "%d" or "%0Nd" (N <= 9) as (position, length, width); nullopt without.
std::optional<std::array<std::size_t, 3>> frame_pattern(const std::string& output) {
    std::size_t at = output.find('%');
    if (at == std::string::npos) return std::nullopt;
    std::size_t k = at + 1, width = 0;
    if (k < output.size() && output[k] == '0') ++k;
    while (k < output.size() && std::isdigit(static_cast<unsigned char>(output[k])) && width < 10)
        width = width * 10 + std::size_t(output[k++] - '0');
    if (k >= output.size() || output[k] != 'd' || width > 9 || output.find('%', k) != std::string::npos)
        return std::nullopt;
    return std::array<std::size_t, 3>{at, k + 1 - at, width};
}

// The frame width used without a pattern: at least 3 digits.
int frame_digits(int n) { return std::max(3, int(std::to_string(std::max(n - 1, 0)).size())); }

// Frame `i` of `n`: OUT with its %d / %0Nd filled in, else "-NNN" before the extension.
std::string frame_path(const std::string& output, int i, int n) {
    if (auto p = frame_pattern(output))
        return output.substr(0, (*p)[0]) + padded(i, int((*p)[2])) + output.substr((*p)[0] + (*p)[1]);
    std::filesystem::path p(output);
    return (p.parent_path() / (p.stem().string() + "-" + padded(i, frame_digits(n)) + p.extension().string())).string();
}

// The ffmpeg on PATH, or empty.
std::string find_program(const std::string& name) {
    const char* path = std::getenv("PATH");
    std::stringstream ss(path ? path : "");
    std::string dir;
    while (std::getline(ss, dir, ':')) {
        if (dir.empty()) continue;
        std::filesystem::path p = std::filesystem::path(dir) / name;
        if (::access(p.c_str(), X_OK) == 0) return p.string();
    }
    return {};
}

// Encodes the numbered PNG frames of `output` into an H.264 MP4 with ffmpeg (no shell).
void encode_video(const std::string& ffmpeg, const std::string& output, int n, int fps, const std::string& video) {
    std::string pattern = output;
    if (!frame_pattern(output)) {
        std::filesystem::path p(output);
        pattern = (p.parent_path() / (p.stem().string() + "-%0" + std::to_string(frame_digits(n)) + "d" +
                                      p.extension().string())).string();
    }
    std::vector<std::string> args = {ffmpeg, "-y", "-loglevel", "error", "-framerate", std::to_string(fps),
                                     "-i", pattern, "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264",
                                     "-pix_fmt", "yuv420p", video};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = ::fork();
    if (pid < 0) throw Error(video, "", "cannot start ffmpeg");
    if (pid == 0) {
        ::execv(argv[0], argv.data());
        ::_exit(127);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        throw Error(video, "", "ffmpeg failed (exit " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")");
}

int run_render(const RenderOptions& o, const CLI::App* cmd) {
    auto t_start = Clock::now();
    Diagnostics diag;
    std::string output;
    std::optional<Job> parsed = job_from_command(o, cmd, diag, output);
    if (!parsed) return kExitUsage;
    std::string ext = lower_extension(output);
    parsed->output.float_output = ext == ".exr" || ext == ".hdr";
    if (!parsed->output.float_output && ext != ".png") {
        print_error("-o: output must end in .png, .exr or .hdr: '" + output + "'");
        return kExitUsage;
    }
    check_writable(output);  // before loading and rendering
    if (!o.video.empty() && (o.turntable < 1 || ext != ".png")) {
        print_error("--video: needs --turntable N and PNG frames");
        return kExitUsage;
    }
    std::string ffmpeg;
    if (!o.video.empty()) {
        ffmpeg = find_program("ffmpeg");
        if (ffmpeg.empty()) {
            print_error("--video: ffmpeg is not installed (Debian: apt-get install ffmpeg); no frames rendered");
            return kExitBadInput;
        }
    }
    Job& job = *parsed;
    if (o.turntable > 0 && (job.camera.scene_camera || job.camera.look_at)) {
        print_error("--turntable: turns the orbit camera; not with --camera or a scene file's lookAt/model camera");
        return kExitUsage;
    }
    const Job::Source::Animation animation = job.source.animation;
    const bool animated = animation.posed() || o.frames;
    if (o.turntable > 0 && o.frames) {
        print_error("--turntable and --frames: one frame sequence at a time (--turntable N --time T turns an animated model posed at T)");
        return kExitUsage;
    }

    // Scene (at rest: posed below, frame by frame), then the rules of docs/shading.md's
    // "Lighting rules" (fresnel/job/job.h).
    // One frame (or a sequence) from one load: each decoded image is freed once its textures
    // are on the GPU (llvmpipe's copies reuse its memory; a texture asked for later decodes it
    // again). `--ao baked` traces the scene, which reads the images: they stay.
    const bool release_images = job.output.ao != AmbientOcclusion::Baked;
    if (release_images) keep_freed_memory_for_reuse();
    auto t_load = Clock::now();
    Scene scene = load_rest_scene(job, diag, LoadKeep{.encoded_images = release_images});
    double load_ms = ms_since(t_load);
    ResolvedJob resolved = resolve(job, scene, &diag);
    print_warnings(diag);
    const std::string model_name = o.models.empty() ? std::string("demo") : o.models[0];
    std::string label = "baking " + (resolved.environment ? resolved.environment->describe() : std::string());
    ProgressBar bar(label);
    // The environment loads (or bakes) while the GPU context starts: independent work, each
    // mostly on one core (the context's start is the GL driver's loading).
    std::future<JobLighting> lighting_task =
        std::async(std::launch::async, [&] { return load_lighting(resolved, [&](double f) { bar.update(f); }); });

    // GPU.
    auto t_gpu = Clock::now();
    auto context = gpu::create_headless_context(context_options(o));
    double context_ms = ms_since(t_gpu);
    JobLighting lighting = lighting_task.get();
    bar.finish();
    t_gpu = Clock::now();
    Renderer renderer(*context);
    double upload_ms = 0.0;

    // Frames: one, a turntable (the orbit camera's yaw advances by 360/N degrees), or an
    // animation (--frames N at --fps from --time; --time alone poses one frame). Animated
    // frames keep the camera fitted to the rest pose, so they line up. GPU posing uploads the
    // bind pose once and moves only the nodes; CPU posing (the reference) uploads each
    // frame's posed meshes.
    RenderSettings rs = lighting.settings(resolved);
    renderer.set_scene(scene, resolved.scene_index,
                       release_images ? Renderer::ImageResidency::GpuOnly : Renderer::ImageResidency::Keep);
    upload_ms += context_ms + ms_since(t_gpu);
    // --ao baked: the tracer's rays at every vertex of the scene as drawn (each posed frame's own).
    double ao_ms = 0.0;
    std::size_t ao_vertices = 0;
    std::optional<VertexOcclusion> occlusion;
    auto bake_occlusion = [&] {
        if (job.output.ao != AmbientOcclusion::Baked) return;
        ProgressBar ao_bar("occlusion");
        occlusion = trace::job_vertex_occlusion(job, scene, resolved.scene_index, [&](double f) { ao_bar.update(f); });
        ao_bar.finish();
        ao_ms += occlusion->bake_ms;
        ao_vertices = occlusion->vertices;
        renderer.set_vertex_occlusion(&*occlusion);
    };
    if (!animated) bake_occlusion();
    const double loaded_mib = resident_mib();  // the scene loaded and uploaded, before any frame
    ScenePosing posing;  // the frame drawn is `scene`, posed in place
    posing.reset(scene, o.posing == "gpu");
    if (std::string why; animated && o.posing == "gpu" && !posing.on_gpu() && !gpu_animatable(scene, &why)) {
        Diagnostics note;
        note.warn(model_name, "--posing gpu", why + "; posing on the CPU");
        print_warnings(note);
    }
    const int frames = o.turntable > 0 ? o.turntable : o.frames.value_or(1);
    const bool numbered = o.turntable > 0 || o.frames.has_value();
    std::vector<float> times;
    std::vector<std::string> outputs;
    double draw_ms = 0.0;
    FrameStats stats;
    for (int i = 0; i < frames; ++i) {
        ResolvedJob frame_job = resolved;
        if (animated) {
            float t = animation.at() + (o.frames ? float(i) / float(o.fps) : 0.0f);
            times.push_back(t);
            auto t_upload = Clock::now();
            posing.show(renderer, animation.index, t, resolved.scene_index);
            upload_ms += ms_since(t_upload);
            bake_occlusion();
            rs.gpu_animation = posing.gpu_animation();
            frame_job = resolve(job, scene);  // the lights and the file's cameras follow their nodes
        }
        if (o.turntable > 0) {
            Job frame = job;
            frame.camera.yaw_deg = job.camera.yaw_deg + 360.0f * float(i) / float(frames);
            frame_job.camera = resolve(frame, scene).camera;
        }
        auto t_draw = Clock::now();
        stats = FrameStats{};
        outputs.push_back(numbered ? frame_path(output, i, frames) : output);
        // PNG: the 8-bit target, a quarter of the float frame's bytes to read back.
        const bool png = lower_extension(outputs.back()) == ".png";
        std::optional<Image8> image8;
        ImageF image;
        if (png) image8 = renderer.render8(frame_job.camera, frame_job.lights, rs, resolved.transparent(), &stats);
        else image = renderer.render(frame_job.camera, frame_job.lights, rs, &stats);
        draw_ms += ms_since(t_draw);
        if (!stats.gl_errors.empty()) throw Error("OpenGL", "", "the frame raised " + stats.gl_errors);
        if (png) write_png(outputs.back(), *image8);
        else write_image(outputs.back(), image, resolved.transparent());
    }
    double frame_ms = draw_ms / frames;
    if (!o.video.empty()) encode_video(ffmpeg, output, frames, o.fps, o.video);

    if (o.json) {
        const CameraSetup& camera = resolved.camera;
        const auto& environment = lighting.environment;
        nlohmann::json j;
        j["output"] = output;
        if (numbered) j["frames"] = frames;
        if (animated) j["times"] = times;
        if (numbered) j["outputs"] = outputs;
        if (!o.video.empty()) j["video"] = o.video;
        j["model"] = o.models.empty() ? "(demo)" : o.models.size() == 1 ? nlohmann::json(o.models[0]) : nlohmann::json(o.models);
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
        j["instanced_draws"] = stats.instanced_draws;
        j["instances_drawn"] = stats.instances_drawn;
        j["culled_draws"] = stats.culled_draws;
        j["ao"] = ambient_occlusion_name(job.output.ao);
        if (occlusion) {
            j["ao_ms"] = ao_ms;  // every bake: the trace scene's build and the rays
            j["ao_vertices"] = ao_vertices;
            j["ao_rays"] = occlusion->rays_per_vertex;
            j["ao_cached"] = occlusion->from_cache;
        }
        j["triangles"] = stats.triangles;
        j["programs"] = renderer.program_count();
        j["texture_bytes"] = renderer.texture_bytes();
        j["rss_loaded_mib"] = loaded_mib;         // resident once loaded and uploaded
        j["peak_rss_mib"] = peak_resident_mib();  // the most resident, frames included
        j["lights"] = resolved.lights.size();
        j["default_lights"] = resolved.default_lights;
        j["environment"] = environment ? environment->source : "none";
        j["environment_ms"] = lighting.environment_ms;
        j["environment_cached"] = environment ? environment->from_cache : false;
        j["env_light"] = env_light_name(job.output.env_light);
        if (environment && environment->dominant_light) {
            const ibl::DominantLight& d = *environment->dominant_light;
            j["environment_light"] = {{"direction", {d.direction.x, d.direction.y, d.direction.z}},
                                      {"irradiance", {d.irradiance.x, d.irradiance.y, d.irradiance.z}},
                                      {"solid_angle", d.solid_angle},
                                      {"share", d.share}};
        }
        j["camera"] = camera_json(camera);
        j["warnings"] = diag.lines();
        std::printf("%s\n", j.dump().c_str());
    }
    return kExitOk;
}

}  // namespace

Runner add_render_command(CLI::App& app) {
    auto o = std::make_shared<RenderOptions>();
    CLI::App* cmd = app.add_subcommand("render", "Render a glTF model (or the built-in demo) to an image, headless");
    cmd->footer("Examples:\n"
                "  fresnel render model.glb -o out.png                       # the camera convention, studio light\n"
                "  fresnel render model.glb -o out.exr --env sky.hdr --size 1920x1080\n"
                "  fresnel render model.glb -o f%03d.png --turntable 36 --video spin.mp4\n"
                "  fresnel render scene.fresnel.json --yaw 30                 # a scene file, a flag overriding it\n"
                "  fresnel render model.glb -o n.png --debug normal           # one channel; --debug lists them all\n");
    add_model_and_output(cmd, *o);
    cmd->add_option("--turntable", o->turntable,
                    "Render N frames around the model (yaw advances 360/N degrees), numbered OUT-000.png ... (or a "
                    "printf pattern in -o, e.g. frame_%04d.png)")
        ->check(CLI::Range(1, 100000));
    cmd->add_option("--video", o->video, "With --turntable: also encode the PNG frames into this MP4 (H.264) with ffmpeg");
    cmd->add_option("--fps", o->fps, "Frames per second of --frames (the animation's time step) and of --video")
        ->capture_default_str()->check(CLI::Range(1, 240));
    cmd->add_option("--frames", o->frames,
                    "Write N frames from --time (default 0) at --fps, numbered as --turntable's: OUT-000.png ...")
        ->check(CLI::Range(1, 100000));
    cmd->add_option("--posing", o->posing,
                    "Where animated frames are skinned and morphed: gpu (vertex shader; skins of up to " +
                        std::to_string(kMaxGpuSkinJoints) + " joints, " + std::to_string(kMaxGpuMorphTargets) +
                        " morph targets a primitive, else the CPU) or cpu (the reference)")
        ->capture_default_str()
        ->check(CLI::IsMember({"gpu", "cpu"}));
    cmd->add_flag("--json", o->json, "Print timings, camera and counts as one JSON line");
    add_job_flags(cmd, *o);
    return [o, cmd] { return run_render(*o, cmd); };
}

}  // namespace fresnel::cli
