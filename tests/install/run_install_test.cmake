# The installable package, end to end (ctest -L install): installs the build tree into a
# temporary prefix, checks the layout, then configures, builds and runs the consumer project
# in consumer/ against it (find_package(fresnel) only, no path into the source tree).
# usage: cmake -DBUILD_DIR=.. -DWORK_DIR=.. -DVERSION=.. -DGENERATOR=.. -DCXX=.. -DBUILD_TYPE=.. -P run_install_test.cmake
foreach(v BUILD_DIR WORK_DIR VERSION GENERATOR CXX BUILD_TYPE)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "run_install_test.cmake: -D${v}= is required")
  endif()
endforeach()
get_filename_component(SOURCE_DIR "${CMAKE_CURRENT_LIST_DIR}/../.." ABSOLUTE)
set(prefix "${WORK_DIR}/prefix")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
endfunction()

# 1. Install (the build tree must be built: ctest runs after the build).
run("cmake --install" ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${prefix}")
foreach(f lib/cmake/fresnel/fresnelConfig.cmake lib/cmake/fresnel/fresnelConfigVersion.cmake
          lib/cmake/fresnel/fresnelTargets.cmake include/fresnel/fresnel.h include/fresnel/core/version.h
          include/fresnel/shaders/shaders.h bin/fresnel)
  if(NOT EXISTS "${prefix}/${f}")
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
foreach(l core scene material ibl gpu render trace viewer shaders)
  if(NOT EXISTS "${prefix}/lib/libfresnel_${l}.a")
    message(FATAL_ERROR "not installed: lib/libfresnel_${l}.a")
  endif()
endforeach()
# The exported targets point into the prefix only, never into the source or build tree.
file(GLOB target_files "${prefix}/lib/cmake/fresnel/fresnelTargets*.cmake")
foreach(f ${target_files})
  file(READ "${f}" text)
  foreach(tree "${SOURCE_DIR}" "${BUILD_DIR}")
    string(FIND "${text}" "${tree}" at)
    if(NOT at EQUAL -1)
      message(FATAL_ERROR "${f} refers to ${tree}")
    endif()
  endforeach()
endforeach()
# The umbrella header includes every installed public header.
file(READ "${prefix}/include/fresnel/fresnel.h" umbrella)
file(GLOB headers RELATIVE "${prefix}/include" "${prefix}/include/fresnel/*/*.h")
foreach(h ${headers})
  string(FIND "${umbrella}" "#include \"${h}\"" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "include/fresnel/fresnel.h does not include ${h}")
  endif()
endforeach()

# 2. The installed program reports the project's version.
run("fresnel --version" "${prefix}/bin/fresnel" --version)
if(NOT out STREQUAL "fresnel ${VERSION}\n")
  message(FATAL_ERROR "fresnel --version printed '${out}', expected 'fresnel ${VERSION}'")
endif()

# 2b. The Python package (when the build has it): installed into the prefix's site-packages, imported
# from there alone, and rendering.
if(EXISTS "${BUILD_DIR}/python/fresnel/__init__.py" AND DEFINED PYTHON)
  set(site "${prefix}/lib/python3/dist-packages")
  foreach(f fresnel/__init__.py fresnel/__init__.pyi fresnel/py.typed)
    if(NOT EXISTS "${site}/${f}")
      message(FATAL_ERROR "not installed: lib/python3/dist-packages/${f}")
    endif()
  endforeach()
  run("importing the installed Python package" "${PYTHON}" "${CMAKE_CURRENT_LIST_DIR}/check_python_package.py" "${site}")
  if(NOT out STREQUAL "${VERSION} (12, 16, 3)\n")
    message(FATAL_ERROR "the installed Python package printed '${out}'")
  endif()
endif()

# 3. The consumer: configure against the prefix alone, build, run.
run("configuring the consumer" ${CMAKE_COMMAND} -S "${SOURCE_DIR}/tests/install/consumer" -B "${WORK_DIR}/build"
    -G "${GENERATOR}" -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_BUILD_TYPE=${BUILD_TYPE} "-DCMAKE_PREFIX_PATH=${prefix}"
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
string(FIND "${out}" "fresnel ${VERSION} found at ${prefix}/lib/cmake/fresnel" at)
if(at EQUAL -1)
  message(FATAL_ERROR "the consumer did not find fresnel ${VERSION} in ${prefix}:\n${out}")
endif()
run("building the consumer" ${CMAKE_COMMAND} --build "${WORK_DIR}/build")
run("running the consumer" "${WORK_DIR}/build/app")
message("${out}")
string(FIND "${out}" "fresnel ${VERSION}\n" at)
if(NOT at EQUAL 0)
  message(FATAL_ERROR "the consumer did not print 'fresnel ${VERSION}' first")
endif()
file(REMOVE_RECURSE "${WORK_DIR}")
