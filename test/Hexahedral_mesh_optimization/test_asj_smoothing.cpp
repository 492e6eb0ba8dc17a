// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The ASJ smoothing (internal/Smoothing/Asj_smoothing.h): on perturbed grids it raises
// the ASJ, no element ends below min(floor, its own start), the boundary
// stays on the target (face vertices in their planes, edge vertices on their
// lines, corners unmoved; a fixed boundary without a target surface), and on
// a curved grid the surface error stays within the deviation bound; a
// focused pass moves only vertices near the worst hexes; the parallel
// (coloured) passes give the same result on one thread as on all of them
// and keep the floor; the start-deviation shortcut spares most calls to the
// surface guard and keeps the surface error within its bound; the guard's
// early-stopping test and caches answer as its full measure. The L-BFGS
// smoothing of the interior (Global_asj_smoothing.h), on a graded perturbed
// grid, raises the ASJ, moves no boundary vertex and no vertex of a hex near
// its floor, leaves no hex below its floor, and gives the same bytes on one
// thread. With the shared data, a real mesh gains ASJ without losing MSJ.

#include "test_meshes.h"
#include "test_util.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/hex_mesh_io.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Smoothing/Asj_smoothing.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Smoothing/Global_asj_smoothing.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Smoothing/Worst_element_smoothing.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Surface_guard.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/quality_statistics.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/surface_distance.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/global_control.h>
#endif

#include <algorithm>
#include <atomic>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <vector>

namespace test_asj_smoothing {

namespace HMO = CGAL::Hexahedral_mesh_optimization;
using HMO::internal::Vec3;
using HMO::internal::Hex_mesh_arrays;
using HMO::internal::Hex_mesh_topology;
using HMO::internal::Target_surface;
using HMO::internal::Asj_smoothing_settings;
using HMO::internal::Asj_smoothing_report;
using HMO::internal::operator-;

namespace {

// n^3 unit-cube grid, MEDIT order; perturbed: interior vertices in 3D, face
// vertices in their face plane, edge vertices along their edge, corners not
// (amplitude `a` times the spacing)
Hex_mesh_arrays perturbed_cube(int n, double a, unsigned seed)
{
  Hex_mesh_arrays m;
  const double h = 1. / n;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-a * h, a * h);
  for(int k = 0; k <= n; ++k)
    for(int j = 0; j <= n; ++j)
      for(int i = 0; i <= n; ++i)
      {
        Vec3 p{i * h, j * h, k * h};
        const int ijk[3] = {i, j, k};
        for(int d = 0; d < 3; ++d)
          if(ijk[d] != 0 && ijk[d] != n) p[d] += u(rng); // only along the free directions
        m.points.push_back(p);
      }
  m.hexes = hmo_test::structured_hexes(n, n, n);
  return m;
}

// a quarter of a thick cylinder (radii 1..2, height 1), perturbed inside
Hex_mesh_arrays perturbed_shell(int nr, int nt, int nz, double a, unsigned seed)
{
  Hex_mesh_arrays m;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-a, a);
  const double pi = 3.14159265358979323846;
  for(int k = 0; k <= nz; ++k)
    for(int j = 0; j <= nt; ++j)
      for(int i = 0; i <= nr; ++i)
      {
        const bool inner = i > 0 && i < nr && j > 0 && j < nt && k > 0 && k < nz;
        const double r = 1. + double(i) / nr + (inner ? u(rng) / nr : 0.);
        const double t = 0.5 * pi * (double(j) + (inner ? u(rng) : 0.)) / nt;
        const double z = double(k) / nz + (inner ? u(rng) / nz : 0.);
        m.points.push_back({r * std::cos(t), r * std::sin(t), z});
      }
  m.hexes = hmo_test::structured_hexes(nr, nt, nz);
  return m;
}

double bbox_diagonal(const std::vector<Vec3>& p)
{
  Vec3 lo = p[0], hi = p[0];
  for(const Vec3& x : p)
    for(int d = 0; d < 3; ++d) { lo[d] = (std::min)(lo[d], x[d]); hi[d] = (std::max)(hi[d], x[d]); }
  return HMO::internal::norm(hi - lo);
}

