// Windowed OpenGL through GLFW (used by `fresnel view`).
#include "fresnel/core/error.h"
#include "fresnel/gpu/context.h"
#include "fresnel/gpu/libraries.h"

#ifdef FRESNEL_HAVE_GLFW
#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace fresnel::gpu {
namespace {
// GLFW is initialised once for the process and glfwTerminate destroys every window, so each
// window holds a reference and the last one to go terminates GLFW (as EGL displays are counted
// in egl_context.cpp). GLFW is called from the main thread only; the count needs no lock.
int& glfw_references() {
    static int n = 0;
    return n;
}
void release_glfw() {
    if (--glfw_references() == 0) glfwTerminate();
}

class GlfwContext final : public Context {
public:
    explicit GlfwContext(GLFWwindow* w) : window_(w) {}
    ~GlfwContext() override {
        glfwDestroyWindow(window_);
        release_glfw();
    }
    void make_current() override { glfwMakeContextCurrent(window_); }
    void swap_buffers() override { glfwSwapBuffers(window_); }
    bool should_close() const override { return glfwWindowShouldClose(window_); }
    void poll_events() override { glfwPollEvents(); }
    void* native_window() const override { return window_; }
    void init(const ContextOptions& o) { init_context(o); }

private:
    GLFWwindow* window_;
};
// GLFW's own account of its last error ("X11: Failed to open display :3"), or "".
std::string glfw_reason() {
    const char* description = nullptr;
    glfwGetError(&description);
    return description ? std::string(": ") + description : std::string();
}
}  // namespace

std::unique_ptr<Context> create_window_context(int width, int height, const std::string& title,
                                               const ContextOptions& options) {
    // Before libepoxy's first call: it aborts the process when it cannot open a library.
    require_libraries(runtime_libraries(options.api, Windowing::Window));
    if (glfw_references() == 0 && !glfwInit())
        throw Error("GLFW", "", "cannot initialise GLFW (no display?)" + glfw_reason());
    ++glfw_references();
    const bool es = options.api == Api::OpenGLES30;
    glfwWindowHint(GLFW_CLIENT_API, es ? GLFW_OPENGL_ES_API : GLFW_OPENGL_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, es ? 0 : 3);
    if (!es) {
        glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
        glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    }
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, options.debug ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
    glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);  // high-DPI: the size is in unscaled screen units
    GLFWwindow* w = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!w) {
        const std::string reason = glfw_reason();
        release_glfw();
        throw Error("GLFW", "", std::string("cannot create an ") + api_name(options.api) + " window" + reason);
    }
    glfwMakeContextCurrent(w);
    auto c = std::make_unique<GlfwContext>(w);
    c->init(options);
    return c;
}

}  // namespace fresnel::gpu
#else
namespace fresnel::gpu {
std::unique_ptr<Context> create_window_context(int, int, const std::string&, const ContextOptions&) {
    throw Error("GLFW", "", "this build of fresnel has no window support (GLFW was not found)");
}
}  // namespace fresnel::gpu
#endif
