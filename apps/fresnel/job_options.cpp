// The job flags of `render`, `batch`, `trace` and `view` (job_options.h): their declaration
// and documentation (add_job_flags; README.md's CLI reference is their --help), and how they
// become a fresnel::Job, alone or over a scene file.
#include "job_options.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <sstream>
#include <thread>

#include "cli_common.h"
#include "fresnel/core/atomic_file.h"
#include "fresnel/ibl/environment.h"
#include "fresnel/render/renderer.h"
#include "fresnel/job/scene_file.h"

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


// --shading, --ambient, --fog, --fog-color into `out` (the same meanings as
// ../shared/tools/ogl1-ref/render's), those given; false after printing a usage error.
bool parse_legacy_options(const RenderOptions& o, Job::Output& out, const GivenFlags& given) {
    auto model = parse_shading_model(o.shading);
    if (!model) {
        print_error("--shading: expected auto, gltf, ogl1, ogl1-pixel or blinn-phong-normalized, got '" + o.shading + "'");
        return false;
    }
    if (given("--shading")) out.shading = *model;
    if (given("--brdf")) {
        std::string why;
        auto terms = brdf::parse_brdf_model(o.brdf, &why);
        if (!terms) {
            print_error("--brdf: " + why);
            return false;
        }
        out.brdf = *terms;
    }
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

}  // namespace



