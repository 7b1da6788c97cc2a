# SPDX-License-Identifier: MIT
# Script mode (cmake -P), run by a test of splinerope_add_scene_test (SplineRopeSceneTest.cmake):
# runs `ropesim run SCENE` and fails unless its exit status is EXPECTED (0: every check held; 1: a
# check failed). ROPESIM, SCENE, JUNIT, EXPECTED; ARGUMENTS: "|"-separated extra arguments.
string(REPLACE "|" ";" arguments "${ARGUMENTS}")
execute_process(COMMAND "${ROPESIM}" run "${SCENE}" --no-render --quiet --junit "${JUNIT}" ${arguments}
  RESULT_VARIABLE status)
if(NOT "${status}" STREQUAL "${EXPECTED}")
  if(EXPECTED EQUAL 1)
    set(wanted "1 (a check fails)")
  else()
    set(wanted "0 (every check holds)")
  endif()
  message(FATAL_ERROR "ropesim run ${SCENE} exited with ${status}, expected ${wanted}")
endif()
