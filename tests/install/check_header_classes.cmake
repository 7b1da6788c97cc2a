# SPDX-License-Identifier: MIT
# Script mode (cmake -DSOURCE_DIR=... -P check_header_classes.cmake): every header under rope/,
# bullet_bridge/ and render/ is in exactly one of the API, SUPPORT and INTERNAL lists of
# cmake/SplineRopeHeaders.cmake, every listed header exists, and every SUPPORT header says "Not API".
cmake_minimum_required(VERSION 3.25)
set(PROJECT_SOURCE_DIR "${SOURCE_DIR}")
include("${SOURCE_DIR}/cmake/SplineRopeHeaders.cmake")

set(problems "")
set(listed "")
foreach(module IN ITEMS ROPE BULLET_BRIDGE RENDER)
  foreach(class IN ITEMS API SUPPORT INTERNAL)
    foreach(header IN LISTS SPLINEROPE_${module}_${class}_HEADERS)
      if(header IN_LIST listed)
        list(APPEND problems "${header} is listed twice")
      endif()
      list(APPEND listed "${header}")
      if(NOT EXISTS "${SOURCE_DIR}/${header}")
        list(APPEND problems "${header} is listed but does not exist")
      elseif(class STREQUAL "SUPPORT")
        file(READ "${SOURCE_DIR}/${header}" text)
        string(FIND "${text}" "Not API" at)
        if(at EQUAL -1)
          list(APPEND problems "${header} is a support header but does not say \"Not API\"")
        endif()
      endif()
    endforeach()
  endforeach()
endforeach()

file(GLOB_RECURSE headers RELATIVE "${SOURCE_DIR}"
  "${SOURCE_DIR}/rope/*.h" "${SOURCE_DIR}/bullet_bridge/*.h" "${SOURCE_DIR}/render/*.h")
foreach(header IN LISTS headers)
  if(NOT header IN_LIST listed)
    list(APPEND problems "${header} is in no class: add it to cmake/SplineRopeHeaders.cmake as API, SUPPORT or INTERNAL")
  endif()
endforeach()

if(problems)
  list(JOIN problems "\n  " report)
  message(FATAL_ERROR "Header classes:\n  ${report}")
endif()
list(LENGTH headers count)
message(STATUS "${count} headers, each in one class")
