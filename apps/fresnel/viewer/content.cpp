// `fresnel view`: opening models, scene files, environments and folders (the file rules are
// fresnel/viewer/files.h's), saving the view and the material edits, and the shader files.
#include <cstdio>

#include "fresnel/job/scene_file.h"
#include "fresnel/scene/scene_writer.h"
#include "fresnel/material/properties.h"
#include "fresnel/viewer/files.h"
#include "viewer_app.h"

namespace fresnel::cli::view {
namespace fs = std::filesystem;
using viewer::image_beside;
using viewer::is_environment;
using viewer::is_folder;
using viewer::is_gltf;
using viewer::list_models;
using viewer::sibling_models;

// Loads `path` (empty: the demo) as the scene; on failure the current one stays and
// the error is shown. keep_camera: the job's camera stays (else: the initial orbit).
// A scene file (is_scene_file) opens as open_scene_file does.
bool Viewer::open_model(const std::string& path, bool keep_camera) {
    if (!path.empty() && is_scene_file(path)) return open_scene_file(path);
    Job job = state_.job;
    job.source.model = path;
    job.source.models.clear();
    job.source.animation = {};  // a new file starts at its rest pose (and plays, interactively)
    if (!keep_camera) {
        job.camera = state_.initial_camera;
        job.camera.scene_camera.reset();
    }
    return load_job(std::move(job), path);
}

// A scene file: its job read onto the flags' job, then the flags given on the command line
// (as `fresnel render SCENE` does); its camera becomes the one R returns to.
bool Viewer::open_scene_file(const std::string& path) {
    Job job;
    Diagnostics diag;
    try {
        SceneFileOptions so;
        so.allow_external_files = options_.job->allow_external();
        SceneFile sf = load_scene_file(path, defaults_, diag, so);
        std::optional<Job> flagged = job_from_options(*options_.job, sf.job, GivenFlags{options_.cmd});
        if (!flagged) throw Error(path, "", "the command line's flags do not apply to it");
        job = *flagged;
    } catch (const std::exception& e) {
        state_.error = e.what();
        std::fprintf(stderr, "fresnel: error: %s\n", e.what());
        return false;
    }
    if (diag.total()) print_warnings(diag);
    std::vector<std::string> file_warnings = diag.lines();
    if (!load_job(std::move(job), path)) return false;
    state_.warnings.insert(state_.warnings.begin(), file_warnings.begin(), file_warnings.end());
    state_.initial_camera = state_.job.camera;
    return true;
}

// Loads the job's scene (`label`: the file opened, empty for the demo); on failure the
// current scene stays and the error is shown.
bool Viewer::load_job(Job job, const std::string& label) {
    const std::string path = label;  // a copy: `label` may be state_.opened, which changes below
    bool uploading = false;
    try {
        Diagnostics diag;
        auto scene = std::make_unique<Scene>(load_rest_scene(job, diag));  // posed by sync_pose()
        ResolvedJob resolved = resolve(job, *scene);  // e.g. --camera or --scene out of range
        uploading = true;
        renderer_->set_scene(*scene, resolved.scene_index);
        occlusion_rays_ = 0;  // set_scene dropped it: sync_occlusion bakes it again when asked for
        posing_.reset(*scene);
        state_.scene = std::move(scene);
        state_.playback.playing = false;
        state_.picked.reset();
        state_.original_materials = state_.scene->materials;
        state_.materials_edited = false;
        state_.job = job;
        loaded_source_ = job.source;
        loaded_source_.animation = {};
        state_.opened = path;
        if (state_.job.source.models.empty() && is_gltf(state_.job.source.model)) {
            fs::path p(state_.job.source.model);
            state_.model_save_path = (p.parent_path() / (p.stem().string() + "-edited" + p.extension().string())).string();
        }
        if (!path.empty() && is_scene_file(path)) state_.scene_save_path = path;
        state_.warnings = diag.lines();
        if (!state_.warnings.empty()) print_warnings(diag);
        state_.error.clear();
        state_.status = path.empty() ? "the built-in demo" : path;
        window_->set_title("fresnel view - " + (path.empty() ? std::string("demo") : fs::path(path).filename().string()));
        if (!path.empty()) state_.remember(path);
        // An animated file plays as it opens, as in other glTF viewers, unless a time was asked
        // for (--time, a scene file's animation) or a script or a screenshot drives the window.
        if (state_.animated() && !state_.job.source.animation.posed() && options_.script.empty() && !options_.frames &&
            options_.screenshot.empty())
            state_.play(true);
        return true;
    } catch (const std::exception& e) {
        state_.error = e.what();
        std::fprintf(stderr, "fresnel: error: %s\n", e.what());
        if (uploading && state_.scene) {  // set_scene failed mid-way: upload the current scene again
            try {
                renderer_->set_scene(*state_.scene, resolve(state_.job, *state_.scene).scene_index);
            } catch (const std::exception&) {
                state_.scene.reset();
            }
        } else if (uploading) {
            state_.scene.reset();
        }
        return false;
    }
}

// A dropped or chosen path: a model, an environment, or a folder of models.
void Viewer::open_path(const std::string& path) {
    if (is_folder(path) && !is_environment(path)) {
        auto models = list_models(path);
        if (models.empty()) {
            state_.error = path + ": no models (.gltf, .glb, .obj, .fresnel.json) in this folder";
            return;
        }
        state_.folder_models = models;
        open_model(models.front(), false);
    } else if (is_environment(path)) {
        state_.open_environment(path);
    } else {
        // Models by extension; anything else goes to the loader, which says what is wrong.
        if (open_model(path, false)) state_.folder_models = sibling_models(path);
    }
}

void Viewer::step_folder(int delta) {
    if (std::optional<std::string> next = state_.step_folder(delta)) open_model(*next, false);
}

// --- saving ----------------------------------------------------------------------

// The view as a scene file (fresnel/job/scene_file.h): the job at the window's size,
// the material edits as overrides of their models, "output" the .png beside it, so
// `fresnel render PATH` renders this frame. Atomic; false (State::error set) when it fails.
bool Viewer::save_scene(const std::string& path) {
    try {
        if (path.empty()) throw Error("", "", "save scene: no file name");
        Job job = state_.shown_job();
        add_material_overrides(job);
        Diagnostics diag;
        save_scene_file(path, job, diag, image_beside(path));
        if (diag.total()) print_warnings(diag);
        state_.status = "saved " + path;
        std::fprintf(stderr, "fresnel: wrote %s\n", path.c_str());
        return true;
    } catch (const std::exception& e) {
        state_.error = e.what();
        std::fprintf(stderr, "fresnel: error: %s\n", e.what());
        return false;
    }
}

// The material edits into `job` as material overrides (by index) of the models they belong
// to: scene files hold every property of the material property registry.
void Viewer::add_material_overrides(Job& job) const {
    const std::unique_ptr<Scene>& scene = state_.scene;
    const std::vector<Material>& original = state_.original_materials;
    if (!scene || !state_.materials_edited || scene->materials.size() != original.size()) return;
    if (job.source.models.empty()) {
        Job::Source::Model m;
        m.path = job.source.model;
        m.scene = job.source.scene;
        job.source.models.push_back(m);
        job.source.model.clear();
        job.source.scene = -1;
    }
    std::vector<std::size_t> visible;  // the scene's parts are the visible models, in order
    for (std::size_t i = 0; i < job.source.models.size(); ++i)
        if (job.source.models[i].visible) visible.push_back(i);
    for (std::size_t i = 0; i < scene->materials.size(); ++i) {
        const Material &now = scene->materials[i], &was = original[i];
        // The models whose material this is: one, or every copy of a model the scene file names
        // several times with the same overrides (they share their materials: Scene::Part).
        std::vector<std::pair<std::size_t, int>> owners;  // model, its material index
        for (std::size_t k = 0; k < scene->parts.size() && k < visible.size(); ++k) {
            const auto& part = scene->parts[k];
            if (int(i) >= part.first_material && int(i) < part.first_material + part.material_count)
                owners.emplace_back(visible[k], int(i) - part.first_material);
        }
        if (owners.empty()) owners.emplace_back(0, int(i));
        // Every property that differs from the material as loaded, kept in its range.
        Job::Source::MaterialOverride mo;
        for (const material_properties::Property& p : material_properties::all()) {
            if (!material_properties::changed(p, was, now)) continue;
            material_properties::Value v = p.get(now);
            for (int k = 0; k < p.width; ++k) v[std::size_t(k)] = std::clamp(v[std::size_t(k)], p.min, p.max);
            mo.values[std::string(p.name)] = v;
        }
        if (mo.values.empty()) continue;
        for (const auto& [model, local] : owners) {
            mo.index = local;
            job.source.models[model].materials.push_back(mo);
        }
    }
}

// The material edits written back into the model's glTF file (or a copy of it) without
// losing what fresnel does not read (fresnel/scene/scene_writer.h). Atomic.
bool Viewer::save_model(const std::string& path) {
    try {
        const Job& job_ = state_.job;
        std::string why;
        if (!state_.scene) why = "no scene is loaded";
        else if (!job_.source.models.empty()) why = "the scene holds several models (a scene file): save the scene";
        else if (job_.source.model.empty()) why = "the built-in demo has no file";
        else if (!is_gltf(job_.source.model)) why = "only glTF models (.gltf, .glb) are saved";
        else if (!job_.source.variant.empty()) why = "a material variant (--variant) replaces the file's materials";
        if (!why.empty()) throw Error(path, "", "cannot save the materials: " + why);
        Diagnostics diag;
        int n = save_gltf_material_edits(job_.source.model, path, state_.original_materials, state_.scene->materials, diag);
        if (diag.total()) print_warnings(diag);
        std::error_code ec;
        if (fs::equivalent(path, job_.source.model, ec)) {  // the file now holds the edits
            state_.original_materials = state_.scene->materials;
            state_.materials_edited = false;
        }
        state_.status = "saved " + path + " (" + std::to_string(n) + " value" + (n == 1 ? "" : "s") + " changed)";
        std::fprintf(stderr, "fresnel: wrote %s (%d material value%s changed)\n", path.c_str(), n, n == 1 ? "" : "s");
        return true;
    } catch (const std::exception& e) {
        state_.error = e.what();
        std::fprintf(stderr, "fresnel: error: %s\n", e.what());
        return false;
    }
}

// --- shaders ---------------------------------------------------------------------

// --watch-shaders: whether a file under --shaders changed (size or time) since the last look.
bool Viewer::shaders_changed() {
    std::map<std::string, std::pair<std::uintmax_t, fs::file_time_type>> now;
    std::error_code ec;
    for (fs::recursive_directory_iterator it(options_.shaders, ec), end; !ec && it != end; it.increment(ec)) {
        if (!it->is_regular_file(ec)) continue;
        now[it->path().string()] = {it->file_size(ec), it->last_write_time(ec)};
    }
    const bool first = shader_files_.empty();
    const bool changed = !first && now != shader_files_;
    shader_files_ = std::move(now);
    return changed;
}

// F5: the shader files read again (from `folder`, else --shaders, else the built-in ones)
// and every program recompiled; on an error the running shaders stay and it is shown.
bool Viewer::reload_shaders(const std::string& folder) {
    if (!folder.empty()) renderer_->set_shader_folder(folder);
    std::string e = renderer_->reload_shaders();
    if (!e.empty()) {
        state_.error = "shader reload failed (the previous shaders stay): " + e;
        std::fprintf(stderr, "fresnel: error: %s\n", state_.error.c_str());
        return false;
    }
    state_.status = "shaders reloaded";
    std::fprintf(stderr, "fresnel: shaders reloaded (%zu programs)\n", renderer_->program_count());
    return true;
}

}  // namespace fresnel::cli::view
