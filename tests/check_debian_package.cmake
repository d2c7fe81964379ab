# The Debian package (CTest debian_package): cpack writes BUILD_DIR/iblbake_<version>_<arch>.deb (what
# .ci/install-package then installs with apt-get); its control fields must carry the Depends of the libraries
# the programs link and of what they open at run time, its contents every installed part, and its programs,
# unpacked into a fresh directory (dpkg-deb -x, no root needed), must run from there: --version, the OCIO
# config unpacked beside them, a small bake of the packaged sample HDRI.
# Run as a script: cmake -DBUILD_DIR=... -DCPACK=... -DVERSION=... -P check_debian_package.cmake
cmake_minimum_required(VERSION 3.22)
include(${CMAKE_CURRENT_LIST_DIR}/package_test_support.cmake)

file(GLOB old "${BUILD_DIR}/iblbake_*.deb")
if(old)
  file(REMOVE ${old})
endif()
package_test_run("cpack" unused "${CPACK}" -G DEB --config "${BUILD_DIR}/CPackConfig.cmake" -B "${BUILD_DIR}")
file(GLOB deb "${BUILD_DIR}/iblbake_${VERSION}_*.deb")
list(LENGTH deb count)
if(NOT count EQUAL 1)
  message(FATAL_ERROR "cpack wrote no single iblbake_${VERSION}_*.deb in ${BUILD_DIR}: ${deb}")
endif()
file(SIZE "${deb}" bytes)
message(STATUS "${deb}: ${bytes} bytes")

# Control fields: the package, and Depends from dpkg-shlibdeps plus the OpenCL implementation and the font.
package_test_run("dpkg-deb -f" fields dpkg-deb -f "${deb}" Package Version Depends Recommends)
message(STATUS "control fields:\n${fields}")
foreach(expected "Package: iblbake\n" "Version: ${VERSION}\n" "libopenimageio[0-9.]+" "libopencolorio[0-9.]+"
                 "libtbb[0-9]+" "ocl-icd-libopencl1" "pocl-opencl-icd \\| opencl-icd" "fonts-dejavu-core"
                 "libstdc\\+\\+6" "Recommends: [^\n]*libglm-dev")
  if(NOT fields MATCHES "${expected}")
    message(FATAL_ERROR "the control fields lack ${expected}")
  endif()
endforeach()

# Contents: programs, the runtime library with headers and packages, the GLSL and JS runtime, the data.
package_test_run("dpkg-deb -c" contents dpkg-deb -c "${deb}")
foreach(path usr/bin/iblbake usr/bin/iblbake-engine "usr/lib/[^\n]*libiblbake_runtime\\.(a|so)"
             usr/include/iblbake/runtime/runtime.h usr/include/iblbake/runtime/runtime_manifest.h
             usr/include/iblbake/core/error.h usr/include/iblbake/opencl/executor.h usr/include/iblbake/kernels/probe.h
             "usr/lib/[^\n]*cmake/iblbake/iblbakeConfig\\.cmake" "usr/lib/[^\n]*cmake/iblbake/iblbakeConfigVersion\\.cmake"
             "usr/lib/[^\n]*cmake/iblbake/iblbakeTargets\\.cmake" "usr/lib/[^\n]*pkgconfig/iblbake-runtime\\.pc"
             usr/share/iblbake/glsl/probe.glsl usr/share/iblbake/glsl/README.md usr/share/iblbake/js/iblbakeCubeLoader.js
             usr/share/iblbake/data/ocio/config.ocio usr/share/iblbake/data/scenes/park.json
             usr/share/iblbake/data/rooitou_park_1k.hdr usr/share/iblbake/data/README.md
             usr/share/doc/iblbake/README.md usr/share/doc/iblbake/docs/conventions.md)
  if(NOT contents MATCHES " \\./${path}\n")
    message(FATAL_ERROR "the package lacks ${path}:\n${contents}")
  endif()
endforeach()
if(contents MATCHES "usr/local")
  message(FATAL_ERROR "the package installs under /usr/local:\n${contents}")
endif()

# Its programs, unpacked.
package_test_work_dir(work)
package_test_run("dpkg-deb -x" unused dpkg-deb -x "${deb}" "${work}/root")
set(iblbake "${work}/root/usr/bin/iblbake")
set(data "${work}/root/usr/share/iblbake/data")
package_test_run("iblbake --version" version "${iblbake}" --version)
if(NOT version MATCHES "^iblbake ${VERSION} ")
  message(FATAL_ERROR "iblbake --version printed: ${version}")
endif()
package_test_expect_ocio_config("${iblbake}" "${data}/ocio/config.ocio" "${data}/rooitou_park_1k.hdr" "${work}")
package_test_write_scene("${work}/small_park.json" "${data}/rooitou_park_1k.hdr" "${work}/bake")
package_test_run("the packaged iblbake's bake" unused "${iblbake}" bake "${work}/small_park.json" --quiet)
if(NOT EXISTS "${work}/bake/manifest.json")
  message(FATAL_ERROR "the packaged iblbake wrote no manifest.json")
endif()
file(REMOVE_RECURSE "${work}")
