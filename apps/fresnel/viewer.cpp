// `fresnel view`: a window that shows what `fresnel render` would write for a Job and
// lets the job change: the camera by mouse (fresnel/job/orbit_controller.h), models and
// environments by drag and drop, a file browser, PageUp/PageDown and recent files, and the
// tone mapping, exposure, background and debug channel from the panel.
//
// The frame is the renderer's, for the Job the state describes at the window's framebuffer
// size (resolve(), the same Renderer, RenderTarget::default_framebuffer); the GUI is drawn
// on top afterwards. Nothing is drawn while nothing changes (the loop waits for events);
// environments bake on a worker thread while the window keeps answering. A file that does
// not load leaves the current scene (or environment) as it was and shows the loader's error.
#include "viewer.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <future>
#include <map>

#include "cli_common.h"
#include "fresnel/gpu/device.h"
#include "fresnel/gpu/resources.h"
#include "fresnel/gui/window.h"
#include "fresnel/ibl/bake.h"
#include "fresnel/job/lights.h"
#include "fresnel/job/orbit_controller.h"
#include "fresnel/job/scene_file.h"
#include "fresnel/job/settings.h"
#include "fresnel/render/renderer.h"
#include "fresnel/scene/pick.h"
#include "fresnel/scene/scene_writer.h"
#include "view_script.h"

