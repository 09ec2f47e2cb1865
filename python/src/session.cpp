// The Python module's scenes, GPU renderer and path tracer: load once, render often.
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <atomic>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>

#include "common.h"
#include "fresnel/core/spelling.h"
#include "fresnel/gpu/context.h"
#include "fresnel/ibl/bake.h"
#include "fresnel/job/scene_file.h"
#include "fresnel/material/properties.h"
#include "fresnel/render/renderer.h"
#include "fresnel/scene/pose.h"
#include "fresnel/scene/scene_textures.h"
#include "fresnel/trace/job_inputs.h"
#include "fresnel/trace/tracer.h"

namespace fresnel::python {

namespace {

// A loaded scene, immutable once loaded, with what the CPU paths build from it on first use.
struct PyScene {
    std::shared_ptr<const Scene> scene;
    Job job;  // what it was loaded with: its source, and a scene file's settings
    std::string name;
    std::mutex mutex;  // guards the caches below
    std::map<int, std::shared_ptr<trace::TraceScene>> trace_scenes;  // by scene index
    std::shared_ptr<SceneTextures> textures;                         // evaluate()'s
};
using ScenePtr = std::shared_ptr<PyScene>;

// Settings a scene is loaded with (fresnel/job/job.h's Source): they are given to load().
const char* const kLoadSettings[] = {"variant", "animation.time", "animation.index", "disable", "poseSkins", "objNormals", "allowExternalFiles", "maxMemory"};

// The job a call renders: `job` (else the scene's own), the keywords applied, the scene's source.
Job effective_job(const PyScene& s, const py::object& job, const py::kwargs& kwargs) {
    Job j = s.job;
    if (py::isinstance<py::dict>(job)) {
        j = Job{};
        set_settings(j, job);
    } else if (!job.is_none()) {
        if (!py::isinstance<Job>(job)) throw py::type_error("job: expected a fresnel.Job, a dict of settings or None");
        j = job.cast<Job>();
    }
    set_settings(j, kwargs);
    Job asked = j;
    j.source = s.job.source;
    j.source.scene = asked.source.scene;  // the glTF scene shown is chosen per frame
    for (const char* key : kLoadSettings) {
        const settings::Setting& setting = settings::at(key);
        if (settings::get(asked, setting) != settings::get(j, setting) && !settings::is_default(asked, setting))
            throw Error(s.name, key,
                        "a load setting: the scene was loaded with " + setting.key + " '" + settings::get(j, setting) +
                            "'; pass it to fresnel.load() to load the scene so");
    }
    return j;
}

ScenePtr load(const py::object& path, const py::kwargs& kwargs) {
    auto s = std::make_shared<PyScene>();
    Diagnostics diag;
    std::string file;
    if (!path.is_none()) file = py::str(py::module_::import("os").attr("fspath")(path)).cast<std::string>();
    if (!file.empty() && is_scene_file(file)) {
        py::gil_scoped_release release;
        s->job = load_scene_file(file, Job{}, diag).job;
    } else {
        s->job.source.model = file;
    }
    set_settings(s->job, kwargs);
    s->name = file.empty() ? "demo" : file;
    {
        py::gil_scoped_release release;
        s->scene = std::make_shared<const Scene>(load_scene(s->job, diag));
    }
    emit_warnings(diag);
    return s;
}

const trace::TraceScene& trace_scene(PyScene& s, const ResolvedJob& r) {
    std::lock_guard<std::mutex> lock(s.mutex);
    auto& t = s.trace_scenes[r.scene_index];
    if (!t) t = std::make_shared<trace::TraceScene>(*s.scene, r.instances, trace::TraceSceneOptions{r.settings.instancing});
    return *t;
}

bool wants_float(const std::string& dtype) {
    if (dtype == "float32") return true;
    if (dtype == "uint8") return false;
    throw py::value_error("dtype: expected 'uint8' (display-encoded) or 'float32' (linear), got '" + dtype + "'");
}

// The headless GPU renderer: one OpenGL context, the scene last uploaded, and the image-based
// lights of recent jobs (by the job layer's lighting key, as batch and the viewer keep them).
class PyRenderer {
public:
    explicit PyRenderer(const std::string& api) {
        if (api == "gles") options_.api = gpu::Api::OpenGLES30;
        else if (api != "gl") throw py::value_error("api: expected 'gl' (OpenGL 3.3 core) or 'gles' (OpenGL ES 3.0), got '" + api + "'");
        py::gil_scoped_release release;
        context_ = gpu::create_headless_context(options_);
        renderer_ = std::make_unique<Renderer>(*context_);
    }

