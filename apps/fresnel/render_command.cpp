// `fresnel render [MODEL] -o OUT ...`: headless rendering to PNG, EXR or HDR.
// Every option is documented here, where it is declared; README.md's CLI
// reference is the output of `fresnel render --help`.
#include <chrono>
#include <cmath>
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

struct RenderOptions {
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
    int msaa = 4;
    float anisotropy = 16;
    std::string debug = "none";
    bool json = false;
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
    std::string shading = "auto";
    std::string ambient;
    std::string fog;
    std::string fog_color;
};

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

std::vector<float> parse_floats(const std::string& s, const std::string& what) {
    std::vector<float> out;
    std::stringstream ss(s);
    std::string item;
    while (std::getline(ss, item, ',')) {
        try {
            std::size_t used = 0;
            out.push_back(std::stof(item, &used));
            if (used != item.size()) throw std::invalid_argument(item);
        } catch (const std::logic_error&) {
            throw CLI::ValidationError(what, "'" + s + "' is not a comma-separated list of numbers");
        }
    }
    return out;
}

std::string lower_extension(const std::string& path) {
    std::string e = std::filesystem::path(path).extension().string();
    for (auto& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

// --shading, --ambient, --fog, --fog-color into `out` (the same meanings as
// ../shared/tools/ogl1-ref/render's); false after printing a usage error.
bool parse_legacy_options(const RenderOptions& o, Job::Output& out) {
    auto model = parse_shading_model(o.shading);
    if (!model) {
        print_error("--shading: expected auto, gltf, ogl1, ogl1-pixel or blinn-phong-normalized, got '" + o.shading + "'");
        return false;
    }
    out.shading = *model;
    auto colour = [](const std::string& flag, const std::string& text, glm::vec3& into) {
        std::vector<float> v;
        try {
            v = parse_floats(text, flag);
        } catch (const CLI::ValidationError&) {
        }
        if (v.size() != 3 || !std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2])) {
            print_error(flag + ": expected R,G,B, got '" + text + "'");
            return false;
        }
        into = glm::vec3(v[0], v[1], v[2]);
        return true;
    };
    if (!o.ambient.empty() && !colour("--ambient", o.ambient, out.ambient)) return false;
    if (!o.fog_color.empty()) {
        glm::vec3 c;
        if (!colour("--fog-color", o.fog_color, c)) return false;
        out.fog_color = c;
    }
    if (o.fog.empty()) return true;
    const std::string usage = "--fog: expected linear:START,END (numbers or the words near, far), exp:DENSITY or "
                              "exp2:DENSITY, got '" + o.fog + "'";
    auto colon = o.fog.find(':');
    std::string kind = o.fog.substr(0, colon), args = colon == std::string::npos ? "" : o.fog.substr(colon + 1);
    if (kind == "linear") {
        auto comma = args.find(',');
        if (comma == std::string::npos) return print_error(usage), false;
        auto edge = [&](const std::string& t, const char* word, std::optional<float>& into) {
            if (t == word) return true;  // the camera's clip distance
            try {
                std::size_t used = 0;
                float f = std::stof(t, &used);
                if (used != t.size() || !std::isfinite(f)) return false;
                into = f;
                return true;
            } catch (const std::logic_error&) {
                return false;
            }
        };
        if (!edge(args.substr(0, comma), "near", out.fog.start) || !edge(args.substr(comma + 1), "far", out.fog.end))
            return print_error(usage), false;
        out.fog.mode = legacy::FogMode::Linear;
    } else if (kind == "exp" || kind == "exp2") {
        std::vector<float> v;
        try {
            v = parse_floats(args, "--fog");
        } catch (const CLI::ValidationError&) {
        }
        if (v.size() != 1 || !std::isfinite(v[0]) || v[0] < 0) return print_error(usage), false;
        out.fog.mode = kind == "exp" ? legacy::FogMode::Exp : legacy::FogMode::Exp2;
        out.fog.density = v[0];
    } else {
        return print_error(usage), false;
    }
    return true;
}

