# Compiles probe.glsl with glslangValidator as one GLSL version: "#version VERSION", probe.glsl, then MAIN
# (the browser suite's fragment shader, tests/js/glsl_runtime_points.frag), as a fragment shader.
# Run as a script: cmake -DVALIDATOR=... -DVERSION="300 es" -DGLSL=.../probe.glsl -DMAIN=... -DOUTPUT=x.frag
#                        -P check_glsl.cmake
cmake_minimum_required(VERSION 3.22)
file(READ "${GLSL}" probe)
file(READ "${MAIN}" main)
file(WRITE "${OUTPUT}" "#version ${VERSION}\n${probe}${main}")
execute_process(COMMAND "${VALIDATOR}" -S frag "${OUTPUT}" RESULT_VARIABLE result OUTPUT_VARIABLE out
                ERROR_VARIABLE out)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "glslangValidator: GLSL ${VERSION} does not compile (${OUTPUT}):\n${out}")
endif()
message(STATUS "GLSL ${VERSION}: ${OUTPUT} compiles")