void test_cube()
{
  const int n = 6;
  const Hex_mesh_arrays in = perturbed_cube(n, 0.3, 7);
  const std::vector<double> sj0 = HMO::internal::scaled_jacobians(in);
  const HMO::internal::Quality_statistics q0 = HMO::internal::quality_statistics(sj0, in.points.size());
  HMO_CHECK(q0.inverted == 0);
  HMO_CHECK(q0.asj < 0.95);

  const Hex_mesh_topology topo(in);
  const Target_surface target(in);
  // a floor above the MSJ: elements below it may not get worse, the others not below it
  Asj_smoothing_settings s;
  s.min_sj_floor = 0.5 * (q0.msj + q0.asj);
  s.max_surface_deviation = 1e-3 * bbox_diagonal(in.points);
  std::vector<Vec3> p = in.points;
  const Asj_smoothing_report rep = HMO::internal::smooth_for_average_quality(topo, &target, p, s);

  Hex_mesh_arrays out = in;
  out.points = p;
  const std::vector<double> sj1 = HMO::internal::scaled_jacobians(out);
  const HMO::internal::Quality_statistics q1 = HMO::internal::quality_statistics(sj1, out.points.size());
  std::cout << "cube: ASJ " << q0.asj << " -> " << q1.asj << ", MSJ " << q0.msj << " -> " << q1.msj
            << ", passes " << rep.passes << ", moves " << rep.accepted_moves << std::endl;
  HMO_CHECK(q1.asj > q0.asj + 0.03);
  HMO_CHECK(q1.msj >= q0.msj);
  HMO_CHECK_CLOSE(rep.asj_before, q0.asj, 1e-12);
  HMO_CHECK_CLOSE(rep.asj_after, q1.asj, 1e-12);
  HMO_CHECK_CLOSE(rep.msj_after, q1.msj, 1e-12);
  std::size_t below = 0;
  for(std::size_t h = 0; h < sj1.size(); ++h)
    if(!(sj1[h] >= (std::min)(s.min_sj_floor, sj0[h]))) ++below;
  HMO_CHECK(below == 0);

  // boundary: on the cube, face vertices in their plane, edge vertices on their line, corners unmoved
  std::size_t off = 0, corners_moved = 0, boundary_moved = 0;
  for(std::size_t v = 0; v < p.size(); ++v)
  {
    int on[3];
    int count = 0;
    for(int d = 0; d < 3; ++d)
    {
      on[d] = (in.points[v][d] == 0. || in.points[v][d] == 1.) ? 1 : 0;
      count += on[d];
    }
    if(count == 0) continue;
    for(int d = 0; d < 3; ++d)
      if(on[d] && std::abs(p[v][d] - in.points[v][d]) > 1e-12) ++off;
    for(int d = 0; d < 3; ++d)
      if(p[v][d] < -1e-12 || p[v][d] > 1. + 1e-12) ++off;
    if(count == 3 && p[v] != in.points[v]) ++corners_moved;
    if(p[v] != in.points[v]) ++boundary_moved;
  }
  HMO_CHECK(off == 0);
  HMO_CHECK(corners_moved == 0);
  HMO_CHECK(boundary_moved > 0); // the boundary does take part
  const double err = HMO::internal::relative_surface_error(out, in);
  std::cout << "cube: surface error " << err << std::endl;
  HMO_CHECK(err < 2e-4); // the Hausdorff distance is computed to 1e-4 of the diagonal

  // without a target surface the boundary is frozen, and it still gains
  std::vector<Vec3> f = in.points;
  Asj_smoothing_settings sf;
  sf.min_sj_floor = q0.msj;
  const Asj_smoothing_report rf = HMO::internal::smooth_for_average_quality(topo, nullptr, f, sf);
  std::size_t frozen_moved = 0;
  for(std::size_t v = 0; v < f.size(); ++v)
    if(topo.is_boundary_vertex(v) && f[v] != in.points[v]) ++frozen_moved;
  HMO_CHECK(frozen_moved == 0);
  HMO_CHECK(rf.asj_after > rf.asj_before + 0.01);
  HMO_CHECK(rf.msj_after >= q0.msj);
  HMO_CHECK(rf.asj_after <= q1.asj + 1e-9); // a free boundary helps

  // the exact objective (no soft minimum) and each candidate alone also work
  for(int variant = 0; variant < 3; ++variant)
  {
    Asj_smoothing_settings sv = s;
    if(variant == 0) sv.objective_sharpness = 0.;
    if(variant == 1) sv.gradient_steps = 0;
    if(variant == 2) sv.cuboid_targets = false;
    std::vector<Vec3> pv = in.points;
    const Asj_smoothing_report rv = HMO::internal::smooth_for_average_quality(topo, &target, pv, sv);
    HMO_CHECK(rv.asj_after > rv.asj_before + 0.01);
    HMO_CHECK(rv.msj_after >= q0.msj);
  }
}

