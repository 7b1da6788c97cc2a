# SPDX-License-Identifier: MIT
# Every source file of the library, its tests, demos and build scripts names its licence in its first
# three lines with "SPDX-License-Identifier: MIT" (LICENSE; https://spdx.dev/ids), so a file copied
# out of the repository still says what it may be used under.
cmake_minimum_required(VERSION 3.25)
# The files to check: the top-level build files, then every source and build file below the module
# directories.
set(paths CMakeLists.txt .ci/run)
foreach(directory IN ITEMS rope bullet_bridge render demos tests cmake)
  file(GLOB_RECURSE found RELATIVE "${SOURCE_DIR}" "${SOURCE_DIR}/${directory}/*")
  foreach(path IN LISTS found)
    if(path MATCHES "(\\.h|\\.cpp|\\.cmake|\\.cmake\\.in|\\.gp|/CMakeLists\\.txt)$")
      list(APPEND paths "${path}")
    endif()
  endforeach()
endforeach()
set(missing "")
list(LENGTH paths count)
foreach(path IN LISTS paths)
  file(STRINGS "${SOURCE_DIR}/${path}" head LIMIT_COUNT 3)
  if(NOT head MATCHES "SPDX-License-Identifier: MIT")
    list(APPEND missing "${path}")
  endif()
endforeach()
if(count LESS 300)
  message(FATAL_ERROR "found only ${count} source files under ${SOURCE_DIR}")
endif()
if(missing)
  list(JOIN missing "\n  " text)
  message(FATAL_ERROR "no \"SPDX-License-Identifier: MIT\" in the first three lines of:\n  ${text}")
endif()
message(STATUS "${count} source files carry the SPDX identifier")
