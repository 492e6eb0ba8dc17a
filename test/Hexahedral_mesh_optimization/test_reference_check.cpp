// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// CGAL::check_hex_mesh_against_reference(): TetGen volume of the reference,
// trilinear hex volumes, vertices outside, boundary self-intersections and
// the errors of invalid references.

#include "test_meshes.h"
#include "test_util.h"

#include <CGAL/hex_mesh_reference_check.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/hex_mesh_io.h>
#include <CGAL/Hexahedral_mesh_optimization/Linear_cell_complex_hex_mesh.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Linear_cell_complex_for_combinatorial_map.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/generators.h>

#include <array>
#include <iomanip>
#include <cmath>
#include <iostream>
#include <random>
#include <string>
#include <vector>

namespace test_reference_check {

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point;
typedef CGAL::Surface_mesh<Point> Surface;
typedef CGAL::Indexed_hex_mesh<Point> Mesh;
typedef CGAL::Linear_cell_complex_for_combinatorial_map<3, 3, CGAL::Linear_cell_complex_traits<3, K> > LCC;
namespace HMO = CGAL::Hexahedral_mesh_optimization::internal;
using HMO::Vec3;
using HMO::operator+;
using HMO::operator-;
using HMO::operator*;

// nx × ny × nz grid of [0,sx]×[0,sy]×[0,sz], MEDIT order
Mesh grid(std::size_t nx, std::size_t ny, std::size_t nz, double sx, double sy, double sz)
{
  Mesh m;
  for(std::size_t k = 0; k <= nz; ++k)
    for(std::size_t j = 0; j <= ny; ++j)
      for(std::size_t i = 0; i <= nx; ++i)
        m.points.push_back(Point(sx * double(i) / double(nx), sy * double(j) / double(ny), sz * double(k) / double(nz)));
  m.hexahedra = hmo_test::structured_hexes(nx, ny, nz);
  return m;
}

// the triangulated surface of the box [x0,x1]×[y0,y1]×[z0,z1]
Surface box_surface(double x0, double y0, double z0, double x1, double y1, double z1)
{
  Surface s;
  CGAL::make_hexahedron(Point(x0, y0, z0), Point(x1, y0, z0), Point(x1, y1, z0), Point(x0, y1, z0),
                        Point(x0, y1, z1), Point(x0, y0, z1), Point(x1, y0, z1), Point(x1, y1, z1), s);
  CGAL::Polygon_mesh_processing::triangulate_faces(s);
  return s;
}

// the 24-tetrahedron decomposition (cell centroid, face centroids)
double volume_24_tets(const std::array<Vec3, 8>& c)
{
  static const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                  {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  Vec3 m{0., 0., 0.};
  for(const Vec3& p : c)
    m = m + 0.125 * p;
  double v = 0.;
  for(const auto& f : faces)
  {
    const Vec3 fc = 0.25 * (c[f[0]] + c[f[1]] + c[f[2]] + c[f[3]]);
    for(int i = 0; i < 4; ++i)
      v += HMO::tetrahedron_volume(m, fc, c[f[i]], c[f[(i + 1) % 4]]);
  }
  return v;
}

void test_hex_volume()
{
  std::array<Vec3, 8> cube = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                               {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};
  HMO_CHECK_CLOSE(HMO::trilinear_hex_volume(cube), 1., 1e-14);
  // non-planar faces: the Gauss rule equals the 24-tetrahedron decomposition
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  for(int trial = 0; trial < 20; ++trial)
  {
    std::array<Vec3, 8> c = cube;
    for(Vec3& p : c)
      p = p + Vec3{u(rng), u(rng), u(rng)};
    HMO_CHECK_CLOSE(HMO::trilinear_hex_volume(c), volume_24_tets(c), 1e-12);
  }
  // an inverted hexahedron has a negative volume
  std::swap(cube[0], cube[4]);
  std::swap(cube[1], cube[5]);
  std::swap(cube[2], cube[6]);
  std::swap(cube[3], cube[7]);
  HMO_CHECK_CLOSE(HMO::trilinear_hex_volume(cube), -1., 1e-14);
}

void test_box()
{
  const Mesh m = grid(4, 3, 2, 2., 1.5, 1.);
  const Surface box = box_surface(0., 0., 0., 2., 1.5, 1.);
  const auto r = CGAL::check_hex_mesh_against_reference(m, box);
  std::cout << "box grid vs box:\n" << r << std::endl;
  HMO_CHECK(!r.has_error());
  HMO_CHECK(r.error.empty());
  HMO_CHECK_CLOSE(r.hex_mesh_volume, 3., 1e-9);
  HMO_CHECK_CLOSE(r.reference_volume, 3., 1e-9);
  HMO_CHECK_CLOSE(r.reference_surface_volume, 3., 1e-9);
  HMO_CHECK(r.relative_volume_difference <= 1e-9);
  HMO_CHECK(r.reference_tetrahedra >= 5);
  HMO_CHECK(r.reference_triangles == 12);
  HMO_CHECK(r.hexahedra == 24 && r.vertices == 60);
  HMO_CHECK(r.nonpositive_volume_hexahedra == 0);
  HMO_CHECK(r.boundary_triangles == 2 * (2 * 12 + 2 * 8 + 2 * 6));
  HMO_CHECK(r.boundary_self_intersections == 0 && r.degenerate_boundary_triangles == 0);
  HMO_CHECK(!r.boundary_self_intersects());
  HMO_CHECK(r.outside_checked);
  HMO_CHECK(r.vertices_outside == 0 && r.vertices_outside_beyond_tolerance == 0);
  HMO_CHECK(r.farthest_outside_vertex == r.npos && r.max_outside_distance == 0.);
  HMO_CHECK_CLOSE(r.reference_diagonal, std::sqrt(4. + 2.25 + 1.), 1e-12);
  HMO_CHECK(r.passed());
  HMO_CHECK(r.summary().find("PASSED") != std::string::npos);

  // the boundary of a hex mesh as the reference
  const auto self = CGAL::check_hex_mesh_against_reference(m, m);
  HMO_CHECK(self.passed());
  HMO_CHECK_CLOSE(self.reference_volume, 3., 1e-9);
  HMO_CHECK(self.reference_triangles == r.boundary_triangles);

  // a linear cell complex, against a box slightly larger: the volume test fails, nothing is outside
  LCC lcc;
  HMO_CHECK(CGAL::build_linear_cell_complex(m, lcc));
  const auto big = CGAL::check_hex_mesh_against_reference(lcc, box_surface(-0.1, 0., 0., 2., 1.5, 1.));
  HMO_CHECK(!big.has_error());
  HMO_CHECK_CLOSE(big.hex_mesh_volume, 3., 1e-9);
  HMO_CHECK_CLOSE(big.reference_volume, 3.15, 1e-9);
  HMO_CHECK_CLOSE(big.relative_volume_difference, 0.15 / 3.15, 1e-9);
  HMO_CHECK(big.vertices_outside == 0);
  HMO_CHECK(!big.passed());
  HMO_CHECK(big.summary().find("volume") != std::string::npos);
  // ... which passes with a volume tolerance of 5 %
  HMO_CHECK(CGAL::check_hex_mesh_against_reference(lcc, box_surface(-0.1, 0., 0., 2., 1.5, 1.),
                                                   CGAL::parameters::volume_tolerance(0.05)).passed());
  // a hex mesh reference given as a linear cell complex
  HMO_CHECK(CGAL::check_hex_mesh_against_reference(m, lcc).passed());
}

void test_vertex_outside()
{
  Mesh m = grid(4, 3, 2, 2., 1.5, 1.);
  const Surface box = box_surface(0., 0., 0., 2., 1.5, 1.);
  const double diag = std::sqrt(4. + 2.25 + 1.);
  // vertex (2, 1, 2): on the top face, pushed up by 10 % of the diagonal
  const std::size_t v = 2 + 5 * (1 + 4 * 2);
  HMO_CHECK(m.points[v] == Point(1., 0.5, 1.));
  m.points[v] = Point(1., 0.5, 1. + 0.1 * diag);
  const auto r = CGAL::check_hex_mesh_against_reference(m, box);
  std::cout << "one vertex pushed out:\n" << r << std::endl;
  HMO_CHECK(!r.has_error());
  HMO_CHECK(r.vertices_outside == 1);
  HMO_CHECK(r.vertices_outside_beyond_tolerance == 1);
  HMO_CHECK(r.farthest_outside_vertex == v);
  HMO_CHECK_CLOSE(r.max_outside_distance, 0.1 * diag, 1e-9);
  HMO_CHECK_CLOSE(r.relative_max_outside_distance(), 0.1, 1e-9);
  HMO_CHECK(r.boundary_self_intersections == 0);
  HMO_CHECK(!r.passed());
  HMO_CHECK(r.summary().find("vertices outside") != std::string::npos);
  // the bump adds the volume under the four bilinear patches around the vertex
  HMO_CHECK(r.hex_mesh_volume > 3.);
  // with a tolerance above 10 % the vertex is still outside but accepted
  const auto tolerant = CGAL::check_hex_mesh_against_reference(
    m, box, CGAL::parameters::outside_tolerance(0.2).volume_tolerance(0.1));
  HMO_CHECK(tolerant.vertices_outside == 1 && tolerant.vertices_outside_beyond_tolerance == 0);
  HMO_CHECK(tolerant.passed());

  // pushed inward: no vertex outside, the volume shrinks
  m.points[v] = Point(1., 0.5, 0.9);
  const auto in = CGAL::check_hex_mesh_against_reference(m, box);
  HMO_CHECK(in.vertices_outside == 0);
  HMO_CHECK(in.hex_mesh_volume < 3.);
}

void test_folded_boundary()
{
  // a top vertex pulled below the bottom face: its boundary triangles cross the bottom face
  Mesh m = grid(4, 3, 2, 2., 1.5, 1.);
  const std::size_t v = 2 + 5 * (1 + 4 * 2);
  m.points[v] = Point(1., 0.5, -0.2);
  const auto r = CGAL::check_hex_mesh_against_reference(m, box_surface(0., 0., 0., 2., 1.5, 1.));
  std::cout << "folded boundary:\n" << r << std::endl;
  HMO_CHECK(!r.has_error());
  HMO_CHECK(r.boundary_self_intersections > 0);
  HMO_CHECK(r.boundary_self_intersects());
  HMO_CHECK(r.hex_mesh_volume < 3.);
  HMO_CHECK(!r.passed());
  HMO_CHECK(r.summary().find("self-intersecting boundary") != std::string::npos);

  // a collapsed boundary quad (3 collinear vertices): degenerate triangles, counted apart
  Mesh c = grid(1, 1, 1, 1., 1., 1.);
  c.points[1] = Point(0.5, 0.5, 0.); // the middle of the bottom diagonal (0, 2)
  const auto d = CGAL::check_hex_mesh_against_reference(c, box_surface(0., 0., 0., 1., 1., 1.));
  HMO_CHECK(d.degenerate_boundary_triangles >= 1);
  HMO_CHECK(d.boundary_self_intersects());
  HMO_CHECK(!d.passed());

  // two cubes touching along an edge only: a non-manifold boundary, which touches itself
  Mesh t;
  for(int k = 0; k < 2; ++k)
    for(int j = 0; j < 3; ++j)
      for(int i = 0; i < 3; ++i)
        t.points.push_back(Point(i, j, k));
  auto id = [](std::size_t i, std::size_t j, std::size_t k) { return i + 3 * (j + 3 * k); };
  for(std::size_t c = 0; c < 2; ++c)
    t.hexahedra.push_back({id(c, c, 0), id(c + 1, c, 0), id(c + 1, c + 1, 0), id(c, c + 1, 0),
                           id(c, c, 1), id(c + 1, c, 1), id(c + 1, c + 1, 1), id(c, c + 1, 1)});
  const auto nm = CGAL::check_hex_mesh_against_reference(t, box_surface(0., 0., 0., 2., 2., 1.));
  HMO_CHECK_CLOSE(nm.hex_mesh_volume, 2., 1e-12);
  HMO_CHECK(nm.boundary_self_intersections > 0);
  HMO_CHECK(!nm.passed());
}

void test_invalid_references()
{
  const Mesh m = grid(4, 3, 2, 2., 1.5, 1.);

  // not closed: one triangle removed
  Surface open = box_surface(0., 0., 0., 2., 1.5, 1.);
  CGAL::Euler::remove_face(halfedge(*faces(open).begin(), open), open);
  open.collect_garbage();
  const auto r = CGAL::check_hex_mesh_against_reference(m, open);
  std::cout << "open reference:\n" << r << std::endl;
  HMO_CHECK(r.has_error());
  HMO_CHECK(r.error.find("not closed") != std::string::npos);
  HMO_CHECK(r.reference_border_edges == 3);
  HMO_CHECK(!r.outside_checked);
  HMO_CHECK(!r.passed());
  HMO_CHECK(r.summary().find("ERROR") != std::string::npos);
  HMO_CHECK_CLOSE(r.hex_mesh_volume, 3., 1e-9); // the hex mesh is still measured
  HMO_CHECK(r.boundary_self_intersections == 0);

  // empty
  const auto e = CGAL::check_hex_mesh_against_reference(m, Surface());
  HMO_CHECK(e.has_error() && !e.passed());

  // self-intersecting: two overlapping boxes in one surface
  Surface two = box_surface(0., 0., 0., 2., 1.5, 1.);
  CGAL::make_hexahedron(Point(1, 1, 0.5), Point(3, 1, 0.5), Point(3, 2, 0.5), Point(1, 2, 0.5),
                        Point(1, 2, 2), Point(1, 1, 2), Point(3, 1, 2), Point(3, 2, 2), two);
  CGAL::Polygon_mesh_processing::triangulate_faces(two);
  const auto s = CGAL::check_hex_mesh_against_reference(m, two);
  std::cout << "self-intersecting reference: " << s.error << std::endl;
  HMO_CHECK(s.has_error() && s.error.find("self-intersects") != std::string::npos);
  HMO_CHECK(s.reference_self_intersections > 0);
  HMO_CHECK(!s.passed());

  // TetGen's own failure path, on the same soup: an error message, no exception
  std::vector<Vec3> pts;
  std::vector<HMO::Tri> tris;
  HMO::Triangle_surface ts;
  for(auto v : two.vertices())
    ts.add_vertex(two.point(v));
  for(auto f : two.faces())
  {
    std::vector<HMO::Triangle_surface::Vertex_index> vs;
    for(auto v : vertices_around_face(two.halfedge(f), two))
      vs.push_back(HMO::Triangle_surface::Vertex_index(std::size_t(v)));
    ts.add_face(vs[0], vs[1], vs[2]);
  }
  HMO::surface_to_soup(ts, pts, tris);
  const HMO::Surface_tetrahedralization t = HMO::tetrahedralize_closed_surface(pts, tris);
  std::cout << "TetGen on the self-intersecting surface: " << (t.ok ? "ok" : t.error) << std::endl;
  HMO_CHECK(!t.ok);
  HMO_CHECK(t.error.find("TetGen") != std::string::npos);
  HMO_CHECK(!HMO::tetrahedralize_closed_surface(pts, std::vector<HMO::Tri>()).ok);

  // TetGen runs in this process: a failure again gives the same message, and
  // TetGen works afterwards (on the box [0,2]x[0,1.5]x[0,1], outward
  // triangles)
  const HMO::Surface_tetrahedralization again = HMO::tetrahedralize_closed_surface(pts, tris);
  HMO_CHECK(!again.ok && again.error == t.error);
  std::vector<Vec3> box_pts;
  for(int i = 0; i < 8; ++i)
    box_pts.push_back({(i & 1) ? 2. : 0., (i & 2) ? 1.5 : 0., (i & 4) ? 1. : 0.});
  const std::vector<HMO::Tri> box_tris = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                                          {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  HMO_CHECK_CLOSE(HMO::closed_surface_volume(box_pts, box_tris), 3., 1e-12);
  const HMO::Surface_tetrahedralization after = HMO::tetrahedralize_closed_surface(box_pts, box_tris, true);
  HMO_CHECK(after.ok);
  HMO_CHECK_CLOSE(after.volume, 3., 1e-12);
  HMO_CHECK(after.tetrahedra.size() == after.number_of_tetrahedra);
}

void test_bunny()
{
  const std::string dir = HMO_EXAMPLE_DATA_DIR;
  Mesh m;
  Surface ref;
  std::string why;
  if(!CGAL::IO::read_hex_mesh(dir + "/bunny_dualsheet.vtk", m) ||
     !CGAL::IO::read_reference_surface(dir + "/bunny_reference.obj", ref, &why))
  {
    std::cout << "bundled bunny files unreadable: " << why << std::endl;
    HMO_CHECK(false);
    return;
  }
  const auto r = CGAL::check_hex_mesh_against_reference(m, ref);
  std::cout << "bunny_dualsheet.vtk vs bunny_reference.obj:\n" << r << std::endl;
  HMO_CHECK(!r.has_error());
  HMO_CHECK(r.reference_volume > 0.);
  std::cout << std::setprecision(17) << "TetGen " << r.reference_volume << " divergence " << r.reference_surface_volume << std::setprecision(6) << std::endl;
  HMO_CHECK_CLOSE(r.reference_volume, r.reference_surface_volume, 1e-6 * r.reference_volume);
  HMO_CHECK(r.outside_checked);
  HMO_CHECK(r.relative_volume_difference < 0.05);
  HMO_CHECK(r.relative_max_outside_distance() < 0.05);
}

HMO_TEST_MAIN(test_reference_check)
{
  if(!HMO::tetgen_available())
  {
    std::cout << "the package was configured without TetGen: reference checks skipped" << std::endl;
    return 77;
  }
  HMO_CASE(test_hex_volume());
  HMO_CASE(test_box());
  HMO_CASE(test_vertex_outside());
  HMO_CASE(test_folded_boundary());
  HMO_CASE(test_invalid_references());
  HMO_CASE(test_bunny());
  return hmo_test::report(argv[0]);
}

} // namespace test_reference_check