std::optional<Job> job_from_options(const RenderOptions& o, Job job, const GivenFlags& given) {
    Job::Output& out = job.output;
    if (given("--size")) {
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
    if (!parse_legacy_options(o, out, given)) return std::nullopt;
    using Mode = Job::Background::Mode;
    if (!given("--background")) {
    } else if (o.background == "env") {
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
    if (given("--light")) {
        job.lights.extra.clear();  // --light replaces a scene file's lights
        for (const auto& spec : o.lights) {
            try {
                job.lights.extra.push_back(parse_light(spec));
            } catch (const Error& e) {
                print_error(e);
                return std::nullopt;
            }
        }
    }
    if (given("--no-scene-lights")) job.lights.scene_lights = !o.no_scene_lights;
    if (given("--tonemap")) out.tone_mapper = *tone;
    if (given("--encoding")) out.encoding = *encoding;
    if (given("--debug")) out.debug = *debug;
    if (given("--msaa") && o.msaa > 0) out.msaa = o.msaa;  // else automatic (Job::Output::msaa)
    if (given("--anisotropy")) out.anisotropy = o.anisotropy;
    if (given("--exposure")) out.exposure_ev = o.exposure;
    if (given("--no-energy-compensation")) out.energy_compensation = !o.no_energy_compensation;

    if (given("--scene")) job.source.scene = o.scene;
    if (given("--allow-external-files")) job.source.allow_external_files = o.allow_external;
    if (given("--pose-skins")) job.source.pose_skins = o.pose_skins;
    if (given("--obj-normals")) {
        using N = Job::Source::ObjNormals;
        job.source.obj_normals = o.obj_normals == "smooth" ? N::Smooth : o.obj_normals == "groups" ? N::Groups : N::Auto;
    }
    if (given("--variant")) job.source.variant = o.variant;

    // A camera flag given on the command line replaces a scene file's camera.
    Job::Camera& cam = job.camera;
    if (given("--camera")) {
        cam.scene_camera = o.camera;
        cam.scene_camera_model = 0;
        if (given.explicitly("--camera")) cam.look_at.reset();
    }
    if (given.explicitly("--yaw") || given.explicitly("--pitch") || given.explicitly("--distance") ||
        given.explicitly("--fov") || given.explicitly("--target")) {
        if (cam.scene_camera || cam.look_at) cam = Job::Camera{};  // to the orbit camera, its defaults
    }
    if (given("--yaw")) cam.yaw_deg = o.yaw;
    if (given("--pitch")) cam.pitch_deg = o.pitch;
    if (given("--distance")) cam.distance_k = o.distance;
    if (given("--fov")) cam.yfov_deg = o.fov;
    if (given("--target") && !o.target.empty()) {
        auto v = parse_floats(o.target, "--target");
        if (v.size() != 3 || !std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2])) {
            print_error("--target: expected X,Y,Z, got '" + o.target + "'");
            return std::nullopt;
        }
        cam.target = glm::vec3(v[0], v[1], v[2]);
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
    if (given("--env-rotation")) env.rotation_deg = o.env_rotation;
    if (given("--env-intensity")) env.intensity = o.env_intensity;
    if (given("--env-samples")) env.bake_samples = o.env_samples;
    if (given("--env-size")) env.bake_size = o.env_size;
    if (given("--no-cache")) env.use_cache = !o.no_cache;
    return job;
}

std::optional<Job> job_from_sources(const RenderOptions& o, const CLI::App* cmd, Diagnostics& diag, const Job& defaults,
                                    std::string* scene_output) {
    // A scene file read onto the default job, then the flags the user gave; or the flags
    // alone (every one, defaults included) for models and the demo.
    bool scene_file = o.models.size() == 1 && is_scene_file(o.models[0]);
    if (!scene_file && o.models.size() > 1)
        for (const auto& m : o.models)
            if (is_scene_file(m)) {
                print_error("a scene file is rendered alone, not with other models: '" + m + "'");
                return std::nullopt;
            }
    std::optional<Job> parsed;
    if (scene_file) {
        SceneFileOptions so;
        so.allow_external_files = o.allow_external;
        // Usage checks of the flags first (exit 2), before the file is read.
        if (!job_from_options(o, defaults, GivenFlags{cmd})) return std::nullopt;
        SceneFile sf = load_scene_file(o.models[0], defaults, diag, so);
        parsed = job_from_options(o, sf.job, GivenFlags{cmd});
        if (scene_output && sf.output) *scene_output = sf.output->string();
    } else {
        parsed = job_from_options(o, defaults);  // usage checks first (exit 2), before touching files
        if (parsed && o.models.size() == 1) parsed->source.model = o.models[0];
        if (parsed && o.models.size() > 1)
            for (const auto& m : o.models) {
                Job::Source::Model model;
                model.path = m;
                parsed->source.models.push_back(model);
            }
    }
    return parsed;
}

std::optional<Job> job_from_command(const RenderOptions& o, const CLI::App* cmd, Diagnostics& diag,
                                    std::string& output) {
    std::string scene_output;
    std::optional<Job> parsed = job_from_sources(o, cmd, diag, Job{}, &scene_output);
    output = o.output.empty() ? scene_output : o.output;
    if (!parsed) return std::nullopt;
    if (output.empty()) {
        print_error("-o,--output is required (or an \"output\" in the scene file)");
        return std::nullopt;
    }
    return parsed;
}

ContextFlags context_flags(const RenderOptions& o) {
    ContextFlags f;
#ifndef NDEBUG
    f.debug = true;  // debug builds always report KHR_debug messages
#else
    f.debug = o.gl_debug;
#endif
    f.es3 = o.gl == "es3";
    return f;
}

void write_image_atomically(const std::string& path, const ImageF& image, bool transparent) {
    const std::string ext = lower_extension(path);
    write_file_atomically(path, [&](const std::filesystem::path& tmp) {
        if (ext == ".png") write_png(tmp, to_image8(image, transparent));
        else if (ext == ".exr") write_exr(tmp, image);
        else write_hdr(tmp, image);
    });
}

void write_png_atomically(const std::string& path, const Image8& image) {
    write_file_atomically(path, [&](const std::filesystem::path& tmp) { write_png(tmp, image); });
}

void add_model_and_output(CLI::App* cmd, RenderOptions& o) {
    cmd->add_option("model", o.models,
                    "glTF 2.0 file (.gltf/.glb), several (one scene, each at its own place), or a scene file "
                    "(.fresnel.json, docs/scene-file.md; the flags given override it); omitted: the built-in demo "
                    "(7x7 spheres)");
    cmd->add_option("-o,--output", o.output,
                    "Output image: .png (8-bit, display-encoded), .exr/.hdr (linear float after exposure and tone "
                    "map). Required unless the scene file names an output");
}

nlohmann::json camera_json(const CameraSetup& camera) {
    return {{"eye", {camera.eye.x, camera.eye.y, camera.eye.z}},
            {"target", {camera.target.x, camera.target.y, camera.target.z}},
            {"znear", camera.znear},
            {"zfar", camera.zfar},
            {"yfov_deg", camera.yfov_deg}};
}

void add_job_flags(CLI::App* cmd, RenderOptions& opts, JobFlagSet set) {
    RenderOptions* o = &opts;
    const bool raster = set == JobFlagSet::Raster;
    cmd->add_option("--size", o->size, "Image size WxH")->capture_default_str();
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
    if (raster) {
        cmd->add_option("--env-samples", o->env_samples, "GGX samples per texel when baking")->capture_default_str()
            ->check(CLI::Range(1, 65536));
        cmd->add_option("--env-size", o->env_size, "Specular cube face size when baking (power of two)")
            ->capture_default_str();
        cmd->add_flag("--no-cache", o->no_cache, "Neither read nor write $XDG_CACHE_HOME/fresnel: bake the environment and the BRDF table again");
        cmd->add_flag("--no-energy-compensation", o->no_energy_compensation,
                      "Single-scattering specular only (no multiple-scattering compensation of punctual lights)");
    }
    cmd->add_option("--light", o->lights,
                    "Add a light: dir:AZIMUTH,ELEVATION,LUX[,R,G,B] (arriving from that direction), "
                    "point:X,Y,Z,CANDELA[,R,G,B] or spot:X,Y,Z,AZIMUTH,ELEVATION,CANDELA,INNER,OUTER[,R,G,B] "
                    "(shining as a dir light from AZIMUTH,ELEVATION; cone half-angles in degrees); repeatable");
    cmd->add_flag("--no-scene-lights", o->no_scene_lights, "Ignore the file's KHR_lights_punctual lights");
    if (raster) {
        cmd->add_option("--msaa", o->msaa, "MSAA samples (1 = off; --shading ogl1 and ogl1-pixel default to 1, as OpenGL 1)")
            ->default_str("4")->check(CLI::Range(1, 16));
        cmd->add_option("--anisotropy", o->anisotropy,
                        "Most anisotropic filtering of the detail maps (base colour, metallic-roughness, normal, "
                        "specular colour, clearcoat normal, sheen colour) with trilinear samplers, in the shader as "
                        "SwiftShader filters (the Khronos Sample Viewer's reference images): up to N probes along "
                        "the footprint's major axis, only where it is that anisotropic. 1 = one trilinear probe")
            ->capture_default_str()->check(CLI::Range(1.0f, 16.0f));
        cmd->add_option("--debug", o->debug,
                        "Show a channel instead of shading: basecolor metallic roughness normal geometry-normal tangent "
                        "bitangent occlusion emissive alpha uv0 uv1 D G F diffuse specular irradiance prefiltered ibl-diffuse "
                        "ibl-specular transmission thickness sheen sheen-roughness anisotropy anisotropy-direction "
                        "iridescence iridescence-thickness diffuse-transmission diffuse-transmission-color (NaN/Inf show "
                        "as magenta)")
            ->capture_default_str();
    }
    cmd->add_flag("--allow-external-files", o->allow_external,
                  "Let URIs point outside the model's folder (absolute paths, ..); never the network");
    if (raster) {
        cmd->add_flag("--gl-debug", o->gl_debug, "Request a debug GL context and print KHR_debug messages");
        cmd->add_option("--gl", o->gl, "Graphics API: gl33 (OpenGL 3.3 core) or es3 (OpenGL ES 3.0; same pictures)")
            ->capture_default_str()
            ->check(CLI::IsMember({"gl33", "es3"}));
    }
    cmd->add_option("--obj-normals", o->obj_normals,
                    "OBJ corners without vn: groups (honour s; none means flat, as the OBJ specification says), smooth "
                    "(a normal per position whatever the groups, as OpenGL 1 viewers like rgl and ogl1-ref do) or auto "
                    "(smooth with --shading ogl1 or ogl1-pixel, groups otherwise)")
        ->capture_default_str()
        ->check(CLI::IsMember({"auto", "groups", "smooth"}));
    cmd->add_flag("--pose-skins", o->pose_skins,
                  "Pose skinned meshes by their joints' rest transforms (default: the bind pose, as the Khronos "
                  "Sample Renderer's reference images show)");
    cmd->add_option("--brdf", o->brdf,
                    "BRDF terms of the glTF model, any of D=ggx|beckmann|blinn-phong, "
                    "G=smith-height-correlated|smith-separable|schlick-ggx|cook-torrance|kelemen, "
                    "F=schlick|exact-dielectric|spherical-gaussian|exact (metals as conductors of n, k: from the base "
                    "colour, or F=exact:iron|gold|aluminium|chromium|copper|lead|platinum|silver), "
                    "diffuse=lambert|burley|oren-nayar, comma-separated "
                    "(default: the first of each, glTF's). render: punctual lights only (image-based light keeps glTF's "
                    "split sum; --debug D, G, F, diffuse, specular show the terms); trace: every light and bounce");
    if (raster) {
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
    }
    cmd->add_option("--variant", o->variant,
                    "KHR_materials_variants: render with the material variant NAME (`fresnel info` lists them)");
}

}  // namespace fresnel::cli
