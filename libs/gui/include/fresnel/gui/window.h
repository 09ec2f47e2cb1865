#pragma once
// A window for the viewer: the GPU layer's GLFW context plus what a GUI needs on top of it
// (Dear ImGui frames, input keys, dropped files, clipboard, waiting for events). ImGui's
// widgets are used directly through <imgui.h>; everything GL or GLFW stays in this library.
#include <memory>
#include <string>
#include <vector>

#include "fresnel/gpu/context.h"

namespace fresnel::gui {

struct Size {
    int width = 0, height = 0;
};

// Keys the viewer binds (GLFW's codes inside).
enum class Key { F, R, PageUp, PageDown, F12, Escape, C, O, Tab, S, A, F5, Space, Q };

class Window {
public:
    // Opens a resizable window of `width` x `height` screen coordinates (scaled by the
    // monitor's content scale on high-DPI screens) with vsync, and starts ImGui on it.
    // Throws fresnel::Error when there is no display.
    Window(int width, int height, const std::string& title, const gpu::ContextOptions& options = {});
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    gpu::Context& context();
    Size framebuffer_size() const;  // pixels (what frames are rendered at)
    Size window_size() const;       // screen coordinates (what mouse positions are in)
    float content_scale() const;    // GUI scale for high-DPI monitors
    bool should_close() const;
    void request_close();
    void set_title(const std::string& title);

    // Returns when events arrived (or after timeout_s, when >= 0). wake() makes a waiting
    // call return; it may be called from any thread (a finished bake).
    void wait_events(double timeout_s = -1.0);
    void poll_events();
    static void wake();

    void begin_frame();  // a new ImGui frame
    void end_frame();    // draws the GUI over the back buffer
    void swap_buffers();

    // Pressed since the last end_frame() (ignored while ImGui types into a field).
    // ctrl: with Control held (and only then).
    bool key_pressed(Key key, bool ctrl = false) const;
    // Paths dropped onto the window since the last call.
    std::vector<std::string> take_dropped_paths();
    void set_clipboard(const std::string& text);

    struct Impl;  // public only for GLFW's C callbacks in window.cpp

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace fresnel::gui
