# What code decides each stage kind's bytes (docs/scenes.md "Cache"): the table behind the stage-code identity
# that every stage-cache key holds. Included by baker/CMakeLists.txt (configure time: the checks below) and
# by cmake/StageCodeIdentity.cmake (build time: the hashes).
#
# An entry is a path relative to the source root: a file, or a directory standing for every .cpp, .h and
# .cl directly in it; or the name of a group defined below (no "/"). From every listed file, #include
# lines are followed ("x.h" and <x.h>, looked up beside the including file, then in each directory of
# IBLBAKE_CODE_INCLUDE_DIRS; names found nowhere there are system or third-party headers), so a stage
# holds the kernel headers its kernels and its CPU code include, and the baker headers its code includes,
# without listing them. What is not reached that way, the .cpp files that implement what a stage calls
# and the .cl programs it builds, is listed here.
#
# Granularity: one identity per stage kind, so that a change reaches only the kinds whose code it touches
# (kernels/dfg.h: dfg-lut alone; kernels/ld.h: specular-ld and probe-ld; kernels/bright_list.h: those and
# irradiance-cube, whose kernel includes it; kernels/cube.h or ingest/: every kind that ingests, and through
# the keys' dependency chain every stage downstream). The scene-stage runner (scene_stages.cpp: all kinds in one file) and the KTX2
# container code are in every kind.
#
# Adding a source file: a new file under baker/src/ or kernels/ must be reached by some kind or be listed
# in IBLBAKE_CODE_NOT_IN_STAGES; configure fails otherwise, and for a listed path that does not exist.

set(IBLBAKE_CODE_INCLUDE_DIRS kernels baker/include/core baker/include/opencl baker/include/ktx2
    baker/include/scene baker/include/bake_state baker/include/baker baker/src/opencl baker/runtime/include)

# Groups shared by several kinds.
set(IBLBAKE_CODE_stage_runner # reads dependency entries, writes every stage's files (products), the entry layout
    baker/src/scene/scene_stages.cpp baker/src/scene/stage_runner.cpp baker/src/scene/stage_cache.cpp
    baker/src/io/ktx2_writer.cpp
    baker/src/io/ktx2_reader.cpp baker/src/io/ktx2_format_names.cpp baker/src/io/ktx2_storage_scale.cpp
    baker/src/io/bc6h_encode.cpp baker/src/io/bc6h_decode.cpp baker/src/io/dds_writer.cpp
    baker/src/io/cube_profile.cpp
    baker/src/products)
set(IBLBAKE_CODE_kernel_host # backend choice, program assembly and build options
    baker/src/executor.cpp baker/src/opencl baker/src/dispatch)
set(IBLBAKE_CODE_ingest # images to cubes, colour spaces, calibration; the OpenImageIO module reads formats
    baker/src/ingest baker/src/calibration baker/src/environment baker/src/io/oiio_module.h
    baker/src/io/oiio_module_loader.cpp baker/oiio_module)
set(IBLBAKE_CODE_ld_chain # the split-sum LD chain: kernel, CPU loops, pyramid, bright texels, level 0
    kernels/ld.cl baker/src/stages/specular.cpp baker/src/stages/lobe_integral.cpp baker/src/stages/ld_host_items.cpp
    baker/src/stages/host_clones.h
    baker/src/stages/cube_pyramid.cpp baker/src/stages/bright_split.cpp baker/src/stages/sun_in_level0.cpp)

# The stage kinds of the planner (baker/src/scene/scene_plan.cpp); a planned kind missing here makes key
# computation throw. "manifest" is no stage: manifest.json is written by every bake that is not up to date,
# and records this identity so that the up-to-date check does not keep one written by other code.
set(IBLBAKE_STAGE_KINDS dfg-lut environment sun-extract sun-in-probe specular-ld diffuse-sh irradiance-cube probe-ld
    gltf-export preview-reference material-preview light-card manifest)
set(IBLBAKE_STAGE_CODE_dfg-lut stage_runner kernel_host kernels/dfg.cl baker/src/stages/dfg_lut.cpp
    baker/src/stages/host_clones.h)
set(IBLBAKE_STAGE_CODE_environment stage_runner ingest)
set(IBLBAKE_STAGE_CODE_sun-extract stage_runner baker/src/calibration baker/src/environment)
# The sun-in-probe check (its facts, which the manifest's warnings read): the shipped probe's bake and the
# runtime module against the converged reference.
set(IBLBAKE_STAGE_CODE_sun-in-probe stage_runner kernel_host ld_chain baker/src/runtime_check
    baker/src/calibration baker/src/environment kernels/dfg.cl baker/src/stages/dfg_lut.cpp
    baker/src/stages/sh_projection.cpp kernels/irradiance.cl baker/src/stages/irradiance.cpp
    baker/runtime/src kernels/runtime.cl)
