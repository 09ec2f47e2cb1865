#include "fresnel/gpu/context.h"

#include <epoxy/gl.h>

#include <cstring>

namespace fresnel::gpu {

std::string Context::renderer() const {
    const GLubyte* s = glGetString(GL_RENDERER);
    return s ? reinterpret_cast<const char*>(s) : "";
}
std::string Context::version() const {
    const GLubyte* s = glGetString(GL_VERSION);
    return s ? reinterpret_cast<const char*>(s) : "";
}
bool Context::has_extension(const char* name) const { return epoxy_has_gl_extension(name); }

namespace {
void GLAPIENTRY debug_callback(GLenum, GLenum type, GLuint, GLenum severity, GLsizei, const GLchar* message,
                               const void* user) {
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
    auto* log = static_cast<const LogFn*>(user);
    if (log && *log) (*log)(std::string("GL: ") + (type == GL_DEBUG_TYPE_ERROR ? "error: " : "") + message);
}
}  // namespace

void Context::install_debug_output(const ContextOptions& options) {
    options_ = options;
    // KHR_debug is not part of GL 3.3 / ES 3.0: used only behind the capability check.
    if (!options_.debug || !options_.log || !epoxy_has_gl_extension("GL_KHR_debug")) return;
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(debug_callback, &options_.log);
}

}  // namespace fresnel::gpu
