# cmake -DBODT=<bodt command> -DINPUT=<mesh> -DOUTPUT=<mesh> -P check_demo.cmake
#
# Runs `bodt improve INPUT OUTPUT` as scripts/demo.sh does, then checks with
# `bodt quality --json` that the output has no inverted tet, a larger
# smallest dihedral angle than the input, and no fewer vertices (flips and
# insertion change the connectivity; input vertices are kept); then runs
# `bodt compare` and `bodt report` as the demo does.
cmake_minimum_required(VERSION 3.20)
get_filename_component(outdir "${OUTPUT}" DIRECTORY)
file(REMOVE_RECURSE "${outdir}")
file(MAKE_DIRECTORY "${outdir}")

execute_process(COMMAND "${BODT}" improve "${INPUT}" "${OUTPUT}" --mode bodt --iterations 20
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "bodt improve exited with ${rc}")
endif()

function(quality path prefix)
  execute_process(COMMAND "${BODT}" quality "${path}" --json
                  RESULT_VARIABLE rc OUTPUT_VARIABLE json ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "bodt quality ${path} exited with ${rc}: ${err}")
  endif()
  foreach(key vertices tets boundary_faces inverted min_dihedral)
    string(JSON value GET "${json}" ${key})
    set(${prefix}_${key} "${value}" PARENT_SCOPE)
  endforeach()
endfunction()

quality("${INPUT}" in)
quality("${OUTPUT}" out)
message("min dihedral: ${in_min_dihedral} -> ${out_min_dihedral} degrees; inverted: ${out_inverted}")
message("vertices: ${in_vertices} -> ${out_vertices}; tets: ${in_tets} -> ${out_tets}")
if(out_vertices LESS in_vertices)
  message(FATAL_ERROR "vertices lost: ${in_vertices} -> ${out_vertices}")
endif()
if(NOT out_inverted EQUAL 0)
  message(FATAL_ERROR "the output has ${out_inverted} inverted tets")
endif()
# if(GREATER) compares the values as floating-point numbers.
if(NOT out_min_dihedral GREATER in_min_dihedral)
  message(FATAL_ERROR "the smallest dihedral angle did not grow: ${in_min_dihedral} -> ${out_min_dihedral}")
endif()

# The rest of the demo: compare (volume kept, markers kept) and the report.
execute_process(COMMAND "${BODT}" compare "${INPUT}" "${OUTPUT}" --json
                RESULT_VARIABLE rc OUTPUT_VARIABLE json ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "bodt compare exited with ${rc}: ${err}")
endif()
message("compare: ${json}")
set(report "${outdir}/report.html")
execute_process(COMMAND "${BODT}" report "${INPUT}" "${OUTPUT}" -o "${report}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT EXISTS "${report}")
  message(FATAL_ERROR "bodt report exited with ${rc}: ${err}")
endif()
file(READ "${report}" html)
string(FIND "${html}" "<svg" at)
if(at EQUAL -1)
  message(FATAL_ERROR "${report} has no histogram")
endif()
