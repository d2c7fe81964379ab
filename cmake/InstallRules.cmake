# What `cmake --install` (and the Debian package, cmake/DebianPackage.cmake) puts where, in two components:
#   runtime  the library engines link (iblbake::runtime, no OpenImageIO/OpenColorIO) with what it needs to
#            compile against: its headers, the portable kernel headers, the CMake package (iblbakeConfig.cmake)
#            and the pkg-config file (iblbake-runtime.pc); the GLSL runtime and the JS cube loader.
#   tools    the programs and the data they read at run time (the OCIO config) or document (the sample scene).
# Paths follow GNUInstallDirs; nothing installed names the prefix, so any --prefix (and the .deb's /usr) works.
include(CMakePackageConfigHelpers)

set(IBLBAKE_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/iblbake)
set(IBLBAKE_INSTALL_SHAREDIR ${CMAKE_INSTALL_DATADIR}/iblbake)

# The runtime and the targets it links, exported as iblbake::<name>. Only iblbake::runtime is meant to be
# linked; core, opencl and ktx2 come along because the runtime's headers and (static) archive need them.
set(_exported iblbake_shading iblbake_core iblbake_opencl iblbake_ktx2 iblbake_runtime)
# Shared libraries (BUILD_SHARED_LIBS) get the soname lib<name>.so.<major>.<minor>: a 0.x minor version may
# change the ABI.
foreach(_target IN LISTS _exported)
  string(REPLACE "iblbake_" "" _name ${_target})
  set_target_properties(${_target} PROPERTIES EXPORT_NAME ${_name})
  if(NOT _target STREQUAL iblbake_shading)
    set_target_properties(${_target} PROPERTIES VERSION ${PROJECT_VERSION}
                          SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR})
  endif()
endforeach()
install(TARGETS ${_exported} EXPORT iblbakeTargets COMPONENT runtime)
# The headers those targets' include folders hold, merged into include/iblbake/; the kernels' portable headers
# (included as <probe.h>, <cube_sample.h>, ...) in include/iblbake/kernels, which iblbake::shading adds.
foreach(_folder baker/include/core baker/include/opencl baker/include/ktx2 baker/runtime/include)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${_folder}/iblbake DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
          COMPONENT runtime FILES_MATCHING PATTERN "*.h")
endforeach()
file(GLOB _portable_headers ${PROJECT_SOURCE_DIR}/kernels/*.h)
install(FILES ${_portable_headers} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/iblbake/kernels COMPONENT runtime)

# find_package(iblbake CONFIG): the exported targets and their dependencies. A static runtime carries TBB
# (the CPU backend) into the consumer's link; a shared one does not.
if(BUILD_SHARED_LIBS)
  set(IBLBAKE_RUNTIME_STATIC FALSE)
else()
  set(IBLBAKE_RUNTIME_STATIC TRUE)
endif()
install(EXPORT iblbakeTargets NAMESPACE iblbake:: DESTINATION ${IBLBAKE_INSTALL_CMAKEDIR} COMPONENT runtime)
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/iblbakeConfig.cmake.in
  ${PROJECT_BINARY_DIR}/iblbakeConfig.cmake INSTALL_DESTINATION ${IBLBAKE_INSTALL_CMAKEDIR})
# 0.x: a new minor version may change the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/iblbakeConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/iblbakeConfig.cmake ${PROJECT_BINARY_DIR}/iblbakeConfigVersion.cmake
        DESTINATION ${IBLBAKE_INSTALL_CMAKEDIR} COMPONENT runtime)

# pkg-config: the prefix found from the .pc file's own folder (${pcfiledir}), so the file is relocatable too.
file(RELATIVE_PATH IBLBAKE_PC_TO_PREFIX ${CMAKE_INSTALL_FULL_LIBDIR}/pkgconfig ${CMAKE_INSTALL_PREFIX})
string(REGEX REPLACE "/$" "" IBLBAKE_PC_TO_PREFIX "${IBLBAKE_PC_TO_PREFIX}")
if(IBLBAKE_RUNTIME_STATIC)
  set(IBLBAKE_PC_REQUIRES_STATIC " tbb libxxhash") # libxxhash: program-binary keys (iblbake_opencl)
else()
  set(IBLBAKE_PC_REQUIRES_STATIC "")
endif()
configure_file(${CMAKE_CURRENT_LIST_DIR}/iblbake-runtime.pc.in ${PROJECT_BINARY_DIR}/iblbake-runtime.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/iblbake-runtime.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig
        COMPONENT runtime)

# The runtime for shaders and the browser: probe.glsl with its integration guide, the three.js cube loader.
get_target_property(_probe_glsl iblbake_probe_glsl IBLBAKE_GLSL_FILE)
install(FILES ${_probe_glsl} ${PROJECT_SOURCE_DIR}/baker/runtime/glsl/README.md
        DESTINATION ${IBLBAKE_INSTALL_SHAREDIR}/glsl COMPONENT runtime)
install(FILES ${PROJECT_SOURCE_DIR}/baker/runtime/js/iblbakeCubeLoader.js
        DESTINATION ${IBLBAKE_INSTALL_SHAREDIR}/js COMPONENT runtime)
install(FILES ${PROJECT_SOURCE_DIR}/baker/runtime/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR}/runtime
        COMPONENT runtime)

# The programs. iblbake runs iblbake-engine from beside itself (cli/front_end.cpp). With BUILD_SHARED_LIBS
# they need the project's other libraries too (found through CMAKE_INSTALL_RPATH, top-level CMakeLists.txt).
install(TARGETS iblbake iblbake-engine COMPONENT tools)
# The OpenImageIO module, loaded on demand from bin/../lib/iblbake (baker/CMakeLists.txt).
install(TARGETS iblbake_oiio LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/iblbake COMPONENT tools)
if(BUILD_SHARED_LIBS)
  install(TARGETS iblbake_scene iblbake_batch iblbake_bake_state iblbake_batch_run iblbake_baker iblbake_accuracy
          COMPONENT tools)
endif()
# data/ as in the source tree, in share/iblbake/data: the OCIO config the engine reads at run time
# (baker/src/ingest/color.cpp finds it relative to the program), the sample HDRI and the example scene, whose
# relative paths then still hold (a copy of the folder bakes to scenes/out/park inside it, docs/install.md "Install"), and
# data/README.md with the sample data's licences and attribution.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/data/ DESTINATION ${IBLBAKE_INSTALL_SHAREDIR}/data COMPONENT tools)
# The README and docs/ beside it, so that the README's links into docs/ hold in the installed tree too.
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT tools)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs COMPONENT tools)