namespace fresnel::cli {
namespace fs = std::filesystem;
namespace {


std::string lower_extension(const fs::path& p) {
    std::string e = p.extension().string();
    for (auto& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
}
// What `open` takes as a scene: a model the loaders read, or a scene file (*.fresnel.json;
// other .json files are not listed, but open as scene files when named).
bool is_model(const fs::path& p) {
    auto e = lower_extension(p);
    return e == ".gltf" || e == ".glb" || e == ".obj" || p.filename().string().ends_with(".fresnel.json");
}
bool is_gltf(const fs::path& p) {
    auto e = lower_extension(p);
    return e == ".gltf" || e == ".glb";
}
// The image beside a scene file that `fresnel render SCENE` writes: shot.fresnel.json -> shot.png.
fs::path image_beside(const fs::path& scene) {
    std::string name = scene.filename().string();
    for (const char* suffix : {".json", ".fresnel"})
        if (name.size() > std::strlen(suffix) && name.ends_with(suffix)) name.resize(name.size() - std::strlen(suffix));
    return scene.parent_path() / (name + ".png");
}
bool is_environment(const fs::path& p) {
    auto e = lower_extension(p);
    std::error_code ec;  // never throws: unreadable entries are simply not environments
    return e == ".hdr" || e == ".exr" || (fs::is_directory(p, ec) && fs::exists(p / "manifest.json", ec));
}
bool is_folder(const fs::path& p) {
    std::error_code ec;
    return fs::is_directory(p, ec);
}

// The models under `folder` (three levels deep; absolute paths, sorted).
std::vector<std::string> list_models(const fs::path& folder) {
    std::vector<std::string> out;
    std::error_code ec;
    fs::recursive_directory_iterator it(folder, fs::directory_options::skip_permission_denied, ec), end;
    for (; !ec && it != end; it.increment(ec)) {
        if (it.depth() > 3) it.disable_recursion_pending();
        if (it->is_regular_file(ec) && is_model(it->path()))
            out.push_back(fs::absolute(it->path()).lexically_normal().string());
    }
    std::sort(out.begin(), out.end());
    return out;
}

// The models PageUp/PageDown step through from `model`: those under its folder, or under
// the folder above when the model is alone in its own (models/NAME/NAME.glb,
// models/NAME/glTF-Binary/NAME.glb), up to two levels.
std::vector<std::string> sibling_models(const std::string& model) {
    fs::path folder = fs::absolute(model).parent_path();
    std::vector<std::string> models = list_models(folder);
    for (int up = 0; up < 2 && models.size() <= 1 && folder.has_parent_path() && folder != folder.root_path(); ++up) {
        folder = folder.parent_path();
        models = list_models(folder);
    }
    return models;
}

// The frame in the window's back buffer as `fresnel render` writes it (rows top to bottom;
// RGB, or RGBA for transparent frames).
Image8 read_frame(int width, int height, bool alpha) {
    gpu::Device device;
    std::vector<std::uint8_t> px = device.read_default_rgba8(0, 0, width, height);
    Image8 img(width, height, alpha ? 4 : 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::uint8_t* s = &px[(std::size_t(height - 1 - y) * std::size_t(width) + std::size_t(x)) * 4];
            std::uint8_t* d = img.at(x, y);
            for (int c = 0; c < img.channels; ++c) d[c] = s[c];
        }
    return img;
}

// Resident memory of this process (VmRSS), kB; -1 when unknown.
long resident_kb() {
    std::ifstream in("/proc/self/status");
    for (std::string line; std::getline(in, line);)
        if (line.rfind("VmRSS:", 0) == 0) return std::atol(line.c_str() + 6);
    return -1;
}

struct Bake {
    std::string key;
    ResolvedJob resolved;
    std::shared_ptr<std::atomic<float>> progress = std::make_shared<std::atomic<float>>(0.0f);
    std::future<JobLighting> result;
};

class Viewer {
public:
    // `defaults`: the job of the flags alone (scene files opened later are read onto it, then
    // the flags given override them, as on the command line).
    Viewer(const ViewOptions& options, Job job, Job defaults, std::vector<ScriptCommand> script)
        : options_(options), job_(std::move(job)), defaults_(std::move(defaults)), script_(std::move(script)) {
        initial_camera_ = job_.camera;
        good_environment_ = job_.environment;
        const std::string model = options.job->models.empty() ? std::string() : options.job->models.front();
        window_size_ = {job_.output.width, job_.output.height};
        opened_ = model;
        if (!model.empty() && is_folder(model)) {
            folder_models_ = list_models(model);
            job_.source.model = folder_models_.empty() ? std::string() : folder_models_.front();
            opened_ = job_.source.model;
            if (folder_models_.empty()) error_ = model + ": no models (.gltf, .glb, .obj, .fresnel.json) in this folder";
            if (!opened_.empty() && is_scene_file(opened_)) {  // a folder that starts with a scene file
                job_.source.model.clear();
                first_scene_file_ = opened_;
            }
        } else if (!model.empty()) {
            folder_models_ = sibling_models(model);
        }
        browser_dir_ = job_.source.model.empty() ? fs::current_path() : fs::absolute(job_.source.model).parent_path();
        load_recent();
    }

    int run() {
        gui::Window window(window_size_.width, window_size_.height, "fresnel view", context_options(*options_.job));
        window_ = &window;
        renderer_ = std::make_unique<Renderer>(window.context());
        if (!options_.shaders.empty()) renderer_->set_shader_folder(options_.shaders);
        int rc = kExitBadInput;
        try {
            rc = loop(window);
        } catch (...) {
            release_gpu();
            throw;
        }
        release_gpu();
        return rc;
    }

private:
    // GL objects go before the window (and its context) does.
    void release_gpu() {
        timer_.reset();
        renderer_.reset();
        window_ = nullptr;
    }

    int loop(gui::Window& window) {
        const bool batch = options_.frames || !options_.screenshot.empty();
        const bool scripted = !options_.script.empty();
        const int frames_wanted = options_.frames.value_or(2);
        bool opened = first_scene_file_.empty() ? load_job(job_, opened_) : open_scene_file(first_scene_file_);
        if (!opened && batch) return kExitBadInput;  // printed
        int ready_frames = 0, redraw = 3;
        while (!window.should_close()) {
            if (bake_ && redraw <= 0 && !batch && script_pos_ >= script_.size()) {
                window.wait_events(0.5);  // the progress bar twice a second (or sooner on input)
                redraw = 1;
            }
            else if (bake_ || redraw > 0 || batch || script_pos_ < script_.size() || spinning()) window.poll_events();
            else if (options_.watch_shaders) {
                window.wait_events(0.5);  // idle, but the shader folder is looked at twice a second
                if (shaders_changed()) reload_shaders(""), redraw = 3;
                else continue;            // nothing to draw
            } else {
                window.wait_events();  // idle: no CPU until something happens
                redraw = 3;             // ImGui settles over a few frames
            }
            window.begin_frame();
            bool ready = false;
            try {
                if (handle_input()) redraw = 3;
                if (spinning()) spin();
                else spin_last_.reset();
                draw_gui();
                ready = update_lighting();
                draw_scene();
            } catch (const std::exception& e) {  // never die on input: show it, keep the window
                error_ = e.what();
                std::fprintf(stderr, "fresnel: error: %s\n", e.what());
                if (batch) return kExitBadInput;
            }
            if (batch && !bake_ && bake_failed_) return kExitBadInput;  // printed by update_lighting()
            if (ready && scene_) ++ready_frames;
            if (scripted && script_pos_ < script_.size()) {
                redraw = 3;
                if (run_script(ready)) {
                    window.end_frame();
                    window.swap_buffers();
                    return script_failed_ ? kExitBadInput : kExitOk;
                }
            }
            if (batch && ready && ready_frames >= frames_wanted) {
                if (options_.with_gui) window.end_frame();
                if (!options_.screenshot.empty()) {
                    write_png(options_.screenshot, read_frame(fb_.width, fb_.height, last_transparent_));
                    std::fprintf(stderr, "fresnel: wrote %s (%dx%d)\n", options_.screenshot.c_str(), fb_.width,
                                 fb_.height);
                }
                if (!options_.with_gui) window.end_frame();
                window.swap_buffers();
                return kExitOk;
            }
            if (screenshot_requested_) {
                screenshot_requested_ = false;
                std::string path = screenshot_name();
                try {
                    write_png(path, read_frame(fb_.width, fb_.height, last_transparent_));
                    status_ = "saved " + path;
                    std::fprintf(stderr, "fresnel: wrote %s\n", path.c_str());
                } catch (const std::exception& e) {
                    error_ = e.what();
                }
            }
            window.end_frame();
            window.swap_buffers();
            --redraw;
        }
        return kExitOk;
    }

    // --- scripts (view_script.h) -----------------------------------------------------

    // Runs script commands until one changes what is drawn (the next frame shows it), a
    // wait or a screenshot that needs the lighting; true at `quit`.
    bool run_script(bool ready) {
        if (script_wait_ > 0) {
            --script_wait_;
            return false;
        }
        while (script_pos_ < script_.size()) {
            ScriptCommand c = script_[script_pos_];  // a copy: `set environment` becomes `env`
            auto failed = [&](const std::string& what) {
                std::fprintf(stderr, "fresnel: error: %s: line %d: %s\n", options_.script.c_str(), c.line, what.c_str());
                script_failed_ = true;
            };
            OrbitViewport view{bounds_, std::max(fb_.width, 1), std::max(fb_.height, 1)};
            if (job_.camera.scene_camera && last_camera_ &&
                (c.name == "orbit" || c.name == "pan" || c.name == "dolly"))
                job_.camera = orbit_from_setup(*last_camera_, bounds_, last_camera_->yfov_deg);
            if (c.name == "screenshot") {
                if (!ready || !scene_) return false;  // after the bake, with the frame drawn
                try {
                    write_png(c.args[0], read_frame(fb_.width, fb_.height, last_transparent_));
                    std::fprintf(stderr, "fresnel: wrote %s (%dx%d)\n", c.args[0].c_str(), fb_.width, fb_.height);
                } catch (const std::exception& e) {
                    failed(e.what());
                }
                ++script_pos_;
                continue;
            }
            ++script_pos_;
            if (c.name == "quit") return true;
            if (c.name == "wait") {
                script_wait_ = int(c.number(0));
                return false;
            }
            if (c.name == "set" && c.args[0] == "environment") {  // as `env`: a file is opened, a broken one reported
                c.name = "env";
                c.args = {c.args[1]};
            } else if (c.name == "set" && c.args[0] != "material") {  // a setting, checked when the script was read
                settings::set(job_, c.args[0], c.args[1], options_.script);
                return false;
            }
            if (c.name == "set") {
                std::size_t index = std::size_t(c.number(1));
                std::vector<float> values;
                for (std::size_t i = 3; i < c.args.size(); ++i) values.push_back(c.number(i));
                if (!scene_ || index >= scene_->materials.size())
                    failed("set material: no material " + c.args[1] + " (the scene has " +
                           std::to_string(scene_ ? scene_->materials.size() : 0) + ")");
                else
                    set_material_field(scene_->materials[index], c.args[2], values), materials_edited_ = true;
                return false;  // the next frame shows it
            }
            if (c.name == "split") {
                split_ = c.args[0] != "off";
                if (split_) {
                    split_output_ = job_.output;
                    split_output_.debug = *parse_debug_channel(c.args[0]);
                    split_pos_ = c.number(1);
                }
                return false;
            }
            if (c.name == "save") {  // the material edits into a glTF file
                if (!save_model(c.args[0])) failed("save " + c.args[0] + ": " + error_);
                continue;
            }
            if (c.name == "save-scene") {
                if (!save_scene(c.args[0])) failed("save-scene " + c.args[0] + ": " + error_);
                continue;
            }
            if (c.name == "reload-shaders") {
                if (!reload_shaders(c.args.empty() ? std::string() : c.args[0])) failed("reload-shaders: " + error_);
                return false;  // the next frame draws with them
            }
            if (c.name == "auto-rotate") {
                (c.args[0] == "env" ? spin_environment_ : spin_camera_) = c.args[1] == "on";
                return false;
            }
            if (c.name == "stats") {
                std::string gpu = gpu_ms_ >= 0.0 ? std::to_string(gpu_ms_) : std::string("null");
                gpu::LiveObjects gl = gpu::Device().live_objects();
                std::printf("{\"frame_ms\":%.2f,\"gpu_ms\":%s,\"width\":%d,\"height\":%d,\"draw_calls\":%d,"
                            "\"triangles\":%zu,\"programs\":%zu,\"rss_kb\":%ld,\"texture_bytes\":%zu,\"gl_objects\":{\"total\":%d,"
                            "\"buffers\":%d,\"vertex_arrays\":%d,\"textures\":%d,\"renderbuffers\":%d,"
                            "\"framebuffers\":%d,\"programs\":%d,\"shaders\":%d}}\n",
                            frame_ms_, gpu.c_str(), fb_.width, fb_.height, stats_.draw_calls, stats_.triangles,
                            renderer_->program_count(), resident_kb(), renderer_->texture_bytes(), gl.total(), gl.buffers, gl.vertex_arrays,
                            gl.textures, gl.renderbuffers, gl.framebuffers, gl.programs, gl.shaders);
                std::fflush(stdout);
                continue;
            }
            if (c.name == "print") {
                std::printf("%s\n", render_command_line(shown_job(), "view.png").c_str());
                std::fflush(stdout);
                continue;
            }
            if (c.name == "pick") {  // after the frame it clicks on is drawn
                if (!ready || !scene_ || !last_camera_) {
                    --script_pos_;
                    return false;
                }
                pick_at({c.number(0), c.number(1)});
                if (picked_) {
                    const int mat = scene_->meshes[std::size_t(picked_->mesh)].primitives[std::size_t(picked_->primitive)].material;
                    std::printf("{\"node\":%d,\"mesh\":%d,\"primitive\":%d,\"material\":%d,\"distance\":%.6g}\n", picked_->node,
                                picked_->mesh, picked_->primitive, mat, double(picked_->distance));
                } else {
                    std::printf("{\"node\":null}\n");
                }
                std::fflush(stdout);
                return false;  // the highlight shows in the next frame
            }
            if (c.name == "light") {
                job_.lights.extra.push_back(parse_light(c.args[0]));  // checked when the script was read
                return false;
            }
            if (c.name == "light-remove") {
                std::size_t i = std::size_t(c.number(0));
                if (i < job_.lights.extra.size()) job_.lights.extra.erase(job_.lights.extra.begin() + std::ptrdiff_t(i));
                else failed("light-remove: no added light " + c.args[0]);
                return false;
            }
            if (c.name == "orbit-lights") {
                orbit_lights_ = c.args[0] == "on";
                return false;
            }
            if (c.name == "select") {
                std::size_t n = std::size_t(c.number(0));
                if (!scene_ || n >= scene_->nodes.size() || scene_->nodes[n].mesh < 0) failed("select: node " + c.args[0] + " has no mesh");
                else select_primitive(int(n), 0);
                return false;
            }
            if (c.name == "hide" || c.name == "show") {
                std::size_t n = std::size_t(c.number(0));
                if (!scene_ || n >= scene_->nodes.size()) failed(c.name + ": no node " + c.args[0]);
                else set_node_visible(int(n), c.name == "show");
                return false;
            }
            if (c.name == "orbit") job_.camera = orbit(job_.camera, -c.number(0), c.number(1), 1.0f);
            else if (c.name == "pan") job_.camera = pan(job_.camera, view, c.number(0), c.number(1));
            else if (c.name == "dolly") job_.camera = dolly(job_.camera, view, c.number(0));
            else if (c.name == "reset") job_.camera = initial_camera_;
            else if (c.name == "frame") job_.camera = frame_all(job_.camera);
            else if (c.name == "camera" && c.args[0] == "orbit") {
                if (job_.camera.scene_camera && last_camera_)
                    job_.camera = orbit_from_setup(*last_camera_, bounds_, last_camera_->yfov_deg);
            } else if (c.name == "camera") {
                job_.camera.scene_camera = int(c.number(0));
            }
            else if (c.name == "open") {
                if (!open_model(c.args[0], false)) failed("open " + c.args[0] + ": " + error_);
            } else if (c.name == "env") {
                env_line_ = c.line;
                try {  // the registry's forms: studio, none, automatic, color:R,G,B or a file
                    Job next = job_;
                    settings::set(next, "environment", c.args[0], options_.script);
                    if (next.environment.kind == Job::Environment::Kind::File) open_environment(next.environment.path);
                    else job_.environment = next.environment;
                } catch (const std::exception& e) {
                    failed(e.what());
                }
            }
            return false;  // the next frame shows the change
        }
        return false;
    }

    // --- content ---------------------------------------------------------------------

    // Loads `path` (empty: the demo) as the scene; on failure the current one stays and
    // the error is shown. keep_camera: the job's camera stays (else: the initial orbit).
    // A scene file (is_scene_file) opens as open_scene_file does.
    bool open_model(const std::string& path, bool keep_camera) {
        if (!path.empty() && is_scene_file(path)) return open_scene_file(path);
        Job job = job_;
        job.source.model = path;
        job.source.models.clear();
        if (!keep_camera) {
            job.camera = initial_camera_;
            job.camera.scene_camera.reset();
        }
        return load_job(std::move(job), path);
    }

    // A scene file: its job read onto the flags' job, then the flags given on the command line
    // (as `fresnel render SCENE` does); its camera becomes the one R returns to.
    bool open_scene_file(const std::string& path) {
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
            error_ = e.what();
            std::fprintf(stderr, "fresnel: error: %s\n", e.what());
            return false;
        }
        if (diag.total()) print_warnings(diag);
        std::vector<std::string> file_warnings = diag.lines();
        if (!load_job(std::move(job), path)) return false;
        warnings_.insert(warnings_.begin(), file_warnings.begin(), file_warnings.end());
        initial_camera_ = job_.camera;
        return true;
    }

    // Loads the job's scene (`label`: the file opened, empty for the demo); on failure the
    // current scene stays and the error is shown.
    bool load_job(Job job, const std::string& label) {
        const std::string& path = label;
        bool uploading = false;
        try {
            Diagnostics diag;
            auto scene = std::make_unique<Scene>(load_scene(job, diag));
            ResolvedJob resolved = resolve(job, *scene);  // e.g. --camera or --scene out of range
            uploading = true;
            renderer_->set_scene(*scene, resolved.scene_index);
            scene_ = std::move(scene);
            picked_.reset();
            original_materials_ = scene_->materials;
            materials_edited_ = false;
            job_ = job;
            opened_ = path;
            if (job_.source.models.empty() && is_gltf(job_.source.model)) {
                fs::path p(job_.source.model);
                model_save_path_ = (p.parent_path() / (p.stem().string() + "-edited" + p.extension().string())).string();
            }
            if (!path.empty() && is_scene_file(path)) scene_save_path_ = path;
            warnings_ = diag.lines();
            if (!warnings_.empty()) print_warnings(diag);
            error_.clear();
            status_ = path.empty() ? "the built-in demo" : path;
            window_->set_title("fresnel view - " + (path.empty() ? std::string("demo") : fs::path(path).filename().string()));
            if (!path.empty()) add_recent(path);
            return true;
        } catch (const std::exception& e) {
            error_ = e.what();
            std::fprintf(stderr, "fresnel: error: %s\n", e.what());
            if (uploading && scene_) {  // set_scene failed mid-way: upload the current scene again
                try {
                    renderer_->set_scene(*scene_, resolve(job_, *scene_).scene_index);
                } catch (const std::exception&) {
                    scene_.reset();
                }
            } else if (uploading) {
                scene_.reset();
            }
            return false;
        }
    }

    void open_environment(const std::string& path) {
        job_.environment.kind = Job::Environment::Kind::File;
        job_.environment.path = path;
        if (!path.empty()) add_recent(path);
    }

    // A dropped or chosen path: a model, an environment, or a folder of models.
    void open_path(const std::string& path) {
        if (is_folder(path) && !is_environment(path)) {
            auto models = list_models(path);
            if (models.empty()) {
                error_ = path + ": no models (.gltf, .glb, .obj, .fresnel.json) in this folder";
                return;
            }
            folder_models_ = models;
            open_model(models.front(), false);
        } else if (is_environment(path)) {
            open_environment(path);
        } else {
            // Models by extension; anything else goes to the loader, which says what is wrong.
            if (open_model(path, false)) folder_models_ = sibling_models(path);
        }
    }

    void step_folder(int delta) {
        if (folder_models_.empty()) return;
        std::string current = opened_.empty() ? std::string() : fs::absolute(opened_).lexically_normal().string();
        auto it = std::find(folder_models_.begin(), folder_models_.end(), current);
        long i = it == folder_models_.end() ? 0 : long(it - folder_models_.begin()) + delta;
        long n = long(folder_models_.size());
        i = ((i % n) + n) % n;
        open_model(folder_models_[std::size_t(i)], false);
    }

    fs::path recent_file() const { return ibl::cache_root() / "viewer-recent.txt"; }
    void load_recent() {
        if (!job_.environment.use_cache) return;
        std::ifstream in(recent_file());
        for (std::string line; std::getline(in, line) && recent_.size() < 12;)
            if (!line.empty()) recent_.push_back(line);
    }
    void add_recent(const std::string& path) {
        std::string p = fs::absolute(path).lexically_normal().string();
        recent_.erase(std::remove(recent_.begin(), recent_.end(), p), recent_.end());
        recent_.insert(recent_.begin(), p);
        if (recent_.size() > 12) recent_.resize(12);
        if (!job_.environment.use_cache) return;
        std::error_code ec;
        fs::create_directories(recent_file().parent_path(), ec);
        std::ofstream out(recent_file());
        for (const auto& r : recent_) out << r << "\n";
    }

    // --- saving ----------------------------------------------------------------------

    // The view as a scene file (fresnel/job/scene_file.h): the job at the window's size,
    // the material edits as overrides of their models, "output" the .png beside it, so
    // `fresnel render PATH` renders this frame. Atomic; false (error_ set) when it fails.
    bool save_scene(const std::string& path) {
        try {
            if (path.empty()) throw Error("", "", "save scene: no file name");
            Job job = shown_job();
            std::vector<std::string> lost = material_overrides(job);
            Diagnostics diag;
            save_scene_file(path, job, diag, image_beside(path));
            for (const auto& l : lost) diag.warn(path, "", l);
            if (diag.total()) print_warnings(diag);
            status_ = "saved " + path;
            std::fprintf(stderr, "fresnel: wrote %s\n", path.c_str());
            return true;
        } catch (const std::exception& e) {
            error_ = e.what();
            std::fprintf(stderr, "fresnel: error: %s\n", e.what());
            return false;
        }
    }

    // The material edits into `job` as material overrides (by index) of the models they belong
    // to; what a scene file cannot hold, as one line each.
    std::vector<std::string> material_overrides(Job& job) const {
        std::vector<std::string> lost;
        if (!scene_ || !materials_edited_ || scene_->materials.size() != original_materials_.size()) return lost;
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
        for (std::size_t i = 0; i < scene_->materials.size(); ++i) {
            const Material &now = scene_->materials[i], &was = original_materials_[i];
            std::size_t model = 0;
            int local = int(i);
            for (std::size_t k = 0; k < scene_->parts.size() && k < visible.size(); ++k) {
                const auto& part = scene_->parts[k];
                if (int(i) >= part.first_material && int(i) < part.first_material + part.material_count) {
                    model = visible[k];
                    local = int(i) - part.first_material;
                }
            }
            Job::Source::MaterialOverride mo;
            mo.index = local;
            bool any = false;
            auto put = [&](auto& field, auto value) { field = value, any = true; };
            if (now.base_color_factor != was.base_color_factor)
                put(mo.base_color_factor, glm::clamp(now.base_color_factor, 0.0f, 1.0f));
            if (now.metallic_factor != was.metallic_factor) put(mo.metallic_factor, std::clamp(now.metallic_factor, 0.0f, 1.0f));
            if (now.roughness_factor != was.roughness_factor) put(mo.roughness_factor, std::clamp(now.roughness_factor, 0.0f, 1.0f));
            if (now.emissive_factor != was.emissive_factor) put(mo.emissive_factor, glm::clamp(now.emissive_factor, 0.0f, 1.0f));
            if (now.emissive_strength &&
                (!was.emissive_strength || now.emissive_strength->emissive_strength != was.emissive_strength->emissive_strength))
                put(mo.emissive_strength, now.emissive_strength->emissive_strength);
            if (now.alpha_cutoff != was.alpha_cutoff) put(mo.alpha_cutoff, now.alpha_cutoff);
            if (now.ior && (!was.ior || now.ior->ior != was.ior->ior)) put(mo.ior, now.ior->ior);
            if (any) job.source.models[model].materials.push_back(mo);
            const bool other = now.normal_scale != was.normal_scale || now.occlusion_strength != was.occlusion_strength ||
                               (now.specular && (!was.specular || now.specular->specular_factor != was.specular->specular_factor)) ||
                               (now.clearcoat && (!was.clearcoat || now.clearcoat->clearcoat_factor != was.clearcoat->clearcoat_factor ||
                                                  now.clearcoat->clearcoat_roughness_factor != was.clearcoat->clearcoat_roughness_factor));
            if (other)
                lost.push_back("material " + std::to_string(i) + ": normal scale, occlusion strength, specular and clearcoat "
                               "edits are not scene-file overrides (not written; save the model as glTF to keep them)");
        }
        return lost;
    }

    // The material edits written back into the model's glTF file (or a copy of it) without
    // losing what fresnel does not read (fresnel/scene/scene_writer.h). Atomic.
    bool save_model(const std::string& path) {
        try {
            std::string why;
            if (!scene_) why = "no scene is loaded";
            else if (!job_.source.models.empty()) why = "the scene holds several models (a scene file): save the scene";
            else if (job_.source.model.empty()) why = "the built-in demo has no file";
            else if (!is_gltf(job_.source.model)) why = "only glTF models (.gltf, .glb) are saved";
            else if (!job_.source.variant.empty()) why = "a material variant (--variant) replaces the file's materials";
            if (!why.empty()) throw Error(path, "", "cannot save the materials: " + why);
            Diagnostics diag;
            int n = save_gltf_material_edits(job_.source.model, path, original_materials_, scene_->materials, diag);
            if (diag.total()) print_warnings(diag);
            std::error_code ec;
            if (fs::equivalent(path, job_.source.model, ec)) {  // the file now holds the edits
                original_materials_ = scene_->materials;
                materials_edited_ = false;
            }
            status_ = "saved " + path + " (" + std::to_string(n) + " value" + (n == 1 ? "" : "s") + " changed)";
            std::fprintf(stderr, "fresnel: wrote %s (%d material value%s changed)\n", path.c_str(), n, n == 1 ? "" : "s");
            return true;
        } catch (const std::exception& e) {
            error_ = e.what();
            std::fprintf(stderr, "fresnel: error: %s\n", e.what());
            return false;
        }
    }

    // --watch-shaders: whether a file under --shaders changed (size or time) since the last look.
    bool shaders_changed() {
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
    bool reload_shaders(const std::string& folder) {
        if (!folder.empty()) renderer_->set_shader_folder(folder);
        std::string e = renderer_->reload_shaders();
        if (!e.empty()) {
            error_ = "shader reload failed (the previous shaders stay): " + e;
            std::fprintf(stderr, "fresnel: error: %s\n", error_.c_str());
            return false;
        }
        status_ = "shaders reloaded";
        std::fprintf(stderr, "fresnel: shaders reloaded (%zu programs)\n", renderer_->program_count());
        return true;
    }

    // --- auto-rotate -----------------------------------------------------------------

    bool spinning() const { return spin_camera_ || spin_environment_ || (orbit_lights_ && !job_.lights.extra.empty()); }
    // Turns the camera (about the target) and/or the environment by 30 degrees a second.
    void spin() {
        auto now = Clock::now();
        double dt = spin_last_ ? std::chrono::duration<double>(now - *spin_last_).count() : 0.0;
        spin_last_ = now;
        float step = float(std::min(dt, 0.25) * 30.0);
        if (spin_camera_) {
            if (job_.camera.scene_camera && last_camera_)
                job_.camera = orbit_from_setup(*last_camera_, bounds_, last_camera_->yfov_deg);
            job_.camera.yaw_deg = std::remainder(job_.camera.yaw_deg + step, 360.0f);
        }
        if (spin_environment_) job_.environment.rotation_deg = std::remainder(job_.environment.rotation_deg + step, 360.0f);
        if (orbit_lights_) orbit_added_lights(step);
    }

    // "Orbit lights around the model": the added lights turn about +Y through the bounds' centre.
    void orbit_added_lights(float degrees) {
        const float a = glm::radians(degrees);
        const glm::mat3 r(glm::vec3(std::cos(a), 0.0f, -std::sin(a)), glm::vec3(0.0f, 1.0f, 0.0f),
                          glm::vec3(std::sin(a), 0.0f, std::cos(a)));
        const glm::vec3 c = bounds_.empty ? glm::vec3(0.0f) : bounds_.center();
        for (LightInstance& l : job_.lights.extra) {
            l.direction = glm::normalize(r * l.direction);
            l.position = c + r * (l.position - c);
        }
    }

    // --- lights, picking and the scene tree -------------------------------------------

    // A window point (ImGui coordinates: points from the top left) as a world-space ray of the
    // last frame's camera.
    bool window_ray(glm::vec2 point, glm::vec3& origin, glm::vec3& direction) const {
        if (!last_camera_) return false;
        gui::Size win = window_->window_size();
        if (win.width <= 0 || win.height <= 0) return false;
        const glm::mat4 inv = glm::inverse(last_camera_->projection * last_camera_->view);
        const float x = 2.0f * point.x / float(win.width) - 1.0f, y = 1.0f - 2.0f * point.y / float(win.height);
        glm::vec4 a = inv * glm::vec4(x, y, -1.0f, 1.0f), b = inv * glm::vec4(x, y, 1.0f, 1.0f);
        if (a.w == 0.0f || b.w == 0.0f) return false;
        origin = glm::vec3(a) / a.w;
        direction = glm::normalize(glm::vec3(b) / b.w - origin);
        return std::isfinite(direction.x);
    }
    // A world point on the window (ImGui points), or nothing behind the camera.
    std::optional<glm::vec2> to_window(glm::vec3 p) const {
        if (!last_camera_) return std::nullopt;
        gui::Size win = window_->window_size();
        glm::vec4 c = last_camera_->projection * last_camera_->view * glm::vec4(p, 1.0f);
        if (!(c.w > 1e-6f)) return std::nullopt;
        return glm::vec2((c.x / c.w * 0.5f + 0.5f) * float(win.width), (0.5f - c.y / c.w * 0.5f) * float(win.height));
    }
    // Where a directional light's handle sits: on a sphere around the model, towards the light.
    float handle_radius() const { return bounds_.empty ? 1.0f : std::max(bounds_.radius() * 1.25f, 1e-3f); }
    glm::vec3 light_handle(const LightInstance& l) const {
        if (l.type != Light::Type::Directional) return l.position;
        return (bounds_.empty ? glm::vec3(0.0f) : bounds_.center()) - l.direction * handle_radius();
    }

    // The click selection at a window point: the nearest visible primitive, or none.
    void pick_at(glm::vec2 point) {
        picked_.reset();
        glm::vec3 o, d;
        if (!scene_ || !window_ray(point, o, d)) return;
        picked_ = pick(*scene_, resolved_.instances, o, d);
        if (picked_) {
            const Primitive& p = scene_->meshes[std::size_t(picked_->mesh)].primitives[std::size_t(picked_->primitive)];
            if (p.material >= 0) edit_material_ = p.material;
        }
    }

    // Left-button drags of a light's handle: a directional light turns to where the ray meets
    // the handle sphere; a point or spot light moves in the plane through it facing the camera.
    // True while a handle is being dragged (the camera stays).
    bool drag_lights(const ImGuiIO& io) {
        if (!gui_visible_ || !show_gizmos_) return false;
        glm::vec2 mouse(io.MousePos.x, io.MousePos.y);
        if (io.MouseClicked[0] && !io.KeyShift) {
            dragging_light_ = -1;
            float best = 10.0f;  // points
            for (int i = 0; i < int(job_.lights.extra.size()); ++i)
                if (auto s = to_window(light_handle(job_.lights.extra[std::size_t(i)])); s && glm::distance(*s, mouse) < best)
                    best = glm::distance(*s, mouse), dragging_light_ = i;
            if (dragging_light_ >= 0) selected_light_ = dragging_light_;
        }
        if (!io.MouseDown[0]) dragging_light_ = -1;
        if (dragging_light_ < 0 || dragging_light_ >= int(job_.lights.extra.size())) return false;
        glm::vec3 o, d;
        if (!window_ray(mouse, o, d)) return true;
        LightInstance& l = job_.lights.extra[std::size_t(dragging_light_)];
        if (l.type == Light::Type::Directional) {
            const glm::vec3 c = bounds_.empty ? glm::vec3(0.0f) : bounds_.center();
            const float r = handle_radius();
            // Nearest point of the ray to the centre, pushed out to the sphere.
            const float t = glm::dot(c - o, d);
            glm::vec3 p = o + d * t;
            const float h2 = r * r - glm::dot(p - c, p - c);
            if (h2 > 0.0f) p = o + d * (t - std::sqrt(h2));  // the near side
            if (glm::length(p - c) > 1e-6f) l.direction = -glm::normalize(p - c);
        } else if (last_camera_) {
            const glm::vec3 n = glm::normalize(last_camera_->eye - last_camera_->target);
            const float den = glm::dot(d, n);
            if (std::fabs(den) > 1e-6f) {
                const float t = glm::dot(l.position - o, n) / den;
                if (t > 0.0f) l.position = o + d * t;
            }
        }
        return true;
    }

    // Light handles and the picked primitive's box, under the panels.
    void draw_gizmos() {
        if (!last_camera_ || !scene_) return;
        ImDrawList* dl = ImGui::GetBackgroundDrawList();
        if (picked_ && std::size_t(picked_->instance) < resolved_.instances.size()) {
            Bounds b = primitive_world_bounds(*scene_, resolved_.instances[std::size_t(picked_->instance)], picked_->primitive);
            if (!b.empty) {
                std::optional<glm::vec2> s[8];
                for (int c = 0; c < 8; ++c)
                    s[c] = to_window(glm::vec3((c & 1) ? b.max.x : b.min.x, (c & 2) ? b.max.y : b.min.y, (c & 4) ? b.max.z : b.min.z));
                for (int a = 0; a < 8; ++a)
                    for (int bit : {1, 2, 4})
                        if (!(a & bit) && s[a] && s[a | bit])
                            dl->AddLine(ImVec2(s[a]->x, s[a]->y), ImVec2(s[a | bit]->x, s[a | bit]->y), IM_COL32(255, 220, 40, 230), 1.5f);
            }
        }
        if (!show_gizmos_) return;
        const glm::vec3 c = bounds_.empty ? glm::vec3(0.0f) : bounds_.center();
        auto draw_light = [&](const LightInstance& l, bool added, bool selected) {
            ImU32 col = !added ? IM_COL32(160, 160, 160, 200) : selected ? IM_COL32(255, 220, 40, 255) : IM_COL32(255, 255, 255, 230);
            glm::vec3 h = added ? light_handle(l) : (l.type == Light::Type::Directional ? c - l.direction * handle_radius() : l.position);
            auto s = to_window(h);
            if (!s) return;
            ImVec2 at(s->x, s->y);
            if (l.type == Light::Type::Directional) {
                if (auto sc = to_window(c)) dl->AddLine(at, ImVec2(sc->x, sc->y), col, 1.0f);
            } else if (l.type == Light::Type::Spot) {
                if (auto e = to_window(l.position + l.direction * handle_radius() * 0.3f)) dl->AddLine(at, ImVec2(e->x, e->y), col, 2.0f);
            }
            dl->AddCircleFilled(at, 6.0f, col);
            dl->AddCircle(at, 8.0f, IM_COL32(0, 0, 0, 200), 0, 1.5f);
        };
        // The scene's lights (resolved_.lights: the scene's, then the added ones), grey, not draggable.
        if (!resolved_.default_lights && resolved_.lights.size() >= job_.lights.extra.size())
            for (std::size_t i = 0; i < resolved_.lights.size() - job_.lights.extra.size(); ++i)
                draw_light(resolved_.lights[i], false, false);
        for (std::size_t i = 0; i < job_.lights.extra.size(); ++i)
            draw_light(job_.lights.extra[i], true, int(i) == selected_light_);
    }

    static const char* light_type_name(Light::Type t) {
        return t == Light::Type::Directional ? "directional" : t == Light::Type::Point ? "point" : "spot";
    }

    void draw_lights_panel() {
        ImGui::Checkbox("scene lights##lights", &job_.lights.scene_lights);
        ImGui::SameLine();
        ImGui::Checkbox("gizmos", &show_gizmos_);
        if (resolved_.default_lights)
            ImGui::TextDisabled("default key + fill lights (the scene has none; adding one replaces them)");
        const glm::vec3 c = bounds_.empty ? glm::vec3(0.0f) : bounds_.center();
        const float r = handle_radius();
        auto add = [&](Light::Type t) {
            LightInstance l;
            l.type = t;
            l.direction = direction_from_angles(30.0f, 45.0f);
            l.position = c - l.direction * r;
            l.radiance = glm::vec3(t == Light::Type::Directional ? 3.0f : 3.0f * r * r);
            l.outer_cone = glm::radians(30.0f);
            l.inner_cone = glm::radians(15.0f);
            job_.lights.extra.push_back(l);
            selected_light_ = int(job_.lights.extra.size()) - 1;
        };
        if (ImGui::Button("+ directional")) add(Light::Type::Directional);
        ImGui::SameLine();
        if (ImGui::Button("+ point")) add(Light::Type::Point);
        ImGui::SameLine();
        if (ImGui::Button("+ spot")) add(Light::Type::Spot);
        if (ImGui::Checkbox("orbit lights around the model", &orbit_lights_) && orbit_lights_) spin_last_.reset();
        int remove = -1;
        for (int i = 0; i < int(job_.lights.extra.size()); ++i) {
            LightInstance& l = job_.lights.extra[std::size_t(i)];
            ImGui::PushID(i);
            bool open = ImGui::TreeNodeEx("light", ImGuiTreeNodeFlags_DefaultOpen | (i == selected_light_ ? ImGuiTreeNodeFlags_Selected : 0),
                                          "%d: %s", i, light_type_name(l.type));
            if (ImGui::IsItemClicked()) selected_light_ = i;
            ImGui::SameLine();
            if (ImGui::SmallButton("delete")) remove = i;
            if (open) {
                int type = int(l.type);
                if (ImGui::Combo("type", &type, "directional\0point\0spot\0")) l.type = Light::Type(type);
                if (l.type != Light::Type::Point) {  // where it shines from, as --light dir:AZ,EL
                    glm::vec3 from = -l.direction;
                    float el = glm::degrees(std::asin(std::clamp(from.y, -1.0f, 1.0f)));
                    float az = glm::degrees(std::atan2(from.x, from.z));
                    bool ch = ImGui::DragFloat("azimuth", &az, 0.5f, -180.0f, 180.0f, "%.1f deg");
                    ch |= ImGui::DragFloat("elevation", &el, 0.5f, -90.0f, 90.0f, "%.1f deg");
                    if (ch) l.direction = direction_from_angles(az, std::clamp(el, -90.0f, 90.0f));
                }
                if (l.type != Light::Type::Directional) ImGui::DragFloat3("position", &l.position.x, 0.01f * r);
                float lum = std::max({l.radiance.x, l.radiance.y, l.radiance.z});
                glm::vec3 color = lum > 0.0f ? l.radiance / lum : glm::vec3(1.0f);
                bool ch = ImGui::ColorEdit3("colour", &color.x);
                ch |= ImGui::DragFloat(l.type == Light::Type::Directional ? "lux" : "candela", &lum, 0.01f * std::max(lum, 1.0f), 0.0f, 1e6f);
                if (ch) l.radiance = color * std::max(lum, 0.0f);
                if (l.type != Light::Type::Directional) ImGui::DragFloat("range (0: infinite)", &l.range, 0.01f * r, 0.0f, 1e6f);
                if (l.type == Light::Type::Spot) {
                    float inner = glm::degrees(l.inner_cone), outer = glm::degrees(l.outer_cone);
                    if (ImGui::DragFloatRange2("cone", &inner, &outer, 0.2f, 0.0f, 90.0f, "inner %.1f", "outer %.1f")) {
                        l.outer_cone = glm::radians(std::clamp(outer, 0.1f, 90.0f));
                        l.inner_cone = glm::radians(std::clamp(inner, 0.0f, glm::degrees(l.outer_cone) - 0.05f));
                    }
                }
                ImGui::TreePop();
            }
            ImGui::PopID();
        }
        if (remove >= 0) {
            job_.lights.extra.erase(job_.lights.extra.begin() + remove);
            selected_light_ = -1;
            dragging_light_ = -1;
        }
        ImGui::TextDisabled("drag a handle in the view to move a light");
    }

    std::string node_label(int n) const {
        const Node& node = scene_->nodes[std::size_t(n)];
        std::string s = node.name.empty() ? "node " + std::to_string(n) : node.name;
        if (node.mesh >= 0) s += "  [mesh " + std::to_string(node.mesh) + "]";
        if (node.light >= 0) s += "  [light " + std::to_string(node.light) + "]";
        if (node.camera >= 0) s += "  [camera " + std::to_string(node.camera) + "]";
        return s;
    }

    // One node of the scene tree: a visibility box, its children, its mesh's primitives.
    void draw_tree_node(int n, int depth) {
        if (n < 0 || std::size_t(n) >= scene_->nodes.size() || depth > 64) return;
        Node& node = scene_->nodes[std::size_t(n)];
        ImGui::PushID(n);
        bool visible = node.visible;
        if (ImGui::Checkbox("##visible", &visible)) set_node_visible(n, visible);
        ImGui::SameLine();
        const bool leaf = node.children.empty() && node.mesh < 0;
        const bool selected = picked_ && picked_->node == n;
        bool open = ImGui::TreeNodeEx("node", (leaf ? ImGuiTreeNodeFlags_Leaf : 0) | (selected ? ImGuiTreeNodeFlags_Selected : 0),
                                      "%s", node_label(n).c_str());
        if (open) {
            if (node.mesh >= 0 && std::size_t(node.mesh) < scene_->meshes.size()) {
                const auto& prims = scene_->meshes[std::size_t(node.mesh)].primitives;
                for (int p = 0; p < int(prims.size()); ++p) {
                    const int mat = prims[std::size_t(p)].material;
                    std::string label = "primitive " + std::to_string(p) + ": " + std::to_string(prims[std::size_t(p)].triangle_count()) +
                                        " triangles, material " +
                                        (mat >= 0 ? std::to_string(mat) + " " + scene_->materials[std::size_t(mat)].name : "default");
                    bool sel = picked_ && picked_->node == n && picked_->primitive == p;
                    if (ImGui::Selectable((label + "##p" + std::to_string(p)).c_str(), sel)) select_primitive(n, p);
                }
            }
            for (int child : node.children) draw_tree_node(child, depth + 1);
            ImGui::TreePop();
        }
        ImGui::PopID();
    }

    void select_primitive(int node, int primitive) {
        for (std::size_t i = 0; i < resolved_.instances.size(); ++i)
            if (resolved_.instances[i].node == node) {
                PickHit h;
                h.instance = int(i);
                h.node = node;
                h.mesh = scene_->nodes[std::size_t(node)].mesh;
                h.primitive = primitive;
                picked_ = h;
                const int mat = scene_->meshes[std::size_t(h.mesh)].primitives[std::size_t(primitive)].material;
                if (mat >= 0) edit_material_ = mat;
                return;
            }
    }

    // KHR_node_visibility, live: the renderer's instances are read again.
    void set_node_visible(int n, bool visible) {
        scene_->nodes[std::size_t(n)].visible = visible;
        renderer_->update_transforms();
        if (picked_ && !visible) picked_.reset();
    }

    void draw_scene_tree() {
        const Scene& s = *scene_;
        ImGui::Text("%zu nodes, %zu meshes, %zu materials, %zu textures, %zu lights, %zu cameras", s.nodes.size(), s.meshes.size(),
                    s.materials.size(), s.textures.size(), s.lights.size(), s.cameras.size());
        if (picked_) {
            ImGui::Text("selected: node %d, primitive %d", picked_->node, picked_->primitive);
            ImGui::SameLine();
            if (ImGui::SmallButton("clear")) picked_.reset();
        } else {
            ImGui::TextDisabled("click the model to select a primitive");
        }
        const int index = resolved_.scene_index >= 0 ? resolved_.scene_index : s.default_scene;
        if (index >= 0 && std::size_t(index) < s.scenes.size())
            for (int root : s.scenes[std::size_t(index)]) draw_tree_node(root, 0);
    }

    // --- input -----------------------------------------------------------------------

    // Mouse and keys; true when something may have changed.
    bool handle_input() {
        bool changed = false;
        for (const auto& p : window_->take_dropped_paths()) {
            open_path(p);
            changed = true;
        }
        ImGuiIO& io = ImGui::GetIO();
        gui::Size win = window_->window_size();
        float to_pixels = win.width > 0 ? float(fb_.width) / float(win.width) : 1.0f;  // high-DPI
        OrbitViewport view{bounds_, std::max(fb_.width, 1), std::max(fb_.height, 1)};
        // Orbiting away from a file's camera starts from where it looks.
        auto orbit_camera_now = [&] {
            if (job_.camera.scene_camera && last_camera_)
                job_.camera = orbit_from_setup(*last_camera_, bounds_, last_camera_->yfov_deg);
        };
        if (split_ && !io.WantCaptureMouse) {
            float x = io.MousePos.x * to_pixels;
            if (io.MouseClicked[0] && std::abs(x - float(divider_pixels())) <= 6.0f * to_pixels) dragging_divider_ = true;
            if (!io.MouseDown[0]) dragging_divider_ = false;
            if (dragging_divider_) {
                split_pos_ = std::clamp(io.MousePos.x / float(std::max(win.width, 1)), 0.0f, 1.0f);
                return true;
            }
        }
        if (!io.WantCaptureMouse && drag_lights(io)) return true;
        if (!io.WantCaptureMouse && io.MouseClicked[0]) press_at_ = glm::vec2(io.MousePos.x, io.MousePos.y), press_moved_ = false;
        if (io.MouseDown[0] && glm::distance(glm::vec2(io.MousePos.x, io.MousePos.y), press_at_) > 3.0f) press_moved_ = true;
        if (!io.WantCaptureMouse && io.MouseReleased[0] && !press_moved_ && !io.KeyShift) {
            pick_at(press_at_);  // a click, not a drag: select what is under it
            changed = true;
        }
        if (!io.WantCaptureMouse) {
            float dx = io.MouseDelta.x, dy = io.MouseDelta.y;
            bool moved = (dx != 0.0f || dy != 0.0f) && io.MouseDelta.x > -1e6f;
            bool pan_drag = io.MouseDown[1] || io.MouseDown[2] || (io.MouseDown[0] && io.KeyShift);
            if (moved && pan_drag) {
                orbit_camera_now();
                job_.camera = pan(job_.camera, view, dx * to_pixels, dy * to_pixels);
                changed = true;
            } else if (moved && io.MouseDown[0]) {
                orbit_camera_now();
                job_.camera = orbit(job_.camera, dx, dy);
                changed = true;
            }
            if (io.MouseWheel != 0.0f) {
                orbit_camera_now();
                job_.camera = dolly(job_.camera, view, dolly_factor(io.MouseWheel));
                changed = true;
            }
        }
        if (!io.WantTextInput) {
            if (window_->key_pressed(gui::Key::F)) job_.camera = frame_all(job_.camera), changed = true;
            if (window_->key_pressed(gui::Key::R)) job_.camera = initial_camera_, changed = true;
            if (window_->key_pressed(gui::Key::PageDown)) step_folder(+1), changed = true;
            if (window_->key_pressed(gui::Key::PageUp)) step_folder(-1), changed = true;
            if (window_->key_pressed(gui::Key::F12)) screenshot_requested_ = true, changed = true;
            if (window_->key_pressed(gui::Key::O)) browser_open_ = true, changed = true;
            if (window_->key_pressed(gui::Key::C, /*ctrl=*/true)) copy_command_line(), changed = true;
            if (window_->key_pressed(gui::Key::Escape)) window_->request_close();
            if (window_->key_pressed(gui::Key::Tab)) gui_visible_ = !gui_visible_, changed = true;
            if (window_->key_pressed(gui::Key::S, /*ctrl=*/true)) save_scene(scene_save_path_), changed = true;
            if (window_->key_pressed(gui::Key::A)) spin_camera_ = !spin_camera_, changed = true;
            if (window_->key_pressed(gui::Key::F5)) reload_shaders(""), changed = true;
        }
        return changed;
    }

    // The job as the window shows it: at the framebuffer's size.
    Job shown_job() const {
        Job job = job_;
        job.output.width = std::max(fb_.width, 1);
        job.output.height = std::max(fb_.height, 1);
        return job;
    }

    void copy_command_line() {
        command_line_ = render_command_line(shown_job(), "view.png");
        window_->set_clipboard(command_line_);
        std::printf("%s\n", command_line_.c_str());
        if (materials_edited_)
            std::fprintf(stderr, "fresnel: note: the material edits are not part of the command line (save the scene: Ctrl+S)\n");
        std::fflush(stdout);
    }

    std::string screenshot_name() const {
        std::time_t t = std::time(nullptr);
        char buf[64];
        std::strftime(buf, sizeof buf, "fresnel-%Y%m%d-%H%M%S.png", std::localtime(&t));
        return buf;
    }

    // --- GUI -------------------------------------------------------------------------

    template <class E>
    static bool combo(const char* label, E& value, const std::vector<std::pair<E, std::string>>& items) {
        std::string current;
        for (const auto& [v, n] : items)
            if (v == value) current = n;
        bool changed = false;
        if (ImGui::BeginCombo(label, current.c_str())) {
            for (const auto& [v, n] : items) {
                if (ImGui::Selectable(n.c_str(), v == value)) {
                    changed = v != value;
                    value = v;
                }
            }
            ImGui::EndCombo();
        }
        return changed;
    }

    int divider_pixels() const { return std::clamp(int(split_pos_ * float(fb_.width) + 0.5f), 0, fb_.width); }

    void draw_gui() {
        draw_gizmos();
        if (split_) {  // the divider, over the frame and under the panels
            gui::Size win = window_->window_size();
            float x = split_pos_ * float(win.width);
            ImDrawList* d = ImGui::GetBackgroundDrawList();
            d->AddLine(ImVec2(x, 0.0f), ImVec2(x, float(win.height)), IM_COL32(255, 255, 255, 200), 2.0f);
        }
        if (!gui_visible_) return;
        ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
        ImGui::SetNextWindowSize(ImVec2(320, 0), ImGuiCond_FirstUseEver);
        ImGui::SetNextWindowBgAlpha(0.8f);
        ImGui::Begin("fresnel view (Tab hides)");
        if (!error_.empty()) {
            ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.4f, 0.35f, 1.0f));
            ImGui::TextWrapped("%s", error_.c_str());
            ImGui::PopStyleColor();
            if (ImGui::SmallButton("dismiss")) error_.clear();
        }
        if (bake_) {
            ImGui::Text("baking %s", bake_->resolved.environment ? bake_->resolved.environment->describe().c_str() : "");
            ImGui::ProgressBar(bake_->progress->load());
        }
        if (ImGui::CollapsingHeader("File", ImGuiTreeNodeFlags_DefaultOpen)) {
            ImGui::TextWrapped("%s", job_.source.model.empty() ? "(built-in demo)" : job_.source.model.c_str());
            if (ImGui::Button("Open... (O)")) browser_open_ = true;
            ImGui::SameLine();
            if (ImGui::Button("< PgUp")) step_folder(-1);
            ImGui::SameLine();
            if (ImGui::Button("PgDn >")) step_folder(+1);
            ImGui::SameLine();
            if (ImGui::Button("Demo")) open_model("", false);
            if (!folder_models_.empty()) ImGui::Text("%zu models in this folder", folder_models_.size());
            if (!recent_.empty() && ImGui::TreeNode("Recent")) {
                std::string chosen;
                for (const auto& r : recent_)
                    if (ImGui::Selectable(r.c_str())) chosen = r;
                ImGui::TreePop();
                if (!chosen.empty()) open_path(chosen);
            }
            if (!warnings_.empty() && ImGui::TreeNode("warnings", "%zu warnings", warnings_.size())) {
                for (const auto& w : warnings_) ImGui::TextWrapped("%s", w.c_str());
                ImGui::TreePop();
            }
            ImGui::TextDisabled("drop a model, a scene file or an environment onto the window");
            ImGui::InputText("##scene-file", &scene_save_path_);
            ImGui::SameLine();
            if (ImGui::Button("Save scene (Ctrl+S)")) save_scene(scene_save_path_);
        }
        if (ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen)) {
            Job::Camera& c = job_.camera;
            if (scene_ && !scene_->cameras.empty()) {
                std::string current = c.scene_camera ? camera_label(*c.scene_camera) : "orbit";
                if (ImGui::BeginCombo("view", current.c_str())) {
                    if (ImGui::Selectable("orbit", !c.scene_camera)) {
                        if (c.scene_camera && last_camera_) c = orbit_from_setup(*last_camera_, bounds_, last_camera_->yfov_deg);
                    }
                    for (int i = 0; i < int(scene_->cameras.size()); ++i)
                        if (ImGui::Selectable(camera_label(i).c_str(), c.scene_camera == i)) c.scene_camera = i;
                    ImGui::EndCombo();
                }
            }
            if (!c.scene_camera) {
                ImGui::DragFloat("yaw", &c.yaw_deg, 0.5f, -180.0f, 180.0f, "%.2f deg");
                ImGui::DragFloat("pitch", &c.pitch_deg, 0.5f, -89.9f, 89.9f, "%.2f deg");
                float k = distance_k(c, std::max(fb_.width, 1), std::max(fb_.height, 1));
                if (ImGui::DragFloat("distance K", &k, 0.01f, 0.01f, 1e4f, "%.3f")) c.distance_k = std::max(k, 0.01f);
                ImGui::DragFloat("fov", &c.yfov_deg, 0.2f, 1.0f, 170.0f, "%.1f deg");
                if (c.target) ImGui::Text("target %.3f %.3f %.3f (panned)", c.target->x, c.target->y, c.target->z);
            }
            if (ImGui::Button("Frame all (F)")) c = frame_all(c);
            ImGui::SameLine();
            if (ImGui::Button("Reset (R)")) c = initial_camera_;
            if (ImGui::Checkbox("auto-rotate (A)", &spin_camera_) && spin_camera_) spin_last_.reset();
            if (ImGui::Button("Copy as command line (Ctrl+C)")) copy_command_line();
            if (!command_line_.empty()) ImGui::TextWrapped("%s", command_line_.c_str());
            ImGui::TextDisabled("left drag: orbit; right/middle or shift+left: pan; wheel: dolly");
        }
        if (ImGui::CollapsingHeader("Environment")) {
            using Kind = Job::Environment::Kind;
            Job::Environment& e = job_.environment;
            combo<Kind>("light", e.kind,
                        {{Kind::Automatic, "automatic"}, {Kind::Studio, "studio"}, {Kind::File, "file"},
                         {Kind::Color, "colour"}, {Kind::None, "none (no IBL)"}});
            if (e.kind == Kind::File) ImGui::TextWrapped("%s", e.path.empty() ? "(drop a .hdr/.exr)" : e.path.c_str());
            if (e.kind == Kind::Color) ImGui::ColorEdit3("colour", &e.color.x, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR);
            ImGui::SliderFloat("rotation", &e.rotation_deg, -180.0f, 180.0f, "%.1f deg");
            ImGui::SameLine();
            ImGui::Checkbox("spin", &spin_environment_);
            ImGui::DragFloat("intensity", &e.intensity, 0.01f, 0.0f, 100.0f, "%.2f");
            using Mode = Job::Background::Mode;
            combo<Mode>("background", job_.background.mode,
                        {{Mode::Automatic, "automatic"}, {Mode::Environment, "environment (sharp)"},
                         {Mode::Blurred, "blurred"}, {Mode::Color, "colour"}, {Mode::Transparent, "transparent"}});
            if (job_.background.mode == Mode::Color) ImGui::ColorEdit3("background colour", &job_.background.color.x);
            ImGui::Checkbox("scene lights", &job_.lights.scene_lights);
        }
        if (ImGui::CollapsingHeader("Output")) {
            Job::Output& o = job_.output;
            combo<ToneMapper>("tone mapper", o.tone_mapper,
                              {{ToneMapper::Neutral, "neutral"}, {ToneMapper::Aces, "aces"},
                               {ToneMapper::AcesHill, "aces-hill"}, {ToneMapper::Reinhard, "reinhard"},
                               {ToneMapper::Agx, "agx"}, {ToneMapper::None, "none"}});
            ImGui::SliderFloat("exposure", &o.exposure_ev, -8.0f, 8.0f, "%.2f EV");
            combo<Encoding>("encoding", o.encoding, {{Encoding::Srgb, "srgb"}, {Encoding::Gamma22, "gamma2.2"}});
            std::vector<std::pair<DebugChannel, std::string>> channels{{DebugChannel::None, "none (shaded)"}};
            for (const auto& n : debug_channel_names()) channels.emplace_back(*parse_debug_channel(n), n);
            combo<DebugChannel>("debug", o.debug, channels);
            ImGui::Checkbox("energy compensation", &o.energy_compensation);
            ImGui::SliderInt("MSAA", &o.msaa, 1, 8);
            if (ImGui::Button("Screenshot (F12)")) screenshot_requested_ = true;
        }
        if (ImGui::CollapsingHeader("Split view")) {
            if (ImGui::Checkbox("split (drag the divider)", &split_) && split_) split_output_ = job_.output;
            if (split_) {
                ImGui::TextDisabled("right of the divider:");
                std::vector<std::pair<DebugChannel, std::string>> channels{{DebugChannel::None, "none (shaded)"}};
                for (const auto& n : debug_channel_names()) channels.emplace_back(*parse_debug_channel(n), n);
                combo<DebugChannel>("debug##right", split_output_.debug, channels);
                combo<ToneMapper>("tone mapper##right", split_output_.tone_mapper,
                                  {{ToneMapper::Neutral, "neutral"}, {ToneMapper::Aces, "aces"},
                                   {ToneMapper::AcesHill, "aces-hill"}, {ToneMapper::Reinhard, "reinhard"},
                                   {ToneMapper::Agx, "agx"}, {ToneMapper::None, "none"}});
                ImGui::SliderFloat("exposure##right", &split_output_.exposure_ev, -8.0f, 8.0f, "%.2f EV");
                ImGui::Checkbox("energy compensation##right", &split_output_.energy_compensation);
            }
        }
        if (scene_ && ImGui::CollapsingHeader("Scene")) draw_scene_tree();
        if (ImGui::CollapsingHeader("Lights")) draw_lights_panel();
        if (scene_ && !scene_->materials.empty() && ImGui::CollapsingHeader("Materials")) draw_material_editor();
        if (ImGui::CollapsingHeader("Statistics")) {
            ImGui::Text("%dx%d pixels, frame %.1f ms (CPU, draw + finish)", fb_.width, fb_.height, frame_ms_);
            if (gpu_ms_ >= 0.0) ImGui::Text("GPU %.2f ms (timer query)", gpu_ms_);
            else ImGui::TextDisabled("GPU time: this context has no timer queries (OpenGL ES 3.0)");
            ImGui::Text("resident memory %.1f MiB, texture memory %.1f MiB", double(resident_kb()) / 1024.0,
                        double(renderer_->texture_bytes()) / (1024.0 * 1024.0));
            ImGui::Text("%d draw calls, %zu triangles, %zu programs", stats_.draw_calls, stats_.triangles,
                        renderer_->program_count());
            ImGui::TextWrapped("%s", window_->context().renderer().c_str());
        }
        if (!status_.empty()) ImGui::TextDisabled("%s", status_.c_str());
        ImGui::End();
        if (browser_open_) draw_browser();
    }