set(IBLBAKE_STAGE_CODE_specular-ld stage_runner kernel_host ld_chain)
set(IBLBAKE_STAGE_CODE_diffuse-sh stage_runner baker/src/stages/sh_projection.cpp baker/src/stages/sh_window_text.cpp)
set(IBLBAKE_STAGE_CODE_irradiance-cube stage_runner kernel_host kernels/irradiance.cl
    baker/src/stages/irradiance.cpp baker/src/stages/cube_pyramid.cpp baker/src/stages/bright_split.cpp)
set(IBLBAKE_STAGE_CODE_probe-ld stage_runner kernel_host ingest ld_chain)
# The engine outputs (outputs.gltf, outputs.preview): the flows of `iblbake gltf` (the residual of a level 0
# that kept the sun, the re-filter to the babylon profile's levels, the RGBD PNG writer) and `iblbake preview`
# (the runtime module and its kernels, the brute-force reference, the labelled grid, PNG and EXR writers).
set(IBLBAKE_STAGE_CODE_gltf-export stage_runner kernel_host ld_chain baker/src/scene/engine_output_stages.cpp
    baker/src/export baker/src/calibration baker/src/io/gltf_ibl.cpp baker/src/io/rgbd_png.cpp
    baker/src/io/encoded_image.cpp)
# The preview's converged reference (issue 46): the balls' points and the adaptive reference, no backend.
set(IBLBAKE_STAGE_CODE_preview-reference stage_runner baker/src/scene/engine_output_stages.cpp
    baker/src/preview/material_preview.cpp baker/src/preview/preview_grid.cpp baker/runtime/src)
set(IBLBAKE_STAGE_CODE_material-preview stage_runner kernel_host baker/src/scene/engine_output_stages.cpp
    baker/src/preview baker/runtime/src kernels/runtime.cl baker/src/io/preview.cpp baker/src/io/exr_output.cpp
    baker/src/io/encoded_image.cpp baker/oiio_module)
# A textured light's card (lights[].texture): the texture's read and colour conversion, the bake and its file.
set(IBLBAKE_STAGE_CODE_light-card stage_runner kernel_host kernels/light_card.cl baker/src/light_card
    baker/src/ingest/read_image.cpp baker/src/ingest/color.cpp baker/src/ingest/sanitize.cpp)
set(IBLBAKE_STAGE_CODE_manifest baker/src/scene/scene_manifest.cpp baker/src/scene/scene_lights.cpp baker/src/scene/bake_scene.cpp
    baker/src/products)

# Sources that decide no stage's bytes: planning and keys (their effect is in the key's settings and
# dependency chain), the bake's bookkeeping, the Filament SH exporter, batch, accuracy, the dispatch test kernel,
# the runtime's area-light kernel.
set(IBLBAKE_CODE_NOT_IN_STAGES
    baker/src/scene/bake_summary.cpp baker/src/scene/bake_report.cpp baker/src/scene/console_progress.cpp
    baker/src/scene/content_hash.cpp baker/src/scene/scene_parse.cpp
    baker/src/scene/scene_plan.cpp baker/src/scene/stage_keys.cpp baker/src/scene/stage_keys.h
    baker/src/scene/up_to_date.cpp baker/src/scene/output_root_check.cpp
    baker/src/scene/product_plans.cpp baker/src/scene/product_run_text.cpp # a command's plan, its files' delivery, its report
    baker/src/batch baker/src/accuracy
    baker/src/light_preview # `iblbake preview --lights`: no stage renders it
    baker/src/export/filament_export.cpp baker/src/io/ktx1_writer.cpp # `iblbake export-filament`: no stage writes it
    baker/src/flows # `iblbake inspect` and `calibrate`: no stage runs them
    baker/src/io/atomic_file.cpp baker/src/io/filament_sh.cpp baker/src/io/muted_stderr.h
    baker/src/io/output_set.cpp baker/src/io/temporary_path.cpp # move finished files into place, decide no bytes
    baker/src/io/output_root.cpp # where outputs may go, decides no bytes
    baker/src/scene/plan_budget.cpp baker/src/scene/image_header_size.cpp baker/src/scene/image_header_size.h # refuse a plan over budget, decide no bytes
    baker/src/io/input_file.cpp baker/src/io/limits.cpp # refuse inputs before work, decide no bytes
    baker/src/io/shipped_file.cpp baker/src/io/shipped_file.h # where shipped files are, not what they hold
    baker/src/io/process_memory.cpp # where freed memory goes, decides no bytes
    baker/src/stages/specular_reference.cpp baker/src/stages/specular_settings.cpp
    kernels/dispatch_check.cl kernels/dispatch_check.h # dispatch_check: the dispatch helper's test kernel
    kernels/area_lights.cl # the runtime's area lights: no stage renders them
    kernels/textured_light.cl) # ... nor textured ones

