// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Boundary extraction, target surface (Section 3.1: smoothing, projection,
// feature classification, per-iteration constraints) and surface error.

#include "test_meshes.h"
#include "test_util.h"

#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_boundary.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Target_surface.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Surface_fitting.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Final_projection.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/quality_statistics.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/surface_distance.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/hex_mesh_io.h>
#include <CGAL/hex_mesh_surface_error.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Real_timer.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace test_target_surface {

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point;
typedef CGAL::Surface_mesh<Point> Surface;
namespace HMO = CGAL::Hexahedral_mesh_optimization::internal;
using HMO::Vec3;
using HMO::Vertex_class;
using HMO::operator+;
using HMO::operator-;
using HMO::operator*;

// ------------------------------------------------------------ generators

using hmo_test::grid;
using hmo_test::cylinder;

CGAL::Indexed_hex_mesh<Point> to_indexed(const HMO::Hex_mesh_arrays& a)
{
  CGAL::Indexed_hex_mesh<Point> m;
  for(const Vec3& p : a.points)
    m.points.push_back(Point(p[0], p[1], p[2]));
  m.hexahedra.assign(a.hexes.begin(), a.hexes.end());
  return m;
}

double distance_to_box_surface(const Vec3& p, const Vec3& lo, const Vec3& hi)
{
  bool inside = true;
  double out2 = 0., in = 1e300;
  for(int d = 0; d < 3; ++d)
  {
    if(p[d] < lo[d]) { inside = false; out2 += (lo[d] - p[d]) * (lo[d] - p[d]); }
    else if(p[d] > hi[d]) { inside = false; out2 += (p[d] - hi[d]) * (p[d] - hi[d]); }
    else in = (std::min)(in, (std::min)(p[d] - lo[d], hi[d] - p[d]));
  }
  return inside ? in : std::sqrt(out2);
}

int on_box_planes(const Vec3& p, const Vec3& lo, const Vec3& hi, double tol)
{
  int c = 0;
  for(int d = 0; d < 3; ++d)
    if(std::abs(p[d] - lo[d]) < tol || std::abs(p[d] - hi[d]) < tol)
      ++c;
  return c;
}

// ------------------------------------------------------------ tests

void test_boundary_extraction()
{
  for(std::size_t n : {1, 2, 5})
  {
    const HMO::Hex_mesh_arrays m = grid(n, n, n);
    CGAL::Real_timer t;
    t.start();
    const HMO::Hex_mesh_boundary b = HMO::extract_boundary(m);
    HMO_CHECK(b.number_of_quads() == 6 * n * n);
    HMO_CHECK(b.number_of_vertices() == (n + 1) * (n + 1) * (n + 1) - (n - 1) * (n - 1) * (n - 1));
    HMO_CHECK(b.number_of_edges() == 12 * n * n);
    HMO_CHECK(b.number_of_overshared_faces == 0);
    HMO_CHECK(std::count(b.edge_is_manifold.begin(), b.edge_is_manifold.end(), false) == 0);
    // vertex map both ways
    bool map_ok = true;
    for(std::size_t i = 0; i < b.vertices.size(); ++i)
      map_ok = map_ok && b.boundary_index[b.vertices[i]] == i;
    std::size_t interior = 0;
    for(std::size_t v = 0; v < m.points.size(); ++v)
      if(!b.is_boundary_vertex(v))
        ++interior;
    HMO_CHECK(map_ok);
    HMO_CHECK(interior == (n - 1) * (n - 1) * (n - 1));
    // every quad has 4 neighbours, symmetric; quads point outward
    bool adj_ok = true, outward = true;
    const Vec3 c{0.5, 0.5, 0.5};
    for(std::size_t q = 0; q < b.quads.size(); ++q)
    {
      for(int i = 0; i < 4; ++i)
      {
        const std::size_t r = b.quad_neighbors[q][i];
        adj_ok = adj_ok && r != b.npos &&
                 std::count(b.quad_neighbors[r].begin(), b.quad_neighbors[r].end(), q) >= 1;
      }
      const auto& Q = b.quads[q];
      const Vec3 centre = 0.25 * (((m.points[Q[0]] + m.points[Q[1]]) + m.points[Q[2]]) + m.points[Q[3]]);
      outward = outward && HMO::dot(HMO::quad_normal(m.points, Q), centre - c) > 0.;
    }
    HMO_CHECK(adj_ok);
    HMO_CHECK(outward);
    // CSR: corners of the grid have 3 quads, 3 edges
    const auto qr = b.quads_of(b.boundary_index[0]);
    const auto er = b.edges_of(b.boundary_index[0]);
    HMO_CHECK(qr.second - qr.first == 3);
    HMO_CHECK(er.second - er.first == 3);
    // triangulated boundary: a closed surface of 12 n² triangles
    Surface s;
    HMO::boundary_to_surface_mesh(b, m.points, s);
    HMO_CHECK(s.number_of_faces() == 12 * n * n);
    HMO_CHECK(CGAL::is_closed(s));
    if(n == 5)
      std::cout << "boundary of a 5x5x5 grid: " << t.time() << " s" << std::endl;
  }

  // two hexes sharing only an edge: 2 non-manifold... 1 edge shared by 4 quads
  {
    HMO::Hex_mesh_arrays m = grid(2, 2, 1);
    m.hexes = {m.hexes[0], m.hexes[3]}; // diagonal cells (0,0) and (1,1) share the edge at x=y=0.5
    const HMO::Hex_mesh_boundary b = HMO::extract_boundary(m);
    HMO_CHECK(b.number_of_quads() == 12);
    HMO_CHECK(std::count(b.edge_is_manifold.begin(), b.edge_is_manifold.end(), false) == 1);
  }

  // a 40k-hex grid is fast
  {
    const HMO::Hex_mesh_arrays m = grid(34, 34, 34);
    CGAL::Real_timer t;
    t.start();
    const HMO::Hex_mesh_boundary b = HMO::extract_boundary(m);
    std::cout << "boundary of a 34^3 grid (" << m.hexes.size() << " hexes): " << t.time() << " s" << std::endl;
    HMO_CHECK(b.number_of_quads() == 6 * 34 * 34);
  }
}

void check_box_classes(const HMO::Target_surface& ts, std::size_t nx, std::size_t ny, std::size_t nz,
                       const char* what)
{
  const std::size_t corners = ts.number_of_vertices_of_class(Vertex_class::corner);
  const std::size_t sharp = ts.number_of_vertices_of_class(Vertex_class::sharp);
  const std::size_t regular = ts.number_of_vertices_of_class(Vertex_class::regular);
  const std::size_t nb = ts.boundary().number_of_vertices();
  std::cout << what << ": " << ts.feature_lines().size() << " feature lines, " << corners << " corners, "
            << sharp << " sharp, " << regular << " regular" << std::endl;
  HMO_CHECK(ts.feature_lines().size() == 12);
  HMO_CHECK(corners == 8);
  HMO_CHECK(sharp == 4 * ((nx - 1) + (ny - 1) + (nz - 1)));
  HMO_CHECK(regular == nb - 8 - sharp);
  for(const auto& l : ts.feature_lines())
    HMO_CHECK(!l.closed);
}

