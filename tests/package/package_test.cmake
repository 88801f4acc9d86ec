# cmake -DSOURCE_DIR=<repo> -DBUILD_DIR=<this build> -DWORK_DIR=<scratch> -DC_COMPILER=<cc> -DNM=<nm>
#       -DPKG_CONFIG=<pkg-config> -DJOBS=<n> [-DLIBDIR=<CMAKE_INSTALL_LIBDIR>] [-DCXX_COMPILER=<c++>]
#       [-DGENERATOR=<generator>] -P package_test.cmake
#
# What a studio does with a release, checked end to end outside the source tree:
#   1. `cmake --install` the static library of this build; the integration program (samples/integration) is
#      configured as a project of its own with find_package(Obscura CONFIG REQUIRED), linked to Obscura::obscura
#      and run; then compiled once more with nothing but `pkg-config --cflags --libs --static obscura`.
#   2. The SDK is configured again from the sources as a shared library (OBSCURA_SHARED=ON), installed; its
#      dynamic symbol table must export obscura_* only (nm), the program must link it through the CMake package
#      and through pkg-config (it must then need libobscura.so.<major>) and run.
foreach(var SOURCE_DIR BUILD_DIR WORK_DIR C_COMPILER NM PKG_CONFIG)
  if(NOT ${var})
    message(FATAL_ERROR "package_test.cmake needs -D${var}=...")
  endif()
endforeach()
if(NOT JOBS)
  set(JOBS 2)
endif()
# Where the build installs its libraries (GNUInstallDirs: lib, lib64, lib/<multiarch> for a /usr prefix).
if(NOT LIBDIR)
  set(LIBDIR lib)
endif()
# The shared rebuild uses the build's own toolchain and generator.
set(rebuild_options "")
if(CXX_COMPILER)
  list(APPEND rebuild_options "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" "-DCMAKE_C_COMPILER=${C_COMPILER}")
endif()
if(GENERATOR)
  list(APPEND rebuild_options -G "${GENERATOR}")
endif()

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${what} failed (${result}):\n${output}")
  endif()
  message(STATUS "${what}: ok")
  set(last_output "${output}" PARENT_SCOPE)
endfunction()

# Runs the integration program and checks what it printed.
function(run_program what program)
  run("${what}" "${program}")
  if(NOT last_output MATCHES "visibility at the crease")
    message(FATAL_ERROR "${what}: unexpected output:\n${last_output}")
  endif()
  message(STATUS "  ${last_output}")
endfunction()

# The program's NEEDED entries must (or must not) name libobscura.so.
function(check_needs_shared program expected)
  run("readelf ${program}" readelf --dynamic "${program}")
  if(last_output MATCHES "NEEDED[^\n]*libobscura\\.so\\.[0-9]+")
    set(needs TRUE)
  else()
    set(needs FALSE)
  endif()
  if(NOT needs STREQUAL expected)
    message(FATAL_ERROR "${program}: needs libobscura.so is ${needs}, expected ${expected}:\n${last_output}")
  endif()
endfunction()

# Compiles the program with only what pkg-config says about obscura (plus the host's own EGL and GL).
function(build_with_pkg_config prefix output static)
  set(ENV{PKG_CONFIG_PATH} "${prefix}/${LIBDIR}/pkgconfig")
  set(flags --cflags --libs obscura)
  if(static)
    list(PREPEND flags --static)
  endif()
  run("pkg-config ${flags}" "${PKG_CONFIG}" ${flags})
  string(STRIP "${last_output}" obscura_flags)
  separate_arguments(obscura_flags UNIX_COMMAND "${obscura_flags}")
  set(rpath "")
  if(NOT static)
    set(rpath "-Wl,-rpath,${prefix}/${LIBDIR}")
  endif()
  run("cc with pkg-config (${output})" "${C_COMPILER}" -std=c99 -Wall -Wextra -Werror
      "${SOURCE_DIR}/samples/integration/obscura_integration.c" ${obscura_flags} ${rpath} -lEGL -lOpenGL -lm
      -o "${output}")
endfunction()

file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# ---- 1. The static library of this build -----------------------------------------------------------------
set(static_prefix "${WORK_DIR}/static-prefix")
run("install the static library" "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${static_prefix}")
foreach(file include/obscura/obscura.h ${LIBDIR}/libobscura.a ${LIBDIR}/cmake/Obscura/ObscuraConfig.cmake
             ${LIBDIR}/cmake/Obscura/ObscuraConfigVersion.cmake ${LIBDIR}/cmake/Obscura/ObscuraTargets.cmake
             ${LIBDIR}/pkgconfig/obscura.pc)
  if(NOT EXISTS "${static_prefix}/${file}")
    message(FATAL_ERROR "cmake --install did not install ${file}")
  endif()
