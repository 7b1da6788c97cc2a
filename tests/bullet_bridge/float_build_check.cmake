# SPDX-License-Identifier: MIT
# The float build (Debian's single-precision Bullet, btScalar = float): configures SplineRope with
# -DSPLINEROPE_BULLET_DOUBLE=OFF into its own build directory, builds the bridge and one scenario
# test there, runs it, and checks that it really ran with a 4-byte btScalar.
# Inputs: SOURCE_DIR, WORK_DIR, GENERATOR, CXX, C.
foreach(var SOURCE_DIR WORK_DIR GENERATOR CXX C)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "float_build_check.cmake: ${var} is not set")
  endif()
endforeach()

execute_process(
  COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR} -G ${GENERATOR}
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_C_COMPILER=${C}
    -DSPLINEROPE_BULLET_DOUBLE=OFF
  RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "configuring the float build failed:\n${output}")
endif()

execute_process(
  COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR} --target bullet_bridge_float_build_test --parallel 2
  RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "building the bridge with float Bullet failed:\n${output}")
endif()

execute_process(
  COMMAND ${WORK_DIR}/tests/bullet_bridge/bullet_bridge_float_build_test
  RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
message("${output}")
if(NOT result EQUAL 0)
  message(FATAL_ERROR "the float-build scenario test failed")
endif()
if(NOT output MATCHES "btScalar 4 bytes")
  message(FATAL_ERROR "the float-build test did not run with btScalar = float")
endif()
