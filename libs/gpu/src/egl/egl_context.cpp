// Headless OpenGL through EGL, without any window system.
#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "fresnel/core/error.h"
#include "fresnel/gpu/context.h"
#include "fresnel/gpu/libraries.h"

namespace fresnel::gpu {
namespace {

// eglInitialize and eglTerminate do not count (EGL 1.5): every context of the process that asks
// for the default display gets the same handle, so one context terminating it pulled it from
// under the others (`fresnel batch --jobs 2`: a worker still deleting its GL objects found no
// current context, and libepoxy aborted). Each context holds a reference to its display instead,
// and the last one to go terminates it. The count is the process's, as the display is.
class DisplayReferences {
public:
    // eglInitialize on the first reference; false (no reference taken) when it fails.
    static bool acquire(EGLDisplay display) {
        std::lock_guard lock(mutex());
        int& n = counts()[display];
        if (n == 0) {
            EGLint major = 0, minor = 0;
            if (!eglInitialize(display, &major, &minor)) return false;
        }
        ++n;
        return true;
    }
    // eglTerminate with the last reference.
    static void release(EGLDisplay display) {
        std::lock_guard lock(mutex());
        auto it = counts().find(display);
        if (it == counts().end() || it->second <= 0) return;
        if (--it->second == 0) {
            eglTerminate(display);
            counts().erase(it);
        }
    }

private:
    // Never destroyed: a context that outlives static destruction (one held in a static) can
    // still release its reference.
    static std::mutex& mutex() {
        static auto* m = new std::mutex;
        return *m;
    }
    static std::map<EGLDisplay, int>& counts() {
        static auto* c = new std::map<EGLDisplay, int>;
        return *c;
    }
};

class EglContext final : public Context {
public:
    EglContext(EGLDisplay display, EGLContext context, EGLSurface surface)
        : display_(display), context_(context), surface_(surface) {}
    ~EglContext() override {
        // Unbound only where it is current: another context current on this thread stays so.
        if (eglGetCurrentContext() == context_) {
            eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            eglReleaseThread();  // this thread's EGL state
        }
        if (surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, surface_);
        eglDestroyContext(display_, context_);
        DisplayReferences::release(display_);
    }
    void make_current() override {
        if (!eglMakeCurrent(display_, surface_, surface_, context_)) throw Error("EGL", "", "eglMakeCurrent failed");
    }
    void init(const ContextOptions& o) { init_context(o); }

private:
    EGLDisplay display_;
    EGLContext context_;
    EGLSurface surface_;
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

struct Created {
    EGLContext context = EGL_NO_CONTEXT;
    EGLSurface surface = EGL_NO_SURFACE;
};

// A context and its surface on `display`, made current; the caller holds a display reference.
Created try_create(EGLDisplay display, const ContextOptions& options) {
    const bool es = options.api == Api::OpenGLES30;
    if (!eglBindAPI(es ? EGL_OPENGL_ES_API : EGL_OPENGL_API)) return {};
    const bool surface = options.surface_width > 0 && options.surface_height > 0;
    EGLConfig config = nullptr;
    const EGLint renderable = es ? EGL_OPENGL_ES3_BIT : EGL_OPENGL_BIT;
    const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, renderable, EGL_NONE};
    const EGLint pbuffer_config_attribs[] = {EGL_RENDERABLE_TYPE, renderable, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT,
                                             EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 8,
                                             EGL_NONE};
    EGLint count = 0;
    bool no_config = !surface && epoxy_has_egl_extension(display, "EGL_KHR_no_config_context");
    if (!eglChooseConfig(display, surface ? pbuffer_config_attribs : config_attribs, &config, 1, &count) || count == 0) {
        if (!no_config) return {};
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
    if (ctx == EGL_NO_CONTEXT) return {};
    EGLSurface surf = EGL_NO_SURFACE;
    if (surface) {
        const EGLint pbuffer_attribs[] = {EGL_WIDTH, options.surface_width, EGL_HEIGHT, options.surface_height, EGL_NONE};
        surf = eglCreatePbufferSurface(display, config, pbuffer_attribs);
        if (surf == EGL_NO_SURFACE) {
            eglDestroyContext(display, ctx);
            return {};
        }
    }
    if (!eglMakeCurrent(display, surf, surf, ctx)) {
        if (surf != EGL_NO_SURFACE) eglDestroySurface(display, surf);
        eglDestroyContext(display, ctx);
        return {};
    }
    return {ctx, surf};
}

}  // namespace

std::unique_ptr<Context> create_headless_context(const ContextOptions& options) {
    // Before libepoxy's first call: it aborts the process when it cannot open a library.
    require_libraries(runtime_libraries(options.api, Windowing::Headless));
    for (EGLDisplay display : candidate_displays()) {
        if (!DisplayReferences::acquire(display)) continue;
        Created made = try_create(display, options);
        if (made.context != EGL_NO_CONTEXT) {
            auto c = std::make_unique<EglContext>(display, made.context, made.surface);  // holds the reference
            c->init(options);
            return c;
        }
        DisplayReferences::release(display);
    }
    throw Error("EGL", "", std::string("no headless ") + api_name(options.api) +
                               " context could be created (is Mesa's libegl-mesa0 installed?)");
}

}  // namespace fresnel::gpu
