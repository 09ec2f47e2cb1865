// fresnel in the browser: the same Job, resolve(), load_lighting() and Renderer as
// `fresnel render` and `fresnel view`, drawing into a WebGL 2 canvas (libs/gpu's WebGL
// context). The page (index.html, fresnel_page.js) writes the files it is given into
// Emscripten's in-memory file system and drives this through the C functions below; one
// App per canvas, held by the page as an opaque handle.
#include <emscripten/emscripten.h>
#include <emscripten/html5.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "fresnel/core/error.h"
#include "fresnel/gpu/context.h"
#include "fresnel/gpu/device.h"
#include "fresnel/ibl/environment.h"
#include "fresnel/job/features.h"
#include "fresnel/job/job.h"
#include "fresnel/job/orbit_controller.h"
#include "fresnel/render/renderer.h"
#include "fresnel/render/scene_posing.h"
#include "fresnel/job/scene_file.h"
#include "fresnel/job/settings.h"
#include "fresnel/material/properties.h"

namespace fresnel::web {
namespace {

bool parse_float(const std::string& s, float& out) {
    char* end = nullptr;
    out = std::strtof(s.c_str(), &end);
    return !s.empty() && end && *end == '\0';
}

// A light as the page edits it: the CLI's --light terms (arriving from azimuth/elevation, or
// a position; colour and intensity = radiance split at its largest component).
nlohmann::json light_json(const LightInstance& l, const std::string& origin, int index) {
    float intensity = std::max({l.radiance.x, l.radiance.y, l.radiance.z, 0.0f});
    glm::vec3 color = intensity > 0 ? l.radiance / intensity : glm::vec3(1.0f);
    glm::vec3 from = -l.direction;
    const float deg = 180.0f / 3.14159265358979f;
    return {{"origin", origin}, {"index", index}, {"type", light_type_name(l.type)}, {"spec", light_spec(l)},
            {"azimuth", std::atan2(from.x, from.z) * deg}, {"elevation", std::asin(std::clamp(from.y, -1.0f, 1.0f)) * deg},
            {"position", {l.position.x, l.position.y, l.position.z}}, {"color", {color.x, color.y, color.z}},
            {"intensity", intensity}};
}

struct App {
    std::string canvas;
    std::unique_ptr<gpu::Context> context;
    std::unique_ptr<Renderer> renderer;
    Job job;
    std::unique_ptr<Scene> scene;
    ScenePosing posing;  // `scene` posed in place at the job's animation time (the page plays it)
    ResolvedJob resolved;
    JobLighting lighting;
    std::string lighting_key = "\n";  // nothing loaded
    Job::Environment good_environment;
    std::string error, warnings, info, info_bake;
    std::string text;  // the last string handed to the page (copied there at once)
    double frame_ms = 0;
    FrameStats stats;
    // Environments baked by the page's Web Worker (fresnel_bake there): lighting key -> the
    // baked folder, or the bake's error. `pending` is the key handed out by pending_bake().
    std::map<std::string, std::string> baked_folders, bake_errors;
    std::string pending, refining;
    std::vector<Material> loaded_materials;  // the scene's materials as loaded (the editor's "revert")
    Job::Environment environment_before_no_ibl;  // what `no-ibl 0` turns back to