// The job the flags describe. Usage errors are printed and give nullopt (exit 2), before
// any file is touched; a malformed --env throws fresnel::Error (exit 1).
std::optional<Job> job_from_options(const RenderOptions& o) {
    Job job;
    Job::Output& out = job.output;
    {
        char x = 0;
        std::stringstream ss(o.size);
        if (!(ss >> out.width >> x >> out.height) || x != 'x' || !ss.eof() || out.width < 1 || out.height < 1 ||
            out.width > 16384 || out.height > 16384) {
            print_error("--size: expected WxH with 1..16384 pixels per side, got '" + o.size + "'");
            return std::nullopt;
        }
    }
    auto tone = parse_tone_mapper(o.tonemap);
    if (!tone) {
        print_error("--tonemap: unknown tone mapper '" + o.tonemap + "' (neutral, aces, aces-hill, reinhard, agx, none)");
        return std::nullopt;
    }
    auto encoding = parse_encoding(o.encoding);
    if (!encoding) {
        print_error("--encoding: expected srgb or gamma2.2, got '" + o.encoding + "'");
        return std::nullopt;
    }
    auto debug = parse_debug_channel(o.debug);
    if (!debug) {
        print_error("--debug: unknown channel '" + o.debug + "'");
        return std::nullopt;
    }
    std::string ext = lower_extension(o.output);
    out.float_output = ext == ".exr" || ext == ".hdr";
    if (!out.float_output && ext != ".png") {
        print_error("-o: output must end in .png, .exr or .hdr: '" + o.output + "'");
        return std::nullopt;
    }
    if (!parse_legacy_options(o, out)) return std::nullopt;
    using Mode = Job::Background::Mode;
    if (o.background == "env") {
        job.background.mode = Mode::Environment;
    } else if (o.background == "blur") {
        job.background.mode = Mode::Blurred;
    } else if (o.background == "transparent") {
        job.background.mode = Mode::Transparent;
    } else if (!o.background.empty()) {
        auto v = parse_floats(o.background, "--background");
        if (v.size() != 3) {
            print_error("--background: expected env, blur, R,G,B (0..1, display-encoded) or transparent");
            return std::nullopt;
        }
        job.background.mode = Mode::Color;
        job.background.color = glm::vec3(v[0], v[1], v[2]);
    }
    for (const auto& spec : o.lights) {
        try {
            job.lights.extra.push_back(parse_light(spec));
        } catch (const Error& e) {
            print_error(e);
            return std::nullopt;
        }
    }
    job.lights.scene_lights = !o.no_scene_lights;
    out.tone_mapper = *tone;
    out.encoding = *encoding;
    out.debug = *debug;
    out.msaa = o.msaa;
    out.anisotropy = o.anisotropy;
    out.exposure_ev = o.exposure;
    out.energy_compensation = !o.no_energy_compensation;

    job.source.model = o.model;
    job.source.scene = o.scene;
    job.source.allow_external_files = o.allow_external;
    job.source.pose_skins = o.pose_skins;

    job.camera.scene_camera = o.camera;
    job.camera.yaw_deg = o.yaw;
    job.camera.pitch_deg = o.pitch;
    job.camera.distance_k = o.distance;
    job.camera.yfov_deg = o.fov;

    Job::Environment& env = job.environment;
    using Kind = Job::Environment::Kind;
    if (o.no_ibl) {
        env.kind = Kind::None;
    } else if (o.env_given) {
        ibl::EnvironmentSource source = ibl::parse_environment(o.env);
        switch (source.kind) {
            case ibl::EnvironmentSource::Kind::File: env.kind = Kind::File; env.path = source.path.string(); break;
            case ibl::EnvironmentSource::Kind::Uniform: env.kind = Kind::Color; env.color = source.color; break;
            case ibl::EnvironmentSource::Kind::Studio: env.kind = Kind::Studio; break;
        }
    }
    env.rotation_deg = o.env_rotation;
    env.intensity = o.env_intensity;
    env.bake_samples = o.env_samples;
    env.bake_size = o.env_size;
    env.use_cache = !o.no_cache;
    return job;
}