    // The factors of one material, edited in place: the renderer reads the scene's
    // materials at every draw, so the next frame shows them. Not saved to the file.
    void draw_material_editor() {
        auto& mats = scene_->materials;
        edit_material_ = std::clamp(edit_material_, 0, int(mats.size()) - 1);
        auto label = [&](int i) {
            return std::to_string(i) + ": " + (mats[std::size_t(i)].name.empty() ? "(unnamed)" : mats[std::size_t(i)].name);
        };
        if (ImGui::BeginCombo("material", label(edit_material_).c_str())) {
            for (int i = 0; i < int(mats.size()); ++i)
                if (ImGui::Selectable(label(i).c_str(), i == edit_material_)) edit_material_ = i;
            ImGui::EndCombo();
        }
        Material& m = mats[std::size_t(edit_material_)];
        bool e = false;
        e |= ImGui::ColorEdit4("baseColorFactor", &m.base_color_factor.x);
        e |= ImGui::SliderFloat("metallicFactor", &m.metallic_factor, 0.0f, 1.0f);
        e |= ImGui::SliderFloat("roughnessFactor", &m.roughness_factor, 0.0f, 1.0f);
        e |= ImGui::ColorEdit3("emissiveFactor", &m.emissive_factor.x, ImGuiColorEditFlags_Float);
        if (m.normal.valid()) e |= ImGui::SliderFloat("normal scale", &m.normal_scale, 0.0f, 2.0f);
        if (m.occlusion.valid()) e |= ImGui::SliderFloat("occlusion strength", &m.occlusion_strength, 0.0f, 1.0f);
        if (m.alpha_mode == AlphaMode::Mask) e |= ImGui::SliderFloat("alphaCutoff", &m.alpha_cutoff, 0.0f, 1.0f);
        if (m.emissive_strength) e |= ImGui::DragFloat("emissiveStrength", &m.emissive_strength->emissive_strength, 0.05f, 0.0f, 1000.0f);
        if (m.ior) e |= ImGui::DragFloat("ior", &m.ior->ior, 0.005f, 1.0f, 3.0f);
        if (m.specular) e |= ImGui::SliderFloat("specularFactor", &m.specular->specular_factor, 0.0f, 1.0f);
        if (m.clearcoat) {
            e |= ImGui::SliderFloat("clearcoatFactor", &m.clearcoat->clearcoat_factor, 0.0f, 1.0f);
            e |= ImGui::SliderFloat("clearcoatRoughness", &m.clearcoat->clearcoat_roughness_factor, 0.0f, 1.0f);
        }
        // The other extensions' factors, for the material's blocks (shaded ones change the frame).
        if (m.sheen && ImGui::TreeNode("KHR_materials_sheen")) {
            e |= ImGui::ColorEdit3("sheenColorFactor", &m.sheen->sheen_color_factor.x, ImGuiColorEditFlags_Float);
            e |= ImGui::SliderFloat("sheenRoughnessFactor", &m.sheen->sheen_roughness_factor, 0.0f, 1.0f);
            ImGui::TreePop();
        }
        if ((m.transmission || m.volume || m.dispersion) && ImGui::TreeNode("transmission, volume, dispersion")) {
            if (m.transmission) e |= ImGui::SliderFloat("transmissionFactor", &m.transmission->transmission_factor, 0.0f, 1.0f);
            if (m.volume) {
                e |= ImGui::DragFloat("thicknessFactor", &m.volume->thickness_factor, 0.01f, 0.0f, 100.0f);
                e |= ImGui::DragFloat("attenuationDistance", &m.volume->attenuation_distance, 0.01f, 1e-4f, 1e6f);
                e |= ImGui::ColorEdit3("attenuationColor", &m.volume->attenuation_color.x, ImGuiColorEditFlags_Float);
            }
            if (m.dispersion) e |= ImGui::DragFloat("dispersion", &m.dispersion->dispersion, 0.01f, 0.0f, 10.0f);
            ImGui::TreePop();
        }
        if (m.iridescence && ImGui::TreeNode("KHR_materials_iridescence")) {
            e |= ImGui::SliderFloat("iridescenceFactor", &m.iridescence->iridescence_factor, 0.0f, 1.0f);
            e |= ImGui::DragFloat("iridescenceIor", &m.iridescence->iridescence_ior, 0.005f, 1.0f, 3.0f);
            e |= ImGui::DragFloatRange2("thickness (nm)", &m.iridescence->iridescence_thickness_minimum,
                                        &m.iridescence->iridescence_thickness_maximum, 1.0f, 0.0f, 2000.0f);
            ImGui::TreePop();
        }
        if (m.anisotropy && ImGui::TreeNode("KHR_materials_anisotropy")) {
            e |= ImGui::SliderFloat("anisotropyStrength", &m.anisotropy->anisotropy_strength, 0.0f, 1.0f);
            e |= ImGui::SliderAngle("anisotropyRotation", &m.anisotropy->anisotropy_rotation, -180.0f, 180.0f);
            ImGui::TreePop();
        }
        if (m.diffuse_transmission && ImGui::TreeNode("KHR_materials_diffuse_transmission")) {
            e |= ImGui::SliderFloat("diffuseTransmissionFactor", &m.diffuse_transmission->diffuse_transmission_factor, 0.0f, 1.0f);
            e |= ImGui::ColorEdit3("diffuseTransmissionColorFactor", &m.diffuse_transmission->diffuse_transmission_color_factor.x);
            ImGui::TreePop();
        }
        const std::pair<const char*, const TextureSlot*> slots[] = {
            {"baseColor", &m.base_color}, {"metallicRoughness", &m.metallic_roughness}, {"normal", &m.normal},
            {"occlusion", &m.occlusion}, {"emissive", &m.emissive}};
        for (const auto& [name, slot] : slots) {
            if (!slot->valid()) continue;
            ImGui::TextDisabled("%s texture %d (uv%d)", name, slot->texture, slot->tex_coord);
            if (auto t = renderer_->texture_preview(slot->texture); t && t->width > 0 && t->height > 0) {
                const float h = 64.0f, w = std::min(h * float(t->width) / float(t->height), 256.0f);
                ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(t->id)), ImVec2(w, h));
                if (ImGui::IsItemHovered())
                    ImGui::SetTooltip("%dx%d%s", t->width, t->height,
                                      t->srgb     ? " (sRGB: shown decoded, darker)"
                                      : t->packed ? " (stored together: occlusion in R, roughness in G, metallic in B)"
                                                  : "");
            }
        }
        if (e) materials_edited_ = true;
        if (materials_edited_ && ImGui::Button("Revert all materials")) {
            mats = original_materials_;
            materials_edited_ = false;
        }
        if (materials_edited_)
            ImGui::TextDisabled("edits: in a saved scene (as overrides) and saved to glTF below; not in the command line");
        if (scene_ && job_.source.models.empty() && is_gltf(job_.source.model)) {
            ImGui::InputText("##model-file", &model_save_path_);
            ImGui::SameLine();
            if (ImGui::Button("Save to glTF")) save_model(model_save_path_);
        }
    }

    std::string camera_label(int i) const {
        const std::string& name = scene_->cameras[std::size_t(i)].name;
        return "camera " + std::to_string(i) + (name.empty() ? "" : ": " + name);
    }

    // A file browser in ImGui: folders, models and environments of one folder at a time.
    void draw_browser() {
        ImGui::SetNextWindowSize(ImVec2(480, 420), ImGuiCond_FirstUseEver);
        if (!ImGui::Begin("Open", &browser_open_)) {
            ImGui::End();
            return;
        }
        std::string dir = browser_dir_.string();
        if (ImGui::InputText("folder", &dir, ImGuiInputTextFlags_EnterReturnsTrue)) browser_dir_ = dir;
        ImGui::BeginChild("entries");
        std::error_code ec;
        std::vector<fs::directory_entry> entries;
        for (fs::directory_iterator it(browser_dir_, ec), end; !ec && it != end; it.increment(ec)) entries.push_back(*it);
        if (ec) ImGui::TextDisabled("%s", ec.message().c_str());
        std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) {
            bool da = is_folder(a.path()), db = is_folder(b.path());
            return da != db ? da : a.path().filename() < b.path().filename();
        });
        fs::path next_dir;
        std::string chosen;
        if (ImGui::Selectable("../")) next_dir = browser_dir_.parent_path();
        for (const auto& e : entries) {
            const fs::path& p = e.path();
            if (p.filename().string().starts_with(".")) continue;
            bool dir_entry = is_folder(p) && !is_environment(p);
            if (!dir_entry && !is_model(p) && !is_environment(p)) continue;
            std::string label = p.filename().string() + (dir_entry ? "/" : is_model(p) ? "" : "  (environment)");
            if (ImGui::Selectable(label.c_str())) {
                if (dir_entry) next_dir = p;
                else chosen = p.string();
            }
        }
        ImGui::EndChild();
        ImGui::End();
        if (!next_dir.empty()) browser_dir_ = next_dir;
        if (!chosen.empty()) {
            open_path(chosen);
            browser_open_ = false;
        }
    }

    // --- frames ----------------------------------------------------------------------

    // Starts, collects or restarts the environment bake for the current job; true when the
    // lighting the job asks for is loaded.
    bool update_lighting() {
        if (!scene_) return false;
        fb_ = window_->framebuffer_size();
        Job job = shown_job();
        try {
            resolved_ = resolve(job, *scene_);
        } catch (const std::exception& e) {  // e.g. a scene camera no node uses
            error_ = e.what();
            job_.camera.scene_camera.reset();
            return false;
        }
        bounds_ = resolved_.bounds;
        std::string key = lighting_key(resolved_);
        if (bake_ && bake_->result.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
            try {
                lighting_ = bake_->result.get();
                lighting_key_ = bake_->key;
                good_environment_ = job_.environment;
                std::fprintf(stderr, "fresnel: lighting ready: %s\n",
                             bake_->resolved.environment ? bake_->resolved.environment->describe().c_str() : "none");
            } catch (const std::exception& e) {
                error_ = e.what();
                std::fprintf(stderr, "fresnel: error: %s\n", e.what());
                bake_failed_ = true;
                script_failed_ = true;
                if (env_line_) std::fprintf(stderr, "fresnel: error: %s: line %d: env failed\n", options_.script.c_str(), env_line_);
                failed_key_ = bake_->key;
                if (key == bake_->key) {  // keep the environment that worked
                    job_.environment = good_environment_;
                }
            }
            bake_.reset();
        }
        if (!bake_ && key != lighting_key_ && key != failed_key_) {
            bake_ = std::make_unique<Bake>();
            bake_->key = key;
            bake_->resolved = resolved_;
            auto progress = bake_->progress;
            ResolvedJob r = resolved_;
            bake_->result = std::async(std::launch::async, [r, progress] {
                struct Wake {  // wake the loop when done, whether it worked or threw
                    ~Wake() { gui::Window::wake(); }
                } wake;
                return load_lighting(r, [progress](double f) { progress->store(float(f)); });
            });
        }
        if (key != failed_key_) failed_key_.clear();
        return !bake_ && key == lighting_key_;
    }

    void draw_scene() {
        fb_ = window_->framebuffer_size();
        if (fb_.width <= 0 || fb_.height <= 0) return;  // minimised
        // No scene, or its first lighting still baking: a plain background under the progress bar.
        if (!scene_ || lighting_key_ == kNoLighting) {
            gpu::Device device;
            device.bind_framebuffer(nullptr);
            device.viewport(0, 0, fb_.width, fb_.height);
            device.clear(glm::vec4(0.12f, 0.12f, 0.12f, 1.0f));
            return;
        }
        RenderSettings rs = lighting_.settings(resolved_);
        rs.width = fb_.width;
        rs.height = fb_.height;
        // GL errors pending from the GUI's last frame (ImGui's desktop GL backend on an ES
        // context, e.g. glPolygonMode) are not this frame's: clear them first.
        std::string gui_errors = gpu::Device().take_errors();
        if (!gui_errors.empty() && gui_gl_errors_.empty()) {
            gui_gl_errors_ = gui_errors;
            std::fprintf(stderr, "fresnel: note: the GUI's GL backend raised %s (not the frame's)\n", gui_errors.c_str());
        }
        auto t = Clock::now();
        // GPU time by a timer query, where the context has them (OpenGL 3.3, not ES 3.0).
        if (!timer_ && window_->context().capabilities().timer_queries) timer_ = std::make_unique<gpu::TimerQuery>();
        if (timer_) timer_->begin();
        renderer_->draw(resolved_.camera, resolved_.lights, rs, RenderTarget::default_framebuffer(0, 0), &stats_);
        if (split_) {  // the same frame with the right side's settings, over the right of the divider
            RenderSettings right = rs;
            right.debug = split_output_.debug;
            right.tone_mapper = split_output_.tone_mapper;
            right.exposure_ev = split_output_.exposure_ev;
            right.energy_compensation = split_output_.energy_compensation;
            RenderTarget target = RenderTarget::default_framebuffer(0, 0);
            int x = divider_pixels();
            target.scissor = RenderTarget::Rect{x, 0, fb_.width - x, fb_.height};
            FrameStats more;
            renderer_->draw(resolved_.camera, resolved_.lights, right, target, &more);
            stats_.draw_calls += more.draw_calls;
            stats_.triangles += more.triangles;
            stats_.gl_errors += more.gl_errors;
        }
        if (timer_) timer_->end();
        renderer_->finish();
        frame_ms_ = ms_since(t);
        if (double ms = 0.0; timer_ && timer_->result_ms(ms)) gpu_ms_ = ms;
        last_camera_ = resolved_.camera;
        last_transparent_ = resolved_.transparent();
        if (!stats_.gl_errors.empty()) error_ = "OpenGL: the frame raised " + stats_.gl_errors;
    }

    const ViewOptions& options_;
    Job job_, defaults_;
    std::string opened_, first_scene_file_;  // the model or scene file shown; a folder's first scene file
    std::string scene_save_path_ = "view.fresnel.json", model_save_path_;
    bool spin_camera_ = false, spin_environment_ = false;
    std::optional<Clock::time_point> spin_last_;
    Job::Camera initial_camera_;
    Job::Environment good_environment_;
    gui::Size window_size_, fb_;
    gui::Window* window_ = nullptr;
    std::unique_ptr<Renderer> renderer_;
    std::unique_ptr<Scene> scene_;
    ResolvedJob resolved_;
    Bounds bounds_;
    std::optional<CameraSetup> last_camera_;
    bool last_transparent_ = false;
    JobLighting lighting_;
    static constexpr const char* kNoLighting = "(none yet)";
    std::string lighting_key_ = kNoLighting, failed_key_;
    std::unique_ptr<Bake> bake_;
    bool bake_failed_ = false;
    FrameStats stats_;
    double frame_ms_ = 0.0, gpu_ms_ = -1.0;  // gpu_ms_ < 0: no timer queries (or no result yet)
    std::unique_ptr<gpu::TimerQuery> timer_;
    std::vector<std::string> folder_models_, recent_, warnings_;
    std::string error_, status_, command_line_, gui_gl_errors_;
    bool screenshot_requested_ = false, browser_open_ = false, gui_visible_ = true;
    std::vector<ScriptCommand> script_;
    std::size_t script_pos_ = 0;
    int script_wait_ = 0, env_line_ = 0;
    bool script_failed_ = false;
    std::vector<Material> original_materials_;
    bool materials_edited_ = false;
    int edit_material_ = 0;
    std::map<std::string, std::pair<std::uintmax_t, fs::file_time_type>> shader_files_;  // --watch-shaders
    bool orbit_lights_ = false, show_gizmos_ = true;
    int selected_light_ = -1, dragging_light_ = -1;
    std::optional<PickHit> picked_;
    glm::vec2 press_at_{0.0f};
    bool press_moved_ = false;
    bool split_ = false, dragging_divider_ = false;
    float split_pos_ = 0.5f;
    Job::Output split_output_;
    fs::path browser_dir_;
};

}  // namespace

int run_viewer(const ViewOptions& options) {
    if (options.job->models.size() > 1) {
        print_error("view: one model or folder at a time");
        return kExitUsage;
    }
    std::optional<Job> defaults = job_from_options(*options.job, Job{});  // usage checks first (exit 2)
    if (!defaults) return kExitUsage;
    // A model, or a scene file read onto the flags' job with the flags given over it (a broken
    // scene file: exit 1 before the window opens).
    Diagnostics diag;
    std::optional<Job> job = job_from_sources(*options.job, options.cmd, diag, *defaults);
    if (!job) return kExitUsage;
    if (diag.total()) print_warnings(diag);
    std::vector<ScriptCommand> script;
    if (!options.script.empty()) script = read_view_script(options.script);  // FILE: line N: ... (exit 1)
    Viewer viewer(options, *job, *defaults, std::move(script));
    return viewer.run();
}

}  // namespace fresnel::cli
