// `fresnel view`: mouse and keys (the camera through fresnel/job/orbit_controller.h, picks and
// light drags through the viewer state), auto-rotation's clock, the command line copy.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>

#include "fresnel/job/orbit_controller.h"
#include "viewer_app.h"

namespace fresnel::cli::view {

// Mouse and keys; true when something may have changed.
bool Viewer::handle_input() {
    bool changed = false;
    for (const auto& p : window_->take_dropped_paths()) {
        open_path(p);
        changed = true;
    }
    ImGuiIO& io = ImGui::GetIO();
    gui::Size win = window_->window_size();
    const glm::ivec2 fb = state_.framebuffer;
    float to_pixels = win.width > 0 ? float(fb.x) / float(win.width) : 1.0f;  // high-DPI
    OrbitViewport view = state_.viewport();
    Job::Camera& camera = state_.job.camera;
    if (state_.split && !io.WantCaptureMouse) {
        float x = io.MousePos.x * to_pixels;
        if (io.MouseClicked[0] && std::abs(x - float(state_.divider_pixels())) <= 6.0f * to_pixels) dragging_divider_ = true;
        if (!io.MouseDown[0]) dragging_divider_ = false;
        if (dragging_divider_) {
            state_.split_pos = std::clamp(state_.in_view({io.MousePos.x, 0.0f}).x / float(state_.view_points().x), 0.0f, 1.0f);
            return true;
        }
    }
    const glm::vec2 mouse(io.MousePos.x, io.MousePos.y);
    if (!io.WantCaptureMouse && state_.drag_lights(mouse, io.MouseClicked[0] && !io.KeyShift, io.MouseDown[0])) return true;
    if (!io.WantCaptureMouse && io.MouseClicked[0]) press_at_ = mouse, press_moved_ = false;
    if (io.MouseDown[0] && glm::distance(mouse, press_at_) > 3.0f) press_moved_ = true;
    if (!io.WantCaptureMouse && io.MouseReleased[0] && !press_moved_ && !io.KeyShift) {
        state_.pick_at(press_at_);  // a click, not a drag: select what is under it
        changed = true;
    }
    if (!io.WantCaptureMouse) {
        float dx = io.MouseDelta.x, dy = io.MouseDelta.y;
        bool moved = (dx != 0.0f || dy != 0.0f) && io.MouseDelta.x > -1e6f;
        bool pan_drag = io.MouseDown[1] || io.MouseDown[2] || (io.MouseDown[0] && io.KeyShift);
        if (moved && pan_drag) {
            state_.orbit_camera_now();
            camera = pan(camera, view, dx * to_pixels, dy * to_pixels);
            changed = true;
        } else if (moved && io.MouseDown[0]) {
            state_.orbit_camera_now();
            camera = orbit(camera, dx, dy);
            changed = true;
        }
        if (io.MouseWheel != 0.0f) {
            state_.orbit_camera_now();
            camera = dolly(camera, view, dolly_factor(io.MouseWheel));
            changed = true;
        }
    }
    if (!io.WantTextInput) {
        if (window_->key_pressed(gui::Key::F)) camera = frame_all(camera), changed = true;
        if (window_->key_pressed(gui::Key::R)) camera = state_.initial_camera, changed = true;
        if (window_->key_pressed(gui::Key::PageDown)) step_folder(+1), changed = true;
        if (window_->key_pressed(gui::Key::PageUp)) step_folder(-1), changed = true;
        if (window_->key_pressed(gui::Key::F12)) state_.screenshot_requested = true, changed = true;
        if (window_->key_pressed(gui::Key::O)) state_.browser_open = true, changed = true;
        if (window_->key_pressed(gui::Key::C, /*ctrl=*/true)) copy_command_line(), changed = true;
        if (window_->key_pressed(gui::Key::Escape) || window_->key_pressed(gui::Key::Q)) window_->request_close();
        if (window_->key_pressed(gui::Key::Tab)) state_.gui_visible = !state_.gui_visible, changed = true;
        if (window_->key_pressed(gui::Key::S, /*ctrl=*/true)) save_scene(state_.scene_save_path), changed = true;
        if (window_->key_pressed(gui::Key::A)) state_.spin_camera = !state_.spin_camera, changed = true;
        if (window_->key_pressed(gui::Key::F5)) reload_shaders(""), changed = true;
        if (window_->key_pressed(gui::Key::Space) && state_.animated()) state_.play(!state_.playback.playing), changed = true;
    }
    return changed;
}

// Turns the camera (about the target), the environment and the added lights by 30 degrees a
// second of the clock, as switched on, and plays the animation.
void Viewer::spin() {
    auto now = Clock::now();
    double dt = spin_last_ ? std::chrono::duration<double>(now - *spin_last_).count() : 0.0;
    spin_last_ = now;
    state_.spin(dt);
    state_.advance(dt);
}

void Viewer::copy_command_line() {
    state_.command_line = render_command_line(state_.shown_job());
    window_->set_clipboard(state_.command_line);
    std::printf("%s\n", state_.command_line.c_str());
    if (state_.materials_edited)
        std::fprintf(stderr, "fresnel: note: the material edits are not part of the command line (save the scene: Ctrl+S)\n");
    std::fflush(stdout);
}

std::string Viewer::screenshot_name() const {
    std::time_t t = std::time(nullptr);
    char buf[64];
    std::strftime(buf, sizeof buf, "fresnel-%Y%m%d-%H%M%S.png", std::localtime(&t));
    return buf;
}

}  // namespace fresnel::cli::view