endforeach()
run("configure the integration program (static, find_package)" "${CMAKE_COMMAND}"
    -S "${SOURCE_DIR}/samples/integration" -B "${WORK_DIR}/consumer-static"
    -DCMAKE_PREFIX_PATH=${static_prefix} -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_COMPILER=${C_COMPILER})
run("build it" "${CMAKE_COMMAND}" --build "${WORK_DIR}/consumer-static")
run_program("run it" "${WORK_DIR}/consumer-static/obscura_integration")
check_needs_shared("${WORK_DIR}/consumer-static/obscura_integration" FALSE)
build_with_pkg_config("${static_prefix}" "${WORK_DIR}/pkg-config-static" TRUE)
run_program("run the pkg-config build (static)" "${WORK_DIR}/pkg-config-static")
# Without --static too: the install holds only the static library, so plain `pkg-config --libs` must link it
# (the C++ runtime is in Libs).
build_with_pkg_config("${static_prefix}" "${WORK_DIR}/pkg-config-static-plain" FALSE)
run_program("run the plain pkg-config build (static library)" "${WORK_DIR}/pkg-config-static-plain")

# A version the package does not satisfy is refused: 0.x packages accept requests of their own major only.
file(WRITE "${WORK_DIR}/version-check/CMakeLists.txt"
     "cmake_minimum_required(VERSION 3.16)\nproject(VersionCheck LANGUAGES NONE)\n"
     "find_package(Obscura 1 CONFIG QUIET)\nif(Obscura_FOUND)\n  message(FATAL_ERROR \"version 1 accepted\")\nendif()\n"
     "find_package(Obscura CONFIG REQUIRED)\nmessage(STATUS \"Obscura \${Obscura_VERSION}\")\n")
run("find_package version check" "${CMAKE_COMMAND}" -S "${WORK_DIR}/version-check" -B "${WORK_DIR}/version-check/build"
    -DCMAKE_PREFIX_PATH=${static_prefix})

# ---- 2. A shared build from the sources --------------------------------------------------------------------
set(shared_prefix "${WORK_DIR}/shared-prefix")
run("configure the shared library" "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${WORK_DIR}/shared-build" ${rebuild_options}
    -DCMAKE_BUILD_TYPE=Release -DOBSCURA_SHARED=ON -DOBSCURA_BUILD_TESTS=OFF -DOBSCURA_BUILD_SAMPLES=OFF
    -DCMAKE_INSTALL_LIBDIR=${LIBDIR})
run("build the shared library" "${CMAKE_COMMAND}" --build "${WORK_DIR}/shared-build" --parallel ${JOBS})
run("install the shared library" "${CMAKE_COMMAND}" --install "${WORK_DIR}/shared-build" --prefix "${shared_prefix}")
file(GLOB shared_files "${shared_prefix}/${LIBDIR}/libobscura.so.*.*.*")
list(LENGTH shared_files count)
if(NOT count EQUAL 1)
  message(FATAL_ERROR "expected one libobscura.so.X.Y.Z in ${shared_prefix}/${LIBDIR}, found: ${shared_files}")
endif()
run("nm: the shared library exports the C API only" "${CMAKE_COMMAND}" -DNM=${NM} -DLIBRARY=${shared_files}
    -DSHARED=ON -DHEADER=${SOURCE_DIR}/sdk/include/obscura/obscura.h -P "${SOURCE_DIR}/tests/check_no_gl_symbols.cmake")
message(STATUS "  ${last_output}")
run("configure the integration program (shared, find_package)" "${CMAKE_COMMAND}"
    -S "${SOURCE_DIR}/samples/integration" -B "${WORK_DIR}/consumer-shared"
    -DCMAKE_PREFIX_PATH=${shared_prefix} -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_COMPILER=${C_COMPILER})
run("build it" "${CMAKE_COMMAND}" --build "${WORK_DIR}/consumer-shared")
check_needs_shared("${WORK_DIR}/consumer-shared/obscura_integration" TRUE)
run_program("run it" "${WORK_DIR}/consumer-shared/obscura_integration")
build_with_pkg_config("${shared_prefix}" "${WORK_DIR}/pkg-config-shared" FALSE)
check_needs_shared("${WORK_DIR}/pkg-config-shared" TRUE)
run_program("run the pkg-config build (shared)" "${WORK_DIR}/pkg-config-shared")
