# One scale-invariance check (tests/stress/CMakeLists.txt): renders a transformed scene and
# its untransformed source with the same seed, camera framing and spp on the CPU, then
# compares them with geocold-imgdiff. Inputs: GEOCOLD, IMGDIFF, SOURCE, SCENE, OUT_DIR,
# MEAN_REL_MAX, REL_MSE_MAX.
foreach(var GEOCOLD IMGDIFF SOURCE SCENE OUT_DIR MEAN_REL_MAX REL_MSE_MAX)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "scale_invariance.cmake needs -D${var}=...")
  endif()
endforeach()
file(MAKE_DIRECTORY "${OUT_DIR}")
get_filename_component(source_name "${SOURCE}" NAME_WE)
get_filename_component(scene_name "${SCENE}" NAME_WE)
set(source_image "${OUT_DIR}/${source_name}.pfm")
set(scene_image "${OUT_DIR}/${scene_name}.pfm")
foreach(pair "${SOURCE};${source_image}" "${SCENE};${scene_image}")
  list(GET pair 0 obj)
  list(GET pair 1 image)
  execute_process(COMMAND "${GEOCOLD}" "${obj}" --device cpu --res 64x64 --spp 32 --quiet -o "${image}"
                  RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "geocold-cl ${obj} exited ${rc}")
  endif()
endforeach()
execute_process(COMMAND "${IMGDIFF}" "${scene_image}" "${source_image}" --mean-rel-max ${MEAN_REL_MAX}
                        --rel-mse-max ${REL_MSE_MAX}
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${scene_name} does not render as ${source_name} does (geocold-imgdiff exited ${rc})")
endif()