// focus_below: one pass visits only the vertices of the hexes below the
// focus value and of the hexes around those; the others stay where they are
void test_focus()
{
  const int n = 8;
  Hex_mesh_arrays in = perturbed_cube(n, 0.25, 3);
  in.points[2 + 3 * (n + 1) + 3 * (n + 1) * (n + 1)][0] += 0.4 / n; // a worse spot inside
  const std::vector<double> sj0 = HMO::internal::scaled_jacobians(in);
  const double msj0 = *std::min_element(sj0.begin(), sj0.end());
  HMO_CHECK(msj0 > 0.);
  const Hex_mesh_topology topo(in);
  const Target_surface target(in);
  Asj_smoothing_settings s;
  s.min_sj_floor = msj0;
  s.max_passes = 1;
  s.focus_below = msj0 + 0.05;
  std::vector<char> near(in.points.size(), 0), of_bad(in.points.size(), 0);
  std::size_t bad = 0;
  for(std::size_t h = 0; h < sj0.size(); ++h)
    if(sj0[h] < s.focus_below) { ++bad; for(std::size_t v : in.hexes[h]) of_bad[v] = 1; }
  for(std::size_t v = 0; v < near.size(); ++v)
    if(of_bad[v])
      for(auto c = topo.vertex_corners_begin(v); c != topo.vertex_corners_end(v); ++c)
        for(std::size_t w : in.hexes[c->hex]) near[w] = 1;
  HMO_CHECK(bad > 0 && bad < sj0.size() / 4);

  std::vector<Vec3> p = in.points;
  const Asj_smoothing_report rep = HMO::internal::smooth_for_average_quality(topo, &target, p, s);
  std::size_t moved = 0, moved_far = 0;
  for(std::size_t v = 0; v < p.size(); ++v)
    if(p[v] != in.points[v]) { ++moved; if(!near[v]) ++moved_far; }
  // the same pass over the whole mesh moves more
  Asj_smoothing_settings all = s;
  all.focus_below = std::numeric_limits<double>::infinity();
  std::vector<Vec3> q = in.points;
  HMO::internal::smooth_for_average_quality(topo, &target, q, all);
  std::size_t moved_all = 0;
  for(std::size_t v = 0; v < q.size(); ++v) moved_all += q[v] != in.points[v];
  std::cout << "focus: " << bad << " hexes below " << s.focus_below << ", " << moved << " vertices moved ("
            << moved_far << " away from them), " << moved_all << " without focus; MSJ " << msj0 << " -> "
            << rep.msj_after << std::endl;
  HMO_CHECK(moved > 0);
  HMO_CHECK(moved_far == 0);
  HMO_CHECK(moved_all > moved);
  HMO_CHECK(rep.msj_after >= msj0);
  HMO_CHECK(rep.asj_after > rep.asj_before);
}

void test_curved()
{
  const Hex_mesh_arrays in = perturbed_shell(4, 8, 4, 0.3, 11);
  const HMO::internal::Quality_statistics q0 = HMO::internal::quality_statistics(in);
  HMO_CHECK(q0.inverted == 0);
  const Hex_mesh_topology topo(in);
  const Target_surface target(in);
  const double diag = bbox_diagonal(in.points);
  Asj_smoothing_settings s;
  s.min_sj_floor = q0.msj;
  s.max_surface_deviation = 1e-3 * diag;
  std::vector<Vec3> p = in.points;
  const Asj_smoothing_report rep = HMO::internal::smooth_for_average_quality(topo, &target, p, s);
  Hex_mesh_arrays out = in;
  out.points = p;
  const double err = HMO::internal::relative_surface_error(out, in);
  std::cout << "shell: ASJ " << rep.asj_before << " -> " << rep.asj_after << ", MSJ " << rep.msj_before
            << " -> " << rep.msj_after << ", surface error " << err << std::endl;
  HMO_CHECK(rep.asj_after > rep.asj_before + 0.01);
  HMO_CHECK(rep.msj_after >= rep.msj_before);
  HMO_CHECK(err < 2e-3); // sample-based bound of 1e-3
  // corners (of the target's classification) unmoved, regular boundary vertices on the reference
  std::size_t corners_moved = 0, off = 0;
  for(std::size_t v = 0; v < p.size(); ++v)
  {
    if(target.vertex_class(v) == HMO::internal::Vertex_class::corner && p[v] != in.points[v]) ++corners_moved;
    if(target.vertex_class(v) == HMO::internal::Vertex_class::regular)
    {
      Vec3 q;
      target.closest_on_reference(p[v], q);
      if(HMO::internal::norm(q - p[v]) > 1e-9 * diag) ++off;
    }
  }
  HMO_CHECK(corners_moved == 0);
  HMO_CHECK(off == 0);
}

// The parallel passes, in colour order and in blocks: a fixed number of
// passes gives the same positions twice, and on one thread as on all; no
// element ends below its floor; the result is comparable with the
// one-vertex-at-a-time passes in index order. One block holding every vertex
// is index order itself, and so is every order without TBB.
void test_parallel_order(Asj_smoothing_settings::Visit_order order, const char* name)
{
  const Hex_mesh_arrays in = perturbed_shell(6, 12, 6, 0.2, 5);
  const std::vector<double> sj0 = HMO::internal::scaled_jacobians(in);
  const HMO::internal::Quality_statistics q0 = HMO::internal::quality_statistics(sj0, in.points.size());
  HMO_CHECK(q0.inverted == 0);
  const Hex_mesh_topology topo(in);
  const Target_surface target(in);
  Asj_smoothing_settings s;
  s.min_sj_floor = 0.5 * (q0.msj + q0.asj);
  s.max_surface_deviation = 1e-3 * bbox_diagonal(in.points);
  s.max_passes = 4;
  s.min_asj_gain = -1.;
  s.order = order;
  s.block_size = 64; // about 10 blocks
  auto run = [&](const Asj_smoothing_settings& settings, Asj_smoothing_report& r) {
    std::vector<Vec3> p = in.points;
    r = HMO::internal::smooth_for_average_quality(topo, &target, p, settings);
    return p;
  };
  Asj_smoothing_report r1, r2, r3, rs;
  const std::vector<Vec3> p1 = run(s, r1);
  const std::vector<Vec3> p2 = run(s, r2);
  HMO_CHECK(p1 == p2);
#ifdef CGAL_LINKED_WITH_TBB
  {
    tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    const std::vector<Vec3> p3 = run(s, r3);
    HMO_CHECK(p1 == p3);
  }
#endif
  Asj_smoothing_settings sequential = s;
  sequential.order = Asj_smoothing_settings::Visit_order::index;
  const std::vector<Vec3> ps = run(sequential, rs);
  std::cout << name << ": ASJ " << r1.asj_before << " -> " << r1.asj_after << " (" << r1.accepted_moves
            << " moves), one at a time " << rs.asj_after << " (" << rs.accepted_moves << " moves)" << std::endl;
  HMO_CHECK(r1.passes == 4);
  HMO_CHECK(r1.asj_after > r1.asj_before + 0.01);
  HMO_CHECK(std::abs(r1.asj_after - rs.asj_after) < 0.5 * (rs.asj_after - rs.asj_before));
#ifdef CGAL_LINKED_WITH_TBB
  HMO_CHECK(p1 != ps); // another order
#else
  HMO_CHECK(p1 == ps); // without TBB every pass runs in index order
#endif
  Hex_mesh_arrays out = in;
  out.points = p1;
  const std::vector<double> sj1 = HMO::internal::scaled_jacobians(out);
  std::size_t below = 0;
  for(std::size_t h = 0; h < sj1.size(); ++h)
    if(!(sj1[h] >= (std::min)(s.min_sj_floor, sj0[h]))) ++below;
  HMO_CHECK(below == 0);
  if(order == Asj_smoothing_settings::Visit_order::index_blocks)
  {
    Asj_smoothing_settings one_block = s;
    one_block.block_size = in.points.size();
    Asj_smoothing_report rb;
    HMO_CHECK(run(one_block, rb) == ps);
  }
}

