// Headless OpenGL through EGL, without any window system.
#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <string>
#include <vector>

#include "fresnel/core/error.h"
#include "fresnel/gpu/context.h"

namespace fresnel::gpu {
namespace {

class EglContext final : public Context {
public:
    EglContext(EGLDisplay display, EGLContext context) : display_(display), context_(context) {}
    ~EglContext() override {
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display_, context_);
        eglTerminate(display_);
    }
    void make_current() override {
        if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
            throw Error("EGL", "", "eglMakeCurrent failed");
    }
    void init(const ContextOptions& o) { init_context(o); }

private:
    EGLDisplay display_;
    EGLContext context_;
};

bool client_has(const char* ext) { return epoxy_has_egl_extension(EGL_NO_DISPLAY, ext); }

// Candidate displays, best first.
std::vector<EGLDisplay> candidate_displays() {
    std::vector<EGLDisplay> out;
    if (client_has("EGL_EXT_platform_base")) {
        if (client_has("EGL_MESA_platform_surfaceless")) {
            EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
            if (d != EGL_NO_DISPLAY) out.push_back(d);
        }
        if (client_has("EGL_EXT_platform_device") && client_has("EGL_EXT_device_enumeration")) {
            EGLDeviceEXT devices[16];
            EGLint n = 0;
            if (eglQueryDevicesEXT(16, devices, &n))
                for (EGLint i = 0; i < n; ++i) {
                    EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
                    if (d != EGL_NO_DISPLAY) out.push_back(d);
                }
        }
    }
    EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (d != EGL_NO_DISPLAY) out.push_back(d);
    return out;
}

EGLContext try_create(EGLDisplay display, const ContextOptions& options) {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) return EGL_NO_CONTEXT;
    const bool es = options.api == Api::OpenGLES30;
    if (!eglBindAPI(es ? EGL_OPENGL_ES_API : EGL_OPENGL_API)) return EGL_NO_CONTEXT;
    EGLConfig config = nullptr;
    const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, es ? EGL_OPENGL_ES3_BIT : EGL_OPENGL_BIT, EGL_NONE};
    EGLint count = 0;
    bool no_config = epoxy_has_egl_extension(display, "EGL_KHR_no_config_context");
    if (!eglChooseConfig(display, config_attribs, &config, 1, &count) || count == 0) {
        if (!no_config) return EGL_NO_CONTEXT;
        config = EGL_NO_CONFIG_KHR;
    }
    const EGLint debug = options.debug ? EGL_TRUE : EGL_FALSE;
    const EGLint gl_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3,
                                 EGL_CONTEXT_MINOR_VERSION, 3,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                 EGL_CONTEXT_OPENGL_DEBUG, debug,
                                 EGL_NONE};
    const EGLint es_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 0,
                                 EGL_CONTEXT_OPENGL_DEBUG, debug, EGL_NONE};
    EGLContext ctx = eglCreateContext(display, config, EGL_NO_CONTEXT, es ? es_attribs : gl_attribs);
    if (ctx == EGL_NO_CONTEXT) return ctx;
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
        eglDestroyContext(display, ctx);
        return EGL_NO_CONTEXT;
    }
    return ctx;
}

}  // namespace

std::unique_ptr<Context> create_headless_context(const ContextOptions& options) {
    for (EGLDisplay display : candidate_displays()) {
        EGLContext ctx = try_create(display, options);
        if (ctx != EGL_NO_CONTEXT) {
            auto c = std::make_unique<EglContext>(display, ctx);
            c->init(options);
            return c;
        }
        eglTerminate(display);
    }
    throw Error("EGL", "", std::string("no headless ") + api_name(options.api) +
                               " context could be created (is Mesa's libegl-mesa0 installed?)");
}

}  // namespace fresnel::gpu
