#pragma once
// The OpenGL client libraries fresnel loads at run time (libepoxy opens them with dlopen when a
// context is made, so the program links none of them), each with the Debian package that
// provides it. A missing one is a clear error naming the package, not libepoxy's abort.
// scripts/packages.txt names every package here; tests/packaging checks it.
#include <string>
#include <vector>

#include "fresnel/gpu/context.h"

namespace fresnel::gpu {

struct RuntimeLibrary {
    std::vector<std::string> sonames;  // any one of them will do (loaders tried in this order)
    std::string package;               // the Debian 12 package of the first soname
    std::string purpose;               // what it is for, in a few words
};

enum class Windowing { Headless, Window };

// The libraries a context of `api` needs: EGL (headless), GLX through GLFW (windows), and the
// client library of the API (libOpenGL.so.0 or libGL.so.1; libGLESv2.so.2 for OpenGL ES).
std::vector<RuntimeLibrary> runtime_libraries(Api api, Windowing windowing);

// Throws fresnel::Error("OpenGL", ...) naming the soname and the package of the first library
// of `libraries` of which no soname can be loaded; returns otherwise.
void require_libraries(const std::vector<RuntimeLibrary>& libraries);

}  // namespace fresnel::gpu