    py::object render(const ScenePtr& scene, const py::object& job, const std::string& dtype, const py::object& progress,
                      const py::kwargs& kwargs) {
        Job j = effective_job(*scene, job, kwargs);
        const bool as_float = wants_float(dtype);
        j.output.float_output = as_float;
        return draw(scene, j, as_float, progress);
    }

    py::array_t<float> channel(const ScenePtr& scene, const std::string& name, const py::object& job, const py::kwargs& kwargs) {
        Job j = effective_job(*scene, job, kwargs);
        set_setting(j, "render.debug", py::str(name));
        j.output.msaa = 1;  // each pixel one surface's value, not a blend at edges
        j.output.float_output = true;
        py::array_t<float> rgba = draw(scene, j, true, py::none());
        // RGB: the channel's value (alpha is 1 on surfaces, 0 on a transparent background).
        return rgba;
    }

    void close() {
        std::lock_guard<std::mutex> lock(mutex_);
        if (context_) context_->make_current();
        lighting_.clear();
        renderer_.reset();
        scene_.reset();
        context_.reset();
    }

    py::dict info() {
        std::lock_guard<std::mutex> lock(mutex_);
        check_open();
        context_->make_current();
        py::dict d;
        d["renderer"] = context_->renderer();
        d["version"] = context_->version();
        d["api"] = gpu::api_name(context_->api());
        d["programs"] = renderer_->program_count();
        d["texture_bytes"] = renderer_->texture_bytes();
        d["environments"] = lighting_.size();
        return d;
    }

    py::dict stats() const {
        py::dict d;
        d["draw_calls"] = stats_.draw_calls;
        d["triangles"] = stats_.triangles;
        d["shadow_tiles_drawn"] = stats_.shadow_tiles_drawn;
        d["frame_ms"] = frame_ms_;
        return d;
    }

    bool closed() const { return !context_; }

private:
    static constexpr std::size_t kLightingKept = 4;

    void check_open() const {
        if (!context_) throw Error("fresnel.Renderer", "", "the renderer is closed");
    }

    py::object draw(const ScenePtr& scene, const Job& j, bool as_float, const py::object& progress) {
        ProgressBridge bridge;
        bridge.callback = progress;
        Diagnostics diag;
        std::optional<ImageF> image;
        std::optional<Image8> image8;
        {
            py::gil_scoped_release release;
            std::lock_guard<std::mutex> lock(mutex_);
            check_open();
            ResolvedJob r = resolve(j, *scene->scene, &diag);
            std::shared_ptr<JobLighting> lighting = lighting_for(r, bridge);
            RenderSettings rs = lighting->settings(r);
            context_->make_current();
            if (scene_ != scene->scene || scene_index_ != r.scene_index) {
                renderer_->set_scene(*scene->scene, r.scene_index);
                scene_ = scene->scene;
                scene_index_ = r.scene_index;
                occlusion_rays_ = 0;  // set_scene dropped it
            }
            // render_ao="baked": baked once per scene and ray count (the scene's pose when baked).
            const int ao_rays = j.output.ao == AmbientOcclusion::Baked ? j.output.ao_rays : 0;
            if (ao_rays != occlusion_rays_) {
                const auto occlusion = trace::job_vertex_occlusion(j, *scene->scene, r.scene_index);
                renderer_->set_vertex_occlusion(occlusion ? &*occlusion : nullptr);
                occlusion_rays_ = ao_rays;
            }
            auto t0 = std::chrono::steady_clock::now();
            stats_ = FrameStats{};
            if (as_float) image = renderer_->render(r.camera, r.lights, rs, &stats_);
            else image8 = renderer_->render8(r.camera, r.lights, rs, r.transparent(), &stats_);
            frame_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
            if (!stats_.gl_errors.empty()) throw Error("OpenGL", "", "the frame raised " + stats_.gl_errors);
        }
        bridge.rethrow();
        emit_warnings(diag);
        if (image) return to_array(std::move(*image));
        return to_array(std::move(*image8));
    }

