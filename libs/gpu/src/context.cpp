#include "fresnel/gpu/context.h"

#include "gl.h"

#include <algorithm>
#include <cstring>

#include "fresnel/core/error.h"

namespace fresnel::gpu {

const char* api_name(Api api) { return api == Api::OpenGLES30 ? "OpenGL ES 3.0" : "OpenGL 3.3 core"; }

std::string Context::renderer() const {
    const GLubyte* s = glGetString(GL_RENDERER);
    return s ? reinterpret_cast<const char*>(s) : "";
}
std::string Context::version() const {
    const GLubyte* s = glGetString(GL_VERSION);
    return s ? reinterpret_cast<const char*>(s) : "";
}
bool Context::has_extension(const char* name) const { return gl::has_extension(name); }

namespace {
void GLAPIENTRY debug_callback(GLenum, GLenum type, GLuint, GLenum severity, GLsizei, const GLchar* message,
                               const void* user) {
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
    auto* log = static_cast<const LogFn*>(user);
    if (log && *log) (*log)(std::string("GL: ") + (type == GL_DEBUG_TYPE_ERROR ? "error: " : "") + message);
}

// Largest sample count of a multisampled renderbuffer of `format` (0 when it is not renderable).
int max_samples_of(GLenum format, bool es) {
#ifdef __EMSCRIPTEN__
    // WebGL 2's getInternalformatParameter answers GL_SAMPLES only (not GL_NUM_SAMPLE_COUNTS).
    GLint samples[32] = {};
    glGetInternalformativ(GL_RENDERBUFFER, format, GL_SAMPLES, 32, samples);
    return samples[0];  // descending order; 0 when not renderable multisampled
#endif
    // glGetInternalformativ is core in ES 3.0 and GL 4.2 (ARB_internalformat_query before).
    if (es || gl::version() >= 42 || gl::has_extension("GL_ARB_internalformat_query")) {
        GLint count = 0;
        glGetInternalformativ(GL_RENDERBUFFER, format, GL_NUM_SAMPLE_COUNTS, 1, &count);
        if (count <= 0) return 0;
        GLint samples[32] = {};
        glGetInternalformativ(GL_RENDERBUFFER, format, GL_SAMPLES, std::min(count, 32), samples);
        return samples[0];  // listed in descending order
    }
    GLint n = 0;
    glGetIntegerv(GL_MAX_SAMPLES, &n);
    return n;
}
}  // namespace

void Context::init_context(const ContextOptions& options) {
    options_ = options;
    const bool es = !gl::is_desktop();
    Capabilities& c = caps_;
    c.api = es ? Api::OpenGLES30 : Api::OpenGL33;
    if (es) {
        c.float_color_targets = gl::has_extension("GL_EXT_color_buffer_float");
        c.half_float_color_targets = c.float_color_targets || gl::has_extension("GL_EXT_color_buffer_half_float");
        c.float_linear_filtering = gl::has_extension("GL_OES_texture_float_linear");
        c.seamless_cube_maps = true;  // always on in ES 3.0; GL_TEXTURE_CUBE_MAP_SEAMLESS does not exist there
        c.multisample_textures = false;  // ES 3.1
    } else {
        c.float_color_targets = c.half_float_color_targets = c.float_linear_filtering = true;
        // Filter across cube faces: a core enable since GL 3.2, off by default. Set once here.
        glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
        c.seamless_cube_maps = true;
    }
    c.timer_queries = !es && (gl::version() >= 33 || gl::has_extension("GL_ARB_timer_query"));
    c.texture_storage = es || gl::version() >= 42 || gl::has_extension("GL_ARB_texture_storage");
    c.max_anisotropy = 1.0f;
    if (gl::has_extension("GL_EXT_texture_filter_anisotropic") ||
        gl::has_extension("GL_ARB_texture_filter_anisotropic")) {
        GLfloat a = 1.0f;
        glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY_EXT, &a);
        c.max_anisotropy = std::max(1.0f, a);
    }
    GLint n = 0;
    glGetIntegerv(GL_MAX_SAMPLES, &n);
    c.max_samples = n;
    n = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &n);
    if (n > 0) c.max_texture_size = n;
    c.max_samples_float = max_samples_of(c.half_float_color_targets ? GL_RGBA16F : GL_RGBA8, es);
    if (c.multisample_textures) {
        n = 0;
        glGetIntegerv(GL_MAX_COLOR_TEXTURE_SAMPLES, &n);
        c.max_color_texture_samples = n;
    }
    glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &n);
    c.max_texture_units = n;
    n = 16;
    glGetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &n);
    c.max_fragment_texture_units = n;
    c.debug_output = gl::has_extension("GL_KHR_debug");
    while (glGetError() != GL_NO_ERROR) {
    }
    if (options_.log && es && !c.float_color_targets)
        options_.log(std::string("OpenGL ES without GL_EXT_color_buffer_float: HDR targets fall back to ") +
                     (c.half_float_color_targets ? "RGBA16F (EXT_color_buffer_half_float)"
                                                 : "RGBA8 (no float render targets; radiance clamps to [0,1])"));

    // KHR_debug is not part of GL 3.3 / ES 3.0: used only behind the capability check.
    if (!options_.debug || !options_.log || !c.debug_output) return;
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(debug_callback, &options_.log);
}

#ifndef __EMSCRIPTEN__
std::unique_ptr<Context> create_webgl_context(const std::string& canvas_selector, const ContextOptions&) {
    throw Error("WebGL", canvas_selector, "WebGL contexts exist only in the web build (make web)");
}
#endif

}  // namespace fresnel::gpu
