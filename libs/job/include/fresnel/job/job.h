#pragma once
// Render jobs: what to render (Job, a plain value), and the rules that turn it into
// what the renderer needs (resolve()). Every front end (the CLI, a viewer, a scene
// file, a batch runner) describes a frame as a Job, so the lighting and background
// rules of docs/shading.md ("Lighting rules") exist once, here:
//   - environment: the job's, else the built-in studio unless the scene's lights or the
//     job's extra lights light the scene; Environment::Kind::None turns image-based light off;
//   - the default pair of directional lights only when nothing else lights the scene;
//   - background: blurred environment by default when there is one, else the colour
//     (black unless given); env/blur need an environment, colour and transparent do not;
//   - without an environment, energy compensation takes the BRDF table alone.
//   - a frame every material of which is drawn with OpenGL 1's model (ShadingModel::Ogl1,
//     Ogl1Pixel, or Auto on classic MTL materials) has no automatic environment (OpenGL 1
//     has no image-based light) and, when nothing else lights it, the OpenGL 1 reference's
//     default light instead of the default pair: one white light of colour 1 from
//     azimuth 30, elevation 45 (../shared/tools/ogl1-ref).
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "fresnel/core/color.h"
#include "fresnel/core/error.h"
#include "fresnel/core/image.h"
#include "fresnel/ibl/bake.h"
#include "fresnel/ibl/environment.h"
#include "fresnel/job/camera.h"
#include "fresnel/job/lights.h"
#include "fresnel/job/render_settings.h"
#include "fresnel/material/properties.h"
#include "fresnel/scene/scene.h"

