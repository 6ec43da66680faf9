# cmake -DCMAKE=... -DGENERATOR=... -DPREFIX=... -DVERSION=... -DCXX=... [-DFC=...]
#       -DSANITIZE_FLAGS=... -DSOURCE_DIR=... -DBINARY_DIR=... [-DEXPECTED_OUTPUT=...]
#       -P find_package_consumer.cmake
# Configures, builds and runs a C++ (or, with FC, Fortran) project that uses
# find_package(bodt) with CMAKE_PREFIX_PATH=PREFIX, as a downstream CMake
# user would, and runs its program without LD_LIBRARY_PATH.
cmake_minimum_required(VERSION 3.20)
file(REMOVE_RECURSE "${BINARY_DIR}")
set(configure "${CMAKE}" -S "${SOURCE_DIR}" -B "${BINARY_DIR}" -G "${GENERATOR}"
    -DCMAKE_BUILD_TYPE=Release
    "-DCMAKE_PREFIX_PATH=${PREFIX}"
    "-DCMAKE_CXX_COMPILER=${CXX}"
    "-DBODT_EXPECTED_VERSION=${VERSION}"
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
if(FC)
  list(APPEND configure "-DCMAKE_Fortran_COMPILER=${FC}")
endif()
if(SANITIZE_FLAGS)
  list(APPEND configure "-DCMAKE_CXX_FLAGS=${SANITIZE_FLAGS}" "-DCMAKE_Fortran_FLAGS=${SANITIZE_FLAGS}"
       "-DCMAKE_EXE_LINKER_FLAGS=${SANITIZE_FLAGS}")
endif()

function(run step)
  list(JOIN ARGN " " shown)
  message("== ${step}: ${shown}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out)
  message("${out}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "find_package consumer: ${step} failed (${rc})")
  endif()
  set(output "${out}" PARENT_SCOPE)
endfunction()

run(configure ${configure})
run(build "${CMAKE}" --build "${BINARY_DIR}")
# No LD_LIBRARY_PATH: CMake's build RPATH finds the imported library, and
# the installed libraries find theirs through their own run paths.
run(run "${CMAKE}" -E env --unset=LD_LIBRARY_PATH "${BINARY_DIR}/consumer")
if(DEFINED EXPECTED_OUTPUT)
  string(STRIP "${output}" output)
  if(NOT output STREQUAL EXPECTED_OUTPUT)
    message(FATAL_ERROR "find_package consumer printed '${output}', expected '${EXPECTED_OUTPUT}'")
  endif()
endif()