void test_parallel()
{
  test_parallel_order(Asj_smoothing_settings::Visit_order::colours, "colour order");
  test_parallel_order(Asj_smoothing_settings::Visit_order::index_blocks, "blocks of 64");
}

// The start-deviation shortcut: with the surface guard as the ASJ smoothing's `guard`,
// a move within the budget of the start boundary skips the guard. Far fewer
// guard calls, a comparable ASJ, and the surface error within the guard's
// tolerance (the shortcut's budget is below it).
void test_shortcut()
{
  const Hex_mesh_arrays in = perturbed_shell(4, 8, 4, 0.3, 11);
  const HMO::internal::Quality_statistics q0 = HMO::internal::quality_statistics(in);
  const Hex_mesh_topology topo(in);
  const Target_surface target(in);
  const double diag = bbox_diagonal(in.points);
  std::vector<Vec3> ref_points;
  std::vector<HMO::internal::Tri> ref_tris;
  HMO::internal::triangulate_boundary(target.boundary(), in.points, HMO::internal::Quad_split::diagonal_02, ref_points,
                                      ref_tris);
  const HMO::internal::Surface_guard guard(target.boundary(), ref_points, ref_tris, in.points);
  Asj_smoothing_settings s;
  s.min_sj_floor = q0.msj;
  s.max_surface_deviation = 1e-3 * diag;
  s.max_passes = 6;
  s.guard = &guard;
  std::vector<Vec3> p = in.points;
  const Asj_smoothing_report guarded = HMO::internal::smooth_for_average_quality(topo, &target, p, s);
  const std::size_t guard_calls = guard.number_of_queries();
  s.start_deviation_budget = 1e-3 * diag;
  std::vector<Vec3> q = in.points;
  const Asj_smoothing_report shortcut = HMO::internal::smooth_for_average_quality(topo, &target, q, s);
  auto calls = [&] { return guard.number_of_queries() - guard_calls; };
  Hex_mesh_arrays out = in;
  out.points = q;
  const double err = HMO::internal::relative_surface_error(out, in);
  std::cout << "shortcut: " << guard_calls << " guard calls, ASJ " << guarded.asj_after << "; with the shortcut "
            << calls() << " calls, ASJ " << shortcut.asj_after << ", surface error " << err << std::endl;
  HMO_CHECK(guarded.asj_after > guarded.asj_before + 0.01);
  HMO_CHECK(calls() < guard_calls / 2);
  HMO_CHECK(shortcut.asj_after > shortcut.asj_before + 0.01);
  HMO_CHECK(shortcut.msj_after >= q0.msj);
  HMO_CHECK(err < 2e-3); // sample-based bound of 1e-3
}

