#pragma once
// An OpenGL context, headless (EGL), windowed (GLFW) or a web page's canvas (WebGL 2, the
// Emscripten build), behind one interface.
// Everything above the GPU layer talks to the GPU only through fresnel/gpu/*.h.
#include <functional>
#include <memory>
#include <string>

namespace fresnel::gpu {

using LogFn = std::function<void(const std::string&)>;

// The API a context speaks. fresnel's GL use is OpenGL 3.3 core ∩ OpenGL ES 3.0; what
// differs between the two is reported by Capabilities and handled inside libs/gpu.
enum class Api { OpenGL33, OpenGLES30 };
const char* api_name(Api api);  // "OpenGL 3.3 core", "OpenGL ES 3.0"

struct ContextOptions {
    Api api = Api::OpenGL33;
    bool debug = false;  // KHR_debug messages to `log` (when the driver has KHR_debug)
    LogFn log;           // where driver messages (and capability fallbacks) go; default: ignored
    // Headless contexts: > 0 gives the context a default framebuffer of this size (an EGL
    // pbuffer), which stands in for a window's in tests of RenderTarget::DefaultFramebuffer.
    int surface_width = 0, surface_height = 0;
};

// What the context can do, queried once when it is made.
struct Capabilities {
    Api api = Api::OpenGL33;
    // Colour render targets: RGBA16F / RGBA32F renderable (always on GL 3.3; on ES 3.0
    // behind EXT_color_buffer_float, RGBA16F alone behind EXT_color_buffer_half_float).
    bool float_color_targets = true;
    bool half_float_color_targets = true;
    // Linear filtering of 32-bit float textures (GL 3.3; OES_texture_float_linear on ES).
    bool float_linear_filtering = true;
    float max_anisotropy = 1.0f;  // 1 when EXT/ARB_texture_filter_anisotropic is absent
    int max_samples = 0;          // GL_MAX_SAMPLES
    // Largest MSAA sample count of the HDR colour target's format: RGBA16F, or RGBA8 where
    // half-float targets are missing.
    int max_samples_float = 0;
    bool seamless_cube_maps = true;  // desktop: enabled once at creation; ES 3.0 filters seamlessly always
    bool debug_output = false;       // KHR_debug
    int max_texture_units = 16;      // GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS
    int max_texture_size = 2048;     // GL_MAX_TEXTURE_SIZE (OpenGL ES 3.0 guarantees 2048)
    // Units a fragment shader can sample (GL_MAX_TEXTURE_IMAGE_UNITS; OpenGL 3.3 and ES 3.0
    // guarantee 16).
    int max_fragment_texture_units = 16;
    // Multisampled textures (texelFetch on sampler2DMS): OpenGL 3.2+, not OpenGL ES 3.0.
    bool multisample_textures = true;
    int max_color_texture_samples = 0;  // GL_MAX_COLOR_TEXTURE_SAMPLES (0 on ES 3.0)
    // GPU timer queries (GL_TIME_ELAPSED, TimerQuery): core in OpenGL 3.3; not in ES 3.0
    // (EXT_disjoint_timer_query there is not used).
    bool timer_queries = false;
    // Immutable texture storage (glTexStorage2D): core in ES 3.0 and GL 4.2, ARB_texture_storage
    // before. Mip chains uploaded level by level are then allocated once, at their final size.
    bool texture_storage = false;
};

class Context {
public:
    virtual ~Context() = default;
    virtual void make_current() = 0;
    // For windowed contexts: present the back buffer / poll events / should close.
    virtual void swap_buffers() {}
    virtual bool should_close() const { return false; }
    virtual void poll_events() {}
    // Windowed contexts: the native window (a GLFWwindow*) for a GUI layer (libs/gui); else nullptr.
    virtual void* native_window() const { return nullptr; }

    std::string renderer() const;  // GL_RENDERER
    std::string version() const;   // GL_VERSION
    bool has_extension(const char* name) const;
    const Capabilities& capabilities() const { return caps_; }
    Api api() const { return caps_.api; }

protected:
    // Called by each backend once its context is current: queries the capabilities, sets
    // the state fresnel keeps for the context's life (seamless cube maps on desktop) and
    // installs the debug callback.
    void init_context(const ContextOptions& options);
    ContextOptions options_;
    Capabilities caps_;
};

// Headless OpenGL 3.3 core (or, with options.api = OpenGLES30, OpenGL ES 3.0) through
// EGL: the Mesa surfaceless platform first (llvmpipe in CI), then the EGL device
// platform (GPU drivers), then the default display. Throws fresnel::Error when no
// context can be made.
std::unique_ptr<Context> create_headless_context(const ContextOptions& options = {});

// A window with an OpenGL 3.3 core (or ES 3.0) context (GLFW). Throws when no display is available.
std::unique_ptr<Context> create_window_context(int width, int height, const std::string& title,
                                               const ContextOptions& options = {});

// The web build (Emscripten): a WebGL 2 context on the page's canvas `canvas_selector`
// (a CSS selector such as "#canvas"), speaking OpenGL ES 3.0; its default framebuffer is the
// canvas (kept after presenting, so the page can read it back). Throws fresnel::Error when
// the browser has no WebGL 2. In the desktop build it throws (there is no canvas); in the web
// build create_headless_context and create_window_context throw.
std::unique_ptr<Context> create_webgl_context(const std::string& canvas_selector, const ContextOptions& options = {});

}  // namespace fresnel::gpu
