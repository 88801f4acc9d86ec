# One viewer smoke test (run by ctest through `cmake -P`): obscura-viewer renders a few frames of a scene
# with one method under Xvfb, saves a screenshot and exits 0; the screenshot must show the scene and the
# panel (obscura_viewer_screenshot_check). Variables: XVFB_RUN, VIEWER, CHECK, METHOD, VIEW, OUT, PANEL.
foreach(var XVFB_RUN VIEWER CHECK METHOD VIEW OUT PANEL)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "viewer_smoke.cmake needs -D${var}=...")
  endif()
endforeach()
file(REMOVE "${OUT}")
execute_process(
  COMMAND "${XVFB_RUN}" -a -s "-screen 0 1024x600x24"
          "${VIEWER}" --size 900x420 --method "${METHOD}" --view "${VIEW}" --reference-rays 8
          --screenshot "${OUT}" --frames 3
  RESULT_VARIABLE viewer_result
  OUTPUT_VARIABLE viewer_output
  ERROR_VARIABLE viewer_output)
if(NOT viewer_result EQUAL 0)
  message(FATAL_ERROR "obscura-viewer exited with ${viewer_result}:\n${viewer_output}")
endif()
if(NOT EXISTS "${OUT}")
  message(FATAL_ERROR "obscura-viewer exited 0 but wrote no ${OUT}:\n${viewer_output}")
endif()
execute_process(COMMAND "${CHECK}" "${OUT}" "${PANEL}" RESULT_VARIABLE check_result OUTPUT_VARIABLE check_output
                ERROR_VARIABLE check_output)
message(STATUS "${check_output}")
if(NOT check_result EQUAL 0)
  message(FATAL_ERROR "screenshot check failed (${check_result}): ${check_output}")
endif()