// The surface guard's shortcuts (the bound test that stops early, and the
// per-quad caches of the sample distances skipped by the Lipschitz bound)
// give the answers of the full measure: along a random walk of boundary
// moves, `allows` agrees with `local_deviations(...).within(bound)` and
// `bound_at` with `local_deviations(...).bound(t)`, measured by a second
// guard that only ever measures in full. The fine grid is on from a fifth of
// the tolerance, so that both caches are used.
void test_guard_answers()
{
  using HMO::internal::operator*;
  using HMO::internal::operator+;
  const Hex_mesh_arrays in = perturbed_shell(4, 8, 4, 0.3, 11);
  const Target_surface target(in);
  std::vector<Vec3> ref_points;
  std::vector<HMO::internal::Tri> ref_tris;
  HMO::internal::triangulate_boundary(target.boundary(), in.points, HMO::internal::Quad_split::diagonal_02, ref_points,
                                      ref_tris);
  HMO::internal::Surface_guard guard(target.boundary(), ref_points, ref_tris, in.points);
  HMO::internal::Surface_guard oracle(target.boundary(), ref_points, ref_tris, in.points);
  const double diag = bbox_diagonal(in.points);
  const double tol = 2e-3 * diag;
  guard.set_dense_sampling_above(0.2 * tol);
  oracle.set_dense_sampling_above(0.2 * tol);
  const std::vector<std::size_t>& bv = target.boundary().vertices;
  std::mt19937 rng(7);
  std::uniform_int_distribution<std::size_t> pick(0, bv.size() - 1);
  std::normal_distribution<double> step(0., 1.);
  std::vector<Vec3> p = in.points;
  std::size_t agreed = 0, allowed = 0, refused = 0, ties = 0, bound_mismatches = 0;
  const int trials = hmo_test::sanitized ? 600 : 3000;
  for(int trial = 0; trial < trials; ++trial)
  {
    const std::size_t v = bv[pick(rng)];
    // moves of up to a few tolerances, mostly small
    const double size = (trial % 3 == 0 ? 3. : 0.3) * tol;
    const Vec3 x = p[v] + size * Vec3{step(rng), step(rng), step(rng)};
    const HMO::internal::Surface_deviation exact_bound = oracle.local_deviations(p, v, p[v]).bound(tol);
    const HMO::internal::Surface_deviation b = guard.bound_at(p, v, p[v], tol);
    if(std::abs(b.to_reference - exact_bound.to_reference) > 1e-12 * diag ||
       std::abs(b.from_reference - exact_bound.from_reference) > 1e-12 * diag)
      ++bound_mismatches;
    const HMO::internal::Surface_deviation d = oracle.local_deviations(p, v, x);
    const bool exact = d.within(exact_bound);
    const bool near_tie = std::abs(d.to_reference - exact_bound.to_reference) < 1e-12 * diag ||
                          std::abs(d.from_reference - exact_bound.from_reference) < 1e-12 * diag;
    const bool answer = guard.allows(p, v, x, exact_bound);
    if(near_tie) ++ties;
    else if(answer == exact) ++agreed;
    (exact ? allowed : refused) += 1;
    if(exact && trial % 2 == 0) p[v] = x; // walk on
  }
  std::cout << "guard answers: " << agreed << " of " << trials - ties << " agree (" << ties << " ties), " << allowed
            << " allowed, " << refused << " refused, " << bound_mismatches << " bound mismatches" << std::endl;
  HMO_CHECK(agreed == trials - ties);
  HMO_CHECK(bound_mismatches == 0);
  HMO_CHECK(allowed > std::size_t(trials / 10) && refused > std::size_t(trials / 10)); // both answers exercised
}

void test_shared_mesh()
{
  const std::string dir = hmo_test::shared_data_dir();
  if(dir.empty()) return;
  typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
  CGAL::Indexed_hex_mesh<K::Point_3> mesh;
  HMO_CHECK(CGAL::IO::read_hex_mesh(dir + "/low-quality/cat_2.mesh", mesh));
  if(mesh.hexahedra.empty()) return;
  const Hex_mesh_arrays in = HMO::internal::make_hex_mesh_arrays(mesh, K());
  const Hex_mesh_topology topo(in);
  const Target_surface target(in);
  const HMO::internal::Quality_statistics q0 = HMO::internal::quality_statistics(in);
  Asj_smoothing_settings s;
  s.min_sj_floor = q0.msj;
  s.max_surface_deviation = 1e-3 * bbox_diagonal(in.points);
  s.max_passes = 10;
  std::vector<Vec3> p = in.points;
  const Asj_smoothing_report rep = HMO::internal::smooth_for_average_quality(topo, &target, p, s);
  Hex_mesh_arrays out = in;
  out.points = p;
  const HMO::internal::Quality_statistics q1 = HMO::internal::quality_statistics(out);
  const double err = HMO::internal::relative_surface_error(out, in);
  std::cout << "cat_2: ASJ " << q0.asj << " -> " << q1.asj << ", MSJ " << q0.msj << " -> " << q1.msj
            << ", surface error " << err << ", " << rep.seconds << " s" << std::endl;
  HMO_CHECK(q1.asj > q0.asj + 0.02);
  HMO_CHECK(q1.msj >= q0.msj);
  HMO_CHECK(q1.inverted == 0);
  HMO_CHECK(err < 3e-3);
}

// exp_minus, the soft minima's exponential, against libm over its whole
// range, and 0 from 40 on
void test_exp_minus()
{
  double worst = 0.;
  for(int i = 0; i <= 400000; ++i)
  {
    const double d = 40. * i / 400001.;
    const double e = std::exp(-d);
    worst = (std::max)(worst, std::abs(HMO::internal::asj_detail::exp_minus(d) - e) / e);
  }
  std::cout << "exp_minus: largest relative error " << worst << std::endl;
  HMO_CHECK(worst < 1e-9);
  HMO_CHECK(HMO::internal::asj_detail::exp_minus(0.) == 1.);
  HMO_CHECK(HMO::internal::asj_detail::exp_minus(40.) == 0.);
  HMO_CHECK(HMO::internal::asj_detail::exp_minus(std::numeric_limits<double>::infinity()) == 0.);
}

} // namespace