int run_render(const RenderOptions& o) {
    auto t_start = Clock::now();
    std::optional<Job> parsed = job_from_options(o);  // usage checks first (exit 2), before touching files
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

    std::string ext = lower_extension(o.output);
    if (ext == ".png") write_png(o.output, to_image8(image, resolved.transparent()));
    else if (ext == ".exr") write_exr(o.output, image);
    else write_hdr(o.output, image);

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
    cmd->add_option("model", o->model, "glTF 2.0 file (.gltf/.glb); omitted: the built-in demo (7x7 spheres)");
    cmd->add_option("-o,--output", o->output,
                    "Output image: .png (8-bit, display-encoded), .exr/.hdr (linear float after exposure and tone map)")
        ->required();
    cmd->add_option("--size", o->size, "Image size WxH")->capture_default_str();
    cmd->add_option("--yaw", o->yaw, "Orbit yaw in degrees (0: from +Z, 90: from +X)")->capture_default_str();
    cmd->add_option("--pitch", o->pitch, "Orbit pitch in degrees (positive: from above)")->capture_default_str();
    cmd->add_option("--distance", o->distance, "Camera distance as a multiple K of the bounds radius (default: fit)");
    cmd->add_option("--fov", o->fov, "Vertical field of view in degrees")->capture_default_str();
    cmd->add_option("--camera", o->camera, "Use the file's N-th camera instead of the orbit camera")
        ->excludes("--yaw")->excludes("--pitch")->excludes("--distance")->excludes("--fov");
    cmd->add_option("--scene", o->scene, "Scene index (default: the file's `scene`)");
    cmd->add_option("--tonemap", o->tonemap, "Tone mapper: neutral, aces, aces-hill, reinhard, agx, none")
        ->capture_default_str();
    cmd->add_option("--exposure", o->exposure, "Exposure in EV (radiance x 2^EV)")->capture_default_str();
    cmd->add_option("--encoding", o->encoding, "PNG encoding: srgb (exact curve) or gamma2.2 (pow 1/2.2)")
        ->capture_default_str();
    cmd->add_option("--background", o->background,
                    "Background: env (the environment, sharp), blur (a prefiltered level; the default with an "
                    "environment), R,G,B (0..1, display-encoded; default 0,0,0 without one) or transparent");
    cmd->add_option("--env", o->env,
                    "Environment light: an equirectangular .hdr/.exr, a folder made by `fresnel bake`, color:R,G,B "
                    "(linear) or studio (built in). Default: studio, unless the scene or --light brings lights")
        ->each([o](const std::string&) { o->env_given = true; });
    cmd->add_option("--env-rotation", o->env_rotation, "Turn the environment about +Y, degrees")->capture_default_str();
    cmd->add_option("--env-intensity", o->env_intensity, "Scale the environment's radiance")->capture_default_str();
    cmd->add_flag("--no-ibl", o->no_ibl, "No image-based light");
    cmd->add_option("--env-samples", o->env_samples, "GGX samples per texel when baking")->capture_default_str()
        ->check(CLI::Range(1, 65536));
    cmd->add_option("--env-size", o->env_size, "Specular cube face size when baking (power of two)")
        ->capture_default_str();
    cmd->add_flag("--no-cache", o->no_cache, "Neither read nor write $XDG_CACHE_HOME/fresnel: bake the environment and the BRDF table again");
    cmd->add_flag("--no-energy-compensation", o->no_energy_compensation,
                  "Single-scattering specular only (no multiple-scattering compensation of punctual lights)");
    cmd->add_option("--light", o->lights,
                    "Add a light: dir:AZIMUTH,ELEVATION,LUX[,R,G,B] (arriving from that direction) or "
                    "point:X,Y,Z,CANDELA[,R,G,B]; repeatable");
    cmd->add_flag("--no-scene-lights", o->no_scene_lights, "Ignore the file's KHR_lights_punctual lights");
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
    cmd->add_flag("--allow-external-files", o->allow_external,
                  "Let URIs point outside the model's folder (absolute paths, ..); never the network");
    cmd->add_flag("--gl-debug", o->gl_debug, "Request a debug GL context and print KHR_debug messages");
    cmd->add_option("--gl", o->gl, "Graphics API: gl33 (OpenGL 3.3 core) or es3 (OpenGL ES 3.0; same pictures)")
        ->capture_default_str()
        ->check(CLI::IsMember({"gl33", "es3"}));
    cmd->add_flag("--pose-skins", o->pose_skins,
                  "Pose skinned meshes by their joints' rest transforms (default: the bind pose, as the Khronos "
                  "Sample Renderer's reference images show)");
    cmd->add_option("--shading", o->shading,
                    "Shading model: auto (per material: OpenGL 1 for OBJ/MTL Phong materials, glTF for the rest), "
                    "gltf, ogl1 (OpenGL 1 fixed function per vertex, no tone mapping or encoding), ogl1-pixel (the "
                    "same per fragment) or blinn-phong-normalized (with its image-based path). In the legacy models "
                    "a light of intensity I is an OpenGL light of colour I")
        ->capture_default_str();
    cmd->add_option("--ambient", o->ambient,
                    "Global ambient light R,G,B (OpenGL 1's GL_LIGHT_MODEL_AMBIENT x Ka; glTF: ambient radiance x "
                    "diffuse colour). Default 0,0,0");
    cmd->add_option("--fog", o->fog,
                    "OpenGL 1 fog on the eye-plane distance (ogl1 models): linear:START,END (START/END may be near, "
                    "far: the clip distances), exp:DENSITY or exp2:DENSITY");
    cmd->add_option("--fog-color", o->fog_color, "Fog colour R,G,B (display values; default: the background colour)");
    return [o] { return run_render(*o); };
}

}  // namespace fresnel::cli
