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
    std::string background = "0,0,0";
    std::vector<std::string> lights;
    bool no_scene_lights = false;
    int msaa = 4;
    std::string debug = "none";
    bool json = false;
    bool allow_external = false;
    bool gl_debug = false;
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
    if (o.background == "transparent") {
        background = glm::vec4(0.0f);
    } else {
        auto v = parse_floats(o.background, "--background");
        if (v.size() != 3) {
            print_error("--background: expected R,G,B (0..1, display-encoded) or 'transparent'");
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

    // Lights: the scene's, then the command line's; the default pair when there are none.
    std::vector<LightInstance> lights;
    if (!o.no_scene_lights) lights = scene_lights(scene, instances);
    lights.insert(lights.end(), cli_lights.begin(), cli_lights.end());
    bool default_lighting = lights.empty();
    if (default_lighting) lights = default_lights();

    // GPU.
    auto t_gpu = Clock::now();
    gpu::ContextOptions co;
    co.debug = o.gl_debug;
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
        j["load_ms"] = load_ms;
        j["upload_ms"] = upload_ms;
        j["frame_ms"] = frame_ms;
        j["total_ms"] = ms_since(t_start);
        j["draw_calls"] = stats.draw_calls;
        j["triangles"] = stats.triangles;
        j["programs"] = renderer.program_count();
        j["lights"] = lights.size();
        j["default_lights"] = default_lighting;
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
    cmd->add_option("--background", o->background, "Background R,G,B (0..1, display-encoded) or 'transparent'")
        ->capture_default_str();
    cmd->add_option("--light", o->lights,
                    "Add a light: dir:AZIMUTH,ELEVATION,LUX[,R,G,B] (arriving from that direction) or "
                    "point:X,Y,Z,CANDELA[,R,G,B]; repeatable");
    cmd->add_flag("--no-scene-lights", o->no_scene_lights, "Ignore the file's KHR_lights_punctual lights");
    cmd->add_option("--msaa", o->msaa, "MSAA samples (1 = off)")->capture_default_str()->check(CLI::Range(1, 16));
    cmd->add_option("--debug", o->debug,
                    "Show a channel instead of shading: basecolor metallic roughness normal geometry-normal tangent "
                    "bitangent occlusion emissive alpha uv0 uv1 D G F diffuse specular")
        ->capture_default_str();
    cmd->add_flag("--json", o->json, "Print timings, camera and counts as one JSON line");
    cmd->add_flag("--allow-external-files", o->allow_external,
                  "Let URIs point outside the model's folder (absolute paths, ..); never the network");
    cmd->add_flag("--gl-debug", o->gl_debug, "Request a debug GL context and print KHR_debug messages");
    return [o] { return run_render(*o); };
}

}  // namespace fresnel::cli
