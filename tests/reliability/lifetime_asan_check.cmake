# SPDX-License-Identifier: MIT
# The lifetime tests under AddressSanitizer in the default test run: configures SplineRope with
# -DSPLINEROPE_SANITIZE=ON into its own build directory (Debug: -O0 compiles faster, and the tests
# are small), builds only the lifetime test binary with the rope and bridge libraries it needs,
# runs it, and checks that it really ran with ASan.
# Inputs: SOURCE_DIR, WORK_DIR, GENERATOR, CXX, C.
foreach(var SOURCE_DIR WORK_DIR GENERATOR CXX C)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "lifetime_asan_check.cmake: ${var} is not set")
  endif()
endforeach()

execute_process(
  COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR} -G ${GENERATOR}
    -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_C_COMPILER=${C}
    -DSPLINEROPE_SANITIZE=ON
  RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "configuring the sanitizer build failed:\n${output}")
endif()

execute_process(
  COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR} --target reliability_lifetime_test --parallel 2
  RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "building the lifetime tests with ASan failed:\n${output}")
endif()

execute_process(
  COMMAND ${WORK_DIR}/tests/reliability/reliability_lifetime_test
  RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
message("${output}")
if(NOT result EQUAL 0)
  message(FATAL_ERROR "the lifetime tests failed under AddressSanitizer")
endif()
if(NOT output MATCHES "AddressSanitizer on")
  message(FATAL_ERROR "the lifetime tests did not run with AddressSanitizer")
endif()
