// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The inversion-free pull-back (Section 3.3, internal/Pull_back.h): a valid
// mesh whose boundary was moved off the target surface is brought back onto
// it without any accepted step inverting an element; an unreachable target
// ends gracefully with a valid mesh.

#include "test_util.h"

#include <CGAL/Hexahedral_mesh_optimization/internal/Pull_back.h>

#include <CGAL/Real_timer.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <vector>

namespace HMO = CGAL::Hexahedral_mesh_optimization::internal;
using HMO::Vec3;
using HMO::Vertex_class;
using HMO::operator+;
using HMO::operator-;
using HMO::operator*;

// nx × ny × nz grid spanning [0,sx]×[0,sy]×[0,sz], MEDIT order
HMO::Hex_mesh_arrays grid(std::size_t nx, std::size_t ny, std::size_t nz,
                          double sx = 1., double sy = 1., double sz = 1.)
{
  HMO::Hex_mesh_arrays m;
  auto id = [&](std::size_t i, std::size_t j, std::size_t k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  for(std::size_t k = 0; k <= nz; ++k)
    for(std::size_t j = 0; j <= ny; ++j)
      for(std::size_t i = 0; i <= nx; ++i)
        m.points.push_back(Vec3{sx * double(i) / double(nx), sy * double(j) / double(ny), sz * double(k) / double(nz)});
  for(std::size_t k = 0; k < nz; ++k)
    for(std::size_t j = 0; j < ny; ++j)
      for(std::size_t i = 0; i < nx; ++i)
        m.hexes.push_back(HMO::Hex{id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k),
                                   id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)});
  return m;
}

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

void test_grid(HMO::Pull_back_rest_shape rest, int rings)
{
  const HMO::Hex_mesh_arrays block = grid(12, 12, 12);
  const HMO::Hex_mesh_topology topo(block);
  const HMO::Target_surface ts(block); // reference: the block's own boundary
  HMO::Hex_mesh_arrays relaxed = block;
  relax(relaxed.points, 0.3);
  const double sj0 = min_sj(block, relaxed.points);
  HMO_CHECK(sj0 > 0.);
  const double d0 = max_distance(ts, relaxed.points);
  HMO_CHECK(d0 > 1.5 / 12.); // more than 1.5 edge lengths off

  HMO::Pull_back_settings s;
  s.rest_shape = rest;
  s.region_rings = rings;
  Step_log log;
  s.on_step = [&](const HMO::Pull_back_step& st) {
    ++log.steps;
    const double m = min_sj(block, relaxed.points);
    if(!(m > 0.)) ++log.invalid;
    log.min_sj = (std::min)(log.min_sj, m);
    HMO_CHECK_CLOSE(st.min_sj, st.min_sj, 0.); // finite
  };
  CGAL::Real_timer timer;
  timer.start();
  std::vector<Vec3>& pts = relaxed.points;
  const HMO::Pull_back_report r = HMO::pull_back_to_target(topo, ts, pts, s);
  timer.stop();
  const double d1 = max_distance(ts, pts);
  const double sj1 = min_sj(block, pts);
  std::cout << "grid 12^3, rest " << (rest == HMO::Pull_back_rest_shape::ideal_cube ? "ideal" : "initial")
            << ", rings " << rings << ": distance " << r.distance_before << " -> " << r.distance_after
            << " (edge " << r.mean_edge_length << "), min SJ " << r.min_sj_before << " -> " << r.min_sj_after
            << " (lowest on the way " << log.min_sj << "), " << r.iterations << " iterations, "
            << log.steps << " steps, " << r.max_free_vertices << " free vertices, growths " << r.region_growths
            << ", snapped " << r.snapped << ", " << timer.time() << " s (solver " << r.seconds << " s, CG " << r.conjugate_gradient_iterations << ")" << std::endl;
  HMO_CHECK(r.reached);
  HMO_CHECK(d1 <= 1e-3 * r.mean_edge_length);
  HMO_CHECK_CLOSE(d1, r.distance_after, 1e-12);
  HMO_CHECK(log.steps > 0);
  HMO_CHECK(log.invalid == 0);
  HMO_CHECK(sj1 > 0.);
  HMO_CHECK_CLOSE(sj1, r.min_sj_after, 1e-12);
  HMO_CHECK(log.min_sj > 0.);
}

int main(int, char** argv)
{
  test_grid(HMO::Pull_back_rest_shape::ideal_cube, 3);
  test_grid(HMO::Pull_back_rest_shape::initial_element, 3);
  test_grid(HMO::Pull_back_rest_shape::ideal_cube, -1);
  return hmo_test::report(argv[0]);
}