void test_features()
{
  // a box grid: 12 feature lines, 8 corners, the rest regular
  {
    const std::size_t nx = 3, ny = 4, nz = 5;
    const HMO::Hex_mesh_arrays m = grid(nx, ny, nz, 3., 4., 5.);
    HMO::Target_surface ts(m);
    check_box_classes(ts, nx, ny, nz, "box 3x4x5");
    // a uniform grid is a fixed point of the smoothing
    double move = 0.;
    for(std::size_t i = 0; i < ts.boundary().vertices.size(); ++i)
      move = (std::max)(move, HMO::norm(ts.target_positions()[i] - m.points[ts.boundary().vertices[i]]));
    HMO_CHECK(move < 1e-9);
    HMO_CHECK_CLOSE(ts.mean_boundary_edge_length(), 1., 1e-12);
    // the corners are where they should be
    for(std::size_t v = 0; v < m.points.size(); ++v)
      if(ts.vertex_class(v) == Vertex_class::corner)
        HMO_CHECK(on_box_planes(m.points[v], Vec3{0, 0, 0}, Vec3{3, 4, 5}, 1e-12) == 3);
      else if(ts.vertex_class(v) == Vertex_class::sharp)
        HMO_CHECK(on_box_planes(m.points[v], Vec3{0, 0, 0}, Vec3{3, 4, 5}, 1e-12) == 2);
  }

  // the same box with its boundary vertices shuffled within their faces and
  // the interior tangled: smoothing + projection keep 12 lines and 8 corners
  {
    const std::size_t n = 6;
    HMO::Hex_mesh_arrays m = grid(n, n, n);
    const HMO::Hex_mesh_arrays ref = m;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-0.3 / double(n), 0.3 / double(n));
    for(Vec3& p : m.points)
    {
      const int planes = on_box_planes(p, Vec3{0, 0, 0}, Vec3{1, 1, 1}, 1e-12);
      if(planes == 3)
        continue;
      for(int d = 0; d < 3; ++d)
      {
        const bool fixed = std::abs(p[d]) < 1e-12 || std::abs(p[d] - 1.) < 1e-12;
        if(!fixed || planes == 0)
          p[d] += (planes == 0 ? 3. : 1.) * u(rng);
      }
    }
    HMO::Target_surface ts(m);
    check_box_classes(ts, n, n, n, "shuffled 6x6x6 box");
    double off = 0.;
    for(const Vec3& p : ts.target_positions())
      off = (std::max)(off, distance_to_box_surface(p, Vec3{0, 0, 0}, Vec3{1, 1, 1}));
    HMO_CHECK(off < 1e-9);
  }

  // a closed cylinder: the two rims are closed feature lines, no corner
  {
    const HMO::Hex_mesh_arrays m = cylinder(8, 6, 2.);
    HMO::Target_surface ts(m);
    std::size_t closed = 0;
    for(const auto& l : ts.feature_lines())
      closed += l.closed ? 1 : 0;
    std::cout << "cylinder: " << ts.feature_lines().size() << " feature lines (" << closed << " closed), "
              << ts.number_of_vertices_of_class(Vertex_class::corner) << " corners, "
              << ts.number_of_vertices_of_class(Vertex_class::sharp) << " sharp" << std::endl;
    HMO_CHECK(ts.number_of_vertices_of_class(Vertex_class::corner) == 0);
    HMO_CHECK(ts.feature_lines().size() == 2);
    HMO_CHECK(closed == 2);
    HMO_CHECK(ts.number_of_vertices_of_class(Vertex_class::sharp) == 2 * 4 * 8);
  }

  // a smooth, coarse surface with θ = 165°: the sphere-like blob made by
  // pushing the boundary of a grid onto a sphere has no short fragments left
  {
    HMO::Hex_mesh_arrays m = grid(8, 8, 8, 2., 2., 2.);
    for(Vec3& p : m.points)
    {
      const Vec3 q = p - Vec3{1, 1, 1};
      const double linf = (std::max)(std::abs(q[0]), (std::max)(std::abs(q[1]), std::abs(q[2])));
      const double l2 = HMO::norm(q);
      if(l2 > 0.)
        p = Vec3{1, 1, 1} + (linf / l2) * q;
    }
    HMO::Target_surface ts(m);
    std::cout << "sphere from a cube: " << ts.number_of_vertices_of_class(Vertex_class::corner)
              << " corners, " << ts.number_of_vertices_of_class(Vertex_class::sharp) << " sharp" << std::endl;
    // no short dangling or isolated fragment is left
    const HMO::Hex_mesh_boundary& b = ts.boundary();
    auto sharp_degree = [&](std::size_t bi) {
      std::size_t d = 0;
      const auto er = b.edges_of(bi);
      for(const std::size_t* e = er.first; e != er.second; ++e)
        d += ts.sharp_edges()[*e] ? 1 : 0;
      return d;
    };
    bool fragments_ok = true;
    for(const auto& l : ts.feature_lines())
      if(l.edges.size() < ts.parameters().min_feature_edges)
        fragments_ok = fragments_ok && !l.closed && sharp_degree(l.vertices.front()) > 2 &&
                       sharp_degree(l.vertices.back()) > 2;
    HMO_CHECK(fragments_ok);
  }
}

// Creases by hysteresis (`Target_surface_parameters::feature_seed_angle`):
// on the top of a unit box grid, (a) ridges of 160° (below θ = 165°, above
// the seed angle 150°) that continue no crease are not features, and (b) a
// valley that fades from 130° to 160° along y is one crease from rim to rim.
void test_crease_hysteresis()
{
  const std::size_t n = 8;
  const double pi = 3.14159265358979323846;
  auto top = [&](const HMO::Hex_mesh_arrays& m, std::size_t v) { return std::abs(m.points[v][2] - 1.) < 1e-12; };
  HMO::Target_surface_parameters seeded; // as the quality stages with crease_seed_angle(150)
  seeded.feature_seed_angle = 150.;
  // (a) a zigzag of ridges across the top: every other column raised so
  // that each top quad tilts by 10°, a dihedral of 160° at each ridge
  {
    HMO::Hex_mesh_arrays m = grid(n, n, n);
    std::vector<std::size_t> raise;
    for(std::size_t v = 0; v < m.points.size(); ++v)
      if(top(m, v) && std::lround(m.points[v][0] * double(n)) % 2 == 1) raise.push_back(v);
    for(std::size_t v : raise) m.points[v][2] += std::tan(10. * pi / 180.) / double(n);
    HMO::Target_surface ts(m, seeded);
    check_box_classes(ts, n, n, n, "box with 160-degree ridges on top");
    // without the hysteresis (the default parameters) every ridge is a
    // crease, meeting the rims in 2 corners each
    HMO::Target_surface all(m);
    std::cout << "  the same, every edge below 165 degrees a crease: "
              << all.number_of_vertices_of_class(Vertex_class::corner) << " corners" << std::endl;
    HMO_CHECK(all.number_of_vertices_of_class(Vertex_class::corner) == 8 + 2 * (n - 1));
  }
  // (b) a valley along y at x = 1/2, one column wide on each side:
  // z = 1 - t(y) max(0, 1/n - |x - 1/2|), its slope from 25° (dihedral
  // 130°) at y = 0 down to 10° (160°) at y = 1; its shoulders are at 155°
  // to 170°, and continue no crease
  {
    HMO::Hex_mesh_arrays m = grid(n, n, n);
    for(std::size_t v = 0; v < m.points.size(); ++v)
    {
      if(!top(m, v)) continue;
      const Vec3 p = m.points[v];
      const double slope = (1. - p[1]) * 25. + p[1] * 10.;
      m.points[v][2] = 1. - std::tan(slope * pi / 180.) * (std::max)(0., 1. / double(n) - std::abs(p[0] - 0.5));
    }
    HMO::Target_surface ts(m, seeded);
    const HMO::Hex_mesh_boundary& b = ts.boundary();
    std::size_t valley = 0, valley_sharp = 0;
    for(std::size_t e = 0; e < b.number_of_edges(); ++e)
    {
      const Vec3 &p = m.points[b.edges[e][0]], &q = m.points[b.edges[e][1]];
      const bool on_valley = std::abs(p[0] - 0.5) < 1e-12 && std::abs(q[0] - 0.5) < 1e-12 && p[2] > 0.5 &&
                             q[2] > 0.5 && std::abs(p[1] - q[1]) > 0.;
      if(!on_valley) continue;
      ++valley;
      valley_sharp += ts.sharp_edges()[e] ? 1 : 0;
    }
    std::cout << "valley fading from 130 to 160 degrees: " << valley_sharp << " of its " << valley
              << " edges sharp, " << ts.number_of_vertices_of_class(Vertex_class::corner) << " corners" << std::endl;
    HMO_CHECK(valley == n);
    HMO_CHECK(valley_sharp == n);
    // the rims' 8 corners and the two where the valley meets the rims
    HMO_CHECK(ts.number_of_vertices_of_class(Vertex_class::corner) == 10);
  }
}

