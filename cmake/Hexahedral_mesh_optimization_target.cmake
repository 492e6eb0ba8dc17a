# The `hmo` interface target that every program of the package links: the
# package's headers, CGAL, Eigen, TetGen (with TETLIBRARY, as tetgen.h
# requires), Exodus II, threads, TBB when present, warnings. Included by the
# root CMakeLists.txt and by examples/ and test/ when they are configured on
# their own (as CGAL's testsuite configures a package's examples and tests),
# after find_package(CGAL).
if(TARGET hmo)
  return()
endif()

find_package(Eigen3 3.3 REQUIRED)
include(CGAL_Eigen3_support)

# TetGen (Debian: libtet1.5-dev), used for the reference-volume checks.
find_path(TETGEN_INCLUDE_DIR tetgen.h)
find_library(TETGEN_LIBRARY NAMES tet tetgen)
set(HMO_HAVE_TETGEN OFF)
if(TETGEN_INCLUDE_DIR AND TETGEN_LIBRARY)
  set(HMO_HAVE_TETGEN ON)
  message(STATUS "TetGen: ${TETGEN_LIBRARY}")
else()
  message(STATUS "TetGen not found: reference-volume checks are disabled")
endif()

# Exodus II (Debian: libexodusii-dev, with netCDF), optional: without it the
# Exodus reader and writer fail with a message saying so.
find_path(EXODUS_INCLUDE_DIR exodusII.h)
find_library(EXODUS_LIBRARY NAMES exoIIv2c exodus)
find_library(NETCDF_LIBRARY NAMES netcdf)
set(HMO_HAVE_EXODUS OFF)
if(EXODUS_INCLUDE_DIR AND EXODUS_LIBRARY AND NETCDF_LIBRARY)
  set(HMO_HAVE_EXODUS ON)
  message(STATUS "Exodus II: ${EXODUS_LIBRARY}")
else()
  message(STATUS "Exodus II not found: .exo/.e files are not supported")
endif()

find_package(TBB QUIET)
include(CGAL_TBB_support OPTIONAL)
find_package(Threads REQUIRED) # the surface error measures its two directions on two threads

get_filename_component(HMO_INCLUDE_DIR "${CMAKE_CURRENT_LIST_DIR}/../include" ABSOLUTE)
add_library(hmo INTERFACE)
target_include_directories(hmo INTERFACE ${HMO_INCLUDE_DIR})
target_link_libraries(hmo INTERFACE CGAL::CGAL CGAL::Eigen3_support Threads::Threads)
if(HMO_HAVE_TETGEN)
  target_include_directories(hmo INTERFACE ${TETGEN_INCLUDE_DIR})
  target_link_libraries(hmo INTERFACE ${TETGEN_LIBRARY})
  target_compile_definitions(hmo INTERFACE TETLIBRARY CGAL_HMO_HAVE_TETGEN)
endif()
if(HMO_HAVE_EXODUS)
  target_include_directories(hmo INTERFACE ${EXODUS_INCLUDE_DIR})
  target_link_libraries(hmo INTERFACE ${EXODUS_LIBRARY} ${NETCDF_LIBRARY})
  target_compile_definitions(hmo INTERFACE CGAL_HMO_HAVE_EXODUS)
endif()
if(TARGET CGAL::TBB_support)
  target_link_libraries(hmo INTERFACE CGAL::TBB_support)
endif()
target_compile_options(hmo INTERFACE -Wall -Wextra)
# CGAL 5.5's number types include a Boost header that Boost 1.74 (Debian 12)
# marks deprecated, with a "#pragma message" note in every translation unit
# that includes the Epick kernel; the note is about CGAL's headers, not ours
target_compile_definitions(hmo INTERFACE BOOST_ALLOW_DEPRECATED_HEADERS)
