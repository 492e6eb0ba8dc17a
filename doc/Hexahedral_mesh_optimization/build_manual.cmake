# Builds the manual and reference with doxygen (the `doc` target, and the
# `doc_manual` test): cmake -D... -P build_manual.cmake, with
#   HMO_SOURCE_DIR      the repository root
#   HMO_DOC_OUTPUT_DIR  where html/ and the figures go
#   HMO_TOOL            hexmesh-optimize
#   HMO_PYTHON          the interpreter of the Python bindings
#   HMO_PYTHONPATH      where the bindings are (for the rendering)
#   HMO_DOXYGEN         doxygen
#   HMO_XVFB_RUN        xvfb-run, or empty when a display is available
# Steps: the tool optimises the bundled bunny and writes the before/after
# histograms (SVG); scripts/render_scaled_jacobian.py renders the mesh before
# and after (PNG, offscreen VTK); doxygen builds the manual. Fails on any
# doxygen warning, listing them.

set(data "${HMO_SOURCE_DIR}/examples/Hexahedral_mesh_optimization/data")
set(doc_source "${HMO_SOURCE_DIR}/doc/Hexahedral_mesh_optimization")
set(figures "${HMO_DOC_OUTPUT_DIR}/fig")
file(MAKE_DIRECTORY "${figures}")

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${what} failed (${status}):\n${out}\n${err}")
  endif()
endfunction()

# 1. the bundled bunny, optimised, and the histograms of its scaled Jacobian
run("hexmesh-optimize" "${HMO_TOOL}" "${data}/bunny_dualsheet.vtk" "${HMO_DOC_OUTPUT_DIR}/bunny_optimized.vtu"
    --reference "${data}/bunny_reference.obj" --histogram-svg "${figures}/bunny_histograms.svg" --quiet)

# 2. pictures before and after, coloured by scaled Jacobian
set(render ${CMAKE_COMMAND} -E env "PYTHONPATH=${HMO_PYTHONPATH}")
if(HMO_XVFB_RUN)
  list(APPEND render ${HMO_XVFB_RUN} -a)
endif()
list(APPEND render ${HMO_PYTHON} "${HMO_SOURCE_DIR}/scripts/render_scaled_jacobian.py")
run("rendering the input" ${render} "${data}/bunny_dualsheet.vtk" "${figures}/bunny_before.png"
    --title "before: bunny_dualsheet.vtk")
run("rendering the output" ${render} "${HMO_DOC_OUTPUT_DIR}/bunny_optimized.vtu" "${figures}/bunny_after.png"
    --title "after: hexmesh-optimize bunny_dualsheet.vtk out.vtu --reference bunny_reference.obj")

# 3. doxygen
set(HMO_DOC_SOURCE_DIR "${doc_source}")
set(HMO_INCLUDE_DIR "${HMO_SOURCE_DIR}/include")
set(HMO_DOC_FIGURE_DIR "${figures}")
configure_file("${doc_source}/standalone/Doxyfile.in" "${HMO_DOC_OUTPUT_DIR}/Doxyfile" @ONLY)
file(REMOVE "${HMO_DOC_OUTPUT_DIR}/doxygen_warnings.log")
run("doxygen" "${HMO_DOXYGEN}" "${HMO_DOC_OUTPUT_DIR}/Doxyfile")
file(READ "${HMO_DOC_OUTPUT_DIR}/doxygen_warnings.log" warnings)
string(REGEX MATCHALL "warning:|error:" found "${warnings}")
list(LENGTH found count)
if(count GREATER 0)
  message(FATAL_ERROR "doxygen: ${count} warnings (${HMO_DOC_OUTPUT_DIR}/doxygen_warnings.log):\n${warnings}")
endif()
message(STATUS "manual: ${HMO_DOC_OUTPUT_DIR}/html/index.html (0 doxygen warnings)")