namespace fresnel {

struct Job {
    // The scene: a glTF 2.0 (.gltf, .glb) or Wavefront OBJ file, or the built-in demo (7x7
    // spheres) when `model` is empty.
    struct Source {
        std::string model;
        int scene = -1;                     // scene index; -1 = the file's `scene`
        bool allow_external_files = false;  // URIs outside the model's folder (GltfLoadOptions)
        bool pose_skins = false;            // skinned meshes posed by their joints' rest transforms
        // KHR_materials_pbrSpecularGlossiness textures' RGB: read as the Khronos Sample Renderer
        // reads them (as stored) or as the extension says (decoded from sRGB).
        enum class SpecularGlossinessTextures { Khronos, Srgb } sg_textures = SpecularGlossinessTextures::Khronos;
        float max_memory_mib = 0;           // a load's memory budget, MiB; 0 = automatic (GltfLoadOptions)
        // Several models composed into one scene (scene files): when not empty it replaces
        // `model` and `scene`; each is loaded as `model` would be and put under a root node
        // holding its transform (fresnel/scene/merge.h). Invisible models are not loaded.
        struct MaterialOverride {
            std::optional<std::string> name;  // the material of this name; neither name nor index: all
            std::optional<int> index;         // the model's material N
            // Properties by their name in the material property registry
            // (fresnel/material/properties.h), each value checked against it.
            std::map<std::string, material_properties::Value> values;
            bool operator==(const MaterialOverride&) const = default;
        };
        struct Model {
            std::string path;  // empty: the built-in demo
            int scene = -1;
            glm::mat4 transform{1.0f};
            bool visible = true;
            std::vector<MaterialOverride> materials;
            bool operator==(const Model&) const = default;
        };
        std::vector<Model> models;
        std::string variant;                // KHR_materials_variants name; empty = the default materials
        // The scene posed at a time of its animations (load_scene poses it on the CPU: skins
        // and morph targets as fresnel::animated_scene); neither set: the rest pose. The camera
        // keeps fitting the rest pose (Scene::framing), so frames at different times line up.
        struct Animation {
            std::optional<float> time;  // seconds (each animation clamps to its keyframes); unset: 0 when `index` is set
            int index = -1;             // the animation played; -1: all of them
            bool posed() const { return time.has_value() || index >= 0; }
            float at() const { return time.value_or(0.0f); }
            bool operator==(const Animation&) const = default;
        };
        Animation animation;
        // Parts of the file turned off at load (fresnel/job/features.h: skinning, morphing,
        // occlusion, material extensions), in feature_names() order.
        std::vector<std::string> disabled;
        // OBJ corners without `vn`: Groups honours `s` (the specification: none means flat),
        // Smooth gives them a normal per position whatever the groups (what OpenGL 1 viewers
        // such as rgl, and ogl1-ref, do); Auto is Smooth under Output::shading ogl1 or
        // ogl1-pixel, Groups otherwise.
        enum class ObjNormals { Auto, Groups, Smooth } obj_normals = ObjNormals::Auto;
        bool operator==(const Source&) const = default;
    };
    // The orbit camera of docs/shading.md's camera convention, or the file's camera N.
    struct Camera {
        std::optional<int> scene_camera;  // set: the file's N-th camera (the orbit fields are unused)
        int scene_camera_model = 0;       // with Source::models: whose file `scene_camera` counts in
        // Set (and scene_camera not): a camera at `eye` looking at `target`, vertical FOV
        // yfov_deg, near and far planes from the bounds as the orbit camera's.
        struct LookAt {
            glm::vec3 eye{0.0f, 0.0f, 1.0f}, target{0.0f}, up{0.0f, 1.0f, 0.0f};
            bool operator==(const LookAt&) const = default;
        };
        std::optional<LookAt> look_at;
        float yaw_deg = 0.0f, pitch_deg = 0.0f;
        std::optional<float> distance_k;  // D = K * R; nullopt = fit the bounds
        float yfov_deg = 45.0f;
        std::optional<glm::vec3> target;  // the point orbited; nullopt = the bounds' centre (a viewer pans it)
        bool operator==(const Camera&) const = default;
    };
    struct Lights {
        bool scene_lights = true;          // the file's KHR_lights_punctual lights
        std::vector<LightInstance> extra;  // added after the scene's (e.g. parse_light())
        bool operator==(const Lights&) const = default;
    };
    struct Environment {
        // Automatic: the studio unless the scene or `Lights::extra` brings lights.
        // File: an equirectangular .hdr/.exr or a folder made by `fresnel bake`.
        // Color: a uniform environment of `color` (linear). None: no image-based light.
        enum class Kind { Automatic, File, Color, Studio, None } kind = Kind::Automatic;
        std::string path;        // Kind::File
        glm::vec3 color{1.0f};   // Kind::Color
        float rotation_deg = 0.0f;  // about +Y
        float intensity = 1.0f;
        int bake_samples = 1024;  // GGX samples per texel when baking a panorama (ibl::BakeOptions::samples)
        int bake_size = 256;      // specular cube face size when baking (power of two)
        // Diffuse image-based light: false, filtered importance sampling as the Khronos Sample
        // Viewer bakes it (its blur); true, the exact cosine convolution (ibl::BakeOptions).
        bool exact_irradiance = false;
        bool use_cache = true;    // load/store bakes and the BRDF table under ibl::cache_root()
        bool operator==(const Environment&) const = default;
    };
    struct Background {
        // Automatic and Blurred: a prefiltered level of the environment; Environment: the
        // environment, sharp. Without an environment these three show `color`.
        // Color: `color` (display-encoded 0..1). Transparent: alpha 0.
        enum class Mode { Automatic, Environment, Blurred, Color, Transparent } mode = Mode::Automatic;
        glm::vec3 color{0.0f};
        bool operator==(const Background&) const = default;
    };
    struct Output {
        int width = 1024, height = 768;
        // Samples, 1 = off; 0 = automatic: 4, or 1 with OpenGL 1 shading (Ogl1, Ogl1Pixel), whose
        // framebuffer has no multisampling (nor has ogl1-ref's). resolve() applies it.
        int msaa = 0;
        float anisotropy = kDefaultAnisotropy;  // anisotropic filtering of the detail maps, 1 = off (RenderSettings::anisotropy)
        ToneMapper tone_mapper = ToneMapper::Neutral;
        float exposure_ev = 0.0f;
        Encoding encoding = Encoding::Srgb;  // display images only
        // Linear float output (EXR, HDR): exposure and tone map, no encoding, premultiplied alpha.
        bool float_output = false;
        DebugChannel debug = DebugChannel::None;
        bool energy_compensation = true;  // multiple-scattering compensation of the specular lobe
        // Repeated meshes drawn instanced (RenderSettings::instancing) and traced as Embree
        // instances (trace::TraceSceneOptions::instancing): the same picture, less work and memory.
        bool instancing = true;
        Shadows shadows = Shadows::Soft;  // punctual lights' shadows in the rasteriser (RenderSettings)
        int shadow_map_size = 2048;
        int shadow_cascades = 2;
        // Occlusion of image-based and ambient light (`--ao`): off (as the Khronos Sample Viewer),
        // or baked, the tracer's rays at every vertex of the static scene
        // (trace::bake_vertex_occlusion, Renderer::set_vertex_occlusion), ao_rays per vertex.
        AmbientOcclusion ao = AmbientOcclusion::Off;
        int ao_rays = 128;
        float ao_radius = 0.0f;  // --ao ssao's reach in scene units (0: a quarter of the scene's radius)
        // The environment's dominant light (a sun, a key light) out of the image-based light and
        // drawn as a shadowed directional light (`--env-light dominant`), or left in it (off).
        EnvLight env_light = EnvLight::Off;
        // The shading model for the frame, or Auto: per material (RenderSettings::shading).
        ShadingModel shading = ShadingModel::Auto;
        brdf::BrdfModel brdf;  // the glTF BRDF's terms for punctual lights (RenderSettings::brdf)
        glm::vec3 ambient{0.0f};  // uniform ambient light (OpenGL 1: GL_LIGHT_MODEL_AMBIENT)
        // OpenGL 1 fog (Ogl1 models). Its colour is fog_color, else the background colour (as rgl).
        Fog fog;
        std::optional<glm::vec3> fog_color;
        bool operator==(const Output&) const = default;
    };

