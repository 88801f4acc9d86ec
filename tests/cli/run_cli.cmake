# Runs one command line of the obscura CLI and checks its exit status (and, optionally, its output).
#   cmake -DPROGRAM=<obscura> -DARGS="diff|a.png|b.png" -DEXPECT_EXIT=0 [-DWORK_DIR=dir]
#         [-DEXPECT_STDOUT=regex] [-DEXPECT_STDERR=regex] [-DEXPECT_FILES="f1|f2"] -P run_cli.cmake
# ARGS and EXPECT_FILES separate items with '|' (a ';' would be split by add_test). EXPECT_FILES are
# relative to WORK_DIR, which is emptied first and is the working directory of the command.
# With a non-zero expected exit status and no EXPECT_STDERR, stderr must be exactly one line.
foreach(required PROGRAM EXPECT_EXIT)
  if(NOT DEFINED ${required})
    message(FATAL_ERROR "run_cli.cmake needs -D${required}=...")
  endif()
endforeach()
string(REPLACE "|" ";" arguments "${ARGS}")
if(NOT WORK_DIR)
  set(WORK_DIR "${CMAKE_CURRENT_BINARY_DIR}")
endif()
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

execute_process(COMMAND "${PROGRAM}" ${arguments}
                WORKING_DIRECTORY "${WORK_DIR}"
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REPLACE ";" " " shown "${arguments}")
message(STATUS "obscura ${shown}\n-- exit ${status}\n-- stdout: ${out}-- stderr: ${err}")

set(problems "")
if(NOT status STREQUAL EXPECT_EXIT)
  string(APPEND problems "exit status ${status}, expected ${EXPECT_EXIT}\n")
endif()
if(DEFINED EXPECT_STDOUT AND NOT out MATCHES "${EXPECT_STDOUT}")
  string(APPEND problems "stdout does not match '${EXPECT_STDOUT}'\n")
endif()
if(DEFINED EXPECT_STDERR)
  if(NOT err MATCHES "${EXPECT_STDERR}")
    string(APPEND problems "stderr does not match '${EXPECT_STDERR}'\n")
  endif()
elseif(NOT EXPECT_EXIT STREQUAL "0")
  # One clear line: text, one newline at the end, none inside.
  string(REGEX MATCHALL "\n" newlines "${err}")
  list(LENGTH newlines newline_count)
  if(NOT newline_count EQUAL 1 OR NOT err MATCHES "\n$")
    string(APPEND problems "stderr is not exactly one line\n")
  endif()
endif()
if(DEFINED EXPECT_FILES)
  string(REPLACE "|" ";" files "${EXPECT_FILES}")
  foreach(file IN LISTS files)
    if(NOT EXISTS "${WORK_DIR}/${file}")
      string(APPEND problems "${file} was not written\n")
    endif()
  endforeach()
endif()
if(problems)
  message(FATAL_ERROR "${problems}")
endif()