    // Sets a job setting by its key (fresnel/job/settings.h: "render.exposure"), its flag
    // name without the dashes ("exposure") or an older name (with a warning); and the page's
    // own commands: no-ibl 1|0 (off, and back to the environment before), light:N SPEC,
    // light-remove N, lights-clear. `size` also sizes the canvas.
    void set(const std::string& key, const std::string& value) {
        if (key == "no-ibl") {  // 1: no image-based light; 0: the environment set before
            using Kind = Job::Environment::Kind;
            if (value != "0" && job.environment.kind != Kind::None) {
                environment_before_no_ibl = job.environment;
                job.environment.kind = Kind::None;
            } else if (value == "0" && job.environment.kind == Kind::None) {
                job.environment = environment_before_no_ibl;
                if (job.environment.kind == Kind::None) job.environment.kind = Kind::Automatic;
            }
        } else if (key.rfind("light:", 0) == 0) {  // light:N = --light SPEC (N = the count adds one)
            float n = 0;
            if (!parse_float(key.substr(6), n) || n < 0 || n > float(job.lights.extra.size()))
                throw Error("--light", "", "no light " + key.substr(6));
            LightInstance l = parse_light(value);
            if (std::size_t(n) == job.lights.extra.size()) job.lights.extra.push_back(l);
            else job.lights.extra[std::size_t(n)] = l;
        } else if (key == "light-remove") {
            float n = 0;
            if (!parse_float(value, n) || n < 0 || n >= float(job.lights.extra.size()))
                throw Error("--light", "", "no light " + value);
            job.lights.extra.erase(job.lights.extra.begin() + std::ptrdiff_t(n));
        } else if (key == "lights-clear") {
            job.lights.extra.clear();
        } else {
            const settings::Setting* s = settings::find(key);
            if (!s || !s->offered(settings::kWeb)) throw Error("fresnel_set", "", "unknown setting '" + key + "'");
            if (!s->choice_offered(value, settings::kWeb))  // (the registry says why: its doc)
                throw Error("fresnel_set", "", "'" + value + "' is not offered by the page for " + s->key + ": " + s->doc);
            Diagnostics diag;
            settings::set(job, key, value, key, &diag);
            for (const std::string& w : diag.lines()) warnings += w + "\n";
            if (s->key == "render.size")
                emscripten_set_canvas_element_size(canvas.c_str(), job.output.width, job.output.height);
            if (s->key == "disable" && scene) {  // parts of the file turned off (fresnel/job/features.h): loaded again without them
                Diagnostics load;
                show(job, load);
            }
            if (s->key == "variant" && scene && !scene->material_variants.empty()) {  // KHR_materials_variants: the scene again with the variant's materials
                Diagnostics load;
                show(job, load);
            }
        }
    }

    // Loads a model (a path in the page's file system; "" = the built-in demo). The scene
    // shown so far stays when it fails.
    void open(const std::string& path) {
        Job j = job;
        j.source.model = path;
        // The orbit (yaw, pitch, K, fov) carries over to the new model; the pan target does not.
        j.camera.target.reset();
        j.camera.scene_camera.reset();
        j.camera.look_at.reset();
        j.source.models.clear();
        j.source.variant.clear();
        j.source.animation = {};  // a new model starts at its rest pose (the page plays an animated one)
        Diagnostics diag;
        show(j, diag);
    }

    // Loads a scene file (docs/scene-file.md) as `fresnel render SCENE.fresnel.json` does:
    // read onto the default job by the CLI's parser; the canvas takes its size. Its models and
    // environment are files the page wrote beside it. What was shown stays when it fails.
    void open_scene_file(const std::string& path) {
        Job defaults;
        defaults.environment.use_cache = false;
        Diagnostics diag;
        SceneFile sf = load_scene_file(path, defaults, diag);
        sf.job.environment.use_cache = false;
        show(sf.job, diag);
        set("size", std::to_string(job.output.width) + "x" + std::to_string(job.output.height));
    }

    void show(const Job& j, Diagnostics& diag) {
        auto s = std::make_unique<Scene>(load_rest_scene(j, diag));  // posed at the job's time by pose()
        ResolvedJob r = resolve(j, *s);
        renderer->set_scene(*s, r.scene_index);
        posing.reset(*s);
        scene = std::move(s);
        loaded_materials = scene->materials;
        job = j;
        warnings.clear();
        for (const std::string& line : diag.lines()) warnings += line + "\n";
    }

