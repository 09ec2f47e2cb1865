#include "fresnel/gui/window.h"

#include <algorithm>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include "fresnel/core/error.h"

namespace fresnel::gui {

struct Window::Impl {
    std::unique_ptr<gpu::Context> context;
    GLFWwindow* window = nullptr;
    ImGuiContext* imgui = nullptr;
    std::vector<std::string> dropped;
    // Keys pressed since the last end_frame(), from GLFW's callback: ImGui 1.86 reads key
    // state once per frame, so a press and release within one frame (a quick tap, xdotool)
    // would be lost to ImGui::IsKeyPressed.
    struct Press {
        int key, mods;
    };
    std::vector<Press> pressed;
    bool imgui_glfw = false, imgui_gl = false;
};

namespace {
void on_drop(GLFWwindow* w, int count, const char** paths) {
    auto* impl = static_cast<Window::Impl*>(glfwGetWindowUserPointer(w));
    if (!impl) return;
    for (int i = 0; i < count; ++i) impl->dropped.emplace_back(paths[i]);
}
void on_key(GLFWwindow* w, int key, int, int action, int mods) {
    auto* impl = static_cast<Window::Impl*>(glfwGetWindowUserPointer(w));
    if (impl && action == GLFW_PRESS) impl->pressed.push_back({key, mods});
}
int glfw_key(Key k) {
    switch (k) {
        case Key::F: return GLFW_KEY_F;
        case Key::R: return GLFW_KEY_R;
        case Key::PageUp: return GLFW_KEY_PAGE_UP;
        case Key::PageDown: return GLFW_KEY_PAGE_DOWN;
        case Key::F12: return GLFW_KEY_F12;
        case Key::Escape: return GLFW_KEY_ESCAPE;
        case Key::C: return GLFW_KEY_C;
        case Key::O: return GLFW_KEY_O;
        case Key::Tab: return GLFW_KEY_TAB;
        case Key::S: return GLFW_KEY_S;
        case Key::A: return GLFW_KEY_A;
        case Key::F5: return GLFW_KEY_F5;
        case Key::Space: return GLFW_KEY_SPACE;
        case Key::Q: return GLFW_KEY_Q;
    }
    return GLFW_KEY_UNKNOWN;
}
}  // namespace

Window::Window(int width, int height, const std::string& title, const gpu::ContextOptions& options)
    : impl_(std::make_unique<Impl>()) {
    impl_->context = gpu::create_window_context(width, height, title, options);
    impl_->window = static_cast<GLFWwindow*>(impl_->context->native_window());
    if (!impl_->window) throw Error("GLFW", "", "the window context has no native window");
    glfwSetWindowUserPointer(impl_->window, impl_.get());
    glfwSetDropCallback(impl_->window, on_drop);
    glfwSetKeyCallback(impl_->window, on_key);  // before ImGui's, which chains to it
    glfwSwapInterval(1);  // vsync

    IMGUI_CHECKVERSION();
    impl_->imgui = ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // no imgui.ini in the working folder
    float scale = content_scale();
    if (scale > 1.0f) {
        ImGui::GetStyle().ScaleAllSizes(scale);
        io.FontGlobalScale = scale;
    }
    // Chains to the key callback above (drop is not one ImGui installs).
    impl_->imgui_glfw = ImGui_ImplGlfw_InitForOpenGL(impl_->window, true);
    const bool es = options.api == gpu::Api::OpenGLES30;
    impl_->imgui_gl = ImGui_ImplOpenGL3_Init(es ? "#version 300 es" : "#version 330 core");
    if (!impl_->imgui_glfw || !impl_->imgui_gl) throw Error("ImGui", "", "cannot start Dear ImGui on the window");
}

Window::~Window() {
    if (impl_->imgui_gl) ImGui_ImplOpenGL3_Shutdown();
    if (impl_->imgui_glfw) ImGui_ImplGlfw_Shutdown();
    if (impl_->imgui) ImGui::DestroyContext(impl_->imgui);
    if (impl_->window) glfwSetWindowUserPointer(impl_->window, nullptr);
    impl_->context.reset();  // destroys the window
}

gpu::Context& Window::context() { return *impl_->context; }

Size Window::framebuffer_size() const {
    Size s;
    glfwGetFramebufferSize(impl_->window, &s.width, &s.height);
    return s;
}
Size Window::window_size() const {
    Size s;
    glfwGetWindowSize(impl_->window, &s.width, &s.height);
    return s;
}
float Window::content_scale() const {
    float x = 1.0f, y = 1.0f;
    glfwGetWindowContentScale(impl_->window, &x, &y);
    return std::max(x, y);
}
bool Window::should_close() const { return glfwWindowShouldClose(impl_->window); }
void Window::request_close() { glfwSetWindowShouldClose(impl_->window, GLFW_TRUE); }
void Window::set_title(const std::string& title) { glfwSetWindowTitle(impl_->window, title.c_str()); }

void Window::wait_events(double timeout_s) {
    if (timeout_s < 0) glfwWaitEvents();
    else glfwWaitEventsTimeout(timeout_s);
}
void Window::poll_events() { glfwPollEvents(); }
void Window::wake() { glfwPostEmptyEvent(); }

void Window::begin_frame() {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}
void Window::end_frame() {
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    impl_->pressed.clear();
}
void Window::swap_buffers() { impl_->context->swap_buffers(); }

bool Window::key_pressed(Key key, bool ctrl) const {
    if (ImGui::GetIO().WantTextInput) return false;
    return std::any_of(impl_->pressed.begin(), impl_->pressed.end(), [&](const Impl::Press& p) {
        return p.key == glfw_key(key) && ((p.mods & GLFW_MOD_CONTROL) != 0) == ctrl;
    });
}

std::vector<std::string> Window::take_dropped_paths() {
    std::vector<std::string> out;
    out.swap(impl_->dropped);
    return out;
}
void Window::set_clipboard(const std::string& text) { glfwSetClipboardString(impl_->window, text.c_str()); }

}  // namespace fresnel::gui
