# A bad argument (run by ctest through `cmake -P`): obscura-viewer must exit 2, as docs/viewer.md says, with a
# message matching EXPECT. Variables: VIEWER, EXPECT; optional ARGS (viewer arguments, separated by spaces) and
# XVFB_RUN (run under a virtual X server: for arguments the viewer can only check once its window is open).
foreach(var VIEWER EXPECT)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "usage_error.cmake needs -D${var}=...")
  endif()
endforeach()
separate_arguments(viewer_args UNIX_COMMAND "${ARGS}")
if(DEFINED XVFB_RUN)
  # xvfb-run's own exit status can be 5 when another xvfb-run cleans up beside it (ctest -j): the viewer's status
  # is printed by a shell inside the X server's run and read from there.
  execute_process(COMMAND "${XVFB_RUN}" -a -s "-screen 0 1024x600x24"
                          sh -c "\"$0\" \"$@\"; echo \"viewer exit status: $?\"" "${VIEWER}" ${viewer_args}
                  OUTPUT_VARIABLE viewer_output ERROR_VARIABLE viewer_output)
  set(viewer_result "none")
  if(viewer_output MATCHES "viewer exit status: ([0-9]+)")
    set(viewer_result "${CMAKE_MATCH_1}")
  endif()
else()
  execute_process(COMMAND "${VIEWER}" ${viewer_args} RESULT_VARIABLE viewer_result OUTPUT_VARIABLE viewer_output
                  ERROR_VARIABLE viewer_output)
endif()
if(NOT viewer_result EQUAL 2)
  message(FATAL_ERROR "obscura-viewer exited with ${viewer_result}, not 2:\n${viewer_output}")
endif()
if(NOT viewer_output MATCHES "${EXPECT}")
  message(FATAL_ERROR "obscura-viewer's output does not match '${EXPECT}':\n${viewer_output}")
endif()
message(STATUS "${viewer_output}")
