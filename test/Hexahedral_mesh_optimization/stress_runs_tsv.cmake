# Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
# Reading the benchmark's stress_runs.tsv (--stress-write), include()d by
# the CMake-script tests that use it: read_stress_runs(<file> <prefix>) sets
# <prefix>_count, <prefix>_indices (the list 0 … count − 1) and, for each
# run k (the header left out), <prefix>_<k>_<column> for the columns of the
# file, in its order:
set(stress_run_columns input reference amplitude inverted_in inverted_out msj_out asj_out surface_error seconds
    directions fraction_moved vertices_moved)

function(read_stress_runs file prefix)
  file(STRINGS ${file} lines)
  set(k 0)
  set(indices "")
  foreach(line IN LISTS lines)
    if(line MATCHES "^input\t") # the header
      continue()
    endif()
    string(REPLACE "\t" ";" fields "${line}")
    set(i 0)
    foreach(column IN LISTS stress_run_columns)
      list(GET fields ${i} value)
      set(${prefix}_${k}_${column} "${value}" PARENT_SCOPE)
      math(EXPR i "${i} + 1")
    endforeach()
    list(APPEND indices ${k})
    math(EXPR k "${k} + 1")
  endforeach()
  set(${prefix}_count ${k} PARENT_SCOPE)
  set(${prefix}_indices "${indices}" PARENT_SCOPE)
endfunction()
