# cmake -DREADME=README.md -DSOURCE=examples/quickstart.c -P check_readme_code.cmake
#
# Fails unless the README's code block that follows the line
#   <!-- NAME: keep identical to examples/NAME (a CTest test checks) -->
# (NAME being SOURCE's file name) is byte-for-byte the content of SOURCE.
# The block's fence names the language: ```c, ```fortran or ```python, from
# SOURCE's extension.
cmake_minimum_required(VERSION 3.20)
foreach(var README SOURCE)
  if(NOT DEFINED ${var} OR NOT EXISTS "${${var}}")
    message(FATAL_ERROR "check_readme_code: ${var}='${${var}}' does not exist")
  endif()
endforeach()
get_filename_component(name "${SOURCE}" NAME)
get_filename_component(ext "${SOURCE}" LAST_EXT)
if(ext STREQUAL ".c")
  set(lang c)
elseif(ext STREQUAL ".f90")
  set(lang fortran)
elseif(ext STREQUAL ".py")
  set(lang python)
else()
  message(FATAL_ERROR "check_readme_code: no fence language for '${ext}' files")
endif()

file(READ "${README}" readme)
file(READ "${SOURCE}" source)
string(REPLACE "\r\n" "\n" readme "${readme}")
string(REPLACE "\r\n" "\n" source "${source}")

set(marker "<!-- ${name}:")
string(FIND "${readme}" "${marker}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "check_readme_code: ${README} has no line starting with '${marker}'")
endif()
string(SUBSTRING "${readme}" ${at} -1 rest)
set(fence "```${lang}\n")
string(FIND "${rest}" "${fence}" at)
if(at EQUAL -1)
  message(FATAL_ERROR "check_readme_code: no ```${lang} block after '${marker}' in ${README}")
endif()
string(LENGTH "${fence}" flen)
math(EXPR at "${at} + ${flen}")
string(SUBSTRING "${rest}" ${at} -1 rest)
string(FIND "${rest}" "\n```" end)
if(end EQUAL -1)
  message(FATAL_ERROR "check_readme_code: the ```${lang} block in ${README} is not closed")
endif()
math(EXPR end "${end} + 1")  # keep the last line's newline
string(SUBSTRING "${rest}" 0 ${end} block)

if(NOT block STREQUAL source)
  set(copy "${CMAKE_CURRENT_BINARY_DIR}/readme_block_${name}")
  file(WRITE "${copy}" "${block}")
  message(FATAL_ERROR
    "The ```${lang} block in ${README} differs from ${SOURCE}.\n"
    "The README's block was written to ${copy}; compare:\n"
    "  diff -u ${SOURCE} ${copy}\n"
    "Copy ${SOURCE} into the README (or the other way round).")
endif()
message(STATUS "README.md shows ${SOURCE} verbatim")