void test_constraints()
{
  const std::size_t n = 4;
  const HMO::Hex_mesh_arrays m = grid(n, n, n);
  const Vec3 lo{0, 0, 0}, hi{1, 1, 1};
  HMO::Target_surface ts(m);

  HMO::Hex_mesh_arrays p = m;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.1 / double(n), 0.1 / double(n));
  for(Vec3& x : p.points)
    for(int d = 0; d < 3; ++d)
      x[d] += u(rng);

  std::vector<HMO::Boundary_constraint> bc;
  ts.update_constraints(p.points, bc);
  HMO_CHECK(bc.size() == m.points.size());
  std::size_t n_reg = 0, n_sharp = 0, n_corner = 0, n_int = 0;
  bool regular_ok = true, sharp_ok = true, corner_ok = true, unit_ok = true, interior_ok = true;
  for(std::size_t v = 0; v < bc.size(); ++v)
  {
    const HMO::Boundary_constraint& c = bc[v];
    switch(c.type)
    {
    case Vertex_class::interior:
      ++n_int;
      interior_ok = interior_ok && !ts.boundary().is_boundary_vertex(v);
      break;
    case Vertex_class::regular:
    {
      ++n_reg;
      regular_ok = regular_ok && distance_to_box_surface(c.anchor, lo, hi) < 1e-12;
      unit_ok = unit_ok && std::abs(HMO::norm(c.direction) - 1.) < 1e-12;
      // the outward axis normal of the face the anchor is on
      const Vec3 centre{0.5, 0.5, 0.5};
      const Vec3 d = c.anchor - centre;
      int axis = 0;
      for(int k = 1; k < 3; ++k)
        if(std::abs(d[k]) > std::abs(d[axis]))
          axis = k;
      regular_ok = regular_ok && std::abs(c.direction[axis] - (d[axis] > 0 ? 1. : -1.)) < 1e-9;
      // the anchor is the closest point: v − anchor is along the normal
      const Vec3 r = p.points[v] - c.anchor;
      regular_ok = regular_ok && HMO::norm(HMO::cross(r, c.direction)) < 1e-9;
      break;
    }
    case Vertex_class::sharp:
    {
      ++n_sharp;
      sharp_ok = sharp_ok && on_box_planes(c.anchor, lo, hi, 1e-12) >= 2;
      unit_ok = unit_ok && std::abs(HMO::norm(c.direction) - 1.) < 1e-12;
      // the tangent is the free axis of the box edge
      int free_axis = -1;
      for(int k = 0; k < 3; ++k)
        if(!(std::abs(c.anchor[k] - lo[k]) < 1e-12 || std::abs(c.anchor[k] - hi[k]) < 1e-12))
          free_axis = k;
      sharp_ok = sharp_ok && free_axis >= 0 && std::abs(std::abs(c.direction[free_axis]) - 1.) < 1e-12;
      break;
    }
    case Vertex_class::corner:
      ++n_corner;
      corner_ok = corner_ok && HMO::norm(c.anchor - m.points[v]) < 1e-12;
      break;
    }
  }
  HMO_CHECK(n_corner == 8);
  HMO_CHECK(n_sharp == 12 * (n - 1));
  HMO_CHECK(n_reg == 6 * (n - 1) * (n - 1));
  HMO_CHECK(n_int == (n - 1) * (n - 1) * (n - 1));
  HMO_CHECK(regular_ok);
  HMO_CHECK(sharp_ok);
  HMO_CHECK(corner_ok);
  HMO_CHECK(unit_ok);
  HMO_CHECK(interior_ok);

  // project_to_target puts the boundary back on the box, leaves the interior
  HMO::Hex_mesh_arrays q = p;
  ts.project_to_target(q.points);
  double off = 0.;
  bool interior_kept = true;
  for(std::size_t v = 0; v < q.points.size(); ++v)
    if(ts.boundary().is_boundary_vertex(v))
      off = (std::max)(off, distance_to_box_surface(q.points[v], lo, hi));
    else
      interior_kept = interior_kept && q.points[v] == p.points[v];
  HMO_CHECK(off < 1e-12);
  HMO_CHECK(interior_kept);

  // target_points: the boundary at Ω_t (here the input grid)
  std::vector<Vec3> tp = p.points;
  ts.target_points(tp);
  bool tp_ok = true;
  for(std::size_t v : ts.boundary().vertices)
    tp_ok = tp_ok && HMO::norm(tp[v] - m.points[v]) < 1e-12;
  HMO_CHECK(tp_ok);

  // a separate reference (the box surface, 2 triangles a face) for a mesh
  // whose boundary is off it: Ω_t lands on the reference
  {
    std::vector<Vec3> rp;
    for(int i = 0; i < 8; ++i)
      rp.push_back(Vec3{double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)});
    // faces of the unit cube, any orientation (the class orients normals itself)
    const std::vector<HMO::Tri> rt = {{0, 1, 3}, {0, 3, 2}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                                      {2, 3, 7}, {2, 7, 6}, {0, 2, 6}, {0, 6, 4}, {1, 3, 7}, {1, 7, 5}};
    HMO::Target_surface ts2(p, rp, rt);
    double off2 = 0.;
    for(const Vec3& x : ts2.target_positions())
      off2 = (std::max)(off2, distance_to_box_surface(x, lo, hi));
    HMO_CHECK(off2 < 1e-12);
    HMO_CHECK(ts2.number_of_vertices_of_class(Vertex_class::corner) == 8);
    std::vector<HMO::Boundary_constraint> bc2;
    ts2.update_constraints(p.points, bc2);
    bool normals_out = true;
    for(std::size_t v = 0; v < bc2.size(); ++v)
      if(bc2[v].type == Vertex_class::regular)
        normals_out = normals_out && HMO::dot(bc2[v].direction, bc2[v].anchor - Vec3{0.5, 0.5, 0.5}) > 0.;
    HMO_CHECK(normals_out);
  }

  // transform: p ← 2p + t moves the anchors alike
  {
    HMO::Target_surface ts3(m);
    const Vec3 t{1., -2., 3.};
    ts3.transform(2., t);
    std::vector<Vec3> moved = p.points;
    for(Vec3& x : moved)
      x = 2. * x + t;
    std::vector<HMO::Boundary_constraint> bc3;
    ts3.update_constraints(moved, bc3);
    double err = 0.;
    for(std::size_t v = 0; v < bc3.size(); ++v)
      if(bc3[v].type != Vertex_class::interior)
        err = (std::max)(err, HMO::norm(bc3[v].anchor - (2. * bc[v].anchor + t)));
    HMO_CHECK(err < 1e-9);
    HMO_CHECK_CLOSE(ts3.mean_boundary_edge_length(), 2. * ts.mean_boundary_edge_length(), 1e-12);
  }
}

void write_cube_off(const std::string& fname, double lo, double hi)
{
  std::ofstream out(fname);
  out << "OFF\n8 6 0\n";
  for(int i = 0; i < 8; ++i)
    out << ((i & 1) ? hi : lo) << " " << (((i >> 1) & 1) ? hi : lo) << " " << (((i >> 2) & 1) ? hi : lo) << "\n";
  out << "4 0 2 3 1\n4 4 5 7 6\n4 0 1 5 4\n4 2 6 7 3\n4 0 4 6 2\n4 1 3 7 5\n";
}