    // The material editor: a property of material `index` by its name in the material
    // property registry (fresnel/material/properties.h; a missing extension block is added
    // with its defaults); "reset" restores the material as loaded. The renderer reads the
    // scene's materials at every frame, so the next frame shows it.
    void set_material(int index, const std::string& key, const std::string& value) {
        if (!scene || index < 0 || std::size_t(index) >= scene->materials.size())
            throw Error("material", "", "no material " + std::to_string(index));
        Material& m = scene->materials[std::size_t(index)];
        if (key == "reset") m = loaded_materials.at(std::size_t(index));
        else material_properties::set(m, key, value, "material " + std::to_string(index));
        posing.keep_materials();
    }

    // The scene at the job's animation time (animation.time, animation.index: the page's
    // playback sets them), when that changed.
    void pose() {
        const Job::Source::Animation& a = job.source.animation;
        std::optional<float> t;
        if (a.posed() && !scene->animations.empty()) t = a.at();
        try {
            posing.show(*renderer, a.index, t, job.source.scene);
        } catch (...) {
            job.source.animation = {};
            throw;
        }
    }

    // The materials as JSON (the page's editor): the registry's properties of the core and of
    // the blocks each material has, by name, as numbers, arrays, booleans or words.
    std::string materials_json() const {
        namespace mp = material_properties;
        nlohmann::json out = nlohmann::json::array();
        if (!scene) return out.dump();
        for (std::size_t i = 0; i < scene->materials.size(); ++i) {
            const Material& m = scene->materials[i];
            nlohmann::json values = nlohmann::json::object(), blocks = nlohmann::json::array();
            for (const mp::Block& b : mp::blocks())
                if (b.present(m)) blocks.push_back(b.name);
            for (const mp::Property& p : mp::all()) {
                if (!mp::editable(p, m)) continue;
                const mp::Value v = p.get(m);
                nlohmann::json& j = values[std::string(p.name)];
                if (p.type == mp::Type::Bool) j = v[0] != 0.0f;
                else if (p.type == mp::Type::Choice) j = mp::format(p, v);
                else if (!std::isfinite(v[0])) j = nullptr;  // attenuationDistance's default: no absorption
                else if (p.width == 1) j = v[0];
                else j = std::vector<float>(v.begin(), v.begin() + p.width);
            }
            out.push_back({{"index", i}, {"name", m.name}, {"blocks", blocks}, {"values", values},
                           {"hasNormalTexture", m.normal.valid()}, {"hasOcclusionTexture", m.occlusion.valid()}});
        }
        return out.dump();
    }

