// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The package called as a CGAL user calls it: CGAL's linear cell complexes
// (combinatorial map over an exact kernel, generalized map, custom items)
// through untangle_hex_mesh(), improve_hex_mesh_quality() and
// hex_mesh_quality(), with chained CGAL::parameters among which CGAL's own
// vertex_is_constrained_map, vertex_point_map and geom_traits, in a
// translation unit that also includes a Mesh_3 header (CGAL 5.5's
// CGAL/make_mesh_3.h includes CGAL/boost/parameter.h, whose Boost.Parameter
// keyword `CGAL::parameters::time_limit` the package's own parameters must
// not hide: that this file compiles is part of the test).
// Own translation unit: the exact kernel compiles slowly.

#include "test_util.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/make_mesh_3.h> // before the package's headers, as a Mesh_3 user may include it
#include <CGAL/Linear_cell_complex_for_combinatorial_map.h>
#include <CGAL/Linear_cell_complex_for_generalized_map.h>
#include <CGAL/Hexahedral_mesh_optimization/Linear_cell_complex_hex_mesh.h>
#include <CGAL/hex_mesh_quality.h>
#include <CGAL/improve_hex_mesh_quality.h>
#include <CGAL/untangle_hex_mesh.h>
#include <CGAL/property_map.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/generators.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>

#include <boost/property_map/property_map.hpp>

#include <tuple>
#include <unordered_set>
#include <vector>