    Source source;
    Camera camera;
    Lights lights;
    Environment environment;
    Background background;
    Output output;
    bool operator==(const Job&) const = default;
};

// Loads the job's scene: its glTF file (warnings into `diag`; throws fresnel::Error) or the demo;
// with Source::models, every visible model merged into one scene (load_models); posed at
// Source::animation when it asks for a time (on the CPU, fresnel/scene/pose.h). Front ends that
// pose the scene themselves load it with load_rest_scene.
// `keep`: what the loaders keep beyond the scene (SceneImage::encoded: a one-shot render that
// frees decoded images once uploaded, Renderer::set_scene's ImageResidency).
struct LoadKeep {
    bool encoded_images = false;
};
Scene load_scene(const Job& job, Diagnostics& diag, LoadKeep keep = {});

// The job's scene at rest, for front ends that pose it themselves (a frame sequence, the
// viewer's and the page's playback: fresnel/render/scene_posing.h): load_scene with the
// animation unset, the job's Source::animation checked against it (an animation index the file
// lacks throws fresnel::Error naming the file; a file without animations warns).
Scene load_rest_scene(const Job& job, Diagnostics& diag, LoadKeep keep = {});

// Source::models: each visible model loaded (through load_scene), its material overrides
// applied, put under a root with its transform. Throws fresnel::Error (the model's file).
Scene load_models(const Job& job, Diagnostics& diag, LoadKeep keep = {});

// Everything the renderer needs for one job on one scene.
struct ResolvedJob {
    int scene_index = -1;                // for the renderer's set_scene
    std::vector<NodeInstance> instances;  // the flattened scene
    Bounds bounds;
    CameraSetup camera;
    std::vector<LightInstance> lights;  // the scene's, the job's extra ones, or the default pair
    bool default_lights = false;        // `lights` is default_lights() (or the OpenGL 1 default light)
    bool ogl1_frame = false;            // every material is drawn with OpenGL 1's model
    // The environment to load or bake (load_lighting()); nullopt: no image-based light.
    std::optional<ibl::EnvironmentSource> environment;
    ibl::BakeOptions bake_options;
    bool use_cache = true;
    bool needs_brdf_lut = false;  // no environment, energy compensation on: the table alone
    // Frame settings. `environment` and `brdf_lut` are null here: take the settings from
    // JobLighting::settings(), which points them at the loaded data.
    RenderSettings settings;
    bool transparent() const { return settings.background.w == 0.0f; }
};

// Applies the lighting, background and camera rules to `job` on `scene` (loaded from
// job.source). Throws fresnel::Error (file: the model, or "demo") when the scene index
// is out of range or no node uses the requested camera.
// `diag`, when given, gets what the job asks that will not do what its user likely meant (an
// 8-bit image as the environment's radiance).
ResolvedJob resolve(const Job& job, const Scene& scene, Diagnostics* diag = nullptr);

// The image-based light and BRDF table a resolved job asks for; owns what the render
// settings point to, so it must outlive the frames rendered with them.
struct JobLighting {
    std::optional<ibl::BakedIbl> environment;
    ImageF brdf_lut;               // empty unless ResolvedJob::needs_brdf_lut
    double environment_ms = 0.0;  // time to load or bake the environment
    RenderSettings settings(const ResolvedJob& resolved) const;
};

// Which image-based light and BRDF table a resolved job needs, as one key: two jobs with the
// same key can share one JobLighting (the viewer, the web page and batch cache by it). The
// environment's description, the bake options, whether the cache is used and whether the
// table alone is needed; "none" when the job needs neither.
std::string lighting_key(const ResolvedJob& resolved);

// Loads or bakes resolved.environment (ibl::load_or_bake; `progress` gets the baking's
// progress, from worker threads) and, when asked for, the BRDF table. Throws fresnel::Error.
JobLighting load_lighting(const ResolvedJob& resolved, const ibl::Progress& progress = {});

}  // namespace fresnel
