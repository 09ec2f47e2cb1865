// The GL client libraries fresnel opens at run time, and the error for a missing one (no GL:
// nothing here makes a context).
#include <gtest/gtest.h>

#include <algorithm>

#include "fresnel/core/error.h"
#include "fresnel/gpu/libraries.h"

using namespace fresnel;
using namespace fresnel::gpu;

namespace {
bool lists(const std::vector<RuntimeLibrary>& libraries, const std::string& soname, const std::string& package) {
    return std::any_of(libraries.begin(), libraries.end(), [&](const RuntimeLibrary& l) {
        return l.package == package && std::find(l.sonames.begin(), l.sonames.end(), soname) != l.sonames.end();
    });
}
}  // namespace

TEST(GpuLibraries, EachApiAndWindowingNamesItsClientLibraryAndPackage) {
    EXPECT_TRUE(lists(runtime_libraries(Api::OpenGLES30, Windowing::Headless), "libGLESv2.so.2", "libgles2"));
    EXPECT_TRUE(lists(runtime_libraries(Api::OpenGLES30, Windowing::Headless), "libEGL.so.1", "libegl1"));
    EXPECT_TRUE(lists(runtime_libraries(Api::OpenGL33, Windowing::Headless), "libOpenGL.so.0", "libopengl0"));
    EXPECT_FALSE(lists(runtime_libraries(Api::OpenGL33, Windowing::Headless), "libGLESv2.so.2", "libgles2"));
    EXPECT_TRUE(lists(runtime_libraries(Api::OpenGLES30, Windowing::Window), "libGLESv2.so.2", "libgles2"));
    EXPECT_TRUE(lists(runtime_libraries(Api::OpenGL33, Windowing::Window), "libGL.so.1", "libgl1"));
}

TEST(GpuLibraries, AMissingLibraryIsAnErrorNamingItsPackage) {
    const std::vector<RuntimeLibrary> wanted = {
        {{"libc.so.6"}, "libc6", "the C library"},
        {{"libfresnel-not-there.so.9", "libfresnel-nor-this.so.1"}, "fresnel-absent-package", "a test library"}};
    try {
        require_libraries(wanted);
        FAIL() << "no error for a library that is not there";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("libfresnel-not-there.so.9"), std::string::npos) << what;
        EXPECT_NE(what.find("fresnel-absent-package"), std::string::npos) << what;
        EXPECT_NE(what.find("apt-get install"), std::string::npos) << what;
    }
}

TEST(GpuLibraries, AnyOneOfTheSonamesWillDo) {
    EXPECT_NO_THROW(require_libraries({{{"libfresnel-not-there.so.9", "libc.so.6"}, "libc6", "the C library"}}));
    EXPECT_NO_THROW(require_libraries({}));
}