namespace test_cgal_user {

typedef CGAL::Exact_predicates_exact_constructions_kernel EK;
typedef CGAL::Exact_predicates_inexact_constructions_kernel IK;

struct Items_with_info
{
  template <class LCC>
  struct Dart_wrapper
  {
    typedef CGAL::Cell_attribute_with_point<LCC, int, CGAL::Tag_true> Vertex_attribute;
    typedef std::tuple<Vertex_attribute> Attributes;
  };
};

typedef CGAL::Linear_cell_complex_traits<3, EK> EK_traits;
typedef CGAL::Linear_cell_complex_for_combinatorial_map<3, 3, EK_traits> Exact_lcc;
typedef CGAL::Linear_cell_complex_for_generalized_map<3, 3> Gmap_lcc;
typedef CGAL::Linear_cell_complex_traits<3, IK> IK_traits;
typedef CGAL::Linear_cell_complex_for_combinatorial_map<3, 3, IK_traits, Items_with_info> Custom_lcc;

/// a vertex_is_constrained_map: the vertex attributes in a set
template <class LCC>
struct Constrained_set
{
  typedef typename LCC::Vertex_attribute_const_handle key_type;
  typedef bool value_type;
  typedef bool reference;
  typedef boost::readable_property_map_tag category;
  const std::unordered_set<key_type>* set;
  friend bool get(const Constrained_set& m, key_type v) { return m.set->count(v) != 0; }
};

/// the 3 x 3 x 3 grid of unit cubes scaled by 1/3 (coordinates k/3, not
/// doubles), made by make_hexahedron() and 3-sewn, with its interior
/// vertex (1, 1, 1) moved past (2, 2, 2), to 5/6: hexes around it are inverted
template <class LCC>
void make_tangled_grid(LCC& lcc)
{
  typedef typename LCC::Point Point;
  typedef typename CGAL::Kernel_traits<Point>::Kernel::FT FT;
  auto p = [](int i, int j, int k) {
    if(i == 1 && j == 1 && k == 1) return Point(FT(5) / FT(6), FT(5) / FT(6), FT(5) / FT(6));
    return Point(FT(i) / FT(3), FT(j) / FT(3), FT(k) / FT(3));
  };
  for(int k = 0; k < 3; ++k)
    for(int j = 0; j < 3; ++j)
      for(int i = 0; i < 3; ++i)
        lcc.make_hexahedron(p(i, j, k), p(i + 1, j, k), p(i + 1, j + 1, k), p(i, j + 1, k),
                            p(i, j + 1, k + 1), p(i, j, k + 1), p(i + 1, j, k + 1), p(i + 1, j + 1, k + 1));
  lcc.sew3_same_facets();
}

template <class LCC>
std::vector<typename LCC::Point> points_of(const LCC& lcc)
{
  std::vector<typename LCC::Point> p;
  for(auto it = lcc.vertex_attributes().begin(); it != lcc.vertex_attributes().end(); ++it) p.push_back(it->point());
  return p;
}

/// Constrains the vertices on the plane x = 0 and the tangled vertex's
/// neighbour (2/3, 2/3, 2/3); untangles the mesh, then improves it, each
/// with these constrained, and checks after each that they are
/// bit-identical, that every other vertex either is exactly as it was or
/// moved (no unmoved point rounded), that the grid corners at x = 1 (corners
/// of the boundary: never moved) are exact, and that the mesh is untangled.
template <class LCC, class Untangle, class Improve>
void check_constrained_run(Untangle untangle, Improve improve)
{
  LCC lcc;
  make_tangled_grid(lcc);
  HMO_CHECK(lcc.template one_dart_per_cell<3>().size() == 27);
  HMO_CHECK(lcc.vertex_attributes().size() == 64);
  const CGAL::Hex_mesh_quality q0 = CGAL::hex_mesh_quality(lcc, CGAL::parameters::geom_traits(
                                                                   typename CGAL::Kernel_traits<typename LCC::Point>::Kernel()));
  HMO_CHECK(q0.hexes == 27 && q0.inverted > 0);

  typedef typename LCC::Vertex_attribute_const_handle VH;
  typedef typename CGAL::Kernel_traits<typename LCC::Point>::Kernel::FT FT;
  std::unordered_set<VH> constrained;
  for(auto it = lcc.vertex_attributes().begin(); it != lcc.vertex_attributes().end(); ++it)
    if(it->point().x() == FT(0) || it->point() == typename LCC::Point(FT(2) / FT(3), FT(2) / FT(3), FT(2) / FT(3)))
      constrained.insert(it);
  HMO_CHECK(constrained.size() == 17);
  const Constrained_set<LCC> vcm{&constrained};
  const auto input = points_of(lcc);
  auto check = [&](const CGAL::Hexahedral_mesh_optimization::Optimization_result& r,
                   const std::vector<typename LCC::Point>& before) {
    const auto after = points_of(lcc);
    HMO_CHECK(r.inverted_after == 0);
    HMO_CHECK(CGAL::hex_mesh_quality(lcc).inverted == 0);
    std::size_t i = 0, moved = 0, exact_corners = 0;
    for(auto it = lcc.vertex_attributes().begin(); it != lcc.vertex_attributes().end(); ++it, ++i)
    {
      if(constrained.count(it)) HMO_CHECK(after[i] == input[i]);
      const auto& p = input[i];
      if(p.x() == FT(1) && (p.y() == FT(0) || p.y() == FT(1)) && (p.z() == FT(0) || p.z() == FT(1)))
      {
        HMO_CHECK(after[i] == p);
        ++exact_corners;
      }
      if(after[i] == before[i]) continue;
      ++moved;
      // a vertex that differs was moved by the optimiser, not rounded
      HMO_CHECK(CGAL::to_double(CGAL::squared_distance(after[i], before[i])) > 1e-20);
    }
    HMO_CHECK(exact_corners == 4);
    return moved;
  };
  const CGAL::Hexahedral_mesh_optimization::Optimization_result ru = untangle(lcc, vcm);
  HMO_CHECK(ru.inverted_before > 0);
  HMO_CHECK(check(ru, input) > 0);
  const auto untangled = points_of(lcc);
  const CGAL::Hexahedral_mesh_optimization::Optimization_result ri = improve(lcc, vcm);
  check(ri, untangled);
  HMO_CHECK(ri.msj_after >= ri.msj_before);
}

void test_exact_lcc()
{
  check_constrained_run<Exact_lcc>(
    [](Exact_lcc& lcc, Constrained_set<Exact_lcc> vcm) {
      return CGAL::untangle_hex_mesh(lcc, CGAL::parameters::maximum_running_time(60).vertex_is_constrained_map(vcm).geom_traits(EK()));
    },
    [](Exact_lcc& lcc, Constrained_set<Exact_lcc> vcm) {
      return CGAL::improve_hex_mesh_quality(
        lcc, CGAL::parameters::target_msj(0.9).sharp_angle(160.).vertex_is_constrained_map(vcm).geom_traits(EK()));
    });
}

void test_gmap_lcc()
{
  check_constrained_run<Gmap_lcc>(
    [](Gmap_lcc& lcc, Constrained_set<Gmap_lcc> vcm) {
      return CGAL::untangle_hex_mesh(lcc, CGAL::parameters::maximum_running_time(60).vertex_is_constrained_map(vcm));
    },
    [](Gmap_lcc& lcc, Constrained_set<Gmap_lcc> vcm) {
      return CGAL::improve_hex_mesh_quality(lcc, CGAL::parameters::surface_tolerance(0.01).vertex_is_constrained_map(vcm));
    });
  // the generalized map's hexahedra are those of the combinatorial map, with their orientation
  Gmap_lcc g;
  make_tangled_grid(g);
  Exact_lcc c;
  make_tangled_grid(c);
  const CGAL::Hex_mesh_quality qg = CGAL::hex_mesh_quality(g), qc = CGAL::hex_mesh_quality(c);
  HMO_CHECK(qg.hexes == qc.hexes && qg.inverted == qc.inverted);
  HMO_CHECK_CLOSE(qg.msj, qc.msj, 1e-12);
  HMO_CHECK_CLOSE(qg.asj, qc.asj, 1e-12);
}

void test_custom_items_lcc()
{
  check_constrained_run<Custom_lcc>(
    [](Custom_lcc& lcc, Constrained_set<Custom_lcc> vcm) {
      return CGAL::optimize_hex_mesh(lcc, CGAL::parameters::target_msj(0.95).vertex_is_constrained_map(vcm).geom_traits(IK()));
    },
    [](Custom_lcc& lcc, Constrained_set<Custom_lcc> vcm) {
      return CGAL::improve_hex_mesh_quality(lcc, CGAL::parameters::vertex_is_constrained_map(vcm));
    });
}

/// every vertex constrained: nothing may move, the inverted hexes are
/// reported unresolved
void test_all_constrained()
{
  Exact_lcc lcc;
  make_tangled_grid(lcc);
  std::unordered_set<Exact_lcc::Vertex_attribute_const_handle> all;
  for(auto it = lcc.vertex_attributes().begin(); it != lcc.vertex_attributes().end(); ++it) all.insert(it);
  const auto before = points_of(lcc);
  const auto r = CGAL::optimize_hex_mesh(lcc, CGAL::parameters::vertex_is_constrained_map(Constrained_set<Exact_lcc>{&all}));
  HMO_CHECK(points_of(lcc) == before);
  HMO_CHECK(r.inverted_after == r.inverted_before && r.inverted_after > 0);
  HMO_CHECK(r.unresolved.size() == r.inverted_after);
  for(const auto& e : r.unresolved) HMO_CHECK(e.reason == CGAL::Hexahedral_mesh_optimization::Unresolved_element::constrained);
}

/// vertex_point_map: the positions are read from and written to the map,
/// never to the mesh's own points
void test_vertex_point_map()
{
  typedef CGAL::Indexed_hex_mesh<IK::Point_3> Mesh;
  Exact_lcc lcc;
  make_tangled_grid(lcc);
  Mesh m;
  std::string message;
  HMO_CHECK(CGAL::indexed_hex_mesh_from_linear_cell_complex(lcc, m, &message));
  std::vector<IK::Point_3> positions = m.points;
  for(IK::Point_3& p : m.points) p = IK::Point_3(p.x() * 2., p.y() * 2., p.z() * 2.); // untouched
  const std::vector<IK::Point_3> own = m.points;
  const auto vpm = CGAL::make_property_map(positions);
  HMO_CHECK(CGAL::hex_mesh_quality(m, CGAL::parameters::vertex_point_map(vpm)).inverted > 0);
  const auto r = CGAL::untangle_hex_mesh(m, CGAL::parameters::maximum_running_time(60).vertex_point_map(vpm));
  HMO_CHECK(r.inverted_before > 0 && r.inverted_after == 0);
  HMO_CHECK(m.points == own);
  HMO_CHECK(CGAL::hex_mesh_quality(m, CGAL::parameters::vertex_point_map(vpm)).inverted == 0);
}

/// a reference_vertex_point_map: points by vertex index in a vector
struct Surface_point_vector
{
  typedef CGAL::Surface_mesh<IK::Point_3>::Vertex_index key_type;
  typedef IK::Point_3 value_type;
  typedef const IK::Point_3& reference;
  typedef boost::readable_property_map_tag category;
  const std::vector<IK::Point_3>* points;
  friend reference get(const Surface_point_vector& m, key_type v) { return (*m.points)[std::size_t(v)]; }
};

/// edge_is_constrained_map and reference_vertex_point_map on the reference
/// surface: a triangulated cube whose one face diagonal (flat: never a
/// detected crease) is given as a crease, its points given through a map
/// that moves them by (10, 0, 0)
void test_reference_maps()
{
  namespace HMOI = CGAL::Hexahedral_mesh_optimization::internal;
  namespace PMP = CGAL::Polygon_mesh_processing;
  typedef CGAL::Surface_mesh<IK::Point_3> Surface;
  typedef boost::graph_traits<Surface>::edge_descriptor edge_descriptor;
  Surface cube;
  CGAL::make_hexahedron(IK::Point_3(0, 0, 0), IK::Point_3(1, 0, 0), IK::Point_3(1, 1, 0), IK::Point_3(0, 1, 0),
                        IK::Point_3(0, 1, 1), IK::Point_3(0, 0, 1), IK::Point_3(1, 0, 1), IK::Point_3(1, 1, 1), cube);
  PMP::triangulate_faces(cube);
  auto given = cube.add_property_map<edge_descriptor, bool>("e:given", false).first;
  std::size_t flat = 0;
  for(edge_descriptor e : edges(cube))
  {
    const auto h = halfedge(e, cube);
    const IK::Vector_3 a = PMP::compute_face_normal(face(h, cube), cube);
    const IK::Vector_3 b = PMP::compute_face_normal(face(opposite(h, cube), cube), cube);
    if(a * b > 0.999 && flat++ == 0) put(given, e, true); // the first flat edge only
  }
  HMO_CHECK(flat == 6);
  std::vector<IK::Point_3> moved;
  for(auto v : vertices(cube)) moved.push_back(cube.point(v) + IK::Vector_3(10, 0, 0));
  const Surface_point_vector reference_points{&moved};

  std::vector<HMOI::Vec3> points, points_given;
  std::vector<HMOI::Tri> tris, tris_given;
  std::vector<std::array<std::size_t, 2> > creases, creases_given;
  HMOI::reference_to_soup(cube, CGAL::parameters::sharp_angle(160.), points, tris, creases);
  HMOI::reference_to_soup(cube, CGAL::parameters::reference_vertex_point_map(reference_points).edge_is_constrained_map(given),
                          points_given, tris_given, creases_given);
  HMO_CHECK(creases.empty() && creases_given.size() == 1);
  HMO_CHECK(points.size() == 8 && points_given.size() == 8);
  for(std::size_t i = 0; i < points.size(); ++i) HMO_CHECK(points_given[i][0] == points[i][0] + 10.);
  const HMOI::Reference_features without = HMOI::detect_reference_features(points, tris, 150., 60., 0., 30.);
  const HMOI::Reference_features with =
    HMOI::detect_reference_features(points, tris, 150., 60., 0., 30., creases_given);
  HMO_CHECK(without.sharp_edges == 12);
  HMO_CHECK(with.sharp_edges == 13);
}

/// A model of `HexMeshOptimizationTraits` over EPICK's points (not a
/// kernel) whose functors count their calls in `counts`: a function that
/// reads or writes the points without the traits given as `geom_traits`
/// (the kernel of the point type instead, or a default-constructed copy of
/// these traits, whose `counts` is null) leaves the counts at 0.
struct Counting_traits
{
  typedef IK::FT FT;
  typedef IK::Point_3 Point_3;
  struct Counts
  {
    std::size_t reads = 0, constructions = 0;
  };
  Counts* counts = nullptr;