void test_surface_error()
{
  // (parallel faces at one distance are the worst case of the bounded-error
  // Hausdorff distance, which cannot prune: keep the grid small)
  const HMO::Hex_mesh_arrays a = grid(2, 2, 2);
  const CGAL::Indexed_hex_mesh<Point> mesh = to_indexed(a);

  // against itself
  CGAL::Real_timer t;
  t.start();
  const double self = CGAL::hex_mesh_surface_error(mesh, mesh);
  HMO_CHECK(self < 1e-12);

  // against a copy scaled by s about the centre: the Hausdorff distance is
  // realised at a corner, (s−1)/2·√3, and the reference diagonal is s·√3
  const double s = 1.1;
  HMO::Hex_mesh_arrays b = a;
  for(Vec3& p : b.points)
    p = Vec3{0.5, 0.5, 0.5} + s * (p - Vec3{0.5, 0.5, 0.5});
  const CGAL::Indexed_hex_mesh<Point> scaled = to_indexed(b);
  const double expected = (s - 1.) / (2. * s);
  const double e = CGAL::hex_mesh_surface_error(mesh, scaled);
  std::cout << "surface error vs scaled copy: " << e << " (analytic " << expected << ")" << std::endl;
  HMO_CHECK_CLOSE(e, expected, 2e-4);
  const CGAL::Hex_mesh_surface_distance d = CGAL::hex_mesh_surface_distance(mesh, scaled);
  HMO_CHECK_CLOSE(d.mesh_to_reference, 0.05, 2e-4 * d.reference_diagonal);
  HMO_CHECK_CLOSE(d.reference_to_mesh, 0.05 * std::sqrt(3.), 2e-4 * d.reference_diagonal);
  HMO_CHECK_CLOSE(d.reference_diagonal, s * std::sqrt(3.), 1e-12);
  HMO_CHECK(d.metro_diagonal > d.reference_diagonal);

  // the same against a triangle-mesh reference read from a (quad) OFF file
  const std::string off = "test_target_surface_cube.off";
  write_cube_off(off, 0.5 - 0.5 * s, 0.5 + 0.5 * s);
  Surface ref;
  std::string err;
  HMO_CHECK(CGAL::IO::read_reference_surface(off, ref, &err));
  HMO_CHECK(CGAL::is_triangle_mesh(ref));
  HMO_CHECK(ref.number_of_faces() == 12);
  HMO_CHECK_CLOSE(CGAL::hex_mesh_surface_error(mesh, ref), expected, 2e-4);
  // 0 up to the error bound of the bounded-error Hausdorff distance (1e-4)
  HMO_CHECK_CLOSE(CGAL::hex_mesh_surface_error(scaled, ref), 0., 2e-4);
  std::remove(off.c_str());
  std::cout << "surface error checks: " << t.time() << " s" << std::endl;

  // reading errors are reported
  Surface bad;
  err.clear();
  HMO_CHECK(!CGAL::IO::read_reference_surface("no_such_file.obj", bad, &err));
  HMO_CHECK(!err.empty());
  std::cout << "missing file: " << err << std::endl;
  const std::string empty = "test_target_surface_empty.off";
  {
    std::ofstream out(empty);
    out << "OFF\n0 0 0\n";
  }
  err.clear();
  HMO_CHECK(!CGAL::IO::read_reference_surface(empty, bad, &err));
  HMO_CHECK(!err.empty());
  std::cout << "empty file: " << err << std::endl;
  std::remove(empty.c_str());
  const std::string unknown = "test_target_surface.xyz";
  {
    std::ofstream out(unknown);
    out << "0 0 0\n";
  }
  err.clear();
  HMO_CHECK(!CGAL::IO::read_reference_surface(unknown, bad, &err));
  HMO_CHECK(!err.empty());
  std::remove(unknown.c_str());

  // what fuzzing found in CGAL 5.5's readers is refused with a message:
  // a negative face index in an OFF file (undefined behaviour in CGAL's
  // scanner), a face index out of range in an OBJ file (a buffer overflow
  // in CGAL's builder), a degenerate face (CGAL's triangulate_faces)
  const char* cube_vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n";
  const struct
  {
    const char* name;
    std::string text;
    const char* expected; // in the message; null: reads
  } cases[] = {
    {"neg.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 -1 2\n", "neg.off:7: face 0: '-1' is not a vertex index"},
    {"nan.off", "OFF 3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n", "nan.off:3: vertex 1: 'nan' is not a finite number"},
    {"short.off", "OFF\n# comment\n3 1 0\n0 0 0\n1 0 0\n", "short.off:5: the file ends at vertex 2 of 3"},
    {"huge.off", "OFF\n4000000000 1 0\n", "number of vertices '4000000000' is not a count the file can hold"},
    {"range.obj", std::string(cube_vertices) + "f 1 2 3\nf 1 2 99\n", "malformed file"},
    {"quads.off", "OFF\n8 6 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n1 1 1\n"
                  "4 0 2 3 1\n4 4 5 7 6\n4 0 1 5 4\n4 2 6 7 3\n4 0 4 6 2\n4 1 3 7 5 255 0 0\n", nullptr},
  };
  for(const auto& c : cases)
  {
    {
      std::ofstream out(c.name);
      out << c.text;
    }
    err.clear();
    const bool read = CGAL::IO::read_reference_surface(c.name, bad, &err);
    std::cout << c.name << ": " << (read ? "read, " + std::to_string(bad.number_of_faces()) + " triangles" : err)
              << std::endl;
    if(c.expected)
      HMO_CHECK(!read && err.find(c.expected) != std::string::npos);
    else
      HMO_CHECK(read && bad.number_of_faces() == 12 && CGAL::is_triangle_mesh(bad) && CGAL::is_closed(bad));
    std::remove(c.name);
  }
}

// The culled one-sided distance agrees with CGAL's bounded-error Hausdorff
// distance computed on all triangles: on a "roof" (a triangle spanning a
// ridge, corners on the roof, middle far from it: a single-triangle bound is
// loose there) and on random perturbations of a curved surface, with and
// without a known lower value.
void test_culled_distance()
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  const double error_bound = 1e-4;
  auto check = [&](const HMO::Triangle_surface& from, const HMO::Triangle_surface& to, double lower) {
    const double full = PMP::bounded_error_Hausdorff_distance<CGAL::Sequential_tag>(from, to, error_bound);
    const double culled =
      HMO::one_sided_distance_above(HMO::surface_distance_detail::triangles_of(from), to, lower, error_bound);
    HMO_CHECK(std::abs(culled - (std::max)(lower, full)) <= 2. * error_bound);
    return culled;
  };
  // the roof: two triangles meeting at a ridge along y, 0.5 high; the flat
  // triangle below it touches it at its three corners only
  HMO::Triangle_surface roof, flat;
  HMO::add_separate_triangle(roof, Vec3{-1, -1, 0}, Vec3{0, -1, 0.5}, Vec3{0, 2, 0.5});
  HMO::add_separate_triangle(roof, Vec3{-1, -1, 0}, Vec3{0, 2, 0.5}, Vec3{-1, 2, 0});
  HMO::add_separate_triangle(roof, Vec3{0, -1, 0.5}, Vec3{1, -1, 0}, Vec3{1, 2, 0});
  HMO::add_separate_triangle(roof, Vec3{0, -1, 0.5}, Vec3{1, 2, 0}, Vec3{0, 2, 0.5});
  HMO::add_separate_triangle(flat, Vec3{-1, -1, 0}, Vec3{1, -1, 0}, Vec3{0, 2, 0.5});
  const double ridge = check(flat, roof, 0.);
  HMO_CHECK(ridge > 0.3); // the flat triangle's middle, under the ridge
  HMO_CHECK_CLOSE(check(flat, roof, 10.), 10., 1e-12); // nothing above a large lower value

  // a quarter cylinder of radius 1 and its copies with every vertex moved
  // by up to 0.02, both ways, with lower values 0, 0.01 and 0.03
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.02, 0.02);
  auto cylinder_patch = [&](bool perturb) {
    HMO::Triangle_surface s;
    const int na = 24, nz = 12;
    auto at = [&](int i, int j) {
      const double a = 1.5707963267948966 * i / na;
      Vec3 p{std::cos(a), std::sin(a), 2. * j / nz};
      if(perturb) p = p + Vec3{jitter(rng), jitter(rng), jitter(rng)};
      return p;
    };
    std::vector<std::vector<Vec3> > p(na + 1, std::vector<Vec3>(nz + 1));
    for(int i = 0; i <= na; ++i)
      for(int j = 0; j <= nz; ++j) p[i][j] = at(i, j);
    for(int i = 0; i < na; ++i)
      for(int j = 0; j < nz; ++j)
      {
        HMO::add_separate_triangle(s, p[i][j], p[i + 1][j], p[i + 1][j + 1]);
        HMO::add_separate_triangle(s, p[i][j], p[i + 1][j + 1], p[i][j + 1]);
      }
    return s;
  };
  const HMO::Triangle_surface exact = cylinder_patch(false);
  for(int trial = 0; trial < 3; ++trial)
  {
    const HMO::Triangle_surface moved = cylinder_patch(true);
    for(double lower : {0., 0.01, 0.03})
    {
      check(moved, exact, lower);
      check(exact, moved, lower);
    }
  }

  // coarse triangles with their corners on a finely triangulated cylinder,
  // each spanning several of its triangles (a boundary quad that slid across
  // the reference): the single-triangle bound is loose on each, the parts of
  // the subdivision are not; every depth (0: none) gives CGAL's answer
  HMO::Triangle_surface coarse;
  const int ca = 3, cz = 3;
  auto on_cylinder = [](double i, double j, double na, double nz) {
    const double a = 1.5707963267948966 * i / na;
    return Vec3{std::cos(a), std::sin(a), 2. * j / nz};
  };
  for(int i = 0; i < ca; ++i)
    for(int j = 0; j < cz; ++j)
    {
      // corners shifted along the surface, off the fine triangulation's vertices
      const double di = 0.37, dj = 0.21;
      HMO::add_separate_triangle(coarse, on_cylinder(i + di, j + dj, ca + 1, cz + 1),
                                 on_cylinder(i + 1 + di, j + dj, ca + 1, cz + 1),
                                 on_cylinder(i + 1 + di, j + 1 + dj, ca + 1, cz + 1));
    }
  const double full = PMP::bounded_error_Hausdorff_distance<CGAL::Sequential_tag>(coarse, exact, error_bound);
  HMO_CHECK(full > 0.01); // the chords' middles are inside the cylinder
  for(int depth : {0, 1, 3, 5})
    for(double lower : {0., 0.5 * full, 2. * full})
    {
      const double culled = HMO::one_sided_distance_above(HMO::surface_distance_detail::triangles_of(coarse), exact,
                                                          lower, error_bound, depth);
      HMO_CHECK(std::abs(culled - (std::max)(lower, full)) <= 2. * error_bound);
    }
}

