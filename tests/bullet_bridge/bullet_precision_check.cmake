# SPDX-License-Identifier: MIT
# cmake -P script: compiles and links bullet_precision_program.cpp twice against the bullet_bridge
# library, once with the library's Bullet precision (must link) and once with the other (must fail
# with an undefined reference to the precision symbol).
foreach(var CXX SOURCE INCLUDES LIBRARY WORK_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "bullet_precision_check.cmake: ${var} not set")
  endif()
endforeach()
file(MAKE_DIRECTORY "${WORK_DIR}")
set(include_flags "")
foreach(dir IN LISTS INCLUDES)
  list(APPEND include_flags "-I${dir}")
endforeach()

function(try_link name flags result_var output_var)
  execute_process(
    COMMAND "${CXX}" -std=c++17 ${flags} ${LINK_FLAGS} ${include_flags} "${SOURCE}" "${LIBRARY}"
            -o "${WORK_DIR}/${name}"
    RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(${result_var} "${result}" PARENT_SCOPE)
  set(${output_var} "${out}${err}" PARENT_SCOPE)
endfunction()

try_link(matching "${MATCHING_FLAGS}" matching_result matching_output)
if(NOT matching_result EQUAL 0)
  message(FATAL_ERROR "the program with the library's precision failed to link:\n${matching_output}")
endif()

try_link(mismatched "${MISMATCHED_FLAGS}" mismatched_result mismatched_output)
if(mismatched_result EQUAL 0)
  message(FATAL_ERROR "the program with the other Bullet precision linked; the guard is broken")
endif()
if(NOT mismatched_output MATCHES "splinerope_bullet_built_with_(float|double)")
  message(FATAL_ERROR "the mismatched program failed for another reason:\n${mismatched_output}")
endif()
message(STATUS "precision guard OK: mismatched link failed on the precision symbol")
