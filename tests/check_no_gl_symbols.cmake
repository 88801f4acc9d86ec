# cmake -DNM=<nm> -DLIBRARY=<libobscura.a> [-DSHARED=ON] -P check_no_gl_symbols.cmake
#
# The SDK loads GL into a private table (glad --mx, entry points static), so a host may link its own
# glad, GLEW or epoxy beside it. Fails when the archive
#   - defines an external (global or weak) symbol whose name starts with gl, glad or GLAD, or
#   - references an undefined gl* symbol (it would need libGL / libOpenGL at link time).
#   - holds even a local (static) symbol named gl* or glad*: gl_loader.c renames glad's static helpers,
#     which GCC may emit as clones such as "..._load_GL_VERSION_4_1.constprop.0".
if(NOT NM OR NOT LIBRARY)
  message(FATAL_ERROR "usage: cmake -DNM=<nm> -DLIBRARY=<archive> -P check_no_gl_symbols.cmake")
endif()
if(NOT EXISTS "${LIBRARY}")
  message(FATAL_ERROR "${LIBRARY} does not exist")
endif()

function(run_nm out_var)
  execute_process(COMMAND "${NM}" ${ARGN} "${LIBRARY}"
                  OUTPUT_VARIABLE output ERROR_VARIABLE errors RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${NM} ${ARGN} failed (${result}): ${errors}")
  endif()
  string(REPLACE "\n" ";" lines "${output}")
  set(${out_var} "${lines}" PARENT_SCOPE)
endfunction()

# A shared build (OBSCURA_SHARED=ON, -DSHARED=ON): the dynamic symbol table must export the C API only.
if(SHARED)
  run_nm(dynamic --dynamic --defined-only)
  set(exported 0)
  set(violations "")
  foreach(line IN LISTS dynamic)
    if(line MATCHES "^[0-9a-fA-F]+ ([A-Za-z]) (.+)$")
      set(name "${CMAKE_MATCH_2}")
      if(name MATCHES "^obscura_")
        math(EXPR exported "${exported} + 1")
      elseif(NOT name MATCHES "^(_init|_fini|_edata|_end|__bss_start)$")
        list(APPEND violations "${name}")
      endif()
    endif()
  endforeach()
  if(exported EQUAL 0)
    message(FATAL_ERROR "${LIBRARY} exports no obscura_* symbol")
  endif()
  if(violations)
    string(REPLACE ";" "\n  " text "${violations}")
    message(FATAL_ERROR "${LIBRARY} exports symbols outside the C API:\n  ${text}")
  endif()
  message(STATUS "OK: ${exported} obscura_* symbols exported, nothing else")
  return()
endif()

# Lines are "<value> <type> <name>" (defined) or "<spaces> U <name>" (undefined); "file.o:" headers.
run_nm(defined_external --defined-only --extern-only)
set(violations "")
set(external_count 0)
foreach(line IN LISTS defined_external)
  if(line MATCHES "^[0-9a-fA-F]+ ([A-Za-z]) (.+)$")
    math(EXPR external_count "${external_count} + 1")
    set(name "${CMAKE_MATCH_2}")
    if(name MATCHES "^(gl|glad|GLAD)")
      list(APPEND violations "defines ${CMAKE_MATCH_1} ${name}")
    endif()
  endif()
endforeach()
if(external_count EQUAL 0)
  message(FATAL_ERROR "nm listed no external symbol in ${LIBRARY}: the check would be vacuous")
endif()

run_nm(undefined --undefined-only)
foreach(line IN LISTS undefined)
  if(line MATCHES "^ *U (gl.*)$")
    list(APPEND violations "references undefined ${CMAKE_MATCH_1}")
  endif()
endforeach()

if(violations)
  string(REPLACE ";" "\n  " text "${violations}")
  message(FATAL_ERROR "libobscura exposes GL loader symbols:\n  ${text}")
endif()

# The C API must be there (guards against checking the wrong file).
set(found_api FALSE)
foreach(line IN LISTS defined_external)
  if(line MATCHES " T obscura_render$")
    set(found_api TRUE)
  endif()
endforeach()
if(NOT found_api)
  message(FATAL_ERROR "obscura_render is not defined in ${LIBRARY}")
endif()

# Local (static) symbols cannot clash, but the SDK renames glad's internal helpers too (gl_loader.c), so a
# host reading `nm` sees no glad code at all: any local gl*/glad* symbol is a regression of that renaming.
run_nm(defined_all --defined-only)
set(local_gl "")
foreach(line IN LISTS defined_all)
  if(line MATCHES "^[0-9a-fA-F]+ ([a-z]) ((gl|glad|GLAD).*)$")
    list(APPEND local_gl "${CMAKE_MATCH_2}")
  endif()
endforeach()
if(local_gl)
  string(REPLACE ";" "\n  " text "${local_gl}")
  message(FATAL_ERROR "libobscura has local gl*/glad* symbols (add them to gl_loader.c's renames):\n  ${text}")
endif()

message(STATUS "OK: ${external_count} external symbols and no local symbol named gl*/glad*")
