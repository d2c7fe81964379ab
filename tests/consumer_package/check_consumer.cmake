# The installed package as an engine uses it (CTest consumer_package): `cmake --install BUILD_DIR --prefix P`
# into a fresh directory, a small bake with the installed iblbake (which must read the OCIO config installed
# with it), then this folder's project copied out of the trees, configured with CMAKE_PREFIX_PATH=P
# (find_package(iblbake CONFIG REQUIRED), iblbake::runtime) and built, and the same source compiled with the
# flags of `pkg-config iblbake-runtime`. Both programs shade the bake's manifest.json; their output must equal
# the in-tree build's (INTREE, linked against iblbake_runtime in the build tree), and neither they nor the
# installed runtime may need OpenImageIO or OpenColorIO.
# Run as a script: cmake -DBUILD_DIR=... -DINTREE=... -DCXX=... [-DLAUNCHER=...] [-DSANITIZE=address,...]
#                        -P check_consumer.cmake
cmake_minimum_required(VERSION 3.22)
include(${CMAKE_CURRENT_LIST_DIR}/../package_test_support.cmake)

package_test_work_dir(work)
set(prefix "${work}/prefix")
package_test_run("cmake --install" unused "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${prefix}")

# A bake by the installed program, from the installed sample data.
set(data "${prefix}/share/iblbake/data")
set(iblbake "${prefix}/bin/iblbake")
package_test_write_scene("${work}/small_park.json" "${data}/rooitou_park_1k.hdr" "${work}/bake")
package_test_run("the installed iblbake's bake" unused "${iblbake}" bake "${work}/small_park.json" --quiet)
package_test_expect_ocio_config("${iblbake}" "${data}/ocio/config.ocio" "${data}/rooitou_park_1k.hdr" "${work}")
set(manifest "${work}/bake/manifest.json")

# The external CMake project.
file(COPY ${CMAKE_CURRENT_LIST_DIR}/CMakeLists.txt ${CMAKE_CURRENT_LIST_DIR}/shade_manifest.cpp
     DESTINATION "${work}/consumer")
set(configure "${CMAKE_COMMAND}" -S "${work}/consumer" -B "${work}/consumer-build" -DCMAKE_BUILD_TYPE=Release
    "-DCMAKE_PREFIX_PATH=${prefix}" "-DCMAKE_CXX_COMPILER=${CXX}")
set(flags "")
if(LAUNCHER)
  list(APPEND configure "-DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER}")
endif()
if(SANITIZE) # the sanitizer build's runtime (.ci/sanitize) needs the sanitizers' libraries at link time
  set(flags "-fsanitize=${SANITIZE}")
  list(APPEND configure "-DCMAKE_EXE_LINKER_FLAGS=${flags}")
endif()
package_test_run("configuring the consumer" configured ${configure})
if(NOT configured MATCHES "iblbake package: ${prefix}/lib[^\n]*/cmake/iblbake")
  message(FATAL_ERROR "find_package(iblbake) did not find the package in ${prefix}:\n${configured}")
endif()
package_test_run("building the consumer" unused "${CMAKE_COMMAND}" --build "${work}/consumer-build")

# The same source through pkg-config (the .pc file in P, relocated by ${pcfiledir}).
set(ENV{PKG_CONFIG_PATH} "${prefix}/lib/pkgconfig")
package_test_run("pkg-config" pc_flags pkg-config --cflags --libs iblbake-runtime)
separate_arguments(pc_flags UNIX_COMMAND "${pc_flags}")
package_test_run("compiling with pkg-config's flags" unused ${LAUNCHER} "${CXX}" -O3 -DNDEBUG ${flags}
                 "${work}/consumer/shade_manifest.cpp" -o "${work}/shade_manifest_pc" ${pc_flags})

package_test_run("the in-tree program" expected "${INTREE}" "${manifest}")
foreach(program "${work}/consumer-build/shade_manifest" "${work}/shade_manifest_pc")
  package_test_run("${program}" shaded "${program}" "${manifest}")
  if(NOT shaded STREQUAL expected)
    message(FATAL_ERROR "${program} shades differently from the in-tree runtime:\n${shaded}\nin-tree:\n${expected}")
  endif()
  package_test_expect_no_oiio_ocio("${program}")
endforeach()
string(REGEX MATCHALL "\n" lines "${expected}")
list(LENGTH lines lineCount)
message(STATUS "the installed runtime's ${lineCount} lines equal the in-tree runtime's")

# The installed runtime library itself: a shared one's NEEDED entries, a static archive's undefined symbols.
file(GLOB shared "${prefix}/lib*/libiblbake_runtime.so" "${prefix}/lib/*/libiblbake_runtime.so")
file(GLOB archives "${prefix}/lib*/libiblbake_*.a" "${prefix}/lib/*/libiblbake_*.a")
foreach(library IN LISTS shared)
  package_test_expect_no_oiio_ocio("${library}")
endforeach()
foreach(archive IN LISTS archives)
  package_test_run("nm" undefined nm -u -C "${archive}")
  if(undefined MATCHES "OpenImageIO|OpenColorIO|OIIO|OCIO")
    message(FATAL_ERROR "${archive} refers to OpenImageIO/OpenColorIO symbols")
  endif()
endforeach()
if(NOT shared AND NOT archives)
  message(FATAL_ERROR "no iblbake_runtime library in ${prefix}")
endif()
file(READ "${prefix}/lib/cmake/iblbake/iblbakeTargets.cmake" targets)
if(targets MATCHES "OpenImageIO|OpenColorIO")
  message(FATAL_ERROR "the exported targets name OpenImageIO/OpenColorIO")
endif()
file(REMOVE_RECURSE "${work}")
