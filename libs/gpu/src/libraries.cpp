#include "fresnel/gpu/libraries.h"

#ifndef __EMSCRIPTEN__
#include <dlfcn.h>
#endif

#include "fresnel/core/error.h"

namespace fresnel::gpu {

std::vector<RuntimeLibrary> runtime_libraries(Api api, Windowing windowing) {
    std::vector<RuntimeLibrary> out;
    if (windowing == Windowing::Headless)
        out.push_back({{"libEGL.so.1"}, "libegl1", "EGL, for headless contexts"});
    else
        out.push_back({{"libGLX.so.0", "libGL.so.1"}, "libglx0", "GLX, for windows"});
    if (api == Api::OpenGLES30)
        out.push_back({{"libGLESv2.so.2"}, "libgles2", "the OpenGL ES 3.0 client library"});
    else
        // libepoxy takes glvnd's libOpenGL.so.0 with EGL, libGL.so.1 with GLX, and the other one
        // when the first is missing.
        out.push_back({windowing == Windowing::Headless ? std::vector<std::string>{"libOpenGL.so.0", "libGL.so.1"}
                                                        : std::vector<std::string>{"libGL.so.1", "libOpenGL.so.0"},
                       windowing == Windowing::Headless ? "libopengl0" : "libgl1", "the OpenGL client library"});
    return out;
}

void require_libraries(const std::vector<RuntimeLibrary>& libraries) {
#ifndef __EMSCRIPTEN__
    for (const RuntimeLibrary& library : libraries) {
        bool found = false;
        for (const std::string& soname : library.sonames) {
            // Loaded and released: libepoxy opens it again (the count keeps it loaded meanwhile
            // only when someone else holds it; reopening is cheap either way).
            if (void* handle = dlopen(soname.c_str(), RTLD_LAZY | RTLD_LOCAL)) {
                dlclose(handle);
                found = true;
                break;
            }
        }
        if (!found)
            throw Error("OpenGL", "",
                        "cannot load " + library.sonames.front() + " (" + library.purpose +
                            "): install Debian's package " + library.package + " (apt-get install " +
                            library.package + ")");
    }
#else
    (void)libraries;
#endif
}

}  // namespace fresnel::gpu
