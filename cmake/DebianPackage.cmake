# The Debian package: `cpack --config build/CPackConfig.cmake -B build` writes build/iblbake_<version>_<arch>.deb
# with everything cmake/InstallRules.cmake installs, under /usr; `apt-get install ./build/iblbake_*.deb` installs
# it with its dependencies (docs/install.md "Install").
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME iblbake)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "image-based-lighting and light-probe baker, and its probe-sampling runtime")
set(CPACK_PACKAGE_DESCRIPTION
    "iblbake bakes the split-sum DFG LUT, prefiltered specular cube chains and SH/irradiance probes from HDR \
environment captures, calibrated to absolute luminance (OpenCL through any ICD, or a TBB CPU backend). The \
package also holds iblbake_runtime, the library engines link to shade points with the baked probes (CMake \
package iblbake::runtime, pkg-config iblbake-runtime), its GLSL port and the sample scene.")
set(IBLBAKE_PACKAGE_MAINTAINER "iblbake maintainers <iblbake@localhost>"
    CACHE STRING "The Debian package's Maintainer field")
set(CPACK_PACKAGE_CONTACT "${IBLBAKE_PACKAGE_MAINTAINER}")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT) # iblbake_<version>_<arch>.deb
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
# Depends: the shared libraries the programs link, as dpkg-shlibdeps (dpkg-dev) names their packages (OpenImageIO,
# OpenColorIO, OpenEXR, TBB, the OpenCL ICD loader, ...), and what they only open at run time: an OpenCL
# implementation for the loader to find (PoCL, or any other ICD) and DejaVu Sans for the material preview's
# labels (baker/src/preview/preview_grid.cpp).
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "pocl-opencl-icd | opencl-icd, fonts-dejavu-core")
# What building against the runtime needs (its headers include GLM and CL/opencl.hpp; a static runtime links
# TBB and the ICD loader): recommended, so that a farm node can leave them out with --no-install-recommends.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "libglm-dev, opencl-clhpp-headers, ocl-icd-opencl-dev, libtbb-dev, libxxhash-dev, pkg-config")
include(CPack)
