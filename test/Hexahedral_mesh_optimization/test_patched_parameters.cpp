// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Built against a copy of CGAL's parameters_interface.h patched with
// package_info/Hexahedral_mesh_optimization/parameters_interface.patch (first
// on the include path, see CMakeLists.txt): the package's parameters are then
// CGAL's own, and a chain may give them after CGAL's parameters, which a
// stock CGAL 5.5 does not compile.

#include "test_util.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/hex_mesh_quality.h>
#include <CGAL/untangle_hex_mesh.h>

#include <type_traits>

#ifndef CGAL_PARAMETERS_INTERFACE_HAS_HEX_MESH_OPTIMIZATION
#error "this test must be built with the patched CGAL/STL_Extension/internal/parameters_interface.h"
#endif

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Indexed_hex_mesh<K::Point_3> Mesh;

// the package reads CGAL's tags
static_assert(std::is_same<CGAL::hex_mesh_internal_np::stop_flag_t, CGAL::internal_np::stop_flag_t>::value,
              "the package's stop_flag is CGAL's");
static_assert(std::is_same<CGAL::hex_mesh_internal_np::sharp_angle_t, CGAL::internal_np::sharp_angle_t>::value,
              "the package's sharp_angle is CGAL's");

/// the 2 x 2 x 2 grid of unit cubes with its centre vertex moved past a corner
static Mesh tangled_grid()
{
  Mesh m;
  for(int k = 0; k < 3; ++k)
    for(int j = 0; j < 3; ++j)
      for(int i = 0; i < 3; ++i) m.points.push_back(K::Point_3(i, j, k));
  auto v = [](int i, int j, int k) { return std::size_t(i + 3 * j + 9 * k); };
  for(int k = 0; k < 2; ++k)
    for(int j = 0; j < 2; ++j)
      for(int i = 0; i < 2; ++i)
        m.hexahedra.push_back({v(i, j, k), v(i + 1, j, k), v(i + 1, j + 1, k), v(i, j + 1, k),
                               v(i, j, k + 1), v(i + 1, j, k + 1), v(i + 1, j + 1, k + 1), v(i, j + 1, k + 1)});
  m.points[v(1, 1, 1)] = K::Point_3(1.7, 1.7, 1.7);
  return m;
}

int main()
{
  // CGAL's parameters first, the package's after them
  const auto np = CGAL::parameters::geom_traits(K()).number_of_iterations(40).maximum_running_time(60.).sharp_angle(160.);
  HMO_CHECK(CGAL::parameters::get_parameter(np, CGAL::internal_np::maximum_running_time) == 60.);
  HMO_CHECK(CGAL::parameters::get_parameter(np, CGAL::hex_mesh_internal_np::sharp_angle) == 160.);
  HMO_CHECK(CGAL::parameters::get_parameter(np, CGAL::internal_np::number_of_iterations) == 40);

  Mesh m = tangled_grid();
  HMO_CHECK(CGAL::hex_mesh_quality(m).inverted > 0);
  const auto r = CGAL::untangle_hex_mesh(m, np);
  HMO_CHECK(r.inverted_before > 0 && r.inverted_after == 0);
  // and the package's first, mixed with CGAL's
  Mesh again = tangled_grid();
  const auto r2 = CGAL::untangle_hex_mesh(
    again, CGAL::parameters::sharp_angle(160.).geom_traits(K()).surface_tolerance(0.005).maximum_running_time(60.).number_of_iterations(40));
  HMO_CHECK(r2.inverted_after == 0);
  HMO_CHECK(again.points == m.points);
  return hmo_test::report("test_patched_parameters");
}
