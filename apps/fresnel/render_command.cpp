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
#include "fresnel/ibl/bake.h"
#include "progress.h"
#include "fresnel/render/renderer.h"
#include "fresnel/scene/gltf_loader.h"
#include "fresnel/scene/procedural.h"

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

int run_render(const RenderOptions& o) {
    auto t_start = Clock::now();
    // Usage checks first (exit 2), before touching files.
    int width = 0, height = 0;
    {
        char x = 0;
        std::stringstream ss(o.size);
        if (!(ss >> width >> x >> height) || x != 'x' || !ss.eof() || width < 1 || height < 1 || width > 16384 ||
            height > 16384) {
            print_error("--size: expected WxH with 1..16384 pixels per side, got '" + o.size + "'");
            return kExitUsage;
        }
    }
    auto tone = parse_tone_mapper(o.tonemap);
    if (!tone) {
        print_error("--tonemap: unknown tone mapper '" + o.tonemap + "' (neutral, aces, aces-hill, reinhard, agx, none)");
        return kExitUsage;
    }
    auto encoding = parse_encoding(o.encoding);
    if (!encoding) {
        print_error("--encoding: expected srgb or gamma2.2, got '" + o.encoding + "'");
        return kExitUsage;
    }
    auto debug = parse_debug_channel(o.debug);
    if (!debug) {
        print_error("--debug: unknown channel '" + o.debug + "'");
        return kExitUsage;
    }
    std::string ext = lower_extension(o.output);
    bool float_output = ext == ".exr" || ext == ".hdr";
    if (!float_output && ext != ".png") {
        print_error("-o: output must end in .png, .exr or .hdr: '" + o.output + "'");
        return kExitUsage;
    }
    glm::vec4 background(0, 0, 0, 1);
    auto background_mode = RenderSettings::Background::Color;
    bool background_given = !o.background.empty();
    if (o.background == "env") {
        background_mode = RenderSettings::Background::Environment;
    } else if (o.background == "blur" || o.background.empty()) {
        background_mode = RenderSettings::Background::Blurred;  // the default when there is an environment
    } else if (o.background == "transparent") {
        background = glm::vec4(0.0f);
    } else {
        auto v = parse_floats(o.background, "--background");
        if (v.size() != 3) {
            print_error("--background: expected env, blur, R,G,B (0..1, display-encoded) or transparent");
            return kExitUsage;
        }
        background = glm::vec4(v[0], v[1], v[2], 1.0f);
    }
    std::vector<LightInstance> cli_lights;
    for (const auto& spec : o.lights) {
        try {
            cli_lights.push_back(parse_light(spec));
        } catch (const Error& e) {
            print_error(e);
            return kExitUsage;
        }
    }

    // Scene.
    Diagnostics diag;
    Scene scene;
    auto t_load = Clock::now();
    if (o.model.empty()) {
        scene = make_demo_scene();
    } else {
        GltfLoadOptions lo;
        lo.allow_external_files = o.allow_external;
        lo.pose_skins = o.pose_skins;
        scene = load_gltf(o.model, diag, lo);
    }
    double load_ms = ms_since(t_load);
    print_warnings(diag);
    if (o.scene >= int(scene.scenes.size())) {
        print_error(o.model + ": --scene " + std::to_string(o.scene) + ": the file has " +
                    std::to_string(scene.scenes.size()) + " scenes");
        return kExitBadInput;
    }
    auto instances = flatten(scene, o.scene);
    Bounds bounds = scene_bounds(scene, instances);

    // Camera.
    CameraSetup camera;
    if (o.camera) {
        auto c = scene_camera(scene, instances, *o.camera, width, height);
        if (!c) {
            print_error((o.model.empty() ? std::string("demo") : o.model) + ": --camera " + std::to_string(*o.camera) +
                        ": no node of the scene uses camera " + std::to_string(*o.camera) + " (the file has " +
                        std::to_string(scene.cameras.size()) + ")");
            return kExitBadInput;
        }
        camera = *c;
    } else {
        OrbitParams op;
        op.yaw_deg = o.yaw;
        op.pitch_deg = o.pitch;
        op.distance_k = o.distance;
        op.yfov_deg = o.fov;
        camera = orbit_camera(bounds, op, width, height);
    }

    // Lights: the scene's, then the command line's.
    std::vector<LightInstance> lights;
    if (!o.no_scene_lights) lights = scene_lights(scene, instances);
    lights.insert(lights.end(), cli_lights.begin(), cli_lights.end());

    // Image-based light: --env, else the built-in studio unless the scene or the command
    // line brings its own lights. --no-ibl turns it off.
    ibl::BakeOptions bake_options;
    bake_options.samples = o.env_samples;
    bake_options.size = o.env_size;
    std::optional<ibl::BakedIbl> environment;
    double env_ms = 0;
    bool use_ibl = !o.no_ibl && (o.env_given || lights.empty());
    if (use_ibl) {
        auto t_env = Clock::now();
        ibl::EnvironmentSource source = ibl::parse_environment(o.env_given ? o.env : "studio");
        ProgressBar bar("baking " + source.describe());
        environment = ibl::load_or_bake(source, bake_options, [&](double f) { bar.update(f); }, !o.no_cache);
        bar.finish();
        env_ms = ms_since(t_env);
    }
    // The default pair of directional lights only when nothing else lights the scene.
    bool default_lighting = lights.empty() && !environment;
    if (default_lighting) lights = default_lights();
    ImageF lut;
    if (!environment && !o.no_energy_compensation) lut = ibl::load_or_bake_lut(bake_options, !o.no_cache);

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
    renderer.set_scene(scene, o.scene);
    double upload_ms = ms_since(t_gpu);

    RenderSettings rs;
    rs.width = width;
    rs.height = height;
    rs.msaa = o.msaa;
    rs.exposure_ev = o.exposure;
    rs.tone_mapper = *tone;
    rs.debug = *debug;
    rs.background = background;
    rs.background_mode = environment && !(background_given && background_mode == RenderSettings::Background::Color)
                             ? background_mode
                             : RenderSettings::Background::Color;
    if (!environment || background_mode == RenderSettings::Background::Color) rs.background_mode = RenderSettings::Background::Color;
    rs.environment = environment ? &*environment : nullptr;
    rs.env_intensity = o.env_intensity;
    rs.env_rotation_deg = o.env_rotation;
    rs.brdf_lut = lut.width > 0 ? &lut : nullptr;
    rs.energy_compensation = !o.no_energy_compensation;
    if (float_output) {
        rs.encoding.reset();
        rs.straight_alpha = false;  // EXR convention: premultiplied alpha
    } else {
        rs.encoding = *encoding;
    }
    auto t_frame = Clock::now();
    FrameStats stats;
    ImageF image = renderer.render(camera, lights, rs, &stats);
    double frame_ms = ms_since(t_frame);
    if (!stats.gl_errors.empty()) throw Error("OpenGL", "", "the frame raised " + stats.gl_errors);

    if (ext == ".png") write_png(o.output, to_image8(image, background.w == 0.0f));
    else if (ext == ".exr") write_exr(o.output, image);
    else write_hdr(o.output, image);

    if (o.json) {
        nlohmann::json j;
        j["output"] = o.output;
        j["model"] = o.model.empty() ? "(demo)" : o.model;
        j["width"] = width;
        j["height"] = height;
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
        j["lights"] = lights.size();
        j["default_lights"] = default_lighting;
        j["environment"] = environment ? environment->source : "none";
        j["environment_ms"] = env_ms;
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
    cmd->add_flag("--no-cache", o->no_cache, "Bake the environment again instead of using $XDG_CACHE_HOME/fresnel");
    cmd->add_flag("--no-energy-compensation", o->no_energy_compensation,
                  "Single-scattering specular only (no multiple-scattering compensation of punctual lights)");
    cmd->add_option("--light", o->lights,
                    "Add a light: dir:AZIMUTH,ELEVATION,LUX[,R,G,B] (arriving from that direction) or "
                    "point:X,Y,Z,CANDELA[,R,G,B]; repeatable");
    cmd->add_flag("--no-scene-lights", o->no_scene_lights, "Ignore the file's KHR_lights_punctual lights");
    cmd->add_option("--msaa", o->msaa, "MSAA samples (1 = off)")->capture_default_str()->check(CLI::Range(1, 16));
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
    return [o] { return run_render(*o); };
}

}  // namespace fresnel::cli
