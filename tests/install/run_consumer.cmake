# SPDX-License-Identifier: MIT
# Script mode (cmake -P): install this build into a scratch prefix, then configure, build and run a
# consumer project against the installed tree only. Any failure is fatal.
#
#   SPLINEROPE_BUILD_DIR, CONSUMER_SOURCE_DIR, WORK_DIR, GENERATOR, BUILD_TYPE   (required)
#   INSTALL_COMPONENTS   "|"-separated install components (cmake --install --component); empty: all
#   CONFIGURE_ARGS       "|"-separated extra arguments for the consumer's configure step
#   PKG_CONFIG_MODULES   "|"-separated pkg-config modules the consumer may see; "NONE": none. When
#                        set, the consumer's configure runs with PKG_CONFIG_LIBDIR pointing at a
#                        directory holding only those modules' .pc files: a system without the others.
#   BUILD_PARALLEL       build jobs for the consumer (default 1: tests run side by side)
#   RUN                  name of the consumer's program to run after building (empty: do not run)
#   RUN_CTEST            true: run the consumer's ctest after building (every test must pass)
#   EXPECT_CONFIGURE_FAILURE  regular expression: the configure step must fail with a message
#                        matching it, white space collapsed to single spaces (nothing is built)
file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")

function(run_step description)
  file(MAKE_DIRECTORY "${WORK_DIR}/build")
  execute_process(COMMAND ${ARGN} WORKING_DIRECTORY "${WORK_DIR}/build"
    RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${description} failed (${result}):\n${out}\n${err}")
  endif()
  message(STATUS "${description}: ok")
  if(out)
    message(STATUS "${out}")
  endif()
endfunction()

# Install.
if(INSTALL_COMPONENTS)
  string(REPLACE "|" ";" components "${INSTALL_COMPONENTS}")
  foreach(component IN LISTS components)
    run_step("install component ${component}" ${CMAKE_COMMAND} --install "${SPLINEROPE_BUILD_DIR}"
      --prefix "${prefix}" --component ${component})
  endforeach()
else()
  run_step("install" ${CMAKE_COMMAND} --install "${SPLINEROPE_BUILD_DIR}" --prefix "${prefix}")
endif()

# The environment of the configure step.
set(environment "")
if(PKG_CONFIG_MODULES)
  set(pcdir "${WORK_DIR}/pkgconfig")
  file(MAKE_DIRECTORY "${pcdir}")
  if(NOT PKG_CONFIG_MODULES STREQUAL "NONE")
    find_program(PKG_CONFIG_EXECUTABLE pkg-config REQUIRED)
    string(REPLACE "|" ";" modules "${PKG_CONFIG_MODULES}")
    foreach(module IN LISTS modules)
      execute_process(COMMAND "${PKG_CONFIG_EXECUTABLE}" --variable=pcfiledir ${module}
        OUTPUT_VARIABLE dir OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE result)
      if(NOT result EQUAL 0 OR NOT EXISTS "${dir}/${module}.pc")
        message(FATAL_ERROR "pkg-config module ${module} not found on this machine")
      endif()
      file(COPY "${dir}/${module}.pc" DESTINATION "${pcdir}")
    endforeach()
  endif()
  set(environment ${CMAKE_COMMAND} -E env "PKG_CONFIG_LIBDIR=${pcdir}" "PKG_CONFIG_PATH=")
endif()
set(arguments "")
if(CONFIGURE_ARGS)
  string(REPLACE "|" ";" arguments "${CONFIGURE_ARGS}")
endif()

set(configure ${environment} ${CMAKE_COMMAND} -S "${CONSUMER_SOURCE_DIR}" -B "${WORK_DIR}/build"
  -G "${GENERATOR}" -DCMAKE_BUILD_TYPE=${BUILD_TYPE} "-DCMAKE_PREFIX_PATH=${prefix}"
  -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF ${arguments})

if(EXPECT_CONFIGURE_FAILURE)
  execute_process(COMMAND ${configure} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(result EQUAL 0)
    message(FATAL_ERROR "configure consumer succeeded, but it was expected to fail:\n${out}\n${err}")
  endif()
  # CMake wraps long messages and indents them: compare with all white space collapsed.
  string(REGEX REPLACE "[ \t\r\n]+" " " flat "${out}${err}")
  if(NOT flat MATCHES "${EXPECT_CONFIGURE_FAILURE}")
    message(FATAL_ERROR "configure consumer failed, but not with a message matching "
      "'${EXPECT_CONFIGURE_FAILURE}':\n${out}\n${err}")
  endif()
  message(STATUS "configure consumer failed as expected")
  return()
endif()

run_step("configure consumer" ${configure})
if(NOT BUILD_PARALLEL)
  set(BUILD_PARALLEL 1)
endif()
run_step("build consumer" ${CMAKE_COMMAND} --build "${WORK_DIR}/build" --parallel ${BUILD_PARALLEL})
if(RUN)
  run_step("run consumer" "${WORK_DIR}/build/${RUN}")
endif()
if(RUN_CTEST)
  run_step("ctest consumer" ${CMAKE_CTEST_COMMAND} --output-on-failure)
endif()
