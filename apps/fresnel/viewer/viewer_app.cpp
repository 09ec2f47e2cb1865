// `fresnel view`: the window's loop, the environment bake, the frame and screenshots, and the
// script's side that needs them (viewer_app.h says where the rest is).
#include "viewer_app.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>

#include "fresnel/core/process_memory.h"
#include "fresnel/trace/job_inputs.h"
#include "fresnel/core/atomic_file.h"
#include "fresnel/gpu/device.h"
#include "fresnel/ibl/bake.h"

namespace fresnel::cli {
namespace view {

Image8 read_frame(int x0, int width, int height, bool alpha) {
    gpu::Device device;
    std::vector<std::uint8_t> px = device.read_default_rgba8(x0, 0, width, height);
    Image8 img(width, height, alpha ? 4 : 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::uint8_t* s = &px[(std::size_t(height - 1 - y) * std::size_t(width) + std::size_t(x)) * 4];
            std::uint8_t* d = img.at(x, y);
            for (int c = 0; c < img.channels; ++c) d[c] = s[c];
        }
    return img;
}

Viewer::Viewer(const ViewOptions& options, Job job, Job defaults, std::vector<viewer::Command> script)
    : options_(options), defaults_(std::move(defaults)), automation_(std::move(script), options.script) {
    state_.job = std::move(job);
    state_.initial_camera = state_.job.camera;
    state_.good_environment = state_.job.environment;
    window_size_ = {state_.job.output.width, state_.job.output.height};
    state_.start_with(options.job->models.empty() ? std::string() : options.job->models.front());
    state_.recent_file = ibl::cache_root() / "viewer-recent.txt";
    state_.load_recent();
}

int Viewer::run() {
    gui::Window window(window_size_.width, window_size_.height, "fresnel view", context_options(*options_.job));
    window_ = &window;
    renderer_ = std::make_unique<Renderer>(window.context());
    // Interactive windows, and --screenshot --with-gui (the window as a user sees it).
    dock_panel_ = (options_.script.empty() && !options_.frames && options_.screenshot.empty()) || options_.with_gui;
    ImGui::GetStyle().Colors[ImGuiCol_PopupBg].w = 1.0f;  // drop-downs and menus opaque over the frame
    if (dock_panel_ && state_.job.environment.use_cache) {  // the panel's width, kept between sessions
        imgui_ini_ = (ibl::cache_root() / "viewer-imgui.ini").string();
        std::ifstream in(imgui_ini_, std::ios::binary);
        const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        if (!text.empty() && text.size() < (1u << 20)) ImGui::LoadIniSettingsFromMemory(text.data(), text.size());
    }
    if (!options_.shaders.empty()) renderer_->set_shader_folder(options_.shaders);
    int rc = kExitBadInput;
    try {
        rc = loop(window);
    } catch (...) {
        release_gpu();
        throw;
    }
    if (!imgui_ini_.empty()) {  // the layout as it is at the end
        ImGui::GetIO().WantSaveIniSettings = true;
        save_gui_layout();
    }
    release_gpu();
    return rc;
}

// The panel's layout (ImGui's settings), written whole or not at all when ImGui asks, best
// effort (the layout is a convenience, never an error).
void Viewer::save_gui_layout() {
    ImGuiIO& io = ImGui::GetIO();
    if (imgui_ini_.empty() || !io.WantSaveIniSettings) return;
    io.WantSaveIniSettings = false;
    try {
        std::error_code ec;
        std::filesystem::create_directories(std::filesystem::path(imgui_ini_).parent_path(), ec);
        write_file_atomically(imgui_ini_, std::string_view(ImGui::SaveIniSettingsToMemory()));
    } catch (const std::exception&) {
    }
}

// GL objects go before the window (and its context) does.
void Viewer::release_gpu() {
    thumbnails_.clear();  // their textures (and any picture still being made)
    timer_.reset();
    renderer_.reset();
    window_ = nullptr;
}

int Viewer::loop(gui::Window& window) {
    const bool batch = options_.frames || !options_.screenshot.empty();
    const bool scripted = !options_.script.empty();
    const int frames_wanted = options_.frames.value_or(2);
    const glm::ivec2& fb = state_.framebuffer;
    bool opened = state_.first_scene_file.empty() ? load_job(state_.job, state_.opened) : open_scene_file(state_.first_scene_file);
    if (!opened && batch) return kExitBadInput;  // printed
    int ready_frames = 0, redraw = 3;
    while (!window.should_close()) {
        if (bake_ && redraw <= 0 && !batch && !automation_.pending()) {
            window.wait_events(0.5);  // the progress bar twice a second (or sooner on input)
            redraw = 1;
        }
        else if (bake_ || redraw > 0 || batch || automation_.pending() || moving()) window.poll_events();
        else if (options_.watch_shaders) {
            window.wait_events(0.5);  // idle, but the shader folder is looked at twice a second
            if (shaders_changed()) reload_shaders(""), redraw = 3;
            else continue;            // nothing to draw
        } else {
            window.wait_events();  // idle: no CPU until something happens
            redraw = 3;             // ImGui settles over a few frames
        }
        window.begin_frame();
        const gui::Size win = window.window_size();
        state_.window = {win.width, win.height};
        bool ready = false;
        try {
            if (handle_input()) redraw = 3;
            if (moving()) spin();
            else spin_last_.reset();
            draw_gui();
            reload_if_needed();
            sync_pose();
            if (sync_occlusion()) redraw = 3;
            const bool baking = bake_ != nullptr;
            ready = update_lighting();
            // The bake ended in this frame, whose panel was drawn before: draw a few more, or its
            // progress bar would stay until the next input.
            if (baking && !bake_) redraw = std::max(redraw, 3);
            draw_scene();
        } catch (const std::exception& e) {  // never die on input: show it, keep the window
            state_.error = e.what();
            std::fprintf(stderr, "fresnel: error: %s\n", e.what());
            if (batch) return kExitBadInput;
        }
        if (batch && !bake_ && bake_failed_) return kExitBadInput;  // printed by update_lighting()
        if (ready && state_.scene) ++ready_frames;
        if (scripted && automation_.pending()) {
            redraw = 3;
            if (automation_.step(state_, *this, ready)) {
                window.end_frame();
                window.swap_buffers();
                return automation_.failed() ? kExitBadInput : kExitOk;
            }
        }
        if (batch && ready && ready_frames >= frames_wanted) {
            if (options_.with_gui) window.end_frame();
            if (!options_.screenshot.empty()) {
                // With the GUI: the whole window; without: the 3D view.
                const int x0 = options_.with_gui ? 0 : state_.view_left_pixels();
                const int w = options_.with_gui ? fb.x : state_.view_pixels().x;
                write_png(options_.screenshot, read_frame(x0, w, fb.y, state_.last_transparent));
                std::fprintf(stderr, "fresnel: wrote %s (%dx%d)\n", options_.screenshot.c_str(), w, fb.y);
            }
            if (!options_.with_gui) window.end_frame();
            window.swap_buffers();
            return kExitOk;
        }
        if (state_.screenshot_requested) {
            state_.screenshot_requested = false;
            std::string path = screenshot_name();
            try {
                write_png(path, read_frame(state_.view_left_pixels(), state_.view_pixels().x, fb.y, state_.last_transparent));
                state_.status = "saved " + path;
                std::fprintf(stderr, "fresnel: wrote %s\n", path.c_str());
            } catch (const std::exception& e) {
                state_.error = e.what();
            }
        }
        window.end_frame();
        window.swap_buffers();
        save_gui_layout();
        --redraw;
    }
    return kExitOk;
}

// Starts, collects or restarts the environment bake for the current job; true when the
// lighting the job asks for is loaded.
bool Viewer::update_lighting() {
    if (!state_.scene) return false;
    const gui::Size size = window_->framebuffer_size();
    state_.framebuffer = {size.width, size.height};
    Job job = state_.shown_job();
    try {
        state_.resolved = resolve(job, *state_.scene);
    } catch (const std::exception& e) {  // e.g. a scene camera no node uses
        state_.error = e.what();
        state_.job.camera.scene_camera.reset();
        return false;
    }
    state_.bounds = state_.resolved.bounds;
    std::string key = lighting_key(state_.resolved);
    if (bake_ && bake_->result.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
        try {
            lighting_ = bake_->result.get();
            lighting_key_ = bake_->key;
            state_.good_environment = state_.job.environment;
            std::fprintf(stderr, "fresnel: lighting ready: %s\n",
                         bake_->resolved.environment ? bake_->resolved.environment->describe().c_str() : "none");
        } catch (const std::exception& e) {
            state_.error = e.what();
            std::fprintf(stderr, "fresnel: error: %s\n", e.what());
            bake_failed_ = true;
            automation_.mark_failed();
            if (automation_.env_line()) automation_.fail(*this, automation_.env_line(), "env failed");
            failed_key_ = bake_->key;
            if (key == bake_->key) {  // keep the environment that worked
                state_.job.environment = state_.good_environment;
            }
        }
        bake_.reset();
    }
    if (!bake_ && key != lighting_key_ && key != failed_key_) {
        bake_ = std::make_unique<Bake>();
        bake_->key = key;
        bake_->resolved = state_.resolved;
        auto progress = bake_->progress;
        ResolvedJob r = state_.resolved;
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

// A change of what the scene is loaded with (variant, disabled parts, pose skins, OBJ normals,
// the glTF scene: the job's Source but its animation, which is posed in place) from the panels or
// a script's `set`: the scene again, the view and the playback kept. A failure (a variant the
// file lacks) is shown and the loaded source stays.
void Viewer::reload_if_needed() {
    if (!state_.scene) return;
    Job::Source wanted = state_.job.source;
    wanted.animation = {};
    if (wanted == loaded_source_) return;
    const bool playing = state_.playback.playing;
    if (load_job(state_.job, state_.opened)) {
        state_.playback.playing = playing;
        return;
    }
    const Job::Source::Animation animation = state_.job.source.animation;
    state_.job.source = loaded_source_;
    state_.job.source.animation = animation;
    if (!options_.script.empty()) automation_.mark_failed();  // a script's `set` that did not load: exit 1, as open and env
}

bool Viewer::sync_occlusion() {
    if (!state_.scene) return false;
    const int wanted = state_.job.output.ao == AmbientOcclusion::Baked ? state_.job.output.ao_rays : 0;
    if (wanted == occlusion_rays_) return false;
    occlusion_rays_ = wanted;
    if (wanted == 0) {
        renderer_->set_vertex_occlusion(nullptr);
        return true;
    }
    if (!state_.scene->animations.empty()) {
        Diagnostics note;
        note.warn(state_.opened.empty() ? std::string("demo") : state_.opened, "render.ao baked",
                  "the file is animated: occlusion is baked for the pose shown");
        print_warnings(note);
    }
    const auto occlusion = trace::job_vertex_occlusion(state_.job, *state_.scene, state_.job.source.scene);  // resolve()'s scene_index
    renderer_->set_vertex_occlusion(occlusion ? &*occlusion : nullptr);
    return true;
}

// The scene posed at the time the state shows (job.source.animation), when that changed.
void Viewer::sync_pose() {
    if (!state_.scene) return;
    const Job::Source::Animation& a = state_.job.source.animation;
    std::optional<float> t;
    if (a.posed() && state_.animated()) t = a.at();
    try {
        posing_.show(*renderer_, a.index, t, state_.job.source.scene);  // resolve()'s scene_index
    } catch (const std::exception& e) {  // an animation index the file lacks: the rest pose
        state_.error = e.what();
        state_.job.source.animation = {};
        state_.playback.playing = false;
    }
}

void Viewer::draw_scene() {
    const gui::Size size = window_->framebuffer_size();
    state_.framebuffer = {size.width, size.height};
    const glm::ivec2 fb = state_.framebuffer;
    if (fb.x <= 0 || fb.y <= 0) return;  // minimised
    // No scene, or its first lighting still baking: a plain background under the progress bar.
    if (!state_.scene || lighting_key_ == kNoLighting) {
        gpu::Device device;
        device.bind_framebuffer(nullptr);
        device.viewport(0, 0, fb.x, fb.y);
        device.clear(glm::vec4(0.12f, 0.12f, 0.12f, 1.0f));
        return;
    }
    RenderSettings rs = lighting_.settings(state_.resolved);
    const glm::ivec2 view = state_.view_pixels();
    const int left = state_.view_left_pixels();
    rs.width = view.x;
    rs.height = view.y;
    rs.gpu_animation = posing_.gpu_animation();
    if (left > 0) {  // under the docked panel: the panel's colour, not last frame's pixels
        gpu::Device device;
        device.bind_framebuffer(nullptr);
        device.viewport(0, 0, fb.x, fb.y);
        device.clear(glm::vec4(0.06f, 0.06f, 0.06f, 1.0f));
    }
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
    renderer_->draw(state_.resolved.camera, state_.resolved.lights, rs, RenderTarget::default_framebuffer(left, 0), &stats_);
    if (state_.split) {  // the same frame with the right side's settings, over the right of the divider
        RenderSettings right = rs;
        right.debug = state_.split_output.debug;
        right.tone_mapper = state_.split_output.tone_mapper;
        right.exposure_ev = state_.split_output.exposure_ev;
        right.energy_compensation = state_.split_output.energy_compensation;
        RenderTarget target = RenderTarget::default_framebuffer(left, 0);
        int x = state_.divider_pixels();
        target.scissor = RenderTarget::Rect{x, 0, fb.x - x, fb.y};
        FrameStats more;
        renderer_->draw(state_.resolved.camera, state_.resolved.lights, right, target, &more);
        stats_.draw_calls += more.draw_calls;
        stats_.triangles += more.triangles;
        stats_.gl_errors += more.gl_errors;
    }
    if (timer_) timer_->end();
    renderer_->finish();
    frame_ms_ = ms_since(t);
    if (double ms = 0.0; timer_ && timer_->result_ms(ms)) gpu_ms_ = ms;
    state_.last_camera = state_.resolved.camera;
    state_.last_transparent = state_.resolved.transparent();
    if (!stats_.gl_errors.empty()) state_.error = "OpenGL: the frame raised " + stats_.gl_errors;
}

// --- the script's side (viewer::AutomationHost) ---------------------------------------

void Viewer::screenshot(const std::string& path) {
    const glm::ivec2 fb = state_.framebuffer;
    write_png(path, read_frame(state_.view_left_pixels(), state_.view_pixels().x, fb.y, state_.last_transparent));
    std::fprintf(stderr, "fresnel: wrote %s (%dx%d)\n", path.c_str(), state_.view_pixels().x, fb.y);
}

void Viewer::set_material_field(Material& material, const std::string& field, const std::vector<float>& values) {
    viewer::set_material_field(material, field, values);
    posing_.keep_materials();  // the playback keeps the edits
}

std::string Viewer::stats() {
    std::string gpu = gpu_ms_ >= 0.0 ? std::to_string(gpu_ms_) : std::string("null");
    gpu::LiveObjects gl = gpu::Device().live_objects();
    char line[1024];
    std::snprintf(line, sizeof line,
                  "{\"frame_ms\":%.2f,\"gpu_ms\":%s,\"width\":%d,\"height\":%d,\"draw_calls\":%d,"
                  "\"triangles\":%zu,\"programs\":%zu,\"rss_kb\":%ld,\"texture_bytes\":%zu,\"gl_objects\":{\"total\":%d,"
                  "\"buffers\":%d,\"vertex_arrays\":%d,\"textures\":%d,\"renderbuffers\":%d,"
                  "\"framebuffers\":%d,\"programs\":%d,\"shaders\":%d}}",
                  frame_ms_, gpu.c_str(), state_.framebuffer.x, state_.framebuffer.y, stats_.draw_calls, stats_.triangles,
                  renderer_->program_count(), long(resident_mib() * 1024.0), renderer_->texture_bytes(), gl.total(), gl.buffers, gl.vertex_arrays,
                  gl.textures, gl.renderbuffers, gl.framebuffers, gl.programs, gl.shaders);
    return line;
}

std::string Viewer::render_command_line(const Job& job) { return cli::render_command_line(job, "view.png"); }

void Viewer::print(const std::string& line) {
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
}

void Viewer::report_error(const std::string& message) { std::fprintf(stderr, "fresnel: error: %s\n", message.c_str()); }

}  // namespace view

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
    std::vector<viewer::Command> script;
    if (!options.script.empty())  // FILE: line N: ... (exit 1)
        script = viewer::read_view_script(options.script);
    view::Viewer viewer(options, *job, *defaults, std::move(script));
    return viewer.run();
}

}  // namespace fresnel::cli
