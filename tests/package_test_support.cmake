# Helpers of the installed-package tests (consumer_package/check_consumer.cmake, check_debian_package.cmake):
# running a step, a small bake of the installed sample HDRI, the OCIO config an installed program reads.
cmake_minimum_required(VERSION 3.22)

# Runs a command; stops the test with its output when it fails. Its stdout goes to the variable `out`.
function(package_test_run what out)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${what} failed (${result}): ${ARGN}\n${stdout}\n${stderr}")
  endif()
  set(${out} "${stdout}" PARENT_SCOPE)
endfunction()

# A fresh directory for the test's files, outside the source and build trees ($TMPDIR or /tmp); removed by
# the caller once the test passed, kept for a look when it failed.
function(package_test_work_dir out)
  package_test_run("mktemp" dir mktemp -d -t iblbake-package-XXXXXX)
  string(STRIP "${dir}" dir)
  set(${out} "${dir}" PARENT_SCOPE)
endfunction()

# Writes `scene` (JSON): the installed sample HDRI (`hdri`) with its sun extracted and the example scene's
# pavilion probe (data/scenes/park.json), small faces, baked to `directory`; `colorSpace` when given.
function(package_test_write_scene scene hdri directory)
  set(colorSpace "")
  if(ARGC GREATER 3)
    set(colorSpace ", \"colorSpace\": \"${ARGV3}\"")
  endif()
  file(WRITE "${scene}" "{
  \"environment\": {\"file\": \"${hdri}\", \"layout\": \"latlong\", \"calibration\": {\"sunIlluminance\": 100000},
                  \"extractSun\": true${colorSpace}},
  \"probes\": [{\"name\": \"pavilion\", \"capture\": \"${hdri}\", \"position\": [20, 1.5, 0],
    \"proxy\": {\"shape\": \"box\", \"center\": [20, 2, 0], \"halfExtents\": [4, 2, 3], \"rotation\": [0, 30, 0]},
    \"influence\": {\"shape\": \"box\", \"center\": [20, 2, 0], \"halfExtents\": [5, 2.5, 4], \"rotation\": [0, 30, 0]},
    \"fadeDistance\": 0.5}],
  \"materials\": {\"roughness\": {\"min\": 0.05, \"max\": 0.8}, \"diffuseModel\": \"disney\"},
  \"outputs\": {\"directory\": \"${directory}\", \"quality\": \"draft\", \"faceSize\": 32, \"probeFaceSize\": 16,
              \"dfgSize\": 32, \"irradianceCube\": true}
}
")
endfunction()

# An installed `iblbake` must read the OCIO config installed with it (`config`), not the source tree's: a scene
# asking for an unknown colour space fails with an error naming the config it looked in.
function(package_test_expect_ocio_config iblbake config hdri work)
  package_test_write_scene("${work}/unknown_space.json" "${hdri}" "${work}/unknown_space" no-such-space)
  execute_process(COMMAND "${iblbake}" bake "${work}/unknown_space.json" --quiet
                  RESULT_VARIABLE result OUTPUT_VARIABLE stdout ERROR_VARIABLE stderr)
  string(FIND "${stderr}" "'no-such-space' is not a colour space of ${config}" at)
  if(result EQUAL 0 OR at EQUAL -1)
    message(FATAL_ERROR "${iblbake} did not read the OCIO config installed with it (${config}): exit ${result}\n"
                        "${stdout}${stderr}")
  endif()
  message(STATUS "${iblbake} reads ${config}")
endfunction()

# No OpenImageIO/OpenColorIO in a binary's NEEDED entries (readelf) nor among what it loads (ldd).
function(package_test_expect_no_oiio_ocio binary)
  package_test_run("readelf" needed readelf -d "${binary}")
  package_test_run("ldd" loaded ldd "${binary}")
  foreach(listing needed loaded)
    if(${listing} MATCHES "OpenImageIO|OpenColorIO")
      message(FATAL_ERROR "${binary} links OpenImageIO/OpenColorIO:\n${${listing}}")
    endif()
  endforeach()
  string(REGEX MATCHALL "NEEDED[^\n]*\\[[^]]*\\]" entries "${needed}")
  string(REGEX REPLACE "[^;]*\\[([^]]*)\\]" "\\1" entries "${entries}")
  message(STATUS "${binary}: NEEDED ${entries}")
endfunction()