// The bound through the neighbour across an edge (`straddle_bound`), on a
// connected triangulation of a quarter cylinder: never below the distance
// sampled densely over random triangles near the surface; on triangles whose
// corners lie on the surface and that cross one edge of it, far tighter than
// the single-triangle bound; and the culled distance on that connected
// surface still gives CGAL's answer.
void test_straddle_bound()
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  namespace SD = HMO::surface_distance_detail;
  const int na = 16, nz = 8;
  auto on_cylinder = [&](double i, double j) {
    const double a = 1.5707963267948966 * i / na;
    return Vec3{std::cos(a), std::sin(a), 2. * j / nz};
  };
  HMO::Triangle_surface surface;
  std::vector<HMO::Triangle_surface::Vertex_index> vi;
  for(int i = 0; i <= na; ++i)
    for(int j = 0; j <= nz; ++j)
    {
      const Vec3 p = on_cylinder(i, j);
      vi.push_back(surface.add_vertex(HMO::Triangle_surface::Point(p[0], p[1], p[2])));
    }
  auto v = [&](int i, int j) { return vi[std::size_t(i * (nz + 1) + j)]; };
  for(int i = 0; i < na; ++i)
    for(int j = 0; j < nz; ++j)
    {
      surface.add_face(v(i, j), v(i + 1, j), v(i + 1, j + 1));
      surface.add_face(v(i, j), v(i + 1, j + 1), v(i, j + 1));
    }
  HMO_CHECK(surface.number_of_faces() == std::size_t(2 * na * nz));
  const std::vector<SD::Soup_triangle> triangles = SD::triangles_of(surface);
  const auto neighbours = SD::face_neighbours(surface);
  std::size_t inner_edges = 0;
  for(const auto& n : neighbours)
    for(std::size_t o : n) inner_edges += o != (std::numeric_limits<std::size_t>::max)();
  HMO_CHECK(inner_edges == 2 * std::size_t(3 * na * nz - na - nz)); // each inner edge seen from both sides
  SD::Soup_tree tree(triangles.begin(), triangles.end());
  tree.accelerate_distance_queries();
  auto point = [](const Vec3& p) { return SD::Soup_point(p[0], p[1], p[2]); };
  auto bounds = [&](const SD::Soup_triangle& t, double& single, double& sampled) {
    const auto hit = tree.closest_point_and_primitive(CGAL::centroid(t));
    const std::size_t r = std::size_t(hit.second - triangles.begin());
    single = 0.;
    for(int k = 0; k < 3; ++k) single = (std::max)(single, CGAL::squared_distance(t.vertex(k), triangles[r]));
    sampled = 0.;
    const int n = 40;
    for(int a = 0; a <= n; ++a)
      for(int b = 0; a + b <= n; ++b)
      {
        const double wa = double(a) / n, wb = double(b) / n;
        const SD::Soup_point x = t.vertex(0) + wa * (t.vertex(1) - t.vertex(0)) + wb * (t.vertex(2) - t.vertex(0));
        sampled = (std::max)(sampled, CGAL::squared_distance(x, tree.closest_point(x)));
      }
    return SD::straddle_bound(t, r, triangles, neighbours);
  };
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> along(1., double(na) - 2.), up(1., double(nz) - 2.), step(0.2, 1.2),
    off(-0.01, 0.01);
  int tighter = 0;
  for(int trial = 0; trial < 200; ++trial)
  {
    // corners on the surface (every other trial: moved off it by up to 0.01)
    const double i = along(rng), j = up(rng);
    Vec3 c[3] = {on_cylinder(i, j), on_cylinder(i + step(rng), j + 0.3 * step(rng)),
                 on_cylinder(i + 0.3 * step(rng), j + step(rng))};
    if(trial % 2)
      for(Vec3& p : c) p = p + Vec3{off(rng), off(rng), off(rng)};
    const SD::Soup_triangle t(point(c[0]), point(c[1]), point(c[2]));
    double single = 0., sampled = 0.;
    const double bound = bounds(t, single, sampled);
    HMO_CHECK(bound >= sampled - 1e-15);
    HMO_CHECK(bound <= single);
    if(bound < 0.25 * single) ++tighter;
  }
  HMO_CHECK(tighter >= 20);
  // a triangle across one edge only: corners on the surface, on both sides of
  // the edge at column 5 between rows 2 and 3
  {
    const SD::Soup_triangle t(point(on_cylinder(4.6, 2.2)), point(on_cylinder(5.2, 2.5)),
                              point(on_cylinder(4.7, 2.6)));
    double single = 0., sampled = 0.;
    const double bound = bounds(t, single, sampled);
    HMO_CHECK(bound >= sampled - 1e-15);
    HMO_CHECK(std::sqrt(bound) < 0.25 * std::sqrt(single));
  }
  // the culled distance on the connected surface, as CGAL computes it
  HMO::Triangle_surface coarse;
  for(int i = 0; i < 4; ++i)
    for(int j = 0; j < 3; ++j)
      HMO::add_separate_triangle(coarse, on_cylinder(3.7 * i + 0.4, 2. * j + 0.3),
                                 on_cylinder(3.7 * i + 3.9, 2. * j + 0.5), on_cylinder(3.7 * i + 2.1, 2. * j + 2.2));
  const double error_bound = 1e-4;
  const double full = PMP::bounded_error_Hausdorff_distance<CGAL::Sequential_tag>(coarse, surface, error_bound);
  for(int depth : {0, 2, 4})
    for(double lower : {0., 0.5 * full})
    {
      const double culled =
        HMO::one_sided_distance_above(SD::triangles_of(coarse), surface, lower, error_bound, depth);
      HMO_CHECK(std::abs(culled - (std::max)(lower, full)) <= 2. * error_bound);
    }
}

// The reference-fit check: the mesh's own boundary fits; scaled by 1.05
// about its centre it is distant (a warning); scaled by 10 and moved away,
// or replaced by a small far-away surface, it is mismatched, with a message
// that says what does not match. Also on the bundled bunny with its reference.
void test_reference_fit()
{
  typedef CGAL::Hexahedral_mesh_optimization::Reference_fit Fit;
  const HMO::Hex_mesh_arrays a = grid(4, 4, 4);
  const CGAL::Indexed_hex_mesh<Point> mesh = to_indexed(a);
  // (HMO::Triangle_surface is a Surface_mesh of this kernel's points)
  auto boundary_transformed = [&](double scale, const Vec3& shift) {
    HMO::Hex_mesh_arrays b = a;
    const Vec3 c{0.5, 0.5, 0.5};
    for(Vec3& p : b.points) p = c + scale * (p - c) + shift;
    Surface s;
    HMO::boundary_surface(b, s);
    return s;
  };
  const Fit same = CGAL::hex_mesh_reference_fit(mesh, boundary_transformed(1., Vec3{0, 0, 0}));
  HMO_CHECK(same.verdict == Fit::fits);
  HMO_CHECK(same.message.empty());
  HMO_CHECK(same.max_mesh_to_reference < 1e-12 && same.max_reference_to_mesh < 1e-12);

  // 1.05: every boundary vertex 0.025 off, 0.025 / (1.05 √3) = 0.0137 diagonals
  const Fit grown = CGAL::hex_mesh_reference_fit(mesh, boundary_transformed(1.05, Vec3{0, 0, 0}));
  HMO_CHECK(grown.verdict == Fit::distant);
  HMO_CHECK_CLOSE(grown.median_mesh_to_reference, 0.025 / (1.05 * std::sqrt(3.)), 1e-9);
  HMO_CHECK(grown.message.find("0.0137") != std::string::npos);
  // the same within a looser tolerance fits (the farthest vertices are the
  // reference's corners, 0.025 √3 / (1.05 √3) = 0.0238 diagonals off)
  HMO_CHECK_CLOSE(grown.max_reference_to_mesh, 0.025 / 1.05, 1e-9);
  const Fit loose = CGAL::hex_mesh_reference_fit(mesh, boundary_transformed(1.05, Vec3{0, 0, 0}),
                                                 CGAL::parameters::surface_tolerance(0.025));
  HMO_CHECK(loose.verdict == Fit::fits);
  // the tolerance is checked as by the three optimisation functions
  for(double bad : {-0.1, 2., std::nan("")})
  {
    bool thrown = false;
    try { CGAL::hex_mesh_reference_fit(mesh, boundary_transformed(1.05, Vec3{0, 0, 0}),
                                       CGAL::parameters::surface_tolerance(bad)); }
    catch(const std::invalid_argument& e) { thrown = std::string(e.what()).find("surface_tolerance") != std::string::npos; }
    HMO_CHECK(thrown);
  }

  const Fit other_frame = CGAL::hex_mesh_reference_fit(mesh, boundary_transformed(10., Vec3{100, 0, 0}));
  std::cout << "mismatched reference: " << other_frame.message << std::endl;
  HMO_CHECK(other_frame.verdict == Fit::mismatched);
  HMO_CHECK(!other_frame.boxes_overlap);
  HMO_CHECK(other_frame.message.find("do not overlap") != std::string::npos);
  HMO_CHECK(other_frame.message.find("factor of 10") != std::string::npos);

  // overlapping boxes of one size, but another object: a thin slab through the middle
  HMO::Hex_mesh_arrays slab = grid(4, 4, 1);
  for(Vec3& p : slab.points) p = Vec3{p[0], p[1], 0.45 + 0.1 * p[2]};
  Surface slab_surface;
  HMO::boundary_surface(slab, slab_surface);
  const Fit slab_fit = CGAL::hex_mesh_reference_fit(mesh, slab_surface);
  HMO_CHECK(slab_fit.verdict == Fit::mismatched);
  HMO_CHECK(slab_fit.boxes_overlap);
  HMO_CHECK(slab_fit.message.find("half the mesh boundary vertices") != std::string::npos);

  // the bundled bunny and its reference (another method's surface of the same shape)
  const std::string dir = HMO_EXAMPLE_DATA_DIR;
  CGAL::Indexed_hex_mesh<Point> bunny;
  Surface ref;
  std::string why;
  HMO_CHECK(CGAL::IO::read_hex_mesh(dir + "/bunny_dualsheet.vtk", bunny));
  HMO_CHECK(CGAL::IO::read_reference_surface(dir + "/bunny_reference.obj", ref, &why));
  const Fit bf = CGAL::hex_mesh_reference_fit(bunny, ref);
  std::cout << "bunny_dualsheet vs bunny_reference.obj: vertices to the reference median " << bf.median_mesh_to_reference
            << " max " << bf.max_mesh_to_reference << ", reference vertices to the boundary median "
            << bf.median_reference_to_mesh << " max " << bf.max_reference_to_mesh << std::endl;
  // its reference is its own boundary cut along other diagonals: every
  // vertex on the other surface, the Hausdorff distance (0.0117) in the quads
  HMO_CHECK(bf.verdict == Fit::fits);
}

