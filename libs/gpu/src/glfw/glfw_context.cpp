// Windowed OpenGL through GLFW (used by `fresnel view`).
#include "fresnel/core/error.h"
#include "fresnel/gpu/context.h"

#ifdef FRESNEL_HAVE_GLFW
#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace fresnel::gpu {
namespace {
class GlfwContext final : public Context {
public:
    explicit GlfwContext(GLFWwindow* w) : window_(w) {}
    ~GlfwContext() override {
        glfwDestroyWindow(window_);
        glfwTerminate();
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
    if (!glfwInit()) throw Error("GLFW", "", "cannot initialise GLFW (no display?)" + glfw_reason());
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
        glfwTerminate();
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
