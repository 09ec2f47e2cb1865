#include "cli_common.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "fresnel/ibl/environment.h"
#include "fresnel/render/renderer.h"

namespace fresnel::cli {

void print_error(const Error& e) { std::fprintf(stderr, "fresnel: error: %s\n", e.what()); }
void print_error(const std::string& m) { std::fprintf(stderr, "fresnel: error: %s\n", m.c_str()); }

void print_warnings(const Diagnostics& d) {
    auto lines = d.lines();
    for (const auto& l : lines) std::fprintf(stderr, "fresnel: warning: %s\n", l.c_str());
    if (!lines.empty())
        std::fprintf(stderr, "fresnel: %zu warning%s (%zu unique)\n", d.total(), d.total() == 1 ? "" : "s", lines.size());
}

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
}  // namespace

std::string lower_extension(const std::string& path) {
    std::string e = std::filesystem::path(path).extension().string();
    for (auto& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

void write_output(const std::string& path, const ImageF& image, bool transparent) {
    std::string ext = lower_extension(path);
    if (ext == ".png") write_png(path, to_image8(image, transparent));
    else if (ext == ".exr") write_exr(path, image);
    else write_hdr(path, image);
}

void add_view_options(CLI::App* cmd, JobOptions& o) {
    JobOptions* p = &o;
    cmd->add_option("model", o.model, "glTF 2.0 file (.gltf/.glb); omitted: the built-in demo (7x7 spheres)");
    cmd->add_option("-o,--output", o.output,
                    "Output image: .png (8-bit, display-encoded), .exr/.hdr (linear float after exposure and tone map)")
        ->required();
    cmd->add_option("--size", o.size, "Image size WxH")->capture_default_str();
    cmd->add_option("--yaw", o.yaw, "Orbit yaw in degrees (0: from +Z, 90: from +X)")->capture_default_str();
    cmd->add_option("--pitch", o.pitch, "Orbit pitch in degrees (positive: from above)")->capture_default_str();
    cmd->add_option("--distance", o.distance, "Camera distance as a multiple K of the bounds radius (default: fit)");
    cmd->add_option("--fov", o.fov, "Vertical field of view in degrees")->capture_default_str();
    cmd->add_option("--camera", o.camera, "Use the file's N-th camera instead of the orbit camera")
        ->excludes("--yaw")->excludes("--pitch")->excludes("--distance")->excludes("--fov");
    cmd->add_option("--scene", o.scene, "Scene index (default: the file's `scene`)");
    cmd->add_option("--tonemap", o.tonemap, "Tone mapper: neutral, aces, aces-hill, reinhard, agx, none")
        ->capture_default_str();
    cmd->add_option("--exposure", o.exposure, "Exposure in EV (radiance x 2^EV)")->capture_default_str();
    cmd->add_option("--encoding", o.encoding, "PNG encoding: srgb (exact curve) or gamma2.2 (pow 1/2.2)")
        ->capture_default_str();
    cmd->add_option("--background", o.background,
                    "Background: env (the environment, sharp), blur (a prefiltered level; the default with an "
                    "environment), R,G,B (0..1, display-encoded; default 0,0,0 without one) or transparent");
    cmd->add_option("--env", o.env,
                    "Environment light: an equirectangular .hdr/.exr, a folder made by `fresnel bake`, color:R,G,B "
                    "(linear) or studio (built in). Default: studio, unless the scene or --light brings lights")
        ->each([p](const std::string&) { p->env_given = true; });
    cmd->add_option("--env-rotation", o.env_rotation, "Turn the environment about +Y, degrees")->capture_default_str();
    cmd->add_option("--env-intensity", o.env_intensity, "Scale the environment's radiance")->capture_default_str();
    cmd->add_flag("--no-ibl", o.no_ibl, "No image-based light");
}

void add_light_options(CLI::App* cmd, JobOptions& o) {
    cmd->add_option("--light", o.lights,
                    "Add a light: dir:AZIMUTH,ELEVATION,LUX[,R,G,B] (arriving from that direction) or "
                    "point:X,Y,Z,CANDELA[,R,G,B]; repeatable");
    cmd->add_flag("--no-scene-lights", o.no_scene_lights, "Ignore the file's KHR_lights_punctual lights");
}

void add_file_options(CLI::App* cmd, JobOptions& o) {
    cmd->add_flag("--allow-external-files", o.allow_external,
                  "Let URIs point outside the model's folder (absolute paths, ..); never the network");
}

void add_pose_options(CLI::App* cmd, JobOptions& o) {
    cmd->add_flag("--pose-skins", o.pose_skins,
                  "Pose skinned meshes by their joints' rest transforms (default: the bind pose, as the Khronos "
                  "Sample Renderer's reference images show)");
}

std::optional<Job> job_from_options(const JobOptions& o) {
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
    std::string ext = lower_extension(o.output);
    out.float_output = ext == ".exr" || ext == ".hdr";
    if (!out.float_output && ext != ".png") {
        print_error("-o: output must end in .png, .exr or .hdr: '" + o.output + "'");
        return std::nullopt;
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
    out.exposure_ev = o.exposure;

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
    return job;
}

}  // namespace fresnel::cli