void test_shared_data()
{
  const std::string dir = hmo_test::shared_data_dir();
  if(dir.empty())
    return;
  const std::string hexfile = dir + "/inverted/bunny_dualsheet.vtk";
  const std::string objfile = dir + "/surfaces/bunny_reference.obj";
  if(!hmo_test::file_exists(hexfile) || !hmo_test::file_exists(objfile))
  {
    std::cout << "bunny files absent: shared-data checks skipped" << std::endl;
    return;
  }
  CGAL::Indexed_hex_mesh<Point> bunny;
  CGAL::IO::Hex_mesh_io_error ioerr;
  HMO_CHECK(CGAL::IO::read_hex_mesh(hexfile, bunny, &ioerr));
  Surface ref;
  std::string err;
  HMO_CHECK(CGAL::IO::read_reference_surface(objfile, ref, &err));
  if(bunny.hexahedra.empty() || ref.number_of_faces() == 0)
  {
    std::cout << "cannot read the bunny: " << ioerr.what() << " " << err << std::endl;
    return;
  }

  CGAL::Real_timer t;
  t.start();
  const CGAL::Hex_mesh_surface_distance d = CGAL::hex_mesh_surface_distance(bunny, ref);
  std::cout << "bunny_dualsheet vs bunny_reference.obj: Hausdorff / diagonal = " << d.relative()
            << " (metro normalisation " << d.metro_relative() << "), " << t.time() << " s" << std::endl;
  HMO_CHECK(d.relative() < 0.012);

  // the target surface with that reference lies on it
  const HMO::Hex_mesh_arrays a = HMO::make_hex_mesh_arrays(bunny, K());
  std::vector<Vec3> rp;
  std::vector<HMO::Tri> rt;
  HMO::face_graph_to_triangle_soup(ref, get(CGAL::vertex_point, ref), K(), rp, rt);
  t.reset();
  HMO::Target_surface ts(a, rp, rt);
  std::cout << "bunny target surface: " << t.time() << " s, "
            << ts.number_of_vertices_of_class(Vertex_class::corner) << " corners, "
            << ts.number_of_vertices_of_class(Vertex_class::sharp) << " sharp, "
            << ts.number_of_vertices_of_class(Vertex_class::regular) << " regular, "
            << ts.feature_lines().size() << " feature lines" << std::endl;
  double off = 0.;
  for(const Vec3& p : ts.target_positions())
  {
    Vec3 q;
    ts.closest_on_reference(p, q);
    off = (std::max)(off, HMO::norm(p - q));
  }
  HMO_CHECK(off < 1e-9 * d.reference_diagonal);
  std::vector<HMO::Boundary_constraint> bc;
  t.reset();
  ts.update_constraints(a.points, bc);
  std::cout << "bunny update_constraints: " << t.time() << " s" << std::endl;
  bool unit = true;
  for(const auto& c : bc)
    if(c.type == Vertex_class::regular || c.type == Vertex_class::sharp)
      unit = unit && std::abs(HMO::norm(c.direction) - 1.) < 1e-9;
  HMO_CHECK(unit);
}

// The surface check after a change (`surface_error_after_change`), with the
// bounds it keeps from one call to the next and without, against the error
// measured in full: on a cylinder whose boundary vertices move in steps,
// mostly a little (what the bounds clear), sometimes one vertex far out (the
// error grows there, which the bounds must not hide), sometimes a step
// undone (the bounds were set on a state that is gone). At the precision
// asked for (`relative_precision` of the diagonal): the quality stages ask
// for 1e-6 (`Optimization_schedule::surface_check_precision`), since a read
// 1e-4 low let a state 0.4 % over the tolerance through.
void test_surface_error_after_change(double relative_precision)
{
  const HMO::Hex_mesh_arrays start = cylinder(8, 6, 1.5);
  const HMO::Hex_mesh_boundary b = HMO::extract_boundary(start);
  HMO::Triangle_surface reference;
  HMO::boundary_to_surface_mesh(b, start.points, reference, HMO::Quad_split::diagonal_02);
  const HMO::Reference_distance_index index(reference);
  const double precision = relative_precision * index.diagonal();
  auto same_frame = [](const Vec3& p) { return p; };
  HMO::Surface_error_bounds bounds;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1., 1.);
  std::uniform_int_distribution<std::size_t> pick(0, b.vertices.size() - 1);
  HMO::Hex_mesh_arrays m = start;
  double error = 0.;
  int grew = 0, steps_checked = 0;
  for(int step = 0; step < 24; ++step)
  {
    const std::vector<Vec3> before = m.points;
    // every boundary vertex a little (0.2 % of the diagonal at most), and
    // every fourth step one vertex 3 % of it out
    for(std::size_t v : b.vertices)
      m.points[v] = m.points[v] + 0.002 * index.diagonal() * Vec3{unit(rng), unit(rng), unit(rng)};
    if(step % 4 == 3)
    {
      const std::size_t v = b.vertices[pick(rng)];
      m.points[v] = m.points[v] + 0.03 * index.diagonal() * Vec3{unit(rng), unit(rng), unit(rng)};
    }
    const double kept =
      HMO::surface_error_after_change(b, before, m.points, index, error, same_frame, relative_precision, &bounds);
    const double plain =
      HMO::surface_error_after_change(b, before, m.points, index, error, same_frame, relative_precision);
    HMO::Triangle_surface now;
    HMO::boundary_to_surface_mesh(b, m.points, now, HMO::Quad_split::diagonal_02);
    const HMO::Surface_distance full = HMO::surface_distance(now, reference, relative_precision);
    const double truth = (std::max)(full.mesh_to_reference, full.reference_to_mesh);
    // an upper bound, exact when the error grew
    HMO_CHECK(kept >= truth - 2. * precision);
    HMO_CHECK(plain >= truth - 2. * precision);
    if(truth > error + 2. * precision)
    {
      ++grew;
      HMO_CHECK_CLOSE(kept, truth, 2. * precision);
    }
    HMO_CHECK_CLOSE(kept, plain, 2. * precision);
    ++steps_checked;
    if(step % 3 == 2) m.points = before; // undone: the error stays
    else error = kept;
  }
  std::cout << "surface error after change, precision " << relative_precision << ": " << steps_checked
            << " steps, the error grew in " << grew << std::endl;
  HMO_CHECK(grew >= 3);
}

