# cmake -DREADME=README.md -DSOURCE=examples/quickstart.c -P check_readme_code.cmake
#
# Fails unless the README's C code block that follows the line
#   <!-- quickstart.c: keep identical to examples/quickstart.c (a CTest test checks) -->
# is byte-for-byte the content of SOURCE.
cmake_minimum_required(VERSION 3.20)
foreach(var README SOURCE)
  if(NOT DEFINED ${var} OR NOT EXISTS "${${var}}")
    message(FATAL_ERROR "check_readme_code: ${var}='${${var}}' does not exist")
  endif()
endforeach()

file(READ "${README}" readme)
file(READ "${SOURCE}" source)
string(REPLACE "\r\n" "\n" readme "${readme}")
string(REPLACE "\r\n" "\n" source "${source}")

set(marker "<!-- quickstart.c:")
string(FIND "${readme}" "${marker}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "check_readme_code: ${README} has no line starting with '${marker}'")
endif()
string(SUBSTRING "${readme}" ${at} -1 rest)
set(fence "```c\n")
string(FIND "${rest}" "${fence}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "check_readme_code: no ```c block after '${marker}' in ${README}")
endif()
string(LENGTH "${fence}" flen)
math(EXPR at "${at} + ${flen}")
string(SUBSTRING "${rest}" ${at} -1 rest)
string(FIND "${rest}" "\n```" end)
if(end EQUAL -1)
  message(FATAL_ERROR "check_readme_code: the ```c block in ${README} is not closed")
endif()
math(EXPR end "${end} + 1")  # keep the last line's newline
string(SUBSTRING "${rest}" 0 ${end} block)

if(NOT block STREQUAL source)
  file(WRITE "${CMAKE_CURRENT_BINARY_DIR}/readme_quickstart_block.c" "${block}")
  message(FATAL_ERROR
    "The C block in ${README} differs from ${SOURCE}.\n"
    "The README's block was written to ${CMAKE_CURRENT_BINARY_DIR}/readme_quickstart_block.c; compare:\n"
    "  diff -u ${SOURCE} ${CMAKE_CURRENT_BINARY_DIR}/readme_quickstart_block.c\n"
    "Copy examples/quickstart.c into the README (or the other way round).")
endif()
message(STATUS "README.md shows ${SOURCE} verbatim")