// The reactivation threshold: a vertex whose visit gained at most
// `min_reactivating_gain` makes no vertex active for the next pass. With an
// infinite threshold the second pass visits nothing, so 10 passes give the
// positions of 1; with a small one the passes (10) visit fewer vertices than with
// none, and reach about the same ASJ.
void test_reactivation()
{
  const Hex_mesh_arrays in = perturbed_cube(8, 0.25, 7);
  const HMO::internal::Quality_statistics q0 = HMO::internal::quality_statistics(in);
  HMO_CHECK(q0.inverted == 0);
  const Hex_mesh_topology topo(in);
  const Target_surface target(in);
  Asj_smoothing_settings s;
  s.min_sj_floor = q0.msj;
  s.max_passes = 10;
  s.min_asj_gain = -1.;
  auto run = [&](const Asj_smoothing_settings& settings, Asj_smoothing_report& r) {
    std::vector<Vec3> p = in.points;
    r = HMO::internal::smooth_for_average_quality(topo, &target, p, settings);
    return p;
  };
  Asj_smoothing_report r_none, r_small, r_inf, r_one;
  run(s, r_none);
  Asj_smoothing_settings small = s;
  small.min_reactivating_gain = 1e-3;
  run(small, r_small);
  Asj_smoothing_settings inf = s;
  inf.min_reactivating_gain = std::numeric_limits<double>::infinity();
  const std::vector<Vec3> p_inf = run(inf, r_inf);
  Asj_smoothing_settings one = s;
  one.max_passes = 1;
  const std::vector<Vec3> p_one = run(one, r_one);
  std::cout << "reactivation: moves " << r_none.accepted_moves << " (ASJ " << r_none.asj_after << "), "
            << r_small.accepted_moves << " (ASJ " << r_small.asj_after << ") with 1e-3, "
            << r_inf.accepted_moves << " with infinity, " << r_one.accepted_moves << " in one pass" << std::endl;
  HMO_CHECK(p_inf == p_one);
  HMO_CHECK(r_inf.accepted_moves == r_one.accepted_moves);
  HMO_CHECK(r_small.accepted_moves < r_none.accepted_moves);
  HMO_CHECK(r_small.asj_after > r_one.asj_after);
  HMO_CHECK(std::abs(r_small.asj_after - r_none.asj_after) < 0.1 * (r_none.asj_after - r_none.asj_before));
}

// The max-min smoothing's sweeps in batches (Worst_element_smoothing.h): the
// same bytes on 1 and 2 threads and on two runs, the MSJ raised and never
// lowered, boundary vertices moving along their class (the batches' ring
// rule); a window of 1 (one vertex a batch: plain worst-first order) takes
// another path to a comparable MSJ.
void test_max_min_batches()
{
  const Hex_mesh_arrays in = perturbed_shell(6, 12, 6, 0.25, 3);
  const HMO::internal::Quality_statistics q0 =
    HMO::internal::quality_statistics(HMO::internal::scaled_jacobians(in), in.points.size());
  HMO_CHECK(q0.inverted == 0);
  const Hex_mesh_topology topo(in);
  const Target_surface target(in);
  HMO::internal::Worst_element_smoothing_settings s;
  s.max_sweeps = 15;
  auto run = [&](const HMO::internal::Worst_element_smoothing_settings& settings,
                 HMO::internal::Worst_element_smoothing_report& r) {
    std::vector<Vec3> p = in.points;
    HMO::internal::Worst_element_smoothing smoothing(topo, &target);
    r = smoothing.run(p, settings);
    return p;
  };
  HMO::internal::Worst_element_smoothing_report r1, r2, r3, rw;
  const std::vector<Vec3> p1 = run(s, r1);
  HMO_CHECK(run(s, r2) == p1);
#ifdef CGAL_LINKED_WITH_TBB
  {
    tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    HMO_CHECK(run(s, r3) == p1);
  }
#endif
  Hex_mesh_arrays out = in;
  out.points = p1;
  const double msj = HMO::internal::quality_statistics(HMO::internal::scaled_jacobians(out), out.points.size()).msj;
  HMO_CHECK(msj == r1.msj_after);
  HMO_CHECK(r1.msj_before == q0.msj);
  HMO_CHECK(msj > q0.msj + 0.05);
  std::size_t boundary_moved = 0;
  for(std::size_t v = 0; v < in.points.size(); ++v)
    if(topo.is_boundary_vertex(v) && p1[v] != in.points[v]) ++boundary_moved;
  HMO_CHECK(boundary_moved > 0);
  HMO::internal::Worst_element_smoothing_settings one = s;
  one.batch_window = 1;
  const std::vector<Vec3> pw = run(one, rw);
  std::cout << "max-min batches: MSJ " << q0.msj << " -> " << msj << " (" << r1.moves << " moves, "
            << boundary_moved << " boundary vertices moved); one vertex a batch " << rw.msj_after << std::endl;
  HMO_CHECK(pw != p1);
  HMO_CHECK(rw.msj_after > q0.msj + 0.05);
}