// Feature recovery (Feature_recovery.h): a box grid whose boundary
// vertices all moved off the creases, with the 12-triangle box as reference
void test_feature_recovery()
{
  const std::size_t n = 6;
  const double h = 1. / double(n);
  const HMO::Hex_mesh_arrays original = grid(n, n, n);
  HMO::Hex_mesh_arrays m = original;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.3 * h, 0.3 * h);
  for(Vec3& p : m.points) // every vertex, in every direction: none stays on a crease
    for(int d = 0; d < 3; ++d) p[d] += u(rng);
  const std::vector<Vec3> box_points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                        {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const std::vector<HMO::Tri> box_triangles = {{{0, 2, 1}}, {{0, 3, 2}}, {{4, 5, 6}}, {{4, 6, 7}},
                                               {{0, 1, 5}}, {{0, 5, 4}}, {{1, 2, 6}}, {{1, 6, 5}},
                                               {{2, 3, 7}}, {{2, 7, 6}}, {{3, 0, 4}}, {{3, 4, 7}}};
  // the features of the reference itself
  const HMO::Reference_features rf = HMO::detect_reference_features(box_points, box_triangles, 150., 60., 2. * h, 30.);
  HMO_CHECK(rf.clear && rf.sharp_edges == 12 && rf.clearly_sharp_edges == 12); // the 12 creases at 90 degrees
  HMO_CHECK(rf.corners.size() == 8);
  HMO_CHECK(rf.curves.size() == 12);
  HMO_CHECK(std::set<std::size_t>(rf.triangle_patch.begin(), rf.triangle_patch.end()).size() == 6);
  for(const std::vector<std::size_t>& around : rf.corner_patches) HMO_CHECK(around.size() == 3);

  HMO::Target_surface_parameters param;
  param.reference_feature_angle = 150.;
  const HMO::Target_surface ts(m, box_points, box_triangles, param);
  const HMO::Feature_recovery_summary& fr = ts.feature_recovery_summary();
  std::cout << "perturbed box, recovered from its reference: " << HMO::describe(fr) << std::endl;
  HMO_CHECK(fr.recovered);
  HMO_CHECK(fr.reference_corners == 8 && fr.corners_matched == 8);
  HMO_CHECK(fr.reference_curves == 12 && fr.curves_recovered == 12);
  check_box_classes(ts, n, n, n, "perturbed box, recovered");
  // the grid's own corner and edge vertices took the corners and creases,
  // and their targets are on them; every target is on the box
  double off_box = 0., off_feature = 0.;
  for(std::size_t i = 0; i < ts.boundary().vertices.size(); ++i)
  {
    const std::size_t v = ts.boundary().vertices[i];
    const Vec3& t = ts.target_positions()[i];
    off_box = (std::max)(off_box, distance_to_box_surface(t, Vec3{0, 0, 0}, Vec3{1, 1, 1}));
    const int planes = on_box_planes(original.points[v], Vec3{0, 0, 0}, Vec3{1, 1, 1}, 1e-12);
    const Vertex_class expected = planes == 3 ? Vertex_class::corner : planes == 2 ? Vertex_class::sharp : Vertex_class::regular;
    HMO_CHECK(ts.vertex_class(v) == expected);
    if(planes >= 2) HMO_CHECK(on_box_planes(t, Vec3{0, 0, 0}, Vec3{1, 1, 1}, 1e-9) == planes);
    if(planes >= 2) off_feature = (std::max)(off_feature, HMO::norm(t - original.points[v]));
  }
  std::cout << "  targets off the box " << off_box << ", feature vertices off their grid place " << off_feature / h
            << " edges" << std::endl;
  HMO_CHECK(off_box < 1e-9);
  HMO_CHECK(off_feature < 0.5 * h);

  // the hex counts of the boundary edges: 1 along the box's edges, 2 elsewhere,
  // 3 along the concave edge of an L-shaped block
  {
    const HMO::Hex_mesh_boundary b = HMO::extract_boundary(original);
    const std::vector<unsigned char> count = HMO::count_boundary_edge_hexes(b, original.hexes);
    std::size_t ones = 0, twos = 0;
    for(unsigned char c : count) { ones += c == 1; twos += c == 2; }
    HMO_CHECK(ones == 12 * n && twos == count.size() - ones);
    HMO::Hex_mesh_arrays l_block = grid(4, 4, 2);
    std::vector<HMO::Hex> kept;
    for(const HMO::Hex& hx : l_block.hexes)
    {
      Vec3 c{0., 0., 0.};
      for(std::size_t v : hx) c = c + 0.125 * l_block.points[v];
      if(c[0] < 0.5 || c[1] < 0.5) kept.push_back(hx);
    }
    l_block.hexes = kept;
    const HMO::Hex_mesh_boundary lb = HMO::extract_boundary(l_block);
    const std::vector<unsigned char> lcount = HMO::count_boundary_edge_hexes(lb, l_block.hexes);
    std::size_t threes = 0;
    for(std::size_t e = 0; e < lcount.size(); ++e)
      if(lcount[e] == 3)
      {
        ++threes;
        const Vec3 a = l_block.points[lb.edges[e][0]], c = l_block.points[lb.edges[e][1]];
        HMO_CHECK(std::abs(a[0] - 0.5) < 1e-12 && std::abs(a[1] - 0.5) < 1e-12);
        HMO_CHECK(std::abs(c[0] - 0.5) < 1e-12 && std::abs(c[1] - 0.5) < 1e-12);
      }
    HMO_CHECK(threes == 2); // the concave edge, two hexes high
  }

  // a boundary perturbed by 0.8 of an edge: positions alone match
  // corners to the wrong vertices; with the hex counts every corner and
  // crease vertex is the grid's own
  {
    HMO::Hex_mesh_arrays strong = original;
    std::mt19937 g(3);
    std::normal_distribution<double> w(0., 1.);
    for(Vec3& p : strong.points) // 0.8 of an edge in a random direction
    {
      const Vec3 d{w(g), w(g), w(g)};
      p = p + (0.8 * h / HMO::norm(d)) * d;
    }
    for(double tau : {0., 1.})
    {
      HMO::Target_surface_parameters sp = param;
      sp.recovery.topological_crease_cost = tau;
      const HMO::Target_surface st(strong, box_points, box_triangles, sp);
      std::size_t wrong = 0;
      for(std::size_t v : st.boundary().vertices)
      {
        const int planes = on_box_planes(original.points[v], Vec3{0, 0, 0}, Vec3{1, 1, 1}, 1e-12);
        const Vertex_class expected = planes == 3 ? Vertex_class::corner : planes == 2 ? Vertex_class::sharp : Vertex_class::regular;
        if(st.vertex_class(v) != expected) ++wrong;
      }
      std::cout << "strongly perturbed box, tau " << tau << ": " << HMO::describe(st.feature_recovery_summary()) << "; "
                << wrong << " boundary vertices of the wrong class" << std::endl;
      HMO_CHECK(st.feature_recovery_summary().topological == (tau > 0.));
      // the input is hard enough that positions alone go wrong (6 vertices)
      HMO_CHECK(tau > 0. ? wrong == 0 : wrong > 0);
    }
  }

  // a faceted round surface: its edges spread over all angles, no clear
  // features, and the reference is left to the dihedral-angle classification
  {
    std::vector<Vec3> points;
    std::vector<HMO::Tri> triangles;
    const std::size_t k = 8;
    std::mt19937 g(5);
    std::uniform_real_distribution<double> r(0.85, 1.15);
    const HMO::Hex_mesh_arrays cube = grid(k, k, k);
    const HMO::Hex_mesh_boundary b = HMO::extract_boundary(cube);
    for(std::size_t v : b.vertices)
    {
      const Vec3 d = cube.points[v] - Vec3{0.5, 0.5, 0.5};
      points.push_back((r(g) / HMO::norm(d)) * d);
    }
    for(const auto& q : b.quads)
    {
      triangles.push_back({{b.boundary_index[q[0]], b.boundary_index[q[1]], b.boundary_index[q[2]]}});
      triangles.push_back({{b.boundary_index[q[0]], b.boundary_index[q[2]], b.boundary_index[q[3]]}});
    }
    const HMO::Reference_features noisy = HMO::detect_reference_features(points, triangles, 150., 60., 0., 30.);
    const HMO::Reference_features unchecked = HMO::detect_reference_features(points, triangles, 150., 60., 0., 0.);
    std::cout << "  rough sphere: " << unchecked.curves.size() << " crease curves at 150 degrees, "
              << noisy.curves.size() << " once the margin is checked" << std::endl;
    HMO_CHECK(!unchecked.empty());
    HMO_CHECK(noisy.empty());
    HMO_CHECK(!noisy.clear && noisy.sharp_edges > 2 * noisy.clearly_sharp_edges);
    // the target surface then keeps its own classification, and says why
    HMO::Hex_mesh_arrays ball = cube;
    for(std::size_t i = 0; i < b.vertices.size(); ++i) ball.points[b.vertices[i]] = points[i];
    const HMO::Target_surface ts_ball(ball, points, triangles, param);
    const std::string why = HMO::describe(ts_ball.feature_recovery_summary());
    std::cout << "  feature recovery on it: " << why << std::endl;
    HMO_CHECK(ts_ball.feature_recovery_summary().attempted && !ts_ball.feature_recovery_summary().recovered);
    HMO_CHECK(why.find("not clear") != std::string::npos);
  }
}

