# cmake -DCMAKE=... -DGENERATOR=... -DPREFIX=... -DVERSION=... -DCXX=...
#       -DSANITIZE_FLAGS=... -DSOURCE_DIR=... -DBINARY_DIR=... -P find_package_consumer.cmake
# Configures, builds and runs a C++ project that uses find_package(bodt) with
# CMAKE_PREFIX_PATH=PREFIX, as a downstream CMake user would.
cmake_minimum_required(VERSION 3.20)
file(REMOVE_RECURSE "${BINARY_DIR}")
set(configure "${CMAKE}" -S "${SOURCE_DIR}" -B "${BINARY_DIR}" -G "${GENERATOR}"
    -DCMAKE_BUILD_TYPE=Release
    "-DCMAKE_PREFIX_PATH=${PREFIX}"
    "-DCMAKE_CXX_COMPILER=${CXX}"
    "-DBODT_EXPECTED_VERSION=${VERSION}"
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
if(SANITIZE_FLAGS)
  list(APPEND configure "-DCMAKE_CXX_FLAGS=${SANITIZE_FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${SANITIZE_FLAGS}")
endif()

function(run step)
  list(JOIN ARGN " " shown)
  message("== ${step}: ${shown}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "find_package consumer: ${step} failed (${rc})")
  endif()
endfunction()

run(configure ${configure})
run(build "${CMAKE}" --build "${BINARY_DIR}")
# No LD_LIBRARY_PATH: CMake's build RPATH must find the imported library.
run(run "${BINARY_DIR}/consumer")
