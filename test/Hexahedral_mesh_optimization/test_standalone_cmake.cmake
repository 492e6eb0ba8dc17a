# examples/ and test/ of the package configured on their own, as CGAL's
# testsuite configures a package's examples and tests (find_package(CGAL),
# create_single_source_cgal_program), without the root's CMakeLists.txt:
# both must configure, and one example must build.
# usage: cmake -DSOURCE_DIR=<package root> -DWORK=<scratch folder>
#              [-DGENERATOR=<CMake generator>] -P test_standalone_cmake.cmake
foreach(var SOURCE_DIR WORK)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "test_standalone_cmake: -D${var}=... is required")
  endif()
endforeach()
set(generator_args)
if(GENERATOR)
  set(generator_args -G "${GENERATOR}")
endif()
file(REMOVE_RECURSE ${WORK})

foreach(dir examples test)
  execute_process(
    COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/${dir}/Hexahedral_mesh_optimization -B ${WORK}/${dir}
            ${generator_args} -DCMAKE_BUILD_TYPE=Release
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${dir}/ does not configure on its own (exit ${rc}):\n${out}\n${err}")
  endif()
  message(STATUS "${dir}/ configures on its own")
endforeach()

# the generated build files name the programs that CGAL's
# create_single_source_cgal_program made, and their compilation tests
execute_process(COMMAND ${CMAKE_CTEST_COMMAND} -N WORKING_DIRECTORY ${WORK}/examples
                RESULT_VARIABLE rc OUTPUT_VARIABLE examples_tests)
foreach(test compilation_of__quality_report compilation_of__reference_check example_quality_report)
  if(NOT examples_tests MATCHES "${test}\n")
    message(FATAL_ERROR "examples/ on its own has no test ${test}:\n${examples_tests}")
  endif()
endforeach()
execute_process(COMMAND ${CMAKE_CTEST_COMMAND} -N WORKING_DIRECTORY ${WORK}/test
                RESULT_VARIABLE rc OUTPUT_VARIABLE test_tests)
foreach(test compilation_of__test_main test_reference_check test_untangle)
  if(NOT test_tests MATCHES "${test}\n")
    message(FATAL_ERROR "test/ on its own has no test ${test}:\n${test_tests}")
  endif()
endforeach()

execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK}/examples --target quality_report
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the example quality_report does not build on its own (exit ${rc}):\n${out}\n${err}")
endif()
message(STATUS "examples/ on its own builds quality_report")