// The surface fit (Surface_fitting.h) on a faceted cylinder whose boundary
// vertices slid around it: every vertex is on the reference
// (the rims on the reference's creases), yet each quad is a chord across a
// kink of the reference. The fit must take the error down by sliding the
// vertices along the surface and the rims along their creases, never
// taking a hex below the floor.
/// Constrained boundary vertices (`Hex_mesh_arrays::constrained`) on the
/// target surface: pinned where they are (a corner whose anchor is its own
/// position, whatever the reference says), so that the surface fit and the
/// final projection move the boundary vertices onto the reference but those. The grid's
/// boundary is moved off the box's boundary, its reference, along the
/// faces' normals; every other boundary vertex is constrained.
void test_constrained_target_and_projection()
{
  HMO::Hex_mesh_arrays m = grid(3, 3, 3);
  const HMO::Hex_mesh_arrays cube = grid(1, 1, 1);
  std::vector<Vec3> ref_points;
  std::vector<HMO::Tri> ref_triangles;
  HMO::triangulate_boundary(HMO::extract_boundary(cube), cube.points, HMO::Quad_split::diagonal_02, ref_points, ref_triangles);
  const HMO::Hex_mesh_boundary boundary = HMO::extract_boundary(m);
  m.constrained.assign(m.points.size(), 0);
  std::size_t n_constrained = 0;
  for(std::size_t bi = 0; bi < boundary.vertices.size(); ++bi)
  {
    const std::size_t v = boundary.vertices[bi];
    Vec3& p = m.points[v];
    for(int c = 0; c < 3; ++c)
      if(p[c] == 0.) p[c] = -0.02 * double(1 + bi % 3);
      else if(p[c] == 1.) p[c] = 1. + 0.02 * double(1 + bi % 3);
    if(bi % 2 == 1) { m.constrained[v] = 1; ++n_constrained; }
  }
  HMO_CHECK(n_constrained > 20);
  HMO::Target_surface_parameters param;
  param.smoothing_iterations = 0;
  const HMO::Target_surface ts(m, ref_points, ref_triangles, param);
  std::vector<HMO::Boundary_constraint> bc;
  ts.update_constraints(m.points, bc);
  for(std::size_t v : boundary.vertices)
    if(m.is_constrained(v))
    {
      HMO_CHECK(ts.vertex_class(v) == Vertex_class::corner);
      HMO_CHECK(bc[v].anchor == m.points[v]);
      HMO_CHECK(ts.constraint_at(v, m.points[v]).anchor == m.points[v]);
    }
  const HMO::Hex_mesh_topology topo(m);
  // the surface fit: the free boundary vertices toward the reference
  {
    HMO::Surface_fitting_settings fs;
    fs.aim = 0.005;
    fs.floor = 0.;
    HMO::Surface_fitting fit(topo, ts, ref_points, ref_triangles, fs);
    std::vector<Vec3> points = m.points;
    HMO_CHECK(fit.run(points).moves > 0);
    std::size_t moved_free = 0;
    for(std::size_t v = 0; v < points.size(); ++v)
    {
      if(m.is_constrained(v)) HMO_CHECK(points[v] == m.points[v]);
      else if(points[v] != m.points[v]) ++moved_free;
    }
    HMO_CHECK(moved_free > 0);
  }
  // the final projection
  std::vector<Vec3> points = m.points;
  const HMO::Final_projection_report r = HMO::project_boundary_onto_target(topo, ts, points, 0., 3);
  HMO_CHECK(r.projected > 0);
  std::size_t moved_free = 0;
  for(std::size_t v : boundary.vertices)
  {
    if(m.is_constrained(v)) HMO_CHECK(points[v] == m.points[v]);
    else if(points[v] != m.points[v]) ++moved_free;
  }
  HMO_CHECK(moved_free == r.projected);
}

void test_surface_fitting()
{
  const HMO::Hex_mesh_arrays start = cylinder(4, 3, 1.);
  const HMO::Hex_mesh_boundary sb = HMO::extract_boundary(start);
  std::vector<Vec3> ref_points;
  std::vector<HMO::Tri> ref_triangles;
  HMO::triangulate_boundary(sb, start.points, HMO::Quad_split::diagonal_02, ref_points, ref_triangles);
  HMO::Triangle_surface reference;
  HMO::boundary_to_surface_mesh(sb, start.points, reference, HMO::Quad_split::diagonal_02);
  // each boundary vertex turned around the axis by up to 0.4 of the angle
  // between two vertices of the rim (16 of them), then put back on the
  // reference (as a boundary moved off its surface and pulled back is)
  HMO::Hex_mesh_arrays m = start;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> turn(-0.4 * CGAL_PI / 8., 0.4 * CGAL_PI / 8.);
  for(std::size_t v : sb.vertices)
  {
    const double a = turn(rng);
    const Vec3 p = m.points[v];
    m.points[v] = Vec3{std::cos(a) * p[0] - std::sin(a) * p[1], std::sin(a) * p[0] + std::cos(a) * p[1], p[2]};
  }
  HMO::Target_surface_parameters param;
  param.reference_feature_angle = 150.;
  param.smoothing_iterations = 0;
  {
    const HMO::Target_surface on(m, ref_points, ref_triangles, param);
    for(std::size_t v : on.boundary().vertices) on.closest_on_reference(m.points[v], m.points[v]);
  }
  const double before = HMO::relative_surface_error(m, reference);
  const HMO::Quality_statistics q0 = HMO::quality_statistics(m);
  const HMO::Target_surface ts(m, ref_points, ref_triangles, param);
  HMO_CHECK(ts.feature_recovery_summary().recovered);
  HMO_CHECK(!ts.reference_creases().empty());
  const HMO::Hex_mesh_topology topo(m);
  HMO::Surface_fitting_settings fs;
  fs.aim = 0.1 * before * HMO::diagonal(HMO::bbox_of(reference));
  // (the cylinder's hexes at the corners of its square rings are at the
  // MSJ, and every vertex around them is in one: at that floor nothing moves)
  fs.floor = 0.1;
  HMO::Surface_fitting fit(topo, ts, ref_points, ref_triangles, fs);
  const HMO::Surface_fitting_report fr = fit.run(m.points);
  const double after = HMO::relative_surface_error(m, reference);
  const HMO::Quality_statistics q1 = HMO::quality_statistics(m);
  std::cout << "surface fit on a turned cylinder: error " << before << " -> " << after << ", " << fr.moves
            << " moves in " << fr.sweeps << " sweeps, MSJ " << q0.msj << " -> " << q1.msj << std::endl;
  HMO_CHECK(before > 0.005);
  HMO_CHECK(after < 0.7 * before);
  HMO_CHECK(fr.error_after < fr.error_before);
  HMO_CHECK(q1.inverted == 0);
  HMO_CHECK(q1.msj >= fs.floor - 1e-12);
  // every boundary vertex is still on the reference
  double off = 0.;
  for(std::size_t v : ts.boundary().vertices)
  {
    Vec3 q;
    ts.closest_on_reference(m.points[v], q);
    off = (std::max)(off, HMO::norm(q - m.points[v]));
  }
  HMO_CHECK(off < 1e-9);

}

HMO_TEST_MAIN(test_target_surface)
{
  HMO_CASE(test_boundary_extraction());
  HMO_CASE(test_features());
  HMO_CASE(test_crease_hysteresis());
  HMO_CASE(test_feature_recovery());
  HMO_CASE(test_constraints());
  HMO_CASE(test_surface_error());
  HMO_CASE(test_culled_distance());
  HMO_CASE(test_straddle_bound());
  HMO_CASE(test_surface_error_after_change(1e-4));
  HMO_CASE(test_surface_error_after_change(1e-6));
  HMO_CASE(test_reference_fit());
  HMO_CASE(test_surface_fitting());
  HMO_CASE(test_constrained_target_and_projection());
  HMO_CASE(test_shared_data());
  return hmo_test::report(argv[0]);
}

} // namespace test_target_surface
