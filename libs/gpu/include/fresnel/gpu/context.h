#pragma once
// An OpenGL context, headless (EGL) or windowed (GLFW), behind one interface.
// Everything above the GPU layer talks to the GPU only through fresnel/gpu/*.h.
#include <functional>
#include <memory>
#include <string>

namespace fresnel::gpu {

using LogFn = std::function<void(const std::string&)>;

struct ContextOptions {
    bool debug = false;  // KHR_debug messages to `log` (when the driver has KHR_debug)
    LogFn log;           // where driver messages go; default: ignored
};

class Context {
public:
    virtual ~Context() = default;
    virtual void make_current() = 0;
    // For windowed contexts: present the back buffer / poll events / should close.
    virtual void swap_buffers() {}
    virtual bool should_close() const { return false; }
    virtual void poll_events() {}

    std::string renderer() const;  // GL_RENDERER
    std::string version() const;   // GL_VERSION
    bool has_extension(const char* name) const;

protected:
    void install_debug_output(const ContextOptions& options);
    ContextOptions options_;
};

// Headless OpenGL 3.3 core through EGL: the Mesa surfaceless platform first
// (llvmpipe in CI), then the EGL device platform (GPU drivers), then the default
// display. Throws fresnel::Error when no context can be made.
std::unique_ptr<Context> create_headless_context(const ContextOptions& options = {});

// A window with an OpenGL 3.3 core context (GLFW). Throws when no display is available.
std::unique_ptr<Context> create_window_context(int width, int height, const std::string& title,
                                               const ContextOptions& options = {});

}  // namespace fresnel::gpu