    std::shared_ptr<JobLighting> lighting_for(const ResolvedJob& r, ProgressBridge& bridge) {
        const std::string key = lighting_key(r);
        for (auto& [k, l] : lighting_)
            if (k == key) return l;
        auto l = std::make_shared<JobLighting>(load_lighting(r, [&](double f) { bridge(f); }));
        lighting_.emplace_back(key, l);
        if (lighting_.size() > kLightingKept) lighting_.pop_front();
        return l;
    }

    gpu::ContextOptions options_;
    std::unique_ptr<gpu::Context> context_;
    std::unique_ptr<Renderer> renderer_;
    std::shared_ptr<const Scene> scene_;  // uploaded; kept alive while the renderer draws it
    int scene_index_ = -1;
    int occlusion_rays_ = 0;  // the renderer's baked occlusion: its rays per vertex, 0 when none
    std::deque<std::pair<std::string, std::shared_ptr<JobLighting>>> lighting_;
    FrameStats stats_;
    double frame_ms_ = 0.0;
    std::mutex mutex_;
};

py::object trace_image(const ScenePtr& scene, const py::object& job, int spp, int max_bounces, std::uint64_t seed,
                       double time_limit, unsigned threads, bool env_visibility, const std::string& dtype, bool radiance,
                       const py::object& progress, const py::kwargs& kwargs) {
    Job j = effective_job(*scene, job, kwargs);
    const bool as_float = radiance || wants_float(dtype);
    j.output.float_output = as_float;
    if (spp < 1) throw py::value_error("spp: expected a whole number >= 1");
    if (max_bounces < 0) throw py::value_error("max_bounces: expected a whole number >= 0");
    Diagnostics diag;
    ProgressBridge bridge;
    bridge.callback = progress;
    ImageF out;
    bool transparent = false;
    {
        py::gil_scoped_release release;
        ResolvedJob r = resolve(j, *scene->scene, &diag);
        trace::JobInputs inputs = trace::load_job_inputs(r);
        const trace::TraceScene& ts_scene = trace_scene(*scene, r);
        trace::TraceSettings ts;
        ts.samples = spp;
        ts.max_bounces = max_bounces;
        ts.time_limit_s = time_limit;
        ts.seed = seed;
        ts.threads = threads;
        ts.env_visibility = env_visibility;
        ts = inputs.settings(r, ts);
        ts.stop = &bridge.stop;
        ImageF traced = trace::trace_image(ts_scene, r.camera, r.lights, inputs.light(), ts, nullptr,
                                           [&](double f) { bridge(f); });
        out = radiance ? std::move(traced) : trace::to_output(traced, r.settings);
        transparent = r.transparent();
    }
    bridge.rethrow();
    emit_warnings(diag);
    if (as_float) return to_array(std::move(out));
    return to_array(to_image8(out, transparent));
}

py::dict surfaces(const ScenePtr& scene, const py::object& job, unsigned threads, const py::kwargs& kwargs) {
    Job j = effective_job(*scene, job, kwargs);
    Diagnostics diag;
    trace::SurfaceImages g;
    {
        py::gil_scoped_release release;
        ResolvedJob r = resolve(j, *scene->scene, &diag);
        g = trace::trace_surfaces(trace_scene(*scene, r), r.camera, r.settings.width, r.settings.height, threads);
    }
    emit_warnings(diag);
    const py::ssize_t h = g.height, w = g.width;
    std::vector<std::uint8_t> mask(g.depth.size());
    for (std::size_t i = 0; i < mask.size(); ++i) mask[i] = std::isfinite(g.depth[i]) ? 1 : 0;
    py::dict d;
    d["depth"] = vector_array(std::move(g.depth), {h, w});
    d["position"] = vector_array(std::move(g.position), {h, w, 3});
    d["normal"] = vector_array(std::move(g.normal), {h, w, 3});
    d["geometric_normal"] = vector_array(std::move(g.geometric_normal), {h, w, 3});
    d["uv"] = vector_array(std::move(g.uv), {h, w, 2});
    d["material"] = vector_array(std::move(g.material), {h, w});
    d["node"] = vector_array(std::move(g.node), {h, w});
    d["mask"] = vector_array(std::move(mask), {h, w}).attr("astype")("bool");
    return d;
}

py::dict camera(const ScenePtr& scene, const py::object& job, const py::kwargs& kwargs) {
    Job j = effective_job(*scene, job, kwargs);
    ResolvedJob r = resolve(j, *scene->scene);
    auto mat = [](const glm::mat4& m) {
        std::vector<float> v(16);
        for (int row = 0; row < 4; ++row)
            for (int col = 0; col < 4; ++col) v[std::size_t(row * 4 + col)] = m[col][row];
        return vector_array(std::move(v), {4, 4});
    };
    py::dict d;
    d["view"] = mat(r.camera.view);
    d["projection"] = mat(r.camera.projection);
    d["eye"] = py::make_tuple(r.camera.eye.x, r.camera.eye.y, r.camera.eye.z);
    d["target"] = py::make_tuple(r.camera.target.x, r.camera.target.y, r.camera.target.z);
    d["near"] = r.camera.znear;
    d["far"] = r.camera.zfar;
    d["yfov"] = r.camera.yfov_deg;
    d["width"] = r.settings.width;
    d["height"] = r.settings.height;
    return d;
}

// A copy of the scene with material properties changed through the material property registry
// (the names and checks of scene files' "materials" overrides and the viewer's editor).
ScenePtr with_material(const PyScene& s, const py::object& material, const py::kwargs& properties) {
    auto out = std::make_shared<PyScene>();
    out->job = s.job;
    out->name = s.name;
    Scene copy = *s.scene;
    std::vector<std::size_t> targets;
    if (material.is_none()) {
        for (std::size_t i = 0; i < copy.materials.size(); ++i) targets.push_back(i);
    } else if (py::isinstance<py::str>(material)) {
        const std::string name = material.cast<std::string>();
        for (std::size_t i = 0; i < copy.materials.size(); ++i)
            if (copy.materials[i].name == name) targets.push_back(i);
        if (targets.empty()) throw Error(s.name, "material", "no material named '" + name + "'");
    } else {
        const int index = material.cast<int>();
        if (index < 0 || std::size_t(index) >= copy.materials.size())
            throw Error(s.name, "material", "no material " + std::to_string(index) + " (the scene has " +
                                                std::to_string(copy.materials.size()) + ")");
        targets.push_back(std::size_t(index));
    }
    for (auto [key, value] : properties) {
        const std::string name = py::str(key).cast<std::string>();
        const material_properties::Property* property = material_properties::find(name);
        if (!property) {
            std::vector<std::string> names;
            for (const auto& p : material_properties::all()) names.emplace_back(p.name);
            throw py::type_error("unknown material property '" + name + "'" + did_you_mean(name, names) +
                                 "; `fresnel settings --materials` lists them");
        }
        const std::string text = python_text(value, ",", name, material_properties::expected(*property));
        for (std::size_t i : targets) material_properties::set(copy.materials[i], name, text, name);
    }
    out->scene = std::make_shared<const Scene>(std::move(copy));
    return out;
}

// The `name` of each item, by index.
template <class T>
py::list names_of(const std::vector<T>& items) {
    py::list l;
    for (const T& item : items) l.append(item.name);
    return l;
}

}  // namespace

const Scene& scene_of(py::handle scene) { return *scene.cast<ScenePtr>()->scene; }

const TextureSource& scene_textures_for(py::handle scene) {
    ScenePtr s = scene.cast<ScenePtr>();
    std::lock_guard<std::mutex> lock(s->mutex);
    if (!s->textures) s->textures = std::make_shared<SceneTextures>(*s->scene);
    return *s->textures;
}

void bind_session(py::module_& m) {
    py::class_<PyScene, ScenePtr>(m, "Scene",
                                  "A loaded scene (glTF, OBJ or a scene file's models), loaded once and rendered, traced or\n"
                                  "evaluated as often as wanted. Made by fresnel.load().")
        .def_property_readonly("path", [](const PyScene& s) { return s.name; })
        .def_property_readonly("job", [](const PyScene& s) { return s.job; },
                               "The job it was loaded with (a scene file's settings): what render() uses without one.")
        .def_property_readonly("materials", [](const PyScene& s) { return names_of(s.scene->materials); },
                               "The materials' names, by index.")
        .def_property_readonly("variants", [](const PyScene& s) { return s.scene->material_variants; },
                               "KHR_materials_variants names (load(path, variant=NAME) applies one).")
        .def_property_readonly("animations", [](const PyScene& s) { return names_of(s.scene->animations); },
                               "The animations' names, by index (pose(time, animation=K) plays one).")
        .def_property_readonly("cameras", [](const PyScene& s) { return s.scene->cameras.size(); },
                               "How many cameras the file has (camera=N looks through one).")
        .def_property_readonly("node_count", [](const PyScene& s) { return s.scene->nodes.size(); })
        .def_property_readonly("triangle_count",
                               [](const PyScene& s) {
                                   std::size_t n = 0;
                                   for (const Mesh& mesh : s.scene->meshes)
                                       for (const Primitive& p : mesh.primitives)
                                           n += (p.indices.empty() ? p.positions.size() : p.indices.size()) / 3;
                                   return n;
                               },
                               "Triangles of the meshes (each mesh once, however many nodes use it).")
        .def_property_readonly("bounds",
                               [](const PyScene& s) {
                                   Bounds b = scene_bounds(*s.scene, flatten(*s.scene));
                                   return py::make_tuple(py::make_tuple(b.min.x, b.min.y, b.min.z),
                                                         py::make_tuple(b.max.x, b.max.y, b.max.z));
                               },
                               "((min x, y, z), (max x, y, z)) of the default scene.")
        .def(
            "pose",
            [](const PyScene& s, float time, int animation) {
                auto out = std::make_shared<PyScene>();
                out->job = s.job;
                out->name = s.name;
                py::gil_scoped_release release;
                out->scene = std::make_shared<const Scene>(animated_scene(*s.scene, animation, time));
                return out;
            },
            py::arg("time"), py::arg("animation") = -1,
            "The scene posed at `time` seconds of its animations (all, or animation K): a new Scene,\n"
            "skins and morph targets applied on the CPU (the reference posing).")
        .def("with_material", &with_material, py::arg("material") = py::none(),
             "with_material(material=None, **properties) -> Scene: a copy with material properties changed, by their\n"
             "glTF names (roughnessFactor=0.3, baseColorFactor=(1, 0, 0, 1), clearcoatFactor=1, ...; `fresnel settings\n"
             "--materials` lists them), checked as scene files' overrides are; `material`: an index, a name, or None\n"
             "(every material). A missing extension is added with its defaults.")
        .def(
            "camera", &camera, py::arg("job") = py::none(),
            "The camera a job sees the scene with: view and projection (4x4, OpenGL conventions), eye, target,\n"
            "near, far, yfov (degrees), width, height.")
        .def("__repr__", [](const PyScene& s) {
            return "<fresnel.Scene '" + s.name + "': " + std::to_string(s.scene->nodes.size()) + " nodes, " +
                   std::to_string(s.scene->materials.size()) + " materials>";
        });

    m.def("load", &load, py::arg("path") = py::none(),
          "load(path=None, **settings) -> Scene: a glTF (.gltf, .glb), Wavefront OBJ or scene file (*.fresnel.json);\n"
          "None: the built-in demo. Load settings (variant, pose_skins, obj_normals, allow_external_files,\n"
          "max_memory) are keywords; a scene file's own settings become scene.job. Raises fresnel.Error naming\n"
          "the file and the place in it.");

    py::class_<PyRenderer>(m, "Renderer",
                           "The GPU rasteriser on a headless OpenGL context (EGL; Mesa's llvmpipe without a GPU). Keeps the\n"
                           "last scene uploaded and recent environments, so many views of one scene cost one upload.\n"
                           "Use it from the thread that made it; close() (or `with`) frees its GPU memory.")
        .def(py::init<const std::string&>(), py::arg("api") = "gl",
             "Renderer(api='gl'): 'gl' (OpenGL 3.3 core) or 'gles' (OpenGL ES 3.0, as the web page).")
        .def("render", &PyRenderer::render, py::arg("scene"), py::arg("job") = py::none(), py::arg("dtype") = "uint8",
             py::arg("progress") = py::none(),
             "render(scene, job=None, dtype='uint8', progress=None, **settings) -> ndarray\n"
             "uint8: display-encoded (H, W, 3), or (H, W, 4) with a transparent background: the PNG `fresnel render`\n"
             "writes. float32: (H, W, 4) linear after exposure and tone mapping, premultiplied alpha: its EXR.\n"
             "`job` defaults to scene.job; keywords are settings. `progress(fraction)` follows an environment bake.")
        .def("channel", &PyRenderer::channel, py::arg("scene"), py::arg("name"), py::arg("job") = py::none(),
             "channel(scene, name, job=None, **settings) -> float32 (H, W, 4): a debug channel (fresnel.debug_channels())\n"
             "without multisampling: scalars as grey, vectors v as v * 0.5 + 0.5, colours sRGB-encoded; alpha 1 on\n"
             "surfaces.")
        .def("info", &PyRenderer::info, "The OpenGL renderer and version, programs compiled, texture bytes held.")
        .def_property_readonly("stats", &PyRenderer::stats, "The last frame's draw calls, triangles, shadow tiles and time.")
        .def_property_readonly("closed", &PyRenderer::closed)
        .def("close", &PyRenderer::close, "Frees the GPU context and everything on it; later calls raise fresnel.Error.")
        .def("__enter__", [](py::object self) { return self; })
        .def("__exit__", [](PyRenderer& r, py::args) { r.close(); });

    m.def("trace", &trace_image, py::arg("scene"), py::arg("job") = py::none(), py::arg("spp") = 64,
          py::arg("max_bounces") = 16, py::arg("seed") = 0, py::arg("time_limit") = 0.0, py::arg("threads") = 0,
          py::arg("env_visibility") = true, py::arg("dtype") = "float32", py::arg("radiance") = false,
          py::arg("progress") = py::none(),
          "trace(scene, job=None, spp=64, max_bounces=16, seed=0, time_limit=0, threads=0, env_visibility=True,\n"
          "      dtype='float32', radiance=False, progress=None, **settings) -> ndarray\n"
          "The CPU path tracer (`fresnel trace`) on the same job: float32 (H, W, 4) as its EXR, uint8 as its PNG;\n"
          "radiance=True: the mean radiance before exposure and tone mapping, alpha the coverage. The GIL is\n"
          "released; progress(fraction) is called as tiles finish; Ctrl+C or an exception in it stops the trace.");
    m.def("surfaces", &surfaces, py::arg("scene"), py::arg("job") = py::none(), py::arg("threads") = 0,
          "surfaces(scene, job=None, threads=0, **settings) -> dict of arrays: what each pixel's centre sees, exact\n"
          "(one ray per pixel): depth (H, W; linear, along the view axis, inf where nothing), position, normal,\n"
          "geometric_normal (H, W, 3; world space), uv (H, W, 2), material and node (H, W; int32, -1 where\n"
          "nothing), mask (H, W; bool).");
}

}  // namespace fresnel::python
