#include "job_flags.h"

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "cli_common.h"
#include "fresnel/ibl/environment.h"

namespace fresnel::cli {
namespace {

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

// The shortest decimal form that reads back as the same float.
std::string num(float v) {
    char buf[32];
    auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}
std::string nums(std::initializer_list<float> v) {
    std::string s;
    for (float f : v) s += (s.empty() ? "" : ",") + num(f);
    return s;
}

}  // namespace

std::optional<Job> job_from_flags(const JobFlags& o, const std::string* output) {
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
    if (output) {
        std::string ext = lower_extension(*output);
        out.float_output = ext == ".exr" || ext == ".hdr";
        if (!out.float_output && ext != ".png") {
            print_error("-o: output must end in .png, .exr or .hdr: '" + *output + "'");
            return std::nullopt;
        }
    }
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
    if (!o.target.empty()) {
        auto v = parse_floats(o.target, "--target");
        if (v.size() != 3) {
            print_error("--target: expected X,Y,Z, got '" + o.target + "'");
            return std::nullopt;
        }
        job.camera.target = glm::vec3(v[0], v[1], v[2]);
    }

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

void add_job_flags(CLI::App* cmd, const std::shared_ptr<JobFlags>& flags, const std::string& size_help) {
    JobFlags* o = flags.get();
    cmd->add_option("--size", o->size, size_help)->capture_default_str();
    cmd->add_option("--yaw", o->yaw, "Orbit yaw in degrees (0: from +Z, 90: from +X)")->capture_default_str();
    cmd->add_option("--pitch", o->pitch, "Orbit pitch in degrees (positive: from above)")->capture_default_str();
    cmd->add_option("--distance", o->distance, "Camera distance as a multiple K of the bounds radius (default: fit)");
    cmd->add_option("--fov", o->fov, "Vertical field of view in degrees")->capture_default_str();
    cmd->add_option("--target", o->target, "Point the orbit camera turns about, X,Y,Z (default: the bounds' centre)");
    cmd->add_option("--camera", o->camera, "Use the file's N-th camera instead of the orbit camera")
        ->excludes("--yaw")->excludes("--pitch")->excludes("--distance")->excludes("--fov")->excludes("--target");
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
}

void add_input_flags(CLI::App* cmd, const std::shared_ptr<JobFlags>& flags) {
    JobFlags* o = flags.get();
    cmd->add_flag("--allow-external-files", o->allow_external,
                  "Let URIs point outside the model's folder (absolute paths, ..); never the network");
    cmd->add_flag("--gl-debug", o->gl_debug, "Request a debug GL context and print KHR_debug messages");
    cmd->add_option("--gl", o->gl, "Graphics API: gl33 (OpenGL 3.3 core) or es3 (OpenGL ES 3.0; same pictures)")
        ->capture_default_str()
        ->check(CLI::IsMember({"gl33", "es3"}));
    cmd->add_flag("--pose-skins", o->pose_skins,
                  "Pose skinned meshes by their joints' rest transforms (default: the bind pose, as the Khronos "
                  "Sample Renderer's reference images show)");
}

gpu::ContextOptions context_options(const JobFlags& o) {
    gpu::ContextOptions co;
#ifndef NDEBUG
    co.debug = true;  // debug builds always report KHR_debug messages
#else
    co.debug = o.gl_debug;
#endif
    co.api = o.gl == "es3" ? gpu::Api::OpenGLES30 : gpu::Api::OpenGL33;
    co.log = [](const std::string& m) { std::fprintf(stderr, "fresnel: %s\n", m.c_str()); };
    return co;
}

std::string shell_quote(const std::string& s) {
    bool plain = !s.empty();
    for (char c : s)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || std::string_view("-_./:,=+@%").find(c) != std::string_view::npos))
            plain = false;
    if (plain) return s;
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

std::string render_command_line(const Job& job, const std::string& output) {
    const Job defaults;
    std::string line = "fresnel render";
    auto add = [&](const std::string& flag, const std::string& value = {}) {
        line += " " + flag;
        if (!value.empty()) line += " " + shell_quote(value);
    };
    if (!job.source.model.empty()) line += " " + shell_quote(job.source.model);
    add("-o", output);
    const Job::Output& out = job.output;
    if (out.width != defaults.output.width || out.height != defaults.output.height)
        add("--size", std::to_string(out.width) + "x" + std::to_string(out.height));
    const Job::Camera& cam = job.camera;
    if (cam.scene_camera) {
        add("--camera", std::to_string(*cam.scene_camera));
    } else {
        add("--yaw", num(cam.yaw_deg));
        add("--pitch", num(cam.pitch_deg));
        if (cam.distance_k) add("--distance", num(*cam.distance_k));
        if (cam.yfov_deg != defaults.camera.yfov_deg) add("--fov", num(cam.yfov_deg));
        if (cam.target) add("--target", nums({cam.target->x, cam.target->y, cam.target->z}));
    }
    if (job.source.scene >= 0) add("--scene", std::to_string(job.source.scene));
    if (out.tone_mapper != defaults.output.tone_mapper) add("--tonemap", std::string(tone_mapper_name(out.tone_mapper)));
    if (out.exposure_ev != defaults.output.exposure_ev) add("--exposure", num(out.exposure_ev));
    if (out.encoding != defaults.output.encoding) add("--encoding", out.encoding == Encoding::Gamma22 ? "gamma2.2" : "srgb");
    using Mode = Job::Background::Mode;
    const Job::Background& bg = job.background;
    switch (bg.mode) {
        case Mode::Automatic: break;
        case Mode::Environment: add("--background", "env"); break;
        case Mode::Blurred: add("--background", "blur"); break;
        case Mode::Transparent: add("--background", "transparent"); break;
        case Mode::Color: add("--background", nums({bg.color.x, bg.color.y, bg.color.z})); break;
    }
    const Job::Environment& env = job.environment;
    using Kind = Job::Environment::Kind;
    switch (env.kind) {
        case Kind::Automatic: break;
        case Kind::File: add("--env", env.path); break;
        case Kind::Color: add("--env", "color:" + nums({env.color.x, env.color.y, env.color.z})); break;
        case Kind::Studio: add("--env", "studio"); break;
        case Kind::None: add("--no-ibl"); break;
    }
    if (env.rotation_deg != defaults.environment.rotation_deg) add("--env-rotation", num(env.rotation_deg));
    if (env.intensity != defaults.environment.intensity) add("--env-intensity", num(env.intensity));
    if (env.bake_samples != defaults.environment.bake_samples) add("--env-samples", std::to_string(env.bake_samples));
    if (env.bake_size != defaults.environment.bake_size) add("--env-size", std::to_string(env.bake_size));
    if (!env.use_cache) add("--no-cache");
    if (!out.energy_compensation) add("--no-energy-compensation");
    // Extra lights come from --light, so they are directional or point lights.
    for (const LightInstance& l : job.lights.extra) {
        float lum = std::max({l.radiance.x, l.radiance.y, l.radiance.z});
        glm::vec3 color = lum > 0 ? l.radiance / lum : glm::vec3(1.0f);
        std::string rgb = color == glm::vec3(1.0f) ? "" : "," + nums({color.x, color.y, color.z});
        if (l.type == Light::Type::Point) {
            add("--light", "point:" + nums({l.position.x, l.position.y, l.position.z, lum}) + rgb);
        } else {
            const float deg = 180.0f / 3.14159265358979f;
            glm::vec3 from = -l.direction;
            float el = std::asin(std::clamp(from.y, -1.0f, 1.0f)) * deg, az = std::atan2(from.x, from.z) * deg;
            add("--light", "dir:" + nums({az, el, lum}) + rgb);
        }
    }
    if (!job.lights.scene_lights) add("--no-scene-lights");
    if (out.msaa != defaults.output.msaa) add("--msaa", std::to_string(out.msaa));
    if (out.anisotropy != defaults.output.anisotropy) add("--anisotropy", num(out.anisotropy));
    if (out.debug != DebugChannel::None) {
        for (const std::string& name : debug_channel_names())
            if (parse_debug_channel(name) == out.debug) add("--debug", name);
    }
    if (job.source.allow_external_files) add("--allow-external-files");
    if (job.source.pose_skins) add("--pose-skins");
    return line;
}

}  // namespace fresnel::cli
