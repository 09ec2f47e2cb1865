// The web build: a WebGL 2 context on a canvas (Emscripten's html5 API), OpenGL ES 3.0 to
// the rest of libs/gpu. Built instead of egl/ and glfw/ when compiling with Emscripten.
#include <emscripten/html5.h>

#include "../gl.h"
#include "fresnel/core/error.h"
#include "fresnel/gpu/context.h"

namespace fresnel::gpu {
namespace {

class WebGlContext final : public Context {
public:
    explicit WebGlContext(EMSCRIPTEN_WEBGL_CONTEXT_HANDLE handle) : handle_(handle) {}
    ~WebGlContext() override { emscripten_webgl_destroy_context(handle_); }
    void make_current() override {
        if (emscripten_webgl_make_context_current(handle_) != EMSCRIPTEN_RESULT_SUCCESS)
            throw Error("WebGL", "", "cannot make the WebGL 2 context current");
    }
    void init(const ContextOptions& o) { init_context(o); }

private:
    EMSCRIPTEN_WEBGL_CONTEXT_HANDLE handle_;
};

}  // namespace

std::unique_ptr<Context> create_webgl_context(const std::string& canvas_selector, const ContextOptions& options) {
    EmscriptenWebGLContextAttributes attrs;
    emscripten_webgl_init_context_attributes(&attrs);
    attrs.majorVersion = 2;
    attrs.minorVersion = 0;
    attrs.alpha = true;        // transparent backgrounds show the page
    attrs.premultipliedAlpha = false;  // the output pass writes straight alpha
    attrs.depth = false;       // frames are drawn into the renderer's own target, then copied here
    attrs.stencil = false;
    attrs.antialias = false;   // the renderer's own MSAA
    attrs.preserveDrawingBuffer = true;  // the frame stays readable (screenshots, tests)
    attrs.enableExtensionsByDefault = true;
    attrs.powerPreference = EM_WEBGL_POWER_PREFERENCE_HIGH_PERFORMANCE;
    EMSCRIPTEN_WEBGL_CONTEXT_HANDLE h = emscripten_webgl_create_context(canvas_selector.c_str(), &attrs);
    if (h <= 0) throw Error("WebGL", canvas_selector, "this browser gives no WebGL 2 context for the canvas");
    if (emscripten_webgl_make_context_current(h) != EMSCRIPTEN_RESULT_SUCCESS) {
        emscripten_webgl_destroy_context(h);
        throw Error("WebGL", canvas_selector, "cannot make the WebGL 2 context current");
    }
    // What fresnel uses when present (Capabilities reports each): float colour targets, linear
    // filtering of float textures, anisotropic filtering.
    for (const char* ext : {"EXT_color_buffer_float", "EXT_color_buffer_half_float", "OES_texture_float_linear",
                            "EXT_texture_filter_anisotropic", "EXT_float_blend"})
        emscripten_webgl_enable_extension(h, ext);
    auto c = std::make_unique<WebGlContext>(h);
    c->init(options);
    return c;
}

std::unique_ptr<Context> create_headless_context(const ContextOptions& options) {
    throw Error("EGL", "", std::string("no headless ") + api_name(options.api) +
                               " context in the web build (use create_webgl_context)");
}

std::unique_ptr<Context> create_window_context(int, int, const std::string&, const ContextOptions&) {
    throw Error("GLFW", "", "no windows in the web build (use create_webgl_context)");
}

}  // namespace fresnel::gpu
