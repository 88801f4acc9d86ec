# One viewer smoke test (run by ctest through `cmake -P`): obscura-viewer renders a few frames of a scene
# with one method under Xvfb, saves a screenshot and exits 0; the screenshot must show the scene and the
# panel (obscura_viewer_screenshot_check). Variables: XVFB_RUN, VIEWER, CHECK, METHOD, VIEW, OUT, PANEL.
# Optional: SIZE (900x420), FRAMES (3), ARGS (more viewer arguments, separated by spaces), CHECK_MODE (`heat`:
# the scene must be an error heat map; `none`: no screenshot check), EXPECT (a regular expression the viewer's
# output must match).
foreach(var XVFB_RUN VIEWER CHECK METHOD VIEW OUT PANEL)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "viewer_smoke.cmake needs -D${var}=...")
  endif()
endforeach()
if(NOT DEFINED SIZE)
  set(SIZE 900x420)
endif()
if(NOT DEFINED FRAMES)
  set(FRAMES 3)
endif()
# ARGS is a shell-like line: paths in it are quoted (a checkout path may hold spaces).
separate_arguments(extra_args UNIX_COMMAND "${ARGS}")
file(REMOVE "${OUT}")
# xvfb-run's own exit status can be 5 when another xvfb-run cleans up beside it (ctest -j), whatever the viewer
# did: the viewer's status is printed by a shell inside the X server's run and read from there (as usage_error.cmake).
execute_process(
  COMMAND "${XVFB_RUN}" -a -s "-screen 0 1024x600x24"
          sh -c "\"$0\" \"$@\"; echo \"viewer exit status: $?\""
          "${VIEWER}" --size "${SIZE}" --method "${METHOD}" --view "${VIEW}" --reference-rays 8 ${extra_args}
          --screenshot "${OUT}" --frames "${FRAMES}"
  OUTPUT_VARIABLE viewer_output
  ERROR_VARIABLE viewer_output)
set(viewer_result "none (xvfb-run did not run it)")
if(viewer_output MATCHES "viewer exit status: ([0-9]+)")
  set(viewer_result "${CMAKE_MATCH_1}")
endif()
if(NOT viewer_result EQUAL 0)
  message(FATAL_ERROR "obscura-viewer exited with ${viewer_result}:\n${viewer_output}")
endif()
if(NOT EXISTS "${OUT}")
  message(FATAL_ERROR "obscura-viewer exited 0 but wrote no ${OUT}:\n${viewer_output}")
endif()
if(DEFINED EXPECT AND NOT viewer_output MATCHES "${EXPECT}")
  message(FATAL_ERROR "obscura-viewer's output does not match '${EXPECT}':\n${viewer_output}")
endif()
message(STATUS "${viewer_output}")
if(CHECK_MODE STREQUAL "none")
  return()
endif()
execute_process(COMMAND "${CHECK}" "${OUT}" "${PANEL}" ${CHECK_MODE} RESULT_VARIABLE check_result OUTPUT_VARIABLE check_output
                ERROR_VARIABLE check_output)
message(STATUS "${check_output}")
if(NOT check_result EQUAL 0)
  message(FATAL_ERROR "screenshot check failed (${check_result}): ${check_output}")
endif()