// The max-min smoothing skips the visits of settled vertices (moved
// nothing at their last visit, nothing moved around them since): the same
// positions as with every visit made, with and without a surface guard
// (whose tests read two rings of boundary quads), and visits were skipped.
void test_max_min_settled_vertices()
{
  // the boundary moved off its reference (the shell's own boundary) by up
  // to 0.15 of an edge, so that the guard's bounds bind
  const Hex_mesh_arrays shell = perturbed_shell(6, 12, 6, 0.25, 3);
  const Hex_mesh_topology topo(shell);
  const Target_surface target(shell);
  std::vector<Vec3> ref_points;
  std::vector<HMO::internal::Tri> ref_tris;
  HMO::internal::triangulate_boundary(target.boundary(), shell.points, HMO::internal::Quad_split::diagonal_02,
                                      ref_points, ref_tris);
  Hex_mesh_arrays in = shell;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.15 / 6., 0.15 / 6.);
  for(std::size_t v = 0; v < in.points.size(); ++v)
    if(topo.is_boundary_vertex(v))
      for(int d = 0; d < 3; ++d) in.points[v][d] += u(rng);
  const HMO::internal::Surface_guard guard(target.boundary(), ref_points, ref_tris, in.points);
  for(int guarded = 0; guarded < 2; ++guarded)
  {
    HMO::internal::Worst_element_smoothing_settings s;
    s.max_sweeps = 40;
    s.max_surface_deviation = guarded ? 5e-4 * bbox_diagonal(in.points) : std::numeric_limits<double>::infinity();
    auto run = [&](bool skip, HMO::internal::Worst_element_smoothing_report& r) {
      std::vector<Vec3> p = in.points;
      HMO::internal::Worst_element_smoothing smoothing(topo, &target, guarded ? &guard : nullptr);
      HMO::internal::Worst_element_smoothing_settings settings = s;
      settings.skip_settled = skip;
      r = smoothing.run(p, settings);
      return p;
    };
    HMO::internal::Worst_element_smoothing_report skipping, visiting;
    const std::vector<Vec3> p_skip = run(true, skipping), p_all = run(false, visiting);
    std::size_t boundary_moved = 0;
    for(std::size_t v = 0; v < in.points.size(); ++v)
      if(topo.is_boundary_vertex(v) && p_skip[v] != in.points[v]) ++boundary_moved;
    std::cout << "max-min settled vertices" << (guarded ? " (guarded)" : "") << ": " << skipping.skipped_visits
              << " visits skipped in " << skipping.sweeps << " sweeps, MSJ " << skipping.msj_before << " -> "
              << skipping.msj_after << ", " << boundary_moved << " boundary vertices moved" << std::endl;
    HMO_CHECK(p_skip == p_all);
    HMO_CHECK(skipping.moves == visiting.moves && skipping.sweeps == visiting.sweeps);
    HMO_CHECK(skipping.skipped_visits > 0 && visiting.skipped_visits == 0);
    HMO_CHECK(boundary_moved > 0);
  }
}

// n^3 grid graded geometrically (each layer `ratio` times the previous one
// along every axis, so that edges span ratio^(n-1)), interior vertices
// perturbed by `a` times their local spacing
Hex_mesh_arrays graded_perturbed_cube(int n, double ratio, double a, unsigned seed)
{
  std::vector<double> x(n + 1, 0.);
  for(int i = 1; i <= n; ++i) x[i] = x[i - 1] + std::pow(ratio, i - 1);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-a, a);
  Hex_mesh_arrays m;
  for(int k = 0; k <= n; ++k)
    for(int j = 0; j <= n; ++j)
      for(int i = 0; i <= n; ++i)
      {
        Vec3 p{x[i], x[j], x[k]};
        const int ijk[3] = {i, j, k};
        const bool inner = i > 0 && i < n && j > 0 && j < n && k > 0 && k < n;
        if(inner)
          for(int d = 0; d < 3; ++d) p[d] += u(rng) * (x[ijk[d]] - x[ijk[d] - 1]);
        m.points.push_back(p);
      }
  m.hexes = hmo_test::structured_hexes(n, n, n);
  return m;
}

