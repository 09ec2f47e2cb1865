#pragma once
// The GL headers of libs/gpu: libepoxy on the desktop (OpenGL 3.3 core or ES 3.0 through EGL
// or GLFW), Emscripten's OpenGL ES 3.0 headers in the web build (WebGL 2). fresnel::gpu::gl
// stands for the three libepoxy queries the layer makes, so the rest of libs/gpu is the same
// code for both.
#ifdef __EMSCRIPTEN__
#include <GLES3/gl3.h>
#include <GLES2/gl2ext.h>  // GL_TEXTURE_MAX_ANISOTROPY_EXT

#include <cstring>

// Desktop-only names, used only behind capabilities that are false on OpenGL ES 3.0
// (Capabilities::multisample_textures, debug_output) or after a desktop check: they exist
// here so that the code compiles unchanged, and are never reached on the web.
#ifndef GLAPIENTRY
#define GLAPIENTRY
#endif
#ifndef GL_TEXTURE_CUBE_MAP_SEAMLESS
#define GL_TEXTURE_CUBE_MAP_SEAMLESS 0x884F
#endif
#ifndef GL_TEXTURE_2D_MULTISAMPLE
#define GL_TEXTURE_2D_MULTISAMPLE 0x9100
#endif
#ifndef GL_MAX_COLOR_TEXTURE_SAMPLES
#define GL_MAX_COLOR_TEXTURE_SAMPLES 0x910E
#endif
#ifndef GL_DEBUG_OUTPUT
#define GL_DEBUG_OUTPUT 0x92E0
#endif
#ifndef GL_DEBUG_OUTPUT_SYNCHRONOUS
#define GL_DEBUG_OUTPUT_SYNCHRONOUS 0x8242
#endif
#ifndef GL_DEBUG_SEVERITY_NOTIFICATION
#define GL_DEBUG_SEVERITY_NOTIFICATION 0x826B
#endif
#ifndef GL_DEBUG_TYPE_ERROR
#define GL_DEBUG_TYPE_ERROR 0x824C
#endif
#ifndef GL_TIME_ELAPSED  // timer queries (Capabilities::timer_queries: desktop only)
#define GL_TIME_ELAPSED 0x88BF
#endif
namespace fresnel::gpu::gl {
using DebugProc = void(GLAPIENTRY*)(GLenum, GLenum, GLuint, GLenum, GLsizei, const GLchar*, const void*);
inline bool is_desktop() { return false; }
inline int version() { return 30; }
// WebGL's extensions as Emscripten lists them (each name also with a GL_ prefix).
inline bool has_extension(const char* name) {
    GLint n = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; ++i) {
        const GLubyte* e = glGetStringi(GL_EXTENSIONS, GLuint(i));
        if (e && std::strcmp(reinterpret_cast<const char*>(e), name) == 0) return true;
    }
    return false;
}
}  // namespace fresnel::gpu::gl
inline void glDebugMessageCallback(fresnel::gpu::gl::DebugProc, const void*) {}
inline void glTexImage2DMultisample(GLenum, GLsizei, GLenum, GLsizei, GLsizei, GLboolean) {}
inline void glGetQueryObjectui64v(GLuint, GLenum, GLuint64* out) { *out = 0; }
inline void glGetQueryObjectiv(GLuint, GLenum, GLint* out) { *out = 0; }
#else
#include <epoxy/gl.h>
namespace fresnel::gpu::gl {
inline bool is_desktop() { return epoxy_is_desktop_gl(); }
inline int version() { return epoxy_gl_version(); }
inline bool has_extension(const char* name) { return epoxy_has_gl_extension(name); }
}  // namespace fresnel::gpu::gl
#endif