    // The lights of the frame (the scene's, the job's extra ones, or the default pair) and the
    // settings the panel shows, as JSON.
    std::string state_json() {
        nlohmann::json lights = nlohmann::json::array();
        bool defaults = false;
        std::optional<ResolvedJob> resolved_now;  // none when the job does not resolve (a camera or scene it lacks)
        if (scene) try {
                resolved_now = resolve(job, *scene);
            } catch (const Error&) {
            }
        if (resolved_now) {
            const ResolvedJob& r = *resolved_now;
            defaults = r.default_lights;
            std::size_t n_scene = job.lights.scene_lights && !defaults ? r.lights.size() - job.lights.extra.size() : 0;
            for (std::size_t i = 0; i < r.lights.size(); ++i) {
                if (defaults) lights.push_back(light_json(r.lights[i], "default", int(i)));
                else if (i < n_scene) lights.push_back(light_json(r.lights[i], "scene", int(i)));
                else lights.push_back(light_json(r.lights[i], "extra", int(i - n_scene)));
            }
        }
        // The scene's lights when they are switched off, listed (greyed) so that the switch shows what it hides.
        nlohmann::json hidden = nlohmann::json::array();
        if (resolved_now && !job.lights.scene_lights) {
            const ResolvedJob& r = *resolved_now;
            for (const LightInstance& l : scene_lights(*scene, r.instances)) hidden.push_back(light_json(l, "scene-off", 0));
        }
        using Kind = Job::Environment::Kind;
        const Job::Environment& e = job.environment;
        nlohmann::json out = {
            {"lights", lights}, {"hiddenSceneLights", hidden}, {"defaultLights", defaults},
            {"ibl", e.kind != Kind::None},
            {"environment", e.kind == Kind::File ? e.path : e.kind == Kind::Studio ? "studio" : e.kind == Kind::None ? "none"
                                                        : e.kind == Kind::Color ? "color" : "auto"}};
        // Every setting the page offers, by its registry key, in the registry's text (the
        // panel shows these; nothing here restates a setting).
        nlohmann::json values = nlohmann::json::object();
        for (const settings::Setting* s : settings::offered_by(settings::kWeb)) values[s->key] = settings::get(job, *s);
        out["settings"] = values;
        // The animations (the page's playback: names and keyframe ranges) and the variants.
        nlohmann::json animations = nlohmann::json::array(), variants = nlohmann::json::array();
        if (scene) {
            for (const Animation& a : scene->animations)
                animations.push_back({{"name", a.name}, {"start", a.start()}, {"end", a.end()}});
            for (const std::string& v : scene->material_variants) variants.push_back(v);
        }
        out["animations"] = animations;
        out["posedOnGpu"] = posing.on_gpu();
        out["variants"] = variants;
        nlohmann::json cameras = nlohmann::json::array();  // the file's cameras (the page's camera picker)
        if (scene)
            for (std::size_t i = 0; i < scene->cameras.size(); ++i)
                cameras.push_back(scene->cameras[i].name.empty() ? "camera " + std::to_string(i) : scene->cameras[i].name);
        out["cameras"] = cameras;
        // The parts of the file its switches turn off (the setting `disable`): what the scene
        // holds, and what is off.
        nlohmann::json features = nlohmann::json::array();
        if (scene) {
            std::vector<std::string> list = scene_features(*scene);
            for (const std::string& f : job.source.disabled)
                if (std::find(list.begin(), list.end(), f) == list.end()) list.push_back(f);
            for (const std::string& f : list)
                features.push_back({{"name", f},
                                    {"on", std::find(job.source.disabled.begin(), job.source.disabled.end(), f) ==
                                               job.source.disabled.end()}});
        }
        out["features"] = features;
        return out.dump();
    }

    // Resolves the job and loads or bakes its lighting when it changed; the environment that
    // worked before stays when the new one fails.
    void prepare() {
        if (!scene) throw Error("fresnel", "", "no model loaded");
        pose();
        resolved = resolve(job, *scene);
        std::string key = fresnel::lighting_key(resolved);
        if (key == lighting_key) return;
        if (key == pending && lighting_key != "\n") return;  // the worker is baking it: the old lighting meanwhile
        try {
            if (auto e = bake_errors.find(key); e != bake_errors.end()) throw Error(resolved.environment->path.string(), "", e->second);
            if (auto f = baked_folders.find(key); f != baked_folders.end()) {
                double t = emscripten_get_now();
                lighting = JobLighting{};
                lighting.environment = ibl::load_baked(f->second);
                lighting.environment_ms = emscripten_get_now() - t;
            } else {
                lighting = load_lighting(resolved, [](double fraction) {
                    EM_ASM({ if (Module.onBakeProgress) Module.onBakeProgress($0); }, fraction);
                });
            }
            lighting_key = key;
            good_environment = job.environment;
            if (lighting.environment) {
                const ibl::BakedIbl& e = *lighting.environment;
                info_bake = "environment " + std::to_string(int(lighting.environment_ms)) + " ms (cube " +
                            std::to_string(int(e.cube_ms)) + ", specular " + std::to_string(int(e.specular_ms)) +
                            ", irradiance " + std::to_string(int(e.irradiance_ms)) + ", table " +
                            std::to_string(int(e.lut_ms)) + ")";
                EM_ASM({ console.log(UTF8ToString($0)); }, info_bake.c_str());
            }
        } catch (...) {
            job.environment = good_environment;
            resolved = resolve(job, *scene);
            throw;
        }
    }