void test_global_interior()
{
  const Hex_mesh_arrays in = graded_perturbed_cube(8, 1.8, 0.3, 11);
  const std::vector<double> sj0 = HMO::internal::scaled_jacobians(in);
  const HMO::internal::Quality_statistics q0 = HMO::internal::quality_statistics(sj0, in.points.size());
  HMO_CHECK(q0.inverted == 0);
  const Hex_mesh_topology topo(in);
  HMO::internal::Global_asj_settings s;
  s.min_sj_floor = q0.msj + 0.3 * (q0.asj - q0.msj); // some hexes start below it
  s.min_gain = 0.;
  s.max_iterations = 30;
  auto run = [&](HMO::internal::Global_asj_report& r) {
    std::vector<Vec3> p = in.points;
    r = HMO::internal::smooth_interior_for_average_quality(topo, p, s);
    return p;
  };
  HMO::internal::Global_asj_report r1, r2;
  const std::vector<Vec3> p1 = run(r1);
#ifdef CGAL_LINKED_WITH_TBB
  {
    tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    HMO_CHECK(run(r2) == p1);
  }
#else
  HMO_CHECK(run(r2) == p1);
#endif
  Hex_mesh_arrays out = in;
  out.points = p1;
  const std::vector<double> sj1 = HMO::internal::scaled_jacobians(out);
  const HMO::internal::Quality_statistics q1 = HMO::internal::quality_statistics(sj1, out.points.size());
  std::cout << "L-BFGS interior, graded grid (edges 1 to " << std::pow(1.8, 7) << "): " << r1.free_vertices
            << " free vertices, " << r1.iterations << " iterations, ASJ " << q0.asj << " -> " << q1.asj << ", MSJ "
            << q0.msj << " -> " << q1.msj << std::endl;
  HMO_CHECK(r1.iterations == 30);
  HMO_CHECK(r1.objective_after > r1.objective_before);
  HMO_CHECK(q1.asj > q0.asj + 0.02);
  std::size_t below = 0, moved_boundary = 0, moved_near_floor = 0, moved = 0;
  for(std::size_t h = 0; h < sj1.size(); ++h)
  {
    const double floor = HMO::internal::element_floor(s.min_sj_floor, sj0[h]);
    if(!(sj1[h] >= floor)) ++below;
    if(sj0[h] < floor + s.floor_margin)
      for(std::size_t v : in.hexes[h]) moved_near_floor += p1[v] != in.points[v];
  }
  for(std::size_t v = 0; v < p1.size(); ++v)
  {
    moved += p1[v] != in.points[v];
    if(topo.is_boundary_vertex(v)) moved_boundary += p1[v] != in.points[v];
  }
  HMO_CHECK(below == 0);
  HMO_CHECK(moved_boundary == 0);
  HMO_CHECK(moved_near_floor == 0);
  HMO_CHECK(moved > 0 && moved <= r1.free_vertices);
}


// The max-min smoothing's cluster moves (`improve_clusters`): on a grid
// with its interior perturbed, the clusters of hexes within the band of the
// MSJ move together: the MSJ rises, no hex ends below the MSJ before, only
// interior vertices of those hexes move, the SJ values it keeps are those of
// the positions; clusters above the size cap, or single hexes, stay where
// they are.
void test_max_min_clusters()
{
  const Hex_mesh_arrays in = graded_perturbed_cube(6, 1.0, 0.25, 4);
  const Hex_mesh_topology topo(in);
  const Target_surface target(in);
  HMO::internal::Worst_element_smoothing smoothing(topo, &target);
  const std::vector<double> sj0 = HMO::internal::scaled_jacobians(in);
  const double msj0 = *std::min_element(sj0.begin(), sj0.end());
  HMO_CHECK(msj0 > 0.);
  HMO::internal::Worst_element_smoothing_settings s;
  s.cluster_band = 0.3;
  std::vector<Vec3> p = in.points;
  std::vector<double> sj = sj0;
  std::size_t moves = 0;
  const double msj = smoothing.improve_clusters(p, sj, msj0, s, moves);
  Hex_mesh_arrays out = in;
  out.points = p;
  const std::vector<double> sj1 = HMO::internal::scaled_jacobians(out);
  std::size_t moved = 0, moved_wrongly = 0;
  for(std::size_t v = 0; v < p.size(); ++v)
  {
    if(p[v] == in.points[v]) continue;
    ++moved;
    bool of_low_hex = false;
    for(auto c = topo.vertex_corners_begin(v); c != topo.vertex_corners_end(v); ++c)
      of_low_hex = of_low_hex || sj0[c->hex] < msj0 + s.cluster_band;
    if(topo.is_boundary_vertex(v) || !of_low_hex) ++moved_wrongly;
  }
  std::cout << "max-min clusters: MSJ " << msj0 << " -> " << msj << ", " << moves << " steps, " << moved
            << " vertices moved" << std::endl;
  HMO_CHECK(sj1 == sj);
  HMO_CHECK(msj == *std::min_element(sj1.begin(), sj1.end()));
  HMO_CHECK(msj > msj0 + 0.01);
  HMO_CHECK(moves > 0 && moved > 0 && moved_wrongly == 0);
  // no cluster within the caps: nothing moves
  for(int cap = 0; cap < 2; ++cap)
  {
    HMO::internal::Worst_element_smoothing_settings capped = s;
    if(cap == 0) capped.max_cluster_hexes = 1;
    else capped.cluster_band = 1e-12; // the worst hex alone
    std::vector<Vec3> q = in.points;
    std::vector<double> sq = sj0;
    std::size_t none = 0;
    HMO_CHECK(smoothing.improve_clusters(q, sq, msj0, capped, none) == msj0);
    HMO_CHECK(none == 0 && q == in.points && sq == sj0);
  }
}

HMO_TEST_MAIN(test_asj_smoothing)
{
  HMO_CASE(test_exp_minus());
  HMO_CASE(test_cube());
  HMO_CASE(test_focus());
  HMO_CASE(test_curved());
  HMO_CASE(test_parallel());
  HMO_CASE(test_reactivation());
  HMO_CASE(test_shortcut());
  HMO_CASE(test_guard_answers());
  HMO_CASE(test_shared_mesh());
  HMO_CASE(test_max_min_batches());
  HMO_CASE(test_max_min_settled_vertices());
  HMO_CASE(test_max_min_clusters());
  HMO_CASE(test_global_interior());
  return hmo_test::report(argv[0]);
}

} // namespace test_asj_smoothing
