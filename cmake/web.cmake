# The web build's dependencies (Emscripten, `make web`): only header-only libraries, from
# Debian's packages. They are reached through a folder of links in the build folder, so that
# the rest of /usr/include (glibc's headers) stays out of the WebAssembly compile. Libraries
# Debian does not build for WebAssembly (OpenEXR, libjpeg-turbo, zlib, meshoptimizer, Draco,
# libwebp, Embree, GLFW, libepoxy, EGL) are left out; where a file needs one the loaders
# say so by name (FRESNEL_NO_* in libs/core, libs/scene/src/web/).
set(FRESNEL_WEB_DEPS_INCLUDE ${CMAKE_BINARY_DIR}/deps-include)
file(MAKE_DIRECTORY ${FRESNEL_WEB_DEPS_INCLUDE})
foreach(pair "glm:libglm-dev" "nlohmann:nlohmann-json3-dev" "stb:libstb-dev" "Imath:libimath-dev")
  string(REPLACE ":" ";" pair ${pair})
  list(GET pair 0 dir)
  list(GET pair 1 package)
  if(NOT EXISTS /usr/include/${dir})
    message(FATAL_ERROR "the web build needs /usr/include/${dir} (Debian package ${package})")
  endif()
  file(CREATE_LINK /usr/include/${dir} ${FRESNEL_WEB_DEPS_INCLUDE}/${dir} SYMBOLIC)
endforeach()
add_library(glm::glm INTERFACE IMPORTED)
target_include_directories(glm::glm SYSTEM INTERFACE ${FRESNEL_WEB_DEPS_INCLUDE})
add_library(nlohmann_json::nlohmann_json INTERFACE IMPORTED)
target_include_directories(nlohmann_json::nlohmann_json SYSTEM INTERFACE ${FRESNEL_WEB_DEPS_INCLUDE})
add_library(Threads::Threads INTERFACE IMPORTED)  # no pthreads on the web: parallel_for runs on the caller
set(STB_INCLUDE_DIR ${FRESNEL_WEB_DEPS_INCLUDE}/stb)
# C++ exceptions carry fresnel::Error: on, in every object and at the link.
# WebAssembly SIMD (every browser with WebGL 2 of the last years has it): the IBL bake vectorises.
add_compile_options(-fexceptions -msimd128)
add_link_options(-fexceptions)