    void draw() {
        prepare();
        RenderSettings rs = lighting.settings(resolved);
        rs.gpu_animation = posing.gpu_animation();
        double t = emscripten_get_now();
        stats = {};
        renderer->draw(resolved.camera, resolved.lights, rs, RenderTarget::default_framebuffer(0, 0), &stats);
        renderer->finish();
        frame_ms = emscripten_get_now() - t;
        if (!stats.gl_errors.empty()) throw Error("WebGL", "", "the frame raised " + stats.gl_errors);
    }

    // What the page's worker should bake for the current job: "" when nothing (the lighting is
    // loaded, or needs no bake), else "SOURCE\nSIZE\nSAMPLES" (SOURCE: a file, or studio).
    std::string pending_bake() {
        if (!scene) return "";
        resolved = resolve(job, *scene);
        std::string key = fresnel::lighting_key(resolved);
        if (key == lighting_key || !resolved.environment || baked_folders.count(key) || bake_errors.count(key)) return "";
        const ibl::EnvironmentSource& e = *resolved.environment;
        if (e.kind == ibl::EnvironmentSource::Kind::Uniform) return "";  // quick enough here
        if (e.kind == ibl::EnvironmentSource::Kind::File && ibl::is_baked_dir(e.path)) return "";  // `fresnel bake`'s folder: loaded
        pending = key;
        return (e.kind == ibl::EnvironmentSource::Kind::File ? e.path.string() : std::string("studio")) + "\n" +
               std::to_string(resolved.bake_options.size) + "\n" + std::to_string(resolved.bake_options.samples);
    }
    // The worker's result. `provisional`: a quick, small bake of `pending` that lights the page's
    // first frame while the full bake runs (`refining` is then its key); the full bake's folder
    // replaces it when it arrives (reloaded at the next frame), and a full bake that failed or was
    // abandoned (no folder) forgets the quick one, so that the key bakes again when next asked.
    void baked(const std::string& folder, const std::string& bake_error, bool provisional) {
        if (provisional) {
            if (pending.empty()) return;
            if (bake_error.empty()) baked_folders[pending] = folder, refining = pending;
            else bake_errors[pending] = bake_error;
            pending.clear();
            return;
        }
        if (pending.empty() && !refining.empty()) {
            if (!folder.empty()) baked_folders[refining] = folder;
            else baked_folders.erase(refining);
            if (!folder.empty() && lighting_key == refining) lighting_key = "\n";  // reload it
            refining.clear();
            return;
        }
        if (pending.empty()) return;
        if (bake_error.empty()) baked_folders[pending] = folder;
        else bake_errors[pending] = bake_error;
        pending.clear();
    }

    OrbitViewport viewport() const { return {resolved.bounds, job.output.width, job.output.height}; }

    // The picture of an environment preset for the page's list (ibl::panorama_thumbnail): "studio",
    // or a panorama in the page's file system. RGBA, `width` x width / 2, in `thumb`.
    std::vector<std::uint8_t> thumb;
    void thumbnail(const std::string& preset, int width) {
        ImageF pano;
        if (preset == "studio") {
            pano = ibl::make_studio_panorama(256);
        } else {
            ibl::EnvironmentSource source;
            source.kind = ibl::EnvironmentSource::Kind::File;
            source.path = preset;
            pano = ibl::load_panorama(source);
        }
        const Image8 rgb = ibl::panorama_thumbnail(pano, width);
        thumb.assign(std::size_t(rgb.width) * std::size_t(rgb.height) * 4, 255);
        for (std::size_t i = 0; i < std::size_t(rgb.width) * std::size_t(rgb.height); ++i)
            for (int c = 0; c < 3; ++c) thumb[i * 4 + std::size_t(c)] = rgb.pixels[i * 3 + std::size_t(c)];
    }
};

// Runs `fn`, keeping its error message for fresnel_error(); 1 when it worked.
template <class Fn>
int guarded(App* app, Fn&& fn) {
    if (!app) return 0;
    try {
        app->error.clear();
        fn();
        return 1;
    } catch (const std::exception& e) {
        app->error = e.what();
        return 0;
    }
}

}  // namespace
}  // namespace fresnel::web

