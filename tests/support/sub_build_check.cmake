# SPDX-License-Identifier: MIT
# A test that needs SplineRope built another way (float Bullet, AddressSanitizer): configures the
# project with OPTION into its own build directory, builds one test program there, runs it, and checks
# that its output shows the build really was that way (MARKER, a regular expression the program
# prints only in such a build). splinerope_add_sub_build_test (tests/CMakeLists.txt) calls it.
# Inputs: SOURCE_DIR, WORK_DIR, GENERATOR, CXX, C, BUILD_TYPE, OPTION (one -D...), TARGET,
# PROGRAM (its path in the build directory), MARKER, WHAT (the build's name for messages).
foreach(var SOURCE_DIR WORK_DIR GENERATOR CXX C BUILD_TYPE OPTION TARGET PROGRAM MARKER WHAT)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "sub_build_check.cmake: ${var} is not set")
  endif()
endforeach()

execute_process(
  COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR} -G ${GENERATOR}
    -DCMAKE_BUILD_TYPE=${BUILD_TYPE} -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_C_COMPILER=${C} ${OPTION}
  RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "configuring the ${WHAT} failed:\n${output}")
endif()

execute_process(
  COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR} --target ${TARGET} --parallel 2
  RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "building ${TARGET} in the ${WHAT} failed:\n${output}")
endif()

execute_process(
  COMMAND ${WORK_DIR}/${PROGRAM}
  RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
message("${output}")
if(NOT result EQUAL 0)
  message(FATAL_ERROR "${TARGET} failed in the ${WHAT}")
endif()
if(NOT output MATCHES "${MARKER}")
  message(FATAL_ERROR "${TARGET} did not print '${MARKER}': it did not run in the ${WHAT}")
endif()
