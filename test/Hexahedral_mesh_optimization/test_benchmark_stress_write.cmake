# Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
# The benchmark's --stress-write on the smallest stress mesh (fandisk, one
# seed per mode): the inputs, the reference and the table are written, and
# the tool, run on each written input with the written reference, ends as
# the benchmark's run did (the same inverted count and MSJ, as printed).
#   cmake -DBENCHMARK=<benchmark program> -DTOOL=<hexmesh-optimize>
#         -DSHARED_DATA=<shared data dir> -DWORK=<scratch dir> -P this_file
# Skipped (prints "skipped:") without the shared data.

cmake_minimum_required(VERSION 3.19) # string(JSON)

if(NOT EXISTS ${SHARED_DATA}/stress-base/fandisk.vtk)
  message("skipped: no shared data at ${SHARED_DATA}")
  return()
endif()

include(${CMAKE_CURRENT_LIST_DIR}/test_check.cmake) # check()
include(${CMAKE_CURRENT_LIST_DIR}/stress_runs_tsv.cmake) # read_stress_runs()

file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

# a folder that does not exist is refused before anything runs
execute_process(COMMAND ${BENCHMARK} ${SHARED_DATA} --stress --stress-write ${WORK}/absent
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
check("--stress-write to a missing folder exits 2 (got ${rc})" rc EQUAL 2)
check("--stress-write to a missing folder says so" err MATCHES "existing folder")

execute_process(COMMAND ${BENCHMARK} ${SHARED_DATA} --stress --stress-seeds 1 --only fandisk --stress-write ${WORK}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
check("the stress run exits 0 (got ${rc}: ${err})" rc EQUAL 0)
check("the table has fandisk's rows" out MATCHES "stress-base/fandisk.vtk \\| interior" AND
      out MATCHES "stress-base/fandisk.vtk \\| all vertices" AND out MATCHES "stress-base/fandisk.vtk \\| boundary-locked")
set(reference ${WORK}/stress-base_fandisk_reference.off)
check("the reference is written" EXISTS ${reference})
read_stress_runs(${WORK}/stress_runs.tsv run)
check("stress_runs.tsv has 3 runs, one per mode (got ${run_count})" run_count EQUAL 3)

set(runs 0)
foreach(k IN LISTS run_indices)
  set(input ${run_${k}_input})
  set(run_reference ${run_${k}_reference})
  set(inverted_out ${run_${k}_inverted_out})
  set(msj_out ${run_${k}_msj_out})
  check("the run's input ${input} is written" EXISTS ${input})
  check("the run names the reference" run_reference STREQUAL reference)
  math(EXPR runs "${runs} + 1")
  execute_process(COMMAND ${TOOL} ${input} ${WORK}/out_${runs}.mesh --reference ${reference}
                          --surface-tolerance 0.005 --report ${WORK}/report_${runs}.json --quiet
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  check("the tool reads the written input and reference (exit ${rc}: ${err})" rc EQUAL 0 OR rc EQUAL 4)
  file(READ ${WORK}/report_${runs}.json json)
  string(JSON tool_inverted GET "${json}" output inverted)
  # the MSJ as the report prints it (string(JSON) would print it again with 17 digits)
  string(FIND "${json}" "\"output\"" at)
  string(SUBSTRING "${json}" ${at} -1 output_part)
  string(REGEX MATCH "\"msj\": *([-+0-9.eE]+)" found "${output_part}")
  set(tool_msj "${CMAKE_MATCH_1}")
  check("run ${runs}: the tool ends with ${tool_inverted} inverted, the benchmark with ${inverted_out}"
        tool_inverted EQUAL inverted_out)
  check("run ${runs}: the tool ends at MSJ ${tool_msj}, the benchmark at ${msj_out}" tool_msj STREQUAL msj_out)
endforeach()
check("the 3 runs were repeated (got ${runs})" runs EQUAL 3)

if(failures GREATER 0)
  message(FATAL_ERROR "${failures} check(s) failed")
endif()
message("all checks passed")