using fresnel::web::App;
using fresnel::web::guarded;

extern "C" {

// A fresnel on the canvas `selector` ("#canvas"); check fresnel_error() (WebGL 2 missing...).
// "" makes one without a canvas, for fresnel_bake in a Web Worker.
EMSCRIPTEN_KEEPALIVE App* fresnel_create(const char* selector) {
    auto* app = new App;
    app->canvas = selector;
    if (app->canvas.empty()) return app;
    guarded(app, [&] {
        app->context = fresnel::gpu::create_webgl_context(app->canvas);
        app->renderer = std::make_unique<fresnel::Renderer>(*app->context);
        const auto& c = app->context->capabilities();
        app->info = app->context->renderer() + " | " + app->context->version() +
                    (c.float_color_targets ? "" : c.half_float_color_targets ? " | HDR target: RGBA16F (no EXT_color_buffer_float)"
                                                                             : " | HDR target: RGBA8, radiance clamps to 1 (no float render targets)");
        app->job.environment.use_cache = false;  // the page's file system is gone when it closes
        app->set("size", std::to_string(app->job.output.width) + "x" + std::to_string(app->job.output.height));
    });
    return app;
}
EMSCRIPTEN_KEEPALIVE void fresnel_destroy(App* app) { delete app; }
EMSCRIPTEN_KEEPALIVE const char* fresnel_error(App* app) { return app ? app->error.c_str() : "no fresnel"; }
// The settings registry as JSON (fresnel/job/settings.h): what fresnel_set takes.
EMSCRIPTEN_KEEPALIVE const char* fresnel_settings() {
    static const std::string registry = fresnel::settings::describe_json();
    return registry.c_str();
}
EMSCRIPTEN_KEEPALIVE const char* fresnel_warnings(App* app) { return app ? app->warnings.c_str() : ""; }
EMSCRIPTEN_KEEPALIVE const char* fresnel_info(App* app) { return app ? app->info.c_str() : ""; }
EMSCRIPTEN_KEEPALIVE double fresnel_frame_ms(App* app) { return app ? app->frame_ms : 0; }
EMSCRIPTEN_KEEPALIVE int fresnel_open(App* app, const char* path) {
    return guarded(app, [&] { app->open(path); });
}
EMSCRIPTEN_KEEPALIVE int fresnel_set(App* app, const char* key, const char* value) {
    return guarded(app, [&] { app->set(key, value); });
}
// Loads a scene file (*.fresnel.json) written into the page's file system with the files it names.
EMSCRIPTEN_KEEPALIVE int fresnel_open_scene(App* app, const char* path) {
    return guarded(app, [&] { app->open_scene_file(path); });
}
// The material editor (App::set_material), and the materials as JSON.
EMSCRIPTEN_KEEPALIVE int fresnel_set_material(App* app, int index, const char* key, const char* value) {
    return guarded(app, [&] { app->set_material(index, key, value); });
}
// The material property registry (fresnel/material/properties.h) as JSON: what the editor offers.
EMSCRIPTEN_KEEPALIVE const char* fresnel_material_properties() {
    static const std::string text = fresnel::material_properties::describe_json();
    return text.c_str();
}
EMSCRIPTEN_KEEPALIVE const char* fresnel_materials(App* app) {
    if (!app) return "[]";
    app->text = "[]";
    guarded(app, [&] { app->text = app->materials_json(); });
    return app->text.c_str();
}
// The frame's lights and the panel's settings as JSON (App::state_json).
EMSCRIPTEN_KEEPALIVE const char* fresnel_state(App* app) {
    if (!app) return "{}";
    app->text = "{}";
    guarded(app, [&] { app->text = app->state_json(); });
    return app->text.c_str();
}
// The accepted values of one --brdf key (D, G, F, diffuse), separated by spaces.
EMSCRIPTEN_KEEPALIVE const char* fresnel_brdf_names(App* app, const char* key) {
    if (!app) return "";
    app->text.clear();
    for (const std::string& n : fresnel::brdf::brdf_model_names(key)) app->text += (app->text.empty() ? "" : " ") + n;
    return app->text.c_str();
}
// Loads or bakes the lighting the settings ask for (the environment kept when it fails).
EMSCRIPTEN_KEEPALIVE int fresnel_prepare(App* app) {
    return guarded(app, [&] { app->prepare(); });
}
EMSCRIPTEN_KEEPALIVE int fresnel_draw(App* app) {
    return guarded(app, [&] { app->draw(); });
}
EMSCRIPTEN_KEEPALIVE int fresnel_orbit(App* app, float dx, float dy) {
    return guarded(app, [&] { app->job.camera = fresnel::orbit(app->job.camera, dx, dy); });
}
EMSCRIPTEN_KEEPALIVE int fresnel_pan(App* app, float dx, float dy) {
    return guarded(app, [&] { app->job.camera = fresnel::pan(app->job.camera, app->viewport(), dx, dy); });
}
EMSCRIPTEN_KEEPALIVE int fresnel_dolly(App* app, float clicks) {
    return guarded(app, [&] {
        app->job.camera = fresnel::dolly(app->job.camera, app->viewport(), fresnel::dolly_factor(clicks));
    });
}
EMSCRIPTEN_KEEPALIVE int fresnel_frame_all(App* app) {
    return guarded(app, [&] { app->job.camera = fresnel::frame_all(app->job.camera); });
}
// The environment the page's worker should bake before the next frame ("" = none), see App::pending_bake.
EMSCRIPTEN_KEEPALIVE const char* fresnel_pending_bake(App* app) {
    if (!app) return "";
    app->text.clear();
    guarded(app, [&] { app->text = app->pending_bake(); });
    return app->text.c_str();
}
// The worker's result for the pending bake: the baked folder, or its error message; `provisional`
// (1): a quick bake lighting the first frame until the full one (see App::baked).
EMSCRIPTEN_KEEPALIVE void fresnel_baked(App* app, const char* folder, const char* error, int provisional) {
    if (app) app->baked(folder, error, provisional != 0);
}
// In the page's Web Worker: bakes `source` (a panorama file, or studio) as load_lighting() would,
// without the cache, into `out_dir` (a folder load_baked() reads; no previews). `quick` (1): the
// first frame's bake, with an eighth of the irradiance and table samples too.
EMSCRIPTEN_KEEPALIVE int fresnel_bake(App* app, const char* source, const char* out_dir, int size, int samples, int quick) {
    return guarded(app, [&] {
        fresnel::ibl::BakeOptions o;
        o.size = size;
        o.samples = samples;
        if (quick) o.irradiance_samples /= 8, o.lut_samples /= 8;
        auto baked = fresnel::ibl::load_or_bake(fresnel::ibl::parse_environment(source), o, [](double fraction) {
            EM_ASM({ if (Module.onBakeProgress) Module.onBakeProgress($0); }, fraction);
        }, /*use_cache=*/false);
        fresnel::ibl::save_baked(baked, out_dir, o, /*previews=*/false);
    });
}
// An environment preset's picture (App::thumbnail): RGBA bytes, `width` x width / 2; null when
// it cannot be made (fresnel_error says why).
EMSCRIPTEN_KEEPALIVE const std::uint8_t* fresnel_env_thumbnail(App* app, const char* preset, int width) {
    if (!app || width < 2 || width > 512) return nullptr;
    return guarded(app, [&] { app->thumbnail(preset, width); }) ? app->thumb.data() : nullptr;
}
// The orbit camera as "yaw pitch" degrees (for the page's URL and panel).
EMSCRIPTEN_KEEPALIVE const char* fresnel_camera(App* app) {
    if (!app) return "";
    app->text = std::to_string(app->job.camera.yaw_deg) + " " + std::to_string(app->job.camera.pitch_deg);
    return app->text.c_str();
}
}  // extern "C"

int main() { return 0; }
