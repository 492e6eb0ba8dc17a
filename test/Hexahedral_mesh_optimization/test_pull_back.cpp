// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The inversion-free pull-back (Section 3.3, internal/Untangling/Pull_back.h): a valid
// mesh whose boundary was moved off the target surface is brought back onto
// it without any accepted step inverting an element; an unreachable target
// ends gracefully with a valid mesh.

#include "test_meshes.h"
#include "test_util.h"

#include <CGAL/Hexahedral_mesh_optimization/internal/Untangling/Pull_back.h>

#include <CGAL/Real_timer.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <vector>

namespace test_pull_back {

namespace HMO = CGAL::Hexahedral_mesh_optimization::internal;
using HMO::Vec3;
using HMO::Vertex_class;
using HMO::operator+;
using HMO::operator-;
using HMO::operator*;

using hmo_test::grid;
using hmo_test::cylinder;

double min_sj(const HMO::Hex_mesh_arrays& m, const std::vector<Vec3>& p)
{
  double r = std::numeric_limits<double>::max();
  for(const HMO::Hex& h : m.hexes)
  {
    std::array<Vec3, 8> c;
    for(int i = 0; i < 8; ++i) c[i] = p[h[i]];
    r = (std::min)(r, HMO::scaled_jacobian(c));
  }
  return r;
}

// max distance of a boundary vertex to its anchor
double max_distance(const HMO::Target_surface& ts, const std::vector<Vec3>& p)
{
  std::vector<HMO::Boundary_constraint> bc;
  ts.update_constraints(p, bc);
  double d = 0.;
  for(std::size_t v : ts.boundary().vertices) d = (std::max)(d, HMO::norm(p[v] - bc[v].anchor));
  return d;
}

struct Step_log
{
  int steps = 0, invalid = 0;
  double min_sj = std::numeric_limits<double>::max();
};

// a smooth displacement of the whole block: bulges of the faces (outward and
// inward) and a twist, so that regular, sharp and corner vertices all leave
// their targets by up to ~2 edge lengths, the mesh staying valid
void relax(std::vector<Vec3>& p, double amplitude)
{
  for(Vec3& q : p)
  {
    const double x = q[0], y = q[1], z = q[2];
    const double bx = std::sin(CGAL_PI * y) * std::sin(CGAL_PI * z);
    const double by = std::sin(CGAL_PI * x) * std::sin(CGAL_PI * z);
    const double t = amplitude * (z - 0.5);
    const double c = std::cos(t), s = std::sin(t);
    const double u = x - 0.5, v = y - 0.5;
    q[0] = 0.5 + c * u - s * v + amplitude * 0.6 * bx * (x - 0.5);
    q[1] = 0.5 + s * u + c * v - amplitude * 0.4 * by * (y - 0.5);
    q[2] = z + amplitude * 0.1 * std::sin(2. * CGAL_PI * x) * std::sin(CGAL_PI * y);
  }
}

struct Case_result
{
  HMO::Pull_back_report report;
  Step_log log;
  double distance = 0., sj = 0.;
};

// pulls `relaxed` back onto `ts`, checking every accepted step
Case_result run_case(const char* name, const HMO::Hex_mesh_arrays& mesh, const HMO::Target_surface& ts,
                     std::vector<Vec3>& pts, HMO::Pull_back_settings s)
{
  const HMO::Hex_mesh_topology topo(mesh);
  Case_result c;
  s.on_step = [&](const HMO::Pull_back_step& st) {
    ++c.log.steps;
    const double m = min_sj(mesh, pts); // `pts` is the state just accepted
    if(!(m > 0.)) ++c.log.invalid;
    c.log.min_sj = (std::min)(c.log.min_sj, m);
    HMO_CHECK(st.min_sj > 0.);
    if(std::getenv("PB_TRACE"))
      std::cout << "  it " << st.iteration << " d " << st.distance << " sj " << st.min_sj << " w " << st.weight
                << " step " << st.step << std::endl;
  };
  CGAL::Real_timer timer;
  timer.start();
  c.report = HMO::pull_back_to_target(topo, ts, pts, s);
  timer.stop();
  c.distance = max_distance(ts, pts);
  c.sj = min_sj(mesh, pts);
  const HMO::Pull_back_report& r = c.report;
  std::cout << name << ": distance " << r.distance_before << " -> " << r.distance_after
            << " (mean edge " << r.mean_edge_length << "), reached " << r.reached << ", min SJ " << r.min_sj_before
            << " -> " << r.min_sj_after << " (lowest accepted " << c.log.min_sj << "), " << r.iterations
            << " iterations, " << c.log.steps << " steps, " << r.max_free_vertices << " free vertices, "
            << r.region_growths << " growths, snapped " << r.snapped << ", " << timer.time() << " s" << std::endl;
  // never an invalid state, and the report tells the truth
  HMO_CHECK(c.log.invalid == 0);
  HMO_CHECK(c.sj > 0.);
  HMO_CHECK_CLOSE(c.sj, r.min_sj_after, 1e-12);
  HMO_CHECK_CLOSE(c.distance, r.distance_after, 1e-12);
  HMO_CHECK(r.distance_after <= r.distance_before);
  HMO_CHECK(r.min_sj_after >= s.min_sj_fraction * r.min_sj_before - 1e-12);
  return c;
}

void test_grid(HMO::Pull_back_rest_shape rest, int rings, const char* name)
{
  const HMO::Hex_mesh_arrays block = grid(12, 12, 12);
  const HMO::Target_surface ts(block); // reference: the block's own boundary
  std::vector<Vec3> pts = block.points;
  relax(pts, 0.3);
  HMO_CHECK(min_sj(block, pts) > 0.);
  HMO_CHECK(max_distance(ts, pts) > 1.2 / 12.); // more than 1.2 edge lengths off

  HMO::Pull_back_settings s;
  s.rest_shape = rest;
  s.region_rings = rings;
  const Case_result c = run_case(name, block, ts, pts, s);
  HMO_CHECK(c.report.reached);
  HMO_CHECK(c.distance <= 1e-3 * c.report.mean_edge_length);
  HMO_CHECK(c.log.steps > 0);
  HMO_CHECK(c.log.min_sj > 0.);
  // the block's corners are back at the cube's corners
  for(std::size_t v : ts.boundary().vertices)
    if(ts.vertex_class(v) == Vertex_class::corner)
      HMO_CHECK(HMO::norm(pts[v] - block.points[v]) < 1e-6);
}

// a curved block: a cylinder (two closed feature circles, no corner) whose
// boundary is twisted, swollen and squeezed
void test_cylinder()
{
  const HMO::Hex_mesh_arrays cyl = cylinder(8, 8, 1.5);
  const HMO::Target_surface ts(cyl);
  HMO_CHECK(ts.number_of_vertices_of_class(Vertex_class::corner) == 0);
  HMO_CHECK(ts.number_of_vertices_of_class(Vertex_class::sharp) > 0);
  std::vector<Vec3> pts = cyl.points;
  for(Vec3& p : pts)
  {
    const double r = std::sqrt(p[0] * p[0] + p[1] * p[1]);
    const double a = std::atan2(p[1], p[0]) + 0.25 * (p[2] / 1.5) * r;
    const double f = 1. + 0.12 * r * std::sin(2. * a) * std::sin(CGAL_PI * p[2] / 1.5);
    p = Vec3{f * r * std::cos(a), f * r * std::sin(a), p[2] * (1. + 0.06 * r * std::cos(a))};
  }
  HMO_CHECK(min_sj(cyl, pts) > 0.);
  const double d0 = max_distance(ts, pts);
  HMO_CHECK(d0 > 0.1);
  HMO::Pull_back_settings s;
  const Case_result c = run_case("cylinder 8x8x8", cyl, ts, pts, s);
  HMO_CHECK(c.report.reached);
  HMO_CHECK(c.distance <= 1e-3 * c.report.mean_edge_length);
  // on the reference: radius 1 on the side, z in {0, 1.5} on the caps
  for(std::size_t v : ts.boundary().vertices)
  {
    const double r = std::sqrt(pts[v][0] * pts[v][0] + pts[v][1] * pts[v][1]);
    const double off = (std::min)({std::abs(r - 1.), std::abs(pts[v][2]), std::abs(pts[v][2] - 1.5)});
    HMO_CHECK(off < 0.02); // the reference is a polyhedral cylinder: chords are within 1 - cos(π/32)
  }
}

// A target that cannot be reached without inverting: the reference of a single
// hex whose vertex 0 is pushed into the element, past the plane of its
// neighbours 1, 3, 4. The target positions invert the element; vertex 0 (a
// regular vertex of the folded reference) cannot reach it while 2, 5, 6, 7
// (corners) stay at their anchors.
void test_unreachable()
{
  const HMO::Hex_mesh_arrays cube = grid(1, 1, 1);
  HMO::Hex_mesh_arrays dented = cube;
  dented.points[0] = Vec3{0.6, 0.6, 0.6};
  const HMO::Target_surface ts(dented);
  HMO_CHECK(ts.number_of_vertices_of_class(Vertex_class::corner) == 4); // 2, 5, 6, 7: fixed anchors
  std::vector<Vec3> target = cube.points;
  ts.target_points(target);
  HMO_CHECK(min_sj(cube, target) < 0.); // the target itself is inverted
  std::vector<Vec3> pts = cube.points;
  HMO::Pull_back_settings s;
  const Case_result c = run_case("unreachable corner", cube, ts, pts, s);
  HMO_CHECK(!c.report.reached);
  HMO_CHECK(c.log.min_sj > 0.);
  HMO_CHECK(c.report.distance_after < c.report.distance_before); // went part of the way
  HMO_CHECK(c.report.distance_after > 1e-3 * c.report.mean_edge_length);
  HMO_CHECK(c.report.min_sj_after >= 0.5 * c.report.min_sj_before - 1e-12);
}

// the relaxed 12^3 block with its centre vertex pushed through its cells:
// the pull-back goes on around the hexes it inverted, which keep their
// vertices (before, one inverted hex kept the whole pull-back from starting)
void test_inverted_inside()
{
  const HMO::Hex_mesh_arrays block = grid(12, 12, 12);
  const HMO::Target_surface ts(block);
  std::vector<Vec3> pts = block.points;
  relax(pts, 0.3);
  const std::size_t centre = 6 + 13 * (6 + 13 * 6);
  pts[centre][0] += 1.5 / 12.;
  HMO::Hex_mesh_arrays start = block;
  start.points = pts;
  std::vector<std::size_t> inverted;
  for(std::size_t h = 0; h < block.hexes.size(); ++h)
    if(HMO::is_inverted(HMO::scaled_jacobian(start, h))) inverted.push_back(h);
  HMO_CHECK(!inverted.empty());
  const HMO::Hex_mesh_topology topo(block);
  HMO::Pull_back_settings s;
  const double before = max_distance(ts, pts);
  const HMO::Pull_back_report r = HMO::pull_back_to_target(topo, ts, pts, s);
  HMO::Hex_mesh_arrays after = block;
  after.points = pts;
  std::size_t inverted_after = 0, pinned_moved = 0;
  for(std::size_t h = 0; h < block.hexes.size(); ++h)
    inverted_after += HMO::is_inverted(HMO::scaled_jacobian(after, h));
  for(std::size_t h : inverted)
    for(std::size_t v : block.hexes[h]) pinned_moved += pts[v] != start.points[v];
  std::cout << "pull-back with " << inverted.size() << " inverted hexes inside: distance " << before << " -> "
            << max_distance(ts, pts) << ", reached " << r.reached << ", " << r.iterations << " iterations"
            << std::endl;
  HMO_CHECK(r.reached);
  HMO_CHECK(max_distance(ts, pts) <= 1e-3 * r.mean_edge_length);
  HMO_CHECK(inverted_after == inverted.size());
  HMO_CHECK(pinned_moved == 0);
}

HMO_TEST_MAIN(test_pull_back)
{
  HMO_CASE(test_grid(HMO::Pull_back_rest_shape::ideal_cube, 3, "grid 12^3, ideal rest, 3 rings"));
  HMO_CASE(test_grid(HMO::Pull_back_rest_shape::initial_element, 3, "grid 12^3, initial rest, 3 rings"));
  HMO_CASE(test_grid(HMO::Pull_back_rest_shape::ideal_cube, -1, "grid 12^3, ideal rest, whole mesh"));
  HMO_CASE(test_cylinder());
  HMO_CASE(test_unreachable());
  HMO_CASE(test_inverted_inside());
  return hmo_test::report(argv[0]);
}

} // namespace test_pull_back
