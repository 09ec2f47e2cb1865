#include "fresnel/job/job.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <chrono>

#include "fresnel/job/features.h"
#include "fresnel/scene/gltf_loader.h"
#include "fresnel/scene/obj_loader.h"
#include "fresnel/scene/pose.h"
#include "fresnel/scene/procedural.h"

namespace fresnel {

namespace {
std::string model_name(const Job& job) {
    if (!job.source.models.empty()) return job.source.models.front().path.empty() ? "demo" : job.source.models.front().path;
    return job.source.model.empty() ? std::string("demo") : job.source.model;
}
// --max-memory's MiB as bytes (at least 1 MiB).
std::size_t mib_bytes(float mib) {
    return std::size_t(std::min<double>(std::max<double>(mib, 1.0) * 1048576.0, double(SIZE_MAX / 2)));
}
}  // namespace

namespace {
void check_animation(const Job& job, const Scene& scene, Diagnostics& diag);

Scene load_unposed(const Job& job, Diagnostics& diag, LoadKeep keep) {
    if (!job.source.models.empty()) return load_models(job, diag, keep);
    if (job.source.model.empty()) return make_demo_scene();
    if (is_obj_path(job.source.model)) {
        ObjLoadOptions oo;
        oo.allow_external_files = job.source.allow_external_files;
        if (job.source.max_memory_mib > 0) oo.max_total_bytes = mib_bytes(job.source.max_memory_mib);
        using N = Job::Source::ObjNormals;
        const bool ogl1 = job.output.shading == ShadingModel::Ogl1 || job.output.shading == ShadingModel::Ogl1Pixel;
        oo.smooth_without_groups = job.source.obj_normals == N::Smooth || (job.source.obj_normals == N::Auto && ogl1);
        return load_obj(job.source.model, diag, oo);
    }
    GltfLoadOptions lo;
    lo.allow_external_files = job.source.allow_external_files;
    if (job.source.max_memory_mib > 0) lo.max_total_bytes = lo.max_geometry_bytes = mib_bytes(job.source.max_memory_mib);
    lo.keep_encoded_images = keep.encoded_images;
    lo.pose_skins = job.source.pose_skins && !job.source.animation.posed();  // animated skins pose from the bind pose
    Scene scene = load_gltf(job.source.model, diag, lo);
    if (!job.source.variant.empty()) apply_material_variant(scene, find_material_variant(scene, job.source.variant));
    disable_features(scene, job.source.disabled);
    if (job.source.sg_textures == Job::Source::SpecularGlossinessTextures::Khronos)
        for (Material& m : scene.materials)
            if (m.specular_glossiness) m.specular_glossiness->linear_textures = true;
    return scene;
}
}  // namespace

Scene load_scene(const Job& job, Diagnostics& diag, LoadKeep keep) {
    Scene scene = load_unposed(job, diag, keep);
    const Job::Source::Animation& a = job.source.animation;
    if (a.posed() && job.source.models.empty()) {  // several models: each was posed as it loaded
        check_animation(job, scene, diag);
        ScenePoser(scene).pose(a.index, a.at(), true);
    }
    return scene;
}

namespace {
void check_animation(const Job& job, const Scene& scene, Diagnostics& diag) {
    const Job::Source::Animation& a = job.source.animation;
    if (!a.posed()) return;
    const std::string name = scene.source.empty() ? model_name(job) : scene.source;
    if (a.index >= int(scene.animations.size()))
        throw Error(name, "--animation " + std::to_string(a.index),
                    "the file has " + std::to_string(scene.animations.size()) + " animations");
    if (scene.animations.empty())
        diag.warn(name, "--time", "the file has no animations; rendering its rest pose posed on the CPU");
}
}  // namespace

Scene load_rest_scene(const Job& job, Diagnostics& diag, LoadKeep keep) {
    Job rest = job;
    rest.source.animation = {};
    Scene scene = load_scene(rest, diag, keep);
    check_animation(job, scene, diag);
    return scene;
}

ResolvedJob resolve(const Job& job, const Scene& scene, Diagnostics* diag) {
    ResolvedJob r;
    const Job::Output& out = job.output;
    if (job.source.scene >= int(scene.scenes.size()))
        throw Error(model_name(job), "--scene " + std::to_string(job.source.scene),
                    "the file has " + std::to_string(scene.scenes.size()) + " scenes");
    r.scene_index = job.source.scene;
    r.instances = flatten(scene, job.source.scene);
    r.bounds = scene_bounds(scene, r.instances);
    const Bounds framing = framing_bounds(scene, job.source.scene, r.instances);

    // Camera.
    if (job.camera.scene_camera) {
        int n = *job.camera.scene_camera;
        int index = n;  // in the merged scene: counted from the model's first camera
        const int model = job.camera.scene_camera_model;
        if (!scene.parts.empty()) {
            if (model < 0 || model >= int(scene.parts.size()) || n >= scene.parts[std::size_t(model)].camera_count)
                throw Error(model_name(job), "camera " + std::to_string(n) + " of model " + std::to_string(model),
                            "no such (visible) model or camera");
            index = scene.parts[std::size_t(model)].first_camera + n;
        }
        auto c = scene_camera(scene, r.instances, index, out.width, out.height);
        if (!c)
            throw Error(model_name(job), "--camera " + std::to_string(n),
                        "no node of the scene uses camera " + std::to_string(n) + " (the file has " +
                            std::to_string(scene.cameras.size()) + ")");
        r.camera = *c;
    } else if (job.camera.look_at) {
        const Job::Camera::LookAt& la = *job.camera.look_at;
        r.camera = look_at_camera(framing, la.eye, la.target, la.up, job.camera.yfov_deg, out.width, out.height);
    } else {
        OrbitParams op;
        op.yaw_deg = job.camera.yaw_deg;
        op.pitch_deg = job.camera.pitch_deg;
        op.distance_k = job.camera.distance_k;
        op.yfov_deg = job.camera.yfov_deg;
        op.target = job.camera.target;
        r.camera = orbit_camera(framing, op, out.width, out.height);
    }

    // OpenGL 1 frames: every material (the default one when the scene has none) in its model.
    {
        static const Material kDefault{};
        auto ogl1 = [&](const Material& m) { return is_ogl1(material_shading(out.shading, m)); };
        r.ogl1_frame = scene.materials.empty() ? ogl1(kDefault)
                                               : std::all_of(scene.materials.begin(), scene.materials.end(), ogl1);
    }

    // Lights: the scene's, then the job's.
    if (job.lights.scene_lights) r.lights = scene_lights(scene, r.instances);
    r.lights.insert(r.lights.end(), job.lights.extra.begin(), job.lights.extra.end());

    // Image-based light: the job's, else the studio unless something else lights the scene.
    using Kind = Job::Environment::Kind;
    const Job::Environment& env = job.environment;
    if (env.kind == Kind::File) {
        r.environment = ibl::EnvironmentSource{};
        r.environment->kind = ibl::EnvironmentSource::Kind::File;
        r.environment->path = env.path;
        std::string ext = std::filesystem::path(env.path).extension().string();
        for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
        if (diag && (ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".bmp" || ext == ".tga" || ext == ".webp"))
            diag->warn(env.path, "--env",
                       "an 8-bit image as the environment: its values are display values / 255, not radiance, so "
                       "the light is dim and clipped (an .hdr or .exr panorama holds radiance)");
    } else if (env.kind == Kind::Color) {
        r.environment = ibl::EnvironmentSource{};
        r.environment->kind = ibl::EnvironmentSource::Kind::Uniform;
        r.environment->color = env.color;
    } else if (env.kind == Kind::Studio || (env.kind == Kind::Automatic && r.lights.empty() && !r.ogl1_frame)) {
        r.environment = ibl::EnvironmentSource{};  // the studio
    }
    r.bake_options.samples = env.bake_samples;
    r.bake_options.size = env.bake_size;
    if (env.exact_irradiance) r.bake_options.irradiance_samples = 0;
    r.use_cache = env.use_cache;
    // --env-light dominant: a panorama's dominant light comes out of the bake as a directional light
    // (BakedIbl::dominant_light), which the renderer adds to the frame's lights and shadows.
    if (r.environment && r.environment->kind != ibl::EnvironmentSource::Kind::Uniform &&
        job.output.env_light == EnvLight::Dominant)
        r.environment->split_dominant_light = true;

    // The default pair of directional lights only when nothing else lights the scene.
    r.default_lights = r.lights.empty() && !r.environment;
    if (r.default_lights) {
        if (r.ogl1_frame) {
            LightInstance key;
            key.direction = direction_from_angles(30.0f, 45.0f);
            key.radiance = glm::vec3(1.0f);
            r.lights = {key};
        } else {
            r.lights = default_lights();
        }
    }
    r.needs_brdf_lut = !r.environment && out.energy_compensation && !r.ogl1_frame;

    RenderSettings& rs = r.settings;
    rs.width = out.width;
    rs.height = out.height;
    rs.msaa = out.msaa > 0 ? out.msaa
                           : (out.shading == ShadingModel::Ogl1 || out.shading == ShadingModel::Ogl1Pixel ? 1 : 4);
    rs.anisotropy = out.anisotropy;
    rs.exposure_ev = out.exposure_ev;
    rs.tone_mapper = out.tone_mapper;
    rs.debug = out.debug;
    rs.env_intensity = env.intensity;
    rs.env_rotation_deg = env.rotation_deg;
    rs.energy_compensation = out.energy_compensation;
    rs.instancing = out.instancing;
    rs.shadows = out.shadows;
    rs.ssao = out.ao == AmbientOcclusion::ScreenSpace;
    rs.ssao_radius = out.ao_radius;
    rs.shadow_map_size = out.shadow_map_size;
    rs.shadow_cascades = out.shadow_cascades;
    rs.shading = out.shading;
    rs.brdf = out.brdf;
    rs.ambient = out.ambient;
    rs.fog = out.fog;
    if (out.float_output) {
        rs.encoding.reset();
        rs.straight_alpha = false;  // EXR convention: premultiplied alpha
    } else {
        rs.encoding = out.encoding;
        // The frame ends as 8-bit display values (a PNG, a window): an 8-bit canvas is enough.
        rs.frame_format = RenderSettings::FrameFormat::Display8;
    }

    // Background: the environment (blurred by default) when there is one, else a colour.
    using Mode = Job::Background::Mode;
    const Job::Background& bg = job.background;
    rs.background = bg.mode == Mode::Transparent ? glm::vec4(0.0f) : glm::vec4(bg.color, 1.0f);
    rs.background_mode = RenderSettings::Background::Color;
    if (r.environment) {
        if (bg.mode == Mode::Environment) rs.background_mode = RenderSettings::Background::Environment;
        if (bg.mode == Mode::Automatic || bg.mode == Mode::Blurred)
            rs.background_mode = RenderSettings::Background::Blurred;
    }
    rs.fog.color = out.fog_color ? *out.fog_color : glm::vec3(rs.background);
    return r;
}

RenderSettings JobLighting::settings(const ResolvedJob& resolved) const {
    RenderSettings rs = resolved.settings;
    rs.environment = environment ? &*environment : nullptr;
    rs.brdf_lut = brdf_lut.width > 0 ? &brdf_lut : nullptr;
    return rs;
}

std::string lighting_key(const ResolvedJob& r) {
    if (!r.environment && !r.needs_brdf_lut) return "none";
    return (r.environment ? r.environment->describe() : std::string("no-environment")) + "|" + r.bake_options.key() +
           (r.use_cache ? "|cache" : "|no-cache") + (r.needs_brdf_lut ? "|lut" : "");
}

JobLighting load_lighting(const ResolvedJob& resolved, const ibl::Progress& progress) {
    JobLighting l;
    if (resolved.environment) {
        auto t = std::chrono::steady_clock::now();
        l.environment = ibl::load_or_bake(*resolved.environment, resolved.bake_options, progress, resolved.use_cache);
        l.environment_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
    }
    if (resolved.needs_brdf_lut) l.brdf_lut = ibl::load_or_bake_lut(resolved.bake_options, resolved.use_cache);
    return l;
}

}  // namespace fresnel
