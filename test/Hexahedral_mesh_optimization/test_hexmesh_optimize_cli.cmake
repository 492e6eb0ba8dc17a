# Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
# SPDX-License-Identifier: GPL-3.0-or-later
#
# Runs the built hexmesh-optimize on good and bad command lines and files.
#   cmake -DTOOL=<hexmesh-optimize> -DEXAMPLE_DATA=<examples data dir>
#         -DSHARED_DATA=<shared data dir> -DWORK=<scratch dir> -P this_file
# Every failed check is printed; the script fails at the end if any did.

cmake_minimum_required(VERSION 3.19) # string(JSON)

# check(<message> <condition>...): the condition as for if()
set(failures 0)
function(check message)
  if(${ARGN})
  else()
    message(SEND_ERROR "check failed: ${message}")
    math(EXPR n "${failures} + 1")
    set(failures ${n} PARENT_SCOPE)
  endif()
endfunction()

# run(<result prefix> args...): sets <prefix>_rc, <prefix>_out, <prefix>_err
function(run prefix)
  execute_process(COMMAND ${TOOL} ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                  WORKING_DIRECTORY ${WORK})
  set(${prefix}_rc "${rc}" PARENT_SCOPE)
  set(${prefix}_out "${out}" PARENT_SCOPE)
  set(${prefix}_err "${err}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(bunny ${EXAMPLE_DATA}/bunny_dualsheet.vtk)

# ------------------------------------------------------------- command line
run(help --help)
check("--help exits 0 (got ${help_rc})" help_rc EQUAL 0)
check("--help prints the usage" help_out MATCHES "usage: hexmesh-optimize INPUT")
check("--help lists --report" help_out MATCHES "--report FILE.json")

run(none)
check("no argument exits 2 (got ${none_rc})" none_rc EQUAL 2)
check("no argument says why: ${none_err}" none_err MATCHES "hexmesh-optimize: error: no input mesh")

run(unknown ${bunny} --frobnicate)
check("unknown option exits 2 (got ${unknown_rc})" unknown_rc EQUAL 2)
check("unknown option message: ${unknown_err}" unknown_err MATCHES "^hexmesh-optimize: error: unknown option '--frobnicate'\n")
check("unknown option prints the usage" unknown_err MATCHES "usage:")

run(novalue ${bunny} --report)
check("option without its value exits 2 (got ${novalue_rc})" novalue_rc EQUAL 2)

run(badext ${bunny} ${WORK}/out.txt)
check("an unknown output format exits 2 (got ${badext_rc})" badext_rc EQUAL 2)
check("and says why: ${badext_err}" badext_err MATCHES "must end in .mesh, .vtk, .vtu, .msh, .inp, .exo or .e")
check("nothing written" NOT EXISTS ${WORK}/out.txt)

run(three a.mesh b.mesh c.mesh)
check("three files exit 2 (got ${three_rc})" three_rc EQUAL 2)

# ------------------------------------------------------------------ bad input
run(missing ${WORK}/no_such_mesh.mesh ${WORK}/missing_out.vtk)
check("a missing file fails" NOT missing_rc EQUAL 0)
check("a missing file is not a usage error" NOT missing_rc EQUAL 2)
check("one error line naming the file: ${missing_err}" missing_err MATCHES "^hexmesh-optimize: error: [^\n]*no_such_mesh.mesh[^\n]*\n$")
check("no output after a read failure" NOT EXISTS ${WORK}/missing_out.vtk)

file(WRITE ${WORK}/broken.mesh "MeshVersionFormatted 2\nDimension 3\nVertices\n2\n0 0 0 0\n1 0 0 0\nHexahedra\n1\n1 2 3 4 5 6 7 8 0\nEnd\n")
run(broken ${WORK}/broken.mesh ${WORK}/broken_out.vtk --report ${WORK}/broken.json)
check("an index out of range fails" NOT broken_rc EQUAL 0)
check("one line file:line: message: ${broken_err}" broken_err MATCHES "^hexmesh-optimize: error: [^\n]*broken.mesh:[0-9]+: [^\n]*\n$")
check("no output after a read failure" NOT EXISTS ${WORK}/broken_out.vtk)
check("no report after a read failure" NOT EXISTS ${WORK}/broken.json)

run(unwritable ${bunny} ${WORK}/no/such/dir/out.vtk)
check("an unwritable output fails" NOT unwritable_rc EQUAL 0)
check("the write error names the file: ${unwritable_err}" unwritable_err MATCHES "^hexmesh-optimize: error: [^\n]*out.vtk")

# a reference surface in another frame (a tetrahedron far from the bunny):
# a bad argument, exit 2, one error line naming both files, nothing written
file(WRITE ${WORK}/far.obj "v 1000 1000 1000\nv 1001 1000 1000\nv 1000 1001 1000\nv 1000 1000 1001\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n")
run(far ${bunny} ${WORK}/far_out.mesh --reference ${WORK}/far.obj --report ${WORK}/far.json)
check("a reference in another frame exits 2 (got ${far_rc})" far_rc EQUAL 2)
check("one error line naming the reference and the mesh: ${far_err}" far_err MATCHES "^hexmesh-optimize: error: reference surface '[^\n]*far.obj' and mesh '[^\n]*bunny_dualsheet.vtk': [^\n]*\n$")
check("the error says what does not match: ${far_err}" far_err MATCHES "do not overlap")
check("no output for a reference that does not fit" NOT EXISTS ${WORK}/far_out.mesh)
check("no report for a reference that does not fit" NOT EXISTS ${WORK}/far.json)

# ------------------------------------------------------------------ good input
run(good ${bunny} ${WORK}/out.vtk --report ${WORK}/report.json --histogram-svg=${WORK}/histogram.svg)
check("the bundled bunny runs (rc ${good_rc}: ${good_err})" good_rc EQUAL 0)
check("before report" good_out MATCHES "before: [^\n]*bunny_dualsheet.vtk")
check("2832 hexes reported" good_out MATCHES "hexes +2832\n")
check("45 inverted reported" good_out MATCHES "inverted +45\n")
check("MSJ reported" good_out MATCHES "MSJ +-0.77")
check("after report" good_out MATCHES "after: [^\n]*out.vtk")
check("progress line per stage" good_out MATCHES "edge-angle: done in")
check("the output has no inverted element" good_out MATCHES "after: [^\n]*out.vtk[^\n]*\n[^\n]*\n[^\n]*\n +inverted +0\n")
check("histogram bars" good_out MATCHES "#")
check("output written" EXISTS ${WORK}/out.vtk)
check("SVG written" EXISTS ${WORK}/histogram.svg)

if(EXISTS ${WORK}/out.vtk)
  file(READ ${WORK}/out.vtk vtk)
  check("the output carries the scaled Jacobian cell field" vtk MATCHES "scaled_jacobian")
  run(reread ${WORK}/out.vtk)
  check("the output reads back" reread_rc EQUAL 0)
  check("same quality after the round trip" reread_out MATCHES "inverted +0\n")
endif()

if(EXISTS ${WORK}/histogram.svg)
  file(READ ${WORK}/histogram.svg svg)
  check("SVG document" svg MATCHES "^<svg ")
  check("complete SVG document" svg MATCHES "</svg>\n$")
  check("SVG axis label" svg MATCHES "scaled Jacobian")
  check("SVG legend for the output" svg MATCHES "after \\(out.vtk\\)")
endif()

if(EXISTS ${WORK}/report.json)
  file(READ ${WORK}/report.json json)
  string(JSON file ERROR_VARIABLE e GET "${json}" input file)
  check("JSON parses and has input.file: ${e}" NOT e)
  check("input.file" file MATCHES "bunny_dualsheet.vtk$")
  foreach(key hexes vertices inverted msj asj)
    string(JSON v_${key} ERROR_VARIABLE e GET "${json}" input ${key})
    check("input.${key}: ${e}" NOT e)
  endforeach()
  check("input.hexes = ${v_hexes}" v_hexes EQUAL 2832)
  check("input.vertices = ${v_vertices}" v_vertices EQUAL 3724)
  check("input.inverted = ${v_inverted}" v_inverted EQUAL 45)
  check("input.msj = ${v_msj}" v_msj LESS -0.77 AND v_msj GREATER -0.772)
  string(JSON n ERROR_VARIABLE e LENGTH "${json}" input histogram counts)
  check("20 histogram bins (${n}, ${e})" n EQUAL 20)
  set(sum 0)
  if(n EQUAL 20)
    foreach(k RANGE 19)
      string(JSON c GET "${json}" input histogram counts ${k})
      math(EXPR sum "${sum} + ${c}")
    endforeach()
  endif()
  check("the histogram counts every hex (${sum})" sum EQUAL 2832)
  foreach(key file hexes vertices inverted msj asj histogram seconds surface_error time_limit_reached)
    string(JSON t_${key} ERROR_VARIABLE e TYPE "${json}" output ${key})
    check("output.${key}: ${e}" NOT e)
  endforeach()
  check("output.seconds is a number (${t_seconds})" t_seconds STREQUAL "NUMBER")
  check("output.surface_error is measured (${t_surface_error})" t_surface_error STREQUAL "NUMBER")
  string(JSON limit_fired ERROR_VARIABLE e GET "${json}" output time_limit_reached)
  check("no time limit, none reached (${limit_fired})" limit_fired STREQUAL "OFF")
endif()

# report only, to a .mesh output
run(medit ${bunny} ${WORK}/out.mesh --quiet --report ${WORK}/report2.json)
check("writing MEDIT (${medit_err})" medit_rc EQUAL 0)
check("--quiet prints nothing: ${medit_out}" NOT medit_out MATCHES ".")
check("MEDIT output written" EXISTS ${WORK}/out.mesh)

# ------------------------------------------------------------ determinism
# the stages end on convergence and work caps, never on the clock: the same
# input and options give the same bytes, on any number of threads
run(again ${bunny} ${WORK}/out_again.mesh --quiet)
run(one_thread ${bunny} ${WORK}/out_1_thread.mesh --quiet --threads 1)
run(two_threads ${bunny} ${WORK}/out_2_threads.mesh --quiet --threads 2)
check("second run (${again_err})" again_rc EQUAL 0)
check("1-thread run (${one_thread_err})" one_thread_rc EQUAL 0)
check("2-thread run (${two_threads_err})" two_threads_rc EQUAL 0)
if(EXISTS ${WORK}/out.mesh AND EXISTS ${WORK}/out_again.mesh AND EXISTS ${WORK}/out_1_thread.mesh
   AND EXISTS ${WORK}/out_2_threads.mesh)
  file(SHA256 ${WORK}/out.mesh h_first)
  file(SHA256 ${WORK}/out_again.mesh h_again)
  file(SHA256 ${WORK}/out_1_thread.mesh h_one)
  file(SHA256 ${WORK}/out_2_threads.mesh h_two)
  check("two runs write the same bytes (${h_first} / ${h_again})" h_first STREQUAL h_again)
  check("1 and 2 threads write the same bytes (${h_one} / ${h_two})" h_one STREQUAL h_two)
  check("the default thread count writes the same bytes (${h_first} / ${h_two})" h_first STREQUAL h_two)
else()
  check("the determinism runs wrote their outputs" FALSE)
endif()
run(bad_threads ${bunny} ${WORK}/out_bad_threads.mesh --threads 1.5)
check("--threads 1.5 is a usage error (got ${bad_threads_rc})" bad_threads_rc EQUAL 2)

# ------------------------------------------------------------- time limit
# a hard stop that fires at once: the run stops, says so, and writes a mesh
# no worse than its input
run(limited ${bunny} ${WORK}/out_limited.mesh --time-limit 0.000001 --report ${WORK}/limited.json)
check("a run stopped by its time limit ends normally (rc ${limited_rc}: ${limited_err})" limited_rc EQUAL 4 OR limited_rc EQUAL 5)
check("it says the limit was reached" limited_out MATCHES "time limit reached")
check("it writes its output" EXISTS ${WORK}/out_limited.mesh)
if(EXISTS ${WORK}/limited.json)
  file(READ ${WORK}/limited.json limited_json)
  string(JSON fired ERROR_VARIABLE e GET "${limited_json}" output time_limit_reached)
  check("the JSON report says the limit was reached (${fired} ${e})" fired STREQUAL "ON")
  string(JSON inverted_after ERROR_VARIABLE e GET "${limited_json}" output inverted)
  check("never worse than the input: ${inverted_after} inverted of 45" inverted_after LESS_EQUAL 45)
  # its status says whether the output can be used: 4 with elements still
  # inverted, 5 (time limit) without
  if(inverted_after GREATER 0)
    check("exit status 4 with ${inverted_after} elements still inverted (got ${limited_rc})" limited_rc EQUAL 4)
  else()
    check("exit status 5 for a valid output cut short (got ${limited_rc})" limited_rc EQUAL 5)
  endif()
  string(JSON msj_after ERROR_VARIABLE e GET "${limited_json}" output msj)
  if(inverted_after EQUAL 45)
    check("at 45 inverted, the MSJ is not lower (${msj_after})" msj_after GREATER -0.772)
  endif()
  # every element still inverted is listed, with its id, value and reason
  string(JSON unresolved ERROR_VARIABLE e LENGTH "${limited_json}" output unresolved)
  check("the JSON lists the ${inverted_after} elements still inverted (${unresolved} ${e})" unresolved EQUAL inverted_after)
  if(inverted_after GREATER 0)
    string(JSON reason ERROR_VARIABLE e GET "${limited_json}" output unresolved 0 reason)
    check("each with a reason (${reason} ${e})" reason MATCHES "^(locked|region_exhausted|time_limit)$")
    check("and standard error names them: ${limited_err}" limited_err MATCHES "warning: hexahedron [0-9]+ still inverted")
  endif()
else()
  check("the time-limited run wrote its report" FALSE)
endif()

# ---------------------------------------------------- simulation formats
# the groups of the simulation formats survive the tool: Abaqus sets, element
# type and ids, gmsh physical groups and names (the tool writes the mesh it
# read with new points)
set(nodes "101, 0, 0, 0\n102, 1, 0, 0\n103, 1, 1, 0\n104, 0, 1, 0\n105, 0, 0, 1\n106, 1, 0, 1\n107, 1, 1, 1\n108, 0, 1, 1\n109, 2, 0, 0\n110, 2, 1, 0\n111, 2, 0, 1\n112, 2, 1, 1.2\n")
file(WRITE ${WORK}/sets.inp "** two hexahedra\n*Node\n${nodes}*Element, type=C3D8R, elset=left\n7, 101, 102, 103, 104, 105, 106, 107, 108\n*ELEMENT, TYPE=C3D8R, ELSET=right\n9, 102, 109, 110, 103,\n106, 111, 112, 107\n*Nset, nset=fixed, generate\n101, 104\n*Elset, elset=all\nleft, right\n*Surface, name=ends\n7, S6\nright, S4\n")
run(inp ${WORK}/sets.inp ${WORK}/sets_out.inp --quiet)
check("the tool reads and writes Abaqus (rc ${inp_rc}: ${inp_err})" inp_rc EQUAL 0)
file(READ ${WORK}/sets_out.inp inp_out)
check("the element type and ids are kept" inp_out MATCHES "\\*ELEMENT, TYPE=C3D8R\n7, 101, 102, 103, 104, 105, 106, 107, 108\n9, 102, ")
check("the node set is kept" inp_out MATCHES "\\*NSET, NSET=fixed\n101, 102, 103, 104\n")
check("the element sets are kept" inp_out MATCHES "\\*ELSET, ELSET=left\n7\n\\*ELSET, ELSET=right\n9\n\\*ELSET, ELSET=all\n7, 9\n")
check("the surface is kept" inp_out MATCHES "\\*SURFACE, NAME=ends, TYPE=ELEMENT\n7, S6\n9, S4\n")
string(REPLACE ", " " " msh_nodes "${nodes}")
file(WRITE ${WORK}/groups.msh "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n3 5 \"core\"\n3 6 \"shell\"\n$EndPhysicalNames\n$Nodes\n12\n${msh_nodes}$EndNodes\n$Elements\n3\n1 3 2 9 1 101 102 103 104\n7 5 2 5 1 101 102 103 104 105 106 107 108\n9 5 2 6 2 102 109 110 103 106 111 112 107\n$EndElements\n")
run(msh ${WORK}/groups.msh ${WORK}/groups_out.msh --quiet)
check("the tool reads and writes gmsh (rc ${msh_rc}: ${msh_err})" msh_rc EQUAL 0)
check("the skipped quadrangle is reported once: ${msh_err}" msh_err MATCHES "^warning: skipped 1 elements of type 3 \\(4-node quadrangle\\)")
file(READ ${WORK}/groups_out.msh msh_out)
check("4.1 by default" msh_out MATCHES "^\\$MeshFormat\n4.1 0 8\n")
check("the physical names are kept" msh_out MATCHES "\\$PhysicalNames\n2\n3 5 \"core\"\n3 6 \"shell\"\n")
check("each hexahedron keeps its physical group" msh_out MATCHES "\n3 1 5 1\n7 101 [^\n]*\n3 2 5 1\n9 102 ")
check("the scaled Jacobian is an element view" msh_out MATCHES "\\$ElementData\n1\n\"scaled_jacobian\"\n")
run(msh_again ${WORK}/groups_out.msh ${WORK}/groups_out.inp --quiet)
check("the tool reads its .msh output (rc ${msh_again_rc}: ${msh_again_err})" msh_again_rc EQUAL 0)

# ---------------------------------------------------------- shared meshes
if(EXISTS ${SHARED_DATA}/inverted/hex_torus.vtk)
  run(torus ${SHARED_DATA}/inverted/hex_torus.vtk)
  check("hex_torus reads (${torus_err})" torus_rc EQUAL 0)
  check("hex_torus's cell type 10 gives a warning: ${torus_err}" torus_err MATCHES "^warning: ")
  check("hex_torus: 121 inverted" torus_out MATCHES "inverted +121\n")
endif()

if(failures GREATER 0)
  message(FATAL_ERROR "${failures} check(s) failed")
endif()
message(STATUS "hexmesh-optimize command line: all checks passed")
