# SPDX-License-Identifier: MIT
# Script mode (cmake -DSOURCE_DIR=... -P check_method_citations.cmake).
#
# 1. No file of the repository refers to material outside it (the method sources the project was
#    written from live outside the repository; the repository carries its own docs/method.md).
# 2. Every citation of the method page in code, tests and documentation names a section and
#    equations that exist: "docs/method.md §N", "method §N", "eq. K", "eqs. K–L" after such a prefix.
# Fails with the list of offending file:line entries.
cmake_minimum_required(VERSION 3.25)

if(NOT SOURCE_DIR)
  message(FATAL_ERROR "SOURCE_DIR not set")
endif()
set(method "${SOURCE_DIR}/docs/method.md")
if(NOT EXISTS "${method}")
  message(FATAL_ERROR "${method} does not exist")
endif()

# Sections ("## N. Title") and equation labels ("(K)  ..." at the start of a line) of the page.
file(STRINGS "${method}" lines ENCODING UTF-8)
set(sections "")
set(equations "")
foreach(line IN LISTS lines)
  if(line MATCHES "^## ([0-9]+)\\. ")
    list(APPEND sections "${CMAKE_MATCH_1}")
  elseif(line MATCHES "^\\(([0-9]+)\\) ")
    list(APPEND equations "${CMAKE_MATCH_1}")
  endif()
endforeach()
list(LENGTH sections sectionCount)
list(LENGTH equations equationCount)
if(sectionCount LESS 10 OR equationCount LESS 30)
  message(FATAL_ERROR "docs/method.md: found only ${sectionCount} sections and ${equationCount} equations")
endif()
# Equations are numbered 1, 2, 3, ... in order, each once.
set(expected 1)
foreach(number IN LISTS equations)
  if(NOT number EQUAL expected)
    message(FATAL_ERROR "docs/method.md: equation (${number}) where (${expected}) was expected")
  endif()
  math(EXPR expected "${expected} + 1")
endforeach()

# The repository's own text files (the build tree and .git are not scanned).
set(files "")
foreach(pattern
    "*.md" "CMakeLists.txt" "CMakePresets.json" ".ci/*"
    "rope/*" "bullet_bridge/*" "render/*" "demos/*" "tests/*" "docs/*" "cmake/*")
  if(pattern MATCHES "/")
    file(GLOB_RECURSE found LIST_DIRECTORIES false RELATIVE "${SOURCE_DIR}" "${SOURCE_DIR}/${pattern}")
  else()
    file(GLOB found LIST_DIRECTORIES false RELATIVE "${SOURCE_DIR}" "${SOURCE_DIR}/${pattern}")
  endif()
  list(APPEND files ${found})
endforeach()
list(FILTER files INCLUDE REGEX "(\\.(h|cpp|md|txt|cmake|json|gp|in)|/run)$")

# Built from pieces so that this script does not match itself.
set(outside "..")
string(APPEND outside "/shared")

set(problems "")
set(citations 0)
foreach(file IN LISTS files)
  # One list element per line: characters that CMake's list syntax interprets are masked first.
  file(READ "${SOURCE_DIR}/${file}" content)
  string(REPLACE "\\" "<bs>" content "${content}")
  string(REPLACE ";" "<sc>" content "${content}")
  string(REPLACE "[" "<lb>" content "${content}")
  string(REPLACE "]" "<rb>" content "${content}")
  string(REPLACE "\n" ";" text "${content}")
  set(number 0)
  foreach(line IN LISTS text)
    math(EXPR number "${number} + 1")
    string(FIND "${line}" "${outside}" at)
    if(NOT at EQUAL -1)
      list(APPEND problems "${file}:${number}: refers to a path outside the repository")
    endif()
    if(file STREQUAL "docs/method.md")
      continue()  # the page's own cross-references are not citations of it
    endif()
    # Each citation: "method.md" or "method" followed by a section sign or an equation, up to the
    # next closing parenthesis, semicolon-free tail or end of line.
    set(rest "${line}")
    while(rest MATCHES "method(\\.md)?:? (§|eqs?\\. )")
      # The leftmost citation, then continue after it.
      string(REGEX MATCH "method(\\.md)?:? (§|eqs?\\. )[^)]*" found "${rest}")
      string(FIND "${rest}" "${found}" position)
      string(LENGTH "${found}" length)
      math(EXPR position "${position} + ${length}")
      string(SUBSTRING "${rest}" ${position} -1 rest)
      string(REGEX REPLACE "^method(\\.md)?:? " "" cite "${found}")
      math(EXPR citations "${citations} + 1")
      # Sections: every "§N" before the first "eq".
      string(FIND "${cite}" "eq" eqAt)
      if(eqAt EQUAL -1)
        set(sectionPart "${cite}")
        set(equationPart "")
      else()
        string(SUBSTRING "${cite}" 0 ${eqAt} sectionPart)
        string(SUBSTRING "${cite}" ${eqAt} -1 equationPart)
      endif()
      string(REGEX MATCHALL "§[0-9]+" cited "${sectionPart}")
      foreach(item IN LISTS cited)
        string(REGEX REPLACE "§" "" n "${item}")
        if(NOT n IN_LIST sections)
          list(APPEND problems "${file}:${number}: cites docs/method.md §${n}, which does not exist")
        endif()
      endforeach()
      # Equations: "eq. K", "eqs. K–L", "eqs. K, L".
      string(REGEX MATCHALL "eqs?\\. [0-9]+((–|-|, | and )[0-9]+)*" groups "${equationPart}")
      foreach(group IN LISTS groups)
        string(REGEX REPLACE "^eqs?\\. " "" group "${group}")
        string(REGEX MATCHALL "[0-9]+" numbers "${group}")
        foreach(n IN LISTS numbers)
          if(NOT n IN_LIST equations)
            list(APPEND problems "${file}:${number}: cites docs/method.md eq. ${n}, which does not exist")
          endif()
        endforeach()
      endforeach()
    endwhile()
  endforeach()
endforeach()

if(problems)
  list(JOIN problems "\n  " report)
  message(FATAL_ERROR "Citation problems:\n  ${report}")
endif()
if(citations LESS 30)
  message(FATAL_ERROR "Found only ${citations} citations of docs/method.md; the scan is broken")
endif()
message(STATUS "${citations} citations of docs/method.md checked against ${sectionCount} sections and "
  "${equationCount} equations; no references outside the repository")