  template <int I>
  struct Compute_coordinate
  {
    Counts* counts;
    FT operator()(const Point_3& p) const
    {
      if(counts) ++counts->reads;
      return p[I];
    }
  };
  typedef Compute_coordinate<0> Compute_x_3;
  typedef Compute_coordinate<1> Compute_y_3;
  typedef Compute_coordinate<2> Compute_z_3;
  struct Construct_point_3
  {
    Counts* counts;
    Point_3 operator()(const FT& x, const FT& y, const FT& z) const
    {
      if(counts) ++counts->constructions;
      return Point_3(x, y, z);
    }
  };
  Compute_x_3 compute_x_3_object() const { return {counts}; }
  Compute_y_3 compute_y_3_object() const { return {counts}; }
  Compute_z_3 compute_z_3_object() const { return {counts}; }
  Construct_point_3 construct_point_3_object() const { return {counts}; }
};

/// geom_traits: the points of the mesh are read through the traits given
/// (x, y and z of every vertex) and the moved ones written through its
/// Construct_point_3, one construction per moved vertex, by the quality
/// measures, untangle_hex_mesh() and improve_hex_mesh_quality()
void test_geom_traits()
{
  Gmap_lcc lcc;
  make_tangled_grid(lcc);
  const std::size_t nv = lcc.vertex_attributes().size();
  Counting_traits::Counts counts;
  Counting_traits gt;
  gt.counts = &counts;

  const std::vector<Gmap_lcc::Point> corners = {IK::Point_3(0, 0, 0), IK::Point_3(1, 0, 0), IK::Point_3(1, 1, 0),
                                                IK::Point_3(0, 1, 0), IK::Point_3(0, 0, 1), IK::Point_3(1, 0, 1),
                                                IK::Point_3(1, 1, 1), IK::Point_3(0, 1, 1)};
  HMO_CHECK_CLOSE(CGAL::hex_scaled_jacobian(corners, CGAL::parameters::geom_traits(gt)), 1., 1e-12);
  HMO_CHECK(counts.reads == 3 * 8 && counts.constructions == 0);

  counts = Counting_traits::Counts();
  const CGAL::Hex_mesh_quality q = CGAL::hex_mesh_quality(lcc, CGAL::parameters::geom_traits(gt));
  HMO_CHECK(q.hexes == 27 && q.inverted > 0);
  HMO_CHECK(counts.reads == 3 * nv && counts.constructions == 0);

  auto moved_between = [](const std::vector<Gmap_lcc::Point>& a, const std::vector<Gmap_lcc::Point>& b) {
    std::size_t n = 0;
    for(std::size_t i = 0; i < a.size(); ++i) n += a[i] != b[i] ? 1 : 0;
    return n;
  };
  counts = Counting_traits::Counts();
  const auto input = points_of(lcc);
  const auto ru = CGAL::untangle_hex_mesh(lcc, CGAL::parameters::maximum_running_time(60).geom_traits(gt));
  HMO_CHECK(ru.inverted_before > 0 && ru.inverted_after == 0);
  const auto untangled = points_of(lcc);
  const std::size_t moved = moved_between(input, untangled);
  HMO_CHECK(moved > 0);
  HMO_CHECK(counts.reads == 3 * nv);
  HMO_CHECK(counts.constructions == moved);

  counts = Counting_traits::Counts();
  const auto ri = CGAL::improve_hex_mesh_quality(lcc, CGAL::parameters::target_msj(0.9).geom_traits(gt));
  HMO_CHECK(ri.inverted_after == 0);
  HMO_CHECK(counts.reads == 3 * nv);
  HMO_CHECK(counts.constructions == moved_between(untangled, points_of(lcc)));
}

/// Mesh_3 and the package in one translation unit: Mesh_3's
/// `CGAL::parameters::time_limit` (CGAL 5.5: a Boost.Parameter keyword) still
/// names Mesh_3's keyword, and the package's time limit, CGAL's
/// `maximum_running_time`, stops an untangling
void test_with_mesh_3()
{
  const auto exude = CGAL::parameters::exude(CGAL::parameters::time_limit = 7.5, CGAL::parameters::sliver_bound = 12.);
  HMO_CHECK(exude.time_limit() == 7.5);
  HMO_CHECK(exude.bound() == 12.);
  Exact_lcc lcc;
  make_tangled_grid(lcc);
  const auto r = CGAL::untangle_hex_mesh(lcc, CGAL::parameters::sharp_angle(160.).maximum_running_time(1e-9));
  HMO_CHECK(r.time_limit_reached);
  HMO_CHECK(r.inverted_after > 0 && r.unresolved.size() == r.inverted_after);
}

HMO_TEST_MAIN(test_cgal_user)
{
  HMO_CASE(test_exact_lcc());
  HMO_CASE(test_gmap_lcc());
  HMO_CASE(test_custom_items_lcc());
  HMO_CASE(test_all_constrained());
  HMO_CASE(test_vertex_point_map());
  HMO_CASE(test_reference_maps());
  HMO_CASE(test_geom_traits());
  HMO_CASE(test_with_mesh_3());
  return hmo_test::report(argv[0]);
}

} // namespace test_cgal_user