# _iblbake_code_files(<root> <out-var> <entry>...): the files (relative to <root>, sorted) that the
# entries name, expanded through groups and directories. Fails for a path that does not exist or a
# directory without sources.
function(_iblbake_code_files root out)
  set(files "")
  foreach(entry IN LISTS ARGN)
    if(NOT entry MATCHES "/")
      if(NOT DEFINED IBLBAKE_CODE_${entry})
        message(FATAL_ERROR "cmake/StageCode.cmake: no group '${entry}'")
      endif()
      _iblbake_code_files("${root}" group ${IBLBAKE_CODE_${entry}})
      list(APPEND files ${group})
    elseif(IS_DIRECTORY "${root}/${entry}")
      file(GLOB found RELATIVE "${root}" "${root}/${entry}/*.cpp" "${root}/${entry}/*.h" "${root}/${entry}/*.cl")
      if(NOT found)
        message(FATAL_ERROR "cmake/StageCode.cmake: ${entry}/ holds no .cpp, .h or .cl file")
      endif()
      list(APPEND files ${found})
    elseif(EXISTS "${root}/${entry}")
      list(APPEND files "${entry}")
    else()
      message(FATAL_ERROR "cmake/StageCode.cmake: ${entry} does not exist")
    endif()
  endforeach()
  list(REMOVE_DUPLICATES files)
  list(SORT files)
  set(${out} ${files} PARENT_SCOPE)
endfunction()

# _iblbake_stage_code(<root> <out-var> <kind>): the kind's files and every file they include (see above),
# relative to <root>, sorted.
function(_iblbake_stage_code root out kind)
  if(NOT DEFINED IBLBAKE_STAGE_CODE_${kind})
    message(FATAL_ERROR "cmake/StageCode.cmake: stage kind '${kind}' has no IBLBAKE_STAGE_CODE_${kind}")
  endif()
  _iblbake_code_files("${root}" pending ${IBLBAKE_STAGE_CODE_${kind}})
  set(seen "")
  while(pending)
    list(POP_FRONT pending file)
    if(file IN_LIST seen)
      continue()
    endif()
    list(APPEND seen "${file}")
    get_filename_component(directory "${file}" DIRECTORY)
    file(STRINGS "${root}/${file}" lines REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"]")
    foreach(line IN LISTS lines)
      if(NOT line MATCHES "^[ \t]*#[ \t]*include[ \t]*[<\"]([^>\"]+)[>\"]")
        continue()
      endif()
      set(name "${CMAKE_MATCH_1}")
      foreach(base IN ITEMS "${directory}" ${IBLBAKE_CODE_INCLUDE_DIRS})
        if(EXISTS "${root}/${base}/${name}" AND NOT IS_DIRECTORY "${root}/${base}/${name}")
          file(RELATIVE_PATH found "${root}" "${root}/${base}/${name}")
          list(APPEND pending "${found}")
          break()
        endif()
      endforeach()
    endforeach()
  endwhile()
  list(SORT seen)
  set(${out} ${seen} PARENT_SCOPE)
endfunction()

# iblbake_check_stage_code(<root>): configure-time check of the table. Every listed path exists, and every
# source under baker/src/ and kernels/ is reached by some kind or listed in IBLBAKE_CODE_NOT_IN_STAGES.
function(iblbake_check_stage_code root)
  set(reached "")
  foreach(kind IN LISTS IBLBAKE_STAGE_KINDS)
    _iblbake_stage_code("${root}" files ${kind})
    list(APPEND reached ${files})
  endforeach()
  _iblbake_code_files("${root}" exempt ${IBLBAKE_CODE_NOT_IN_STAGES})
  file(GLOB_RECURSE unreached CONFIGURE_DEPENDS RELATIVE "${root}" "${root}/baker/src/*.cpp"
       "${root}/baker/src/*.h" "${root}/kernels/*.h" "${root}/kernels/*.cl")
  list(REMOVE_ITEM unreached ${reached} ${exempt})
  if(unreached)
    list(JOIN unreached ", " names)
    message(FATAL_ERROR "cmake/StageCode.cmake: no stage kind's code reaches ${names}: add each to the kinds "
                        "whose bytes it decides, or to IBLBAKE_CODE_NOT_IN_STAGES")
  endif()
endfunction()
