// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// All rights reserved.
//
// This file is part of CGAL (www.cgal.org)
//
// $URL$
// $Id$
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Author(s) : Hexahedral_mesh_optimization contributors

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SMOOTHING_ASJ_SMOOTHING_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SMOOTHING_ASJ_SMOOTHING_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The last stage of the pipeline ("Improve ASJ", optional in the paper): a
// smoothing that raises the average scaled Jacobian (ASJ) of a valid mesh
// without letting any element fall below a floor, the boundary staying on the
// target surface.
//
// Method: Gauss-Seidel passes over the vertices. At a vertex v, candidate
// positions are tried in turn, each with backtracking (t = 1, 1/2, 1/4, ...):
//   1. a quality-driven target: for each hex around v, the best-fitting
//      cuboid (centre and principal axes of the hex, the axes made
//      orthonormal by a polar decomposition, each keeping its length) gives a
//      place for v's corner; the target is the mean of these places;
//   2. steps along the gradient of F_v = Σ over the hexes around v of a soft
//      minimum of their 9 Verdict samples, with a per-vertex step length
//      (× 1.5 after a full step, halved with each backtracking).
// A candidate is accepted only if
//   - every hex around v keeps a scaled Jacobian (exact Verdict value) of at
//     least min(floor, its value at the start of the stage): no element ends
//     below min(floor, its own start), in particular the MSJ never drops
//     under min(floor, MSJ before);
//   - F_v rises (the objective: see "Choices");
//   - for a boundary vertex, the local surface deviation (`guard`, or the
//     built-in check) stays within max(`max_surface_deviation`, the
//     deviation with v where it was).
// Only vertices near a move of the previous pass are visited again; the run
// stops when a pass raises the ASJ by less than `min_asj_gain`, after
// `max_passes` passes or at the time limit.
//
// Parallel passes (`order`, with TBB): the vertices, or blocks of vertices
// close in space, are coloured so that two of one colour never touch the
// same hex or read each other's boundary quads (`colour_units`); a pass
// visits the colours in turn, the vertices or blocks of one colour on all
// threads, each block in index order. The result does not depend on the
// number of threads.
//
// Boundary, with a target surface: a regular vertex moves in the tangent
// plane of the reference at its place and is projected onto the reference
// (closest point, `Target_surface::constraint_at`); a sharp vertex slides on
// its feature line as the stage received it: the two segments joining its
// start position to the start positions of its two neighbours along the
// feature line of the target surface, at most 0.45 of the way along each
// (so that two neighbours never meet); a corner is fixed. Without a target
// surface every boundary vertex is fixed. Quality and deviation are tested
// at the projected position.
//
// Choices (the measurements behind them are in the benchmark's RESULTS.md):
// - Objective: the sum of soft minima (sharpness 30) rather than of the exact
//   Verdict minima. The exact sum has a kink wherever two samples tie, which
//   is where a single-vertex ascent stops; the soft sum is smooth, so the
//   ascent goes on, and its maximiser has a higher exact ASJ. A sharper soft
//   minimum tends to the exact one and stops earlier.
// - Candidates: the cuboid target and one gradient step per visit; the
//   cuboid alone stalls, more gradient steps cost more than they gain.
// - Sharp vertices slide on their start polyline, not on the target
//   surface's feature line: that line is a polyline of the smoothed Ω_t,
//   which on coarse meshes lies visibly off the input's crease.
// - Deviation bound: the tangential moves alone, projected onto a coarse
//   reference, drift off the input's surface; the bound keeps them near it.
// - Cost: the ASJ keeps rising slowly for tens of passes (Gauss-Seidel on a
//   smooth objective), so `max_passes` and `min_asj_gain` bound the work.

#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Boundary_constraint.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_topology.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Surface_guard.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Target_surface.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/Time_limit.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/parallel_for_each_index.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/scaled_jacobian.h>


#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

struct Asj_smoothing_settings
{
  /// No element ends below min(min_sj_floor, its scaled Jacobian at the
  /// start): set it to the MSJ reached by the previous stages.
  double min_sj_floor = -std::numeric_limits<double>::infinity();
  /// maximum number of Gauss-Seidel passes
  int max_passes = 30;
  /// stop when a pass raises the ASJ by less than this
  double min_asj_gain = 1e-4;
  /// the run's hard stop (null: none), read between vertices
  const Time_limit* time_limit = nullptr;
  /// try the mean of the best-fitting cuboid corners (candidate 1)
  bool cuboid_targets = true;
  /// soft-min gradient steps per vertex visit (candidate 2); 0 disables
  int gradient_steps = 1;
  /// sharpness of the soft minimum -log(Σ exp(-k s_i)) / k of the 9 samples
  /// in the gradient
  double gradient_sharpness = 30.;
  /// sharpness of the soft minimum in the accepted objective; 0 = exact minimum
  double objective_sharpness = 30.;
  /// continuation: the first pass uses this sharpness, multiplied by
  /// `sharpness_growth` after every pass up to `objective_sharpness`
  double initial_objective_sharpness = 30.;
  double sharpness_growth = 1.5;
  /// a move must raise the vertex's objective (a sum of soft minima) by more
  /// than this; a vertex that cannot is left alone until a neighbour moves
  double min_move_gain = 1e-6;
  /// a vertex whose visit raised its objective by at most this makes no
  /// vertex around it active for the next pass (it moved, but too little to
  /// give its neighbours much to gain); 0: every move does
  double min_reactivating_gain = 0.;
  /// backtracking: at most this many halvings of a step
  int max_halvings = 3;
  /// with a target surface: whether regular and sharp boundary vertices move
  bool move_boundary = true;
  /// largest distance, in mesh units, between the boundary around a moved
  /// vertex and the reference; a move never takes it beyond
  /// max(this, the distance before the move). Infinity disables the check.
  double max_surface_deviation = std::numeric_limits<double>::infinity();
  /// How the deviation is measured. Null: the built-in test against the
  /// boundary as the stage received it (see `builtin_surface_test`), which
  /// bounds what this stage adds to the surface error. Given: each direction
  /// of `Surface_guard::local_deviations` with v at x must stay within
  /// max(`max_surface_deviation`, its value with v where it is).
  const Surface_guard* guard = nullptr;
  /// With `guard` given: a move that passes the built-in test
  /// against the boundary as the stage received it, with this distance
  /// instead of `max_surface_deviation`, is accepted without calling
  /// the guard. Set it to what the surface error may still grow by
  /// (bound − error at the start, in mesh units): by the triangle
  /// inequality such a move keeps the error within the bound (up to the
  /// sampling of both tests). The built-in test costs a few point-quad
  /// distances, far less than the guard's AABB queries, so a pass that
  /// mostly takes the shortcut runs much faster.
  /// 0 disables the shortcut.
  double start_deviation_budget = 0.;
  /// When finite, only the vertices of the hexes whose scaled Jacobian is
  /// below it, and of the hexes around those, are visited (then, as always,
  /// those near a move): the turns of the quality improver reshape the
  /// neighbourhood of the worst elements, and a pass over the whole mesh
  /// would cost each turn time in proportion to the mesh, not to them.
  double focus_below = std::numeric_limits<double>::infinity();
  /// The order of a pass, and what runs in parallel (with TBB; the result
  /// never depends on the number of threads):
  ///   - `index`: one vertex at a time, in index order;
  ///   - `colours`: colour by colour (see `colour_units`), the vertices
  ///     of one colour on all threads;
  ///   - `index_blocks`: the vertices cut into blocks of `block_size`
  ///     vertices close in space (`sort_into_blocks`), each block in index
  ///     order; the blocks are coloured as the vertices are in
  ///     `colours` (two blocks of one colour share no hex and read none of
  ///     each other's boundary quads), the blocks of one colour run on all
  ///     threads, and each block runs in index order.
  /// Index order suits the short focused passes of the turns better than
  /// colour order (a Gauss-Seidel sweep in index order carries a move on to
  /// the neighbours visited next, where colour order scatters the visits
  /// and the turns stall sooner); blocks keep index order but for the few
  /// vertices where two blocks meet.
  enum class Visit_order { index, colours, index_blocks };
  Visit_order order = Visit_order::colours;
  /// the vertices per block of `Visit_order::index_blocks`
  std::size_t block_size = 256;
};

struct Asj_smoothing_report
{
  double asj_before = 0., asj_after = 0.;
  double msj_before = 0., msj_after = 0.;
  int passes = 0;
  std::size_t accepted_moves = 0;
  double seconds = 0.; ///< wall-clock time
};

namespace asj_detail {

/// the 9 Verdict samples of a hex (8 corners, then the centre)
inline void all_samples(const std::array<Vec3, 8>& p, double s[9]) { hex_samples(p, s); }

inline double exact_minimum(const double s[9])
{
  double m = s[0];
  for(int i = 1; i < 9; ++i) m = (std::min)(m, s[i]);
  return m;
}

/// exp(-d) for d >= 0, to a relative 7e-10 (d < 40; 0 beyond): the soft
/// minima take 9 of them per hex and per trial, which puts libm's exp on the
/// hot path. exp(-d) = 2^(-n/8) exp(-f) with n = floor(8 d / ln 2) and
/// f = d - n ln 2 / 8 in [0, 0.087): a table for the first factor, the
/// Taylor series to f^5 / 5! for the second (short, because f is small: a
/// series on the whole [0, ln 2) needs more terms for less accuracy).
inline double exp_minus(double d)
{
  if(!(d < 40.)) return 0.;
  const double y = d * (8. * 1.4426950408889634);
  const int n = int(y); // at most 461
  const double f = (y - n) * (0.6931471805599453 / 8.);
  const double e = 1. - f * (1. - f * (0.5 - f * (1. / 6. - f * (1. / 24. - f * (1. / 120.)))));
  static const std::array<double, 462> power = [] {
    std::array<double, 462> t;
    for(int i = 0; i < 462; ++i) t[i] = std::exp2(-i / 8.);
    return t;
  }();
  return e * power[n];
}

/// m - log(Σ exp(-k (s_i - m))) / k with m the minimum; the minimum when k = 0
inline double soft_minimum(const double s[9], double k)
{
  const double m = exact_minimum(s);
  if(!(k > 0.)) return m;
  double sum = 0.;
  for(int i = 0; i < 9; ++i) sum += exp_minus(k * (s[i] - m));
  return m - std::log(sum) / k;
}

/// Gradient, with respect to corner c, of the soft minimum (sharpness k) of
/// the hex's 9 samples `s` (already computed for the corners `p`).
inline Vec3 soft_minimum_gradient(const std::array<Vec3, 8>& p, int c, const double s[9], double k)
{
  const double m = exact_minimum(s);
  double wsum = 0.;
  for(int i = 0; i < 9; ++i) wsum += exp_minus(k * (s[i] - m));
  Vec3 r{0., 0., 0.};
  const int* dep = corner_samples_of_corner(c);
  for(int j = 0; j < 5; ++j)
  {
    const int i = j < 4 ? dep[j] : 8;
    const double d = k * (s[i] - m);
    if(d >= 40.) continue;
    r = r + (exp_minus(d) / wsum) * hex_sample_gradient(p, i, c, s[i]);
  }
  return r;
}

/// Where corner c of the hex p sits in the best-fitting cuboid: centre and
/// principal axes of the hex, the axes made orthonormal (polar decomposition
/// by Newton iteration), each keeping its length.
inline Vec3 cuboid_corner(const std::array<Vec3, 8>& p, int c)
{
  Vec3 centre{0., 0., 0.};
  for(int i = 0; i < 8; ++i) centre = centre + p[i];
  centre = 0.125 * centre;
  Vec3 a[3];
  principal_axes(p, a[0], a[1], a[2]);
  double len[3];
  Vec3 r[3];
  for(int k = 0; k < 3; ++k)
  {
    len[k] = 0.125 * norm(a[k]); // half extent
    if(!(len[k] > 0.)) return p[c];
    r[k] = (0.125 / len[k]) * a[k];
  }
  // R <- (R + R^-T) / 2; the columns of R^-T are (r1 x r2, r2 x r0, r0 x r1) / det R
  for(int it = 0; it < 10; ++it)
  {
    const Vec3 c0 = cross(r[1], r[2]), c1 = cross(r[2], r[0]), c2 = cross(r[0], r[1]);
    const double det = dot(r[0], c0);
    if(!(det > 1e-12)) return p[c];
    const double id = 1. / det;
    const Vec3 n0 = 0.5 * (r[0] + id * c0), n1 = 0.5 * (r[1] + id * c1), n2 = 0.5 * (r[2] + id * c2);
    const double change = squared_norm(n0 - r[0]) + squared_norm(n1 - r[1]) + squared_norm(n2 - r[2]);
    r[0] = n0; r[1] = n1; r[2] = n2;
    if(change < 1e-16) break;
  }
  return centre + (hex_axis_sign(c, 0) * len[0]) * r[0] + (hex_axis_sign(c, 1) * len[1]) * r[1]
                + (hex_axis_sign(c, 2) * len[2]) * r[2];
}

/// closest point to p on segment [a, b]
inline Vec3 closest_on_segment(const Vec3& p, const Vec3& a, const Vec3& b)
{
  const Vec3 ab = b - a;
  const double l = squared_norm(ab);
  double t = l > 0. ? dot(p - a, ab) / l : 0.;
  t = (std::max)(0., (std::min)(1., t));
  return a + t * ab;
}

/// squared distance from p to triangle abc (Ericson, Real-Time Collision
/// Detection, 5.1.5)
inline double squared_distance_to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c)
{
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if(d1 <= 0. && d2 <= 0.) return squared_norm(ap);
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if(d3 >= 0. && d4 <= d3) return squared_norm(bp);
  const double vc = d1 * d4 - d3 * d2;
  if(vc <= 0. && d1 >= 0. && d3 <= 0.) return squared_norm(ap - (d1 / (d1 - d3)) * ab);
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if(d6 >= 0. && d5 <= d6) return squared_norm(cp);
  const double vb = d5 * d2 - d1 * d6;
  if(vb <= 0. && d2 >= 0. && d6 <= 0.) return squared_norm(ap - (d2 / (d2 - d6)) * ac);
  const double va = d3 * d6 - d5 * d4;
  if(va <= 0. && d4 - d3 >= 0. && d5 - d6 >= 0.)
    return squared_norm(bp - ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b));
  const double sum = va + vb + vc;
  if(!(sum > 0.)) // degenerate triangle
    return (std::min)(squared_norm(ap), (std::min)(squared_norm(bp), squared_norm(cp)));
  return squared_norm(ap - (vb / sum) * ab - (vc / sum) * ac);
}

/// squared distance from p to the quad abcd cut along its (a, c) diagonal
inline double squared_distance_to_quad(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
  return (std::min)(squared_distance_to_triangle(p, a, b, c), squared_distance_to_triangle(p, a, c, d));
}

} // namespace asj_detail

class Asj_smoother
{
  typedef Hex_mesh_topology::Corner Corner;
  enum Kind : unsigned char { FREE = 0, ON_SURFACE, ON_LINE, FIXED };

public:
  Asj_smoother(const Hex_mesh_topology& topo, const Target_surface* target, std::vector<Vec3>& points,
               const Asj_smoothing_settings& s)
    : m_topo(topo), m_target(target), m_p(points), m_s(s)
  {
    CGAL_precondition(points.size() == topo.number_of_vertices());
    CGAL_precondition(target == nullptr || target->number_of_vertices() == topo.number_of_vertices());
    classify_vertices();
    m_check_surface = checks_surface(s);
    if(m_check_surface)
      collect_deviation_rings();
    else
      m_ring_off.assign(topo.number_of_vertices() + 1, 0);
    order_vertices();
    start_from_current_positions();
  }

  /// Makes the next `run()` a new smoothing from the current positions with
  /// the settings `s`, keeping what depends only on the mesh and on the
  /// choices below (the vertex classes, the rings of the built-in deviation
  /// test, the visit order and its colours): the turns of the quality
  /// improver run one focused pass after another, each with its own floor,
  /// budget and focus. `s` must agree with the constructor's settings on
  /// `move_boundary`, `order` and `block_size`, and check the surface if
  /// those did.
  void restart(const Asj_smoothing_settings& s)
  {
    CGAL_precondition(s.move_boundary == m_s.move_boundary && s.order == m_s.order && s.block_size == m_s.block_size);
    CGAL_precondition(!checks_surface(s) || m_check_surface);
    m_s = s;
    m_check_surface = checks_surface(s);
    start_from_current_positions();
  }

  Asj_smoothing_report run()
  {
    const auto start = std::chrono::steady_clock::now();
    auto elapsed = [start] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    Asj_smoothing_report rep;
    const std::size_t nv = m_topo.number_of_vertices(), nh = m_topo.number_of_hexes();
    if(nh == 0) return rep;
    double sum = 0., msj = std::numeric_limits<double>::max();
    for(double x : m_sj) { sum += x; msj = (std::min)(msj, x); }
    rep.asj_before = sum / double(nh);
    rep.msj_before = msj;

    std::vector<unsigned char> active = initial_active_set(), next(nv, 0), moved(nv, 0);
    double asj = rep.asj_before;
    m_kappa = m_s.objective_sharpness > 0. ? (std::min)(m_s.initial_objective_sharpness, m_s.objective_sharpness) : 0.;
    for(int pass = 0; pass < m_s.max_passes; ++pass)
    {
      if(pass > 0 && m_kappa > 0. && m_kappa < m_s.objective_sharpness)
      {
        m_kappa = (std::min)(m_kappa * m_s.sharpness_growth, m_s.objective_sharpness);
        std::fill(active.begin(), active.end(), 1); // the objective changed everywhere
        for(std::size_t v = 0; v < nv; ++v) if(m_kind[v] == FIXED) active[v] = 0;
      }
      parallel_for_each_index(nh, [&](std::size_t h) { m_value[h] = asj_detail::soft_minimum(&m_samples[9 * h], m_kappa); }, 1024);
      if(time_limit_reached(m_s.time_limit)) break;
      ++rep.passes;
      // one colour at a time, its vertices in parallel (a pass over a large
      // mesh is long: the clock is read within it too)
      std::fill(moved.begin(), moved.end(), 0);
      std::atomic<bool> out_of_time(false);
      for(std::size_t colour = 0; colour < m_colours.size(); ++colour)
      {
        if(out_of_time) break;
        for_each_vertex(colour, [&](std::size_t v) {
          if(!active[v] || out_of_time.load(std::memory_order_relaxed)) return;
          // 1: moved, 2: moved enough to make the vertices around it active
          const double gain = optimize_vertex(v);
          if(gain > 0.) moved[v] = gain > m_s.min_reactivating_gain ? 2 : 1;
          if(time_limit_reached(m_s.time_limit)) out_of_time = true;
        });
      }
      std::fill(next.begin(), next.end(), 0);
      for(std::size_t v = 0; v < nv; ++v)
      {
        if(!moved[v]) continue;
        ++rep.accepted_moves;
        if(moved[v] < 2) continue;
        for(const Corner* c = m_topo.vertex_corners_begin(v); c != m_topo.vertex_corners_end(v); ++c)
          for(std::size_t w : m_topo.hexes()[c->hex])
            if(m_kind[w] != FIXED) next[w] = 1;
      }
      active.swap(next);
      sum = 0.;
      for(double x : m_sj) sum += x;
      const double gain = sum / double(nh) - asj;
      asj = sum / double(nh);
      if(gain < m_s.min_asj_gain || out_of_time) break;
    }
    // recomputed from the positions (not from the samples kept up to date):
    // what the report says is what the mesh has
    std::vector<double> sj(nh);
    parallel_for_each_index(nh, [&](std::size_t h) { sj[h] = scaled_jacobian(corners(h)); }, 1024);
    sum = 0.; msj = std::numeric_limits<double>::max();
    for(double x : sj) { sum += x; msj = (std::min)(msj, x); }
    rep.asj_after = sum / double(nh);
    rep.msj_after = msj;
    rep.seconds = elapsed();
    return rep;
  }

private:
  // the vertices the first pass visits: every vertex that may move, or with
  // `focus_below`, those of the hexes below it and of one ring of hexes more
  std::vector<unsigned char> initial_active_set() const
  {
    const std::size_t nv = m_topo.number_of_vertices(), nh = m_topo.number_of_hexes();
    std::vector<unsigned char> active(nv, 1);
    if(std::isfinite(m_s.focus_below))
    {
      std::vector<unsigned char> below(nv, 0);
      std::fill(active.begin(), active.end(), 0);
      for(std::size_t h = 0; h < nh; ++h)
        if(m_sj[h] < m_s.focus_below)
          for(std::size_t w : m_topo.hexes()[h]) below[w] = 1;
      for(std::size_t v = 0; v < nv; ++v)
        if(below[v])
          for(const Corner* c = m_topo.vertex_corners_begin(v); c != m_topo.vertex_corners_end(v); ++c)
            for(std::size_t w : m_topo.hexes()[c->hex]) active[w] = 1;
    }
    for(std::size_t v = 0; v < nv; ++v) if(m_kind[v] == FIXED) active[v] = 0;
    return active;
  }

  // How each vertex may move: interior vertices freely, regular boundary
  // vertices on the surface, sharp ones along their feature line (with their
  // two neighbours on it), the others (corners, or every boundary vertex
  // without a target surface) not at all.
  void classify_vertices()
  {
    const std::size_t nv = m_topo.number_of_vertices();
    const bool boundary_moves = m_target != nullptr && m_s.move_boundary;
    m_kind.assign(nv, FREE);
    for(std::size_t v = 0; v < nv; ++v)
    {
      if(m_topo.is_constrained(v)) { m_kind[v] = FIXED; continue; } // the user's constrained vertices
      if(!m_topo.is_boundary_vertex(v)) continue;
      m_kind[v] = FIXED;
      if(boundary_moves && m_target->vertex_class(v) == Vertex_class::regular) m_kind[v] = ON_SURFACE;
    }
    m_line.assign(nv, {nv, nv});
    if(!boundary_moves) return;
    for(const Target_surface::Feature_line& l : m_target->feature_lines())
    {
      const std::size_t n = l.vertices.size();
      for(std::size_t j = 0; j < n; ++j)
      {
        if(!l.closed && (j == 0 || j + 1 == n)) continue;
        const std::size_t v = m_target->boundary().vertices[l.vertices[j]];
        if(m_target->vertex_class(v) != Vertex_class::sharp || !m_topo.is_boundary_vertex(v) ||
           m_topo.is_constrained(v)) continue;
        m_line[v] = {m_target->boundary().vertices[l.vertices[(j + n - 1) % n]],
                     m_target->boundary().vertices[l.vertices[(j + 1) % n]]};
        m_kind[v] = ON_LINE;
      }
    }
  }

  // for the built-in deviation test: the boundary quads within two rings of
  // each moving boundary vertex, its own first
  void collect_deviation_rings()
  {
    const std::size_t nv = m_topo.number_of_vertices();
    const auto& bf = m_topo.boundary_faces();
    m_ring_off.assign(nv + 1, 0);
    std::vector<std::size_t> ring;
    for(std::size_t v = 0; v < nv; ++v)
    {
      if(m_kind[v] == ON_SURFACE || m_kind[v] == ON_LINE)
      {
        const std::size_t first = ring.size();
        ring.insert(ring.end(), m_topo.vertex_boundary_faces_begin(v), m_topo.vertex_boundary_faces_end(v));
        for(const std::size_t* k = m_topo.vertex_boundary_faces_begin(v); k != m_topo.vertex_boundary_faces_end(v); ++k)
          for(std::size_t u : bf[*k])
            for(const std::size_t* j = m_topo.vertex_boundary_faces_begin(u); j != m_topo.vertex_boundary_faces_end(u); ++j)
              if(std::find(ring.begin() + first, ring.end(), *j) == ring.end()) ring.push_back(*j);
      }
      m_ring_off[v + 1] = ring.size();
    }
    m_ring.swap(ring);
  }

  bool checks_surface(const Asj_smoothing_settings& s) const
  {
    return m_target != nullptr && s.move_boundary && std::isfinite(s.max_surface_deviation);
  }

  // what a run starts from: the boundary it received (for the built-in
  // deviation test), the samples of every hex, the step lengths
  void start_from_current_positions()
  {
    m_start = m_p;
    compute_samples();
    m_step.assign(m_topo.number_of_vertices(), 0.1);
  }

  // the 9 samples, the scaled Jacobian and the floor of every hex, and the
  // size of the per-thread trial buffer (9 samples per hex around a vertex)
  void compute_samples()
  {
    const std::size_t nv = m_topo.number_of_vertices(), nh = m_topo.number_of_hexes();
    m_samples.resize(9 * nh);
    m_sj.resize(nh);
    m_floor.resize(nh);
    m_value.resize(nh);
    parallel_for_each_index(nh, [&](std::size_t h) {
      asj_detail::all_samples(corners(h), &m_samples[9 * h]);
      m_sj[h] = asj_detail::exact_minimum(&m_samples[9 * h]);
      m_floor[h] = element_floor(m_s.min_sj_floor, m_sj[h]);
    }, 1024);
    std::size_t maxdeg = 0;
    for(std::size_t v = 0; v < nv; ++v)
      maxdeg = (std::max)(maxdeg, std::size_t(m_topo.vertex_corners_end(v) - m_topo.vertex_corners_begin(v)));
    m_trial_size = 9 * maxdeg;
  }

  std::array<Vec3, 8> corners(std::size_t h) const
  {
    std::array<Vec3, 8> c;
    const Hex& hx = m_topo.hexes()[h];
    for(int i = 0; i < 8; ++i) c[i] = m_p[hx[i]];
    return c;
  }

  // f(v) for each vertex of one colour (`Visit_order::colours`: on the TBB
  // threads, a colour's vertices moving independently) or of the blocks of
  // one colour (`Visit_order::index_blocks`: the blocks on the TBB threads,
  // each in index order); for `Visit_order::index`, the one colour is every
  // vertex in index order
  template <class F>
  void for_each_vertex(std::size_t colour, F f) const
  {
    const std::vector<std::size_t>& members = m_colours[colour];
    if(m_order == Asj_smoothing_settings::Visit_order::index_blocks)
      parallel_for_each_index(members.size(), [&](std::size_t i) {
        const std::size_t b = members[i];
        for(std::size_t k = m_block_begin[b]; k < m_block_begin[b + 1]; ++k) f(m_movable[k]);
      });
    else if(m_order == Asj_smoothing_settings::Visit_order::colours && m_colours.size() > 1)
      parallel_for_each_index(members.size(), [&](std::size_t i) { f(members[i]); }, 64);
    else
      for(std::size_t v : members) f(v);
  }

  // scratch for the samples of the hexes around the vertex being moved, one
  // per thread
  double* trial_buffer() const
  {
    thread_local std::vector<double> buffer;
    if(buffer.size() < m_trial_size) buffer.resize(m_trial_size);
    return buffer.data();
  }

  // The order of a pass (`Asj_smoothing_settings::order`): `m_colours` holds
  // the vertices of each colour, or (`index_blocks`) the blocks of each
  // colour, block b being m_movable[m_block_begin[b] .. m_block_begin[b + 1]).
  void order_vertices()
  {
    const std::size_t nv = m_topo.number_of_vertices();
    for(std::size_t v = 0; v < nv; ++v)
      if(m_kind[v] != FIXED) m_movable.push_back(v);
    typedef Asj_smoothing_settings::Visit_order Order;
    m_order = m_s.order;
#ifndef CGAL_LINKED_WITH_TBB
    m_order = Order::index; // nothing to run in parallel
#endif
    const Order order = m_order;
    if(order == Order::index)
    {
      m_colours.assign(1, m_movable);
      return;
    }
    // the units coloured: single vertices, or blocks of vertices close in
    // space (cut from the Morton order of their positions), each block in
    // index order
    const std::size_t size = order == Order::colours ? 1 : (std::max<std::size_t>)(m_s.block_size, 1);
    if(order == Order::index_blocks) sort_into_blocks(size);
    const std::size_t none = std::numeric_limits<std::size_t>::max();
    std::vector<std::size_t> unit_of(nv, none);
    for(std::size_t k = 0; k < m_movable.size(); ++k) unit_of[m_movable[k]] = k / size;
    const std::size_t units = (m_movable.size() + size - 1) / size;
    m_block_begin.clear();
    for(std::size_t u = 0; u <= units; ++u) m_block_begin.push_back((std::min)(u * size, m_movable.size()));
    colour_units(unit_of, units);
    if(order == Order::colours) // a unit is a vertex
      for(std::vector<std::size_t>& c : m_colours)
        for(std::size_t& u : c) u = m_movable[u];
  }

  // Reorders `m_movable` into blocks of `size` vertices close in space: the
  // vertices sorted by the Morton code of their position in the bounding box
  // (ties by index), cut into blocks, each block sorted back by index.
  void sort_into_blocks(std::size_t size)
  {
    Vec3 lo = m_p[m_movable.empty() ? 0 : m_movable[0]], hi = lo;
    for(std::size_t v : m_movable)
      for(int k = 0; k < 3; ++k) { lo[k] = (std::min)(lo[k], m_p[v][k]); hi[k] = (std::max)(hi[k], m_p[v][k]); }
    auto spread = [](std::uint64_t x) { // the 21 bits of x, two zero bits between each
      x &= 0x1fffff;
      x = (x | x << 32) & 0x1f00000000ffffULL;
      x = (x | x << 16) & 0x1f0000ff0000ffULL;
      x = (x | x << 8) & 0x100f00f00f00f00fULL;
      x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
      x = (x | x << 2) & 0x1249249249249249ULL;
      return x;
    };
    std::vector<std::pair<std::uint64_t, std::size_t> > keyed;
    keyed.reserve(m_movable.size());
    for(std::size_t v : m_movable)
    {
      std::uint64_t code = 0;
      for(int k = 0; k < 3; ++k)
      {
        const double t = hi[k] > lo[k] ? (m_p[v][k] - lo[k]) / (hi[k] - lo[k]) : 0.;
        code |= spread(std::uint64_t(t * double(0x1fffff))) << k;
      }
      keyed.push_back({code, v});
    }
    std::sort(keyed.begin(), keyed.end());
    for(std::size_t k = 0; k < keyed.size(); ++k) m_movable[k] = keyed[k].second;
    for(std::size_t b = 0; b < m_movable.size(); b += size)
      std::sort(m_movable.begin() + b, m_movable.begin() + (std::min)(b + size, m_movable.size()));
  }

  // Greedy colouring, in unit order, of the units (vertices or blocks) so
  // that two units of one colour can run at the same time: no vertex of one
  // shares a hex with a vertex of the other (a move reads and writes the
  // hexes around its vertex only) and, when both move on the boundary,
  // neither is a vertex of a boundary quad around a quad neighbour of the
  // other (the surface tests read the quads two rings out).
  void colour_units(const std::vector<std::size_t>& unit_of, std::size_t units)
  {
    const std::size_t none = std::numeric_limits<std::size_t>::max();
    std::vector<std::size_t> colour(units, none), stamp, near, ring;
    for(std::size_t u = 0; u < units; ++u)
    {
      near.clear();
      for(std::size_t k = m_block_begin[u]; k < m_block_begin[u + 1]; ++k)
      {
        const std::size_t v = m_movable[k];
        for(const Corner* c = m_topo.vertex_corners_begin(v); c != m_topo.vertex_corners_end(v); ++c)
          for(std::size_t w : m_topo.hexes()[c->hex]) near.push_back(unit_of[w]);
        if(m_kind[v] != FREE)
        {
          ring.clear();
          m_topo.append_two_ring_boundary_vertices(v, ring);
          for(std::size_t w : ring) near.push_back(unit_of[w]);
        }
      }
      // smallest colour not used by a coloured unit near u
      for(std::size_t w : near)
        if(w != none && w != u && colour[w] != none)
        {
          if(stamp.size() <= colour[w]) stamp.resize(colour[w] + 1, none);
          stamp[colour[w]] = u;
        }
      std::size_t k = 0;
      while(k < stamp.size() && stamp[k] == u) ++k;
      colour[u] = k;
      if(m_colours.size() <= k) m_colours.resize(k + 1);
      m_colours[k].push_back(u);
    }
  }

  // The hexes around the vertex being visited, as the trials see them: the
  // 5 samples that move with the vertex (`Corner_dependent_samples`), and
  // the minimum m0 of the 4 that do not and their part of the soft
  // minimum's sum, Σ exp(-κ (s_i - m0)). One per thread, set up by
  // `prepare_visit` (a visit moves only its vertex: they stay valid).
  struct Hex_in_visit
  {
    Corner_dependent_samples frames;
    double fixed_min, fixed_sum;
  };

  std::vector<Hex_in_visit>& visit_buffer() const
  {
    thread_local std::vector<Hex_in_visit> buffer;
    return buffer;
  }

  void prepare_visit(std::size_t v)
  {
    std::vector<Hex_in_visit>& around = visit_buffer();
    around.resize(std::size_t(m_topo.vertex_corners_end(v) - m_topo.vertex_corners_begin(v)));
    std::size_t k = 0;
    for(const Corner* c = m_topo.vertex_corners_begin(v); c != m_topo.vertex_corners_end(v); ++c, ++k)
    {
      Hex_in_visit& a = around[k];
      a.frames.set(corners(c->hex), c->local);
      const double* s = &m_samples[9 * c->hex];
      const int* dep = corner_samples_of_corner(c->local);
      bool moves[8] = {false, false, false, false, false, false, false, false};
      for(int j = 0; j < 4; ++j) moves[dep[j]] = true;
      a.fixed_min = std::numeric_limits<double>::max();
      for(int i = 0; i < 8; ++i) if(!moves[i]) a.fixed_min = (std::min)(a.fixed_min, s[i]);
      a.fixed_sum = 0.;
      for(int i = 0; i < 8; ++i) if(!moves[i]) a.fixed_sum += asj_detail::exp_minus(m_kappa * (s[i] - a.fixed_min));
    }
  }

  // The objective F_v with v at x (Σ over the hexes around v of the soft
  // minimum of their samples: Σ q_h - log(Π_h sum_h) / κ, one logarithm),
  // or -infinity when a hex falls below its floor; the 5 samples of each
  // hex that moved are left in this thread's `trial_buffer()`. Needs
  // `prepare_visit(v)`.
  double evaluate(std::size_t v, const Vec3& x)
  {
    const std::vector<Hex_in_visit>& around = visit_buffer();
    double* trial = trial_buffer();
    double f = 0., product = 1.;
    std::size_t k = 0;
    for(const Corner* c = m_topo.vertex_corners_begin(v); c != m_topo.vertex_corners_end(v); ++c, ++k)
    {
      const Hex_in_visit& a = around[k];
      double* s = trial + 5 * k;
      a.frames.evaluate(x, s);
      double q = a.fixed_min;
      for(int j = 0; j < 5; ++j) q = (std::min)(q, s[j]);
      if(!(q >= m_floor[c->hex])) return -std::numeric_limits<double>::infinity();
      f += q;
      if(m_kappa > 0.)
      {
        double sum = a.fixed_sum * asj_detail::exp_minus(m_kappa * (a.fixed_min - q));
        for(int j = 0; j < 5; ++j) sum += asj_detail::exp_minus(m_kappa * (s[j] - q));
        product *= sum;
      }
    }
    return m_kappa > 0. ? f - std::log(product) / m_kappa : f;
  }

  double current_value(std::size_t v) const
  {
    double f = 0.;
    for(const Corner* c = m_topo.vertex_corners_begin(v); c != m_topo.vertex_corners_end(v); ++c)
      f += m_value[c->hex];
    return f;
  }

  void commit(std::size_t v, const Vec3& x)
  {
    const double* trial = trial_buffer();
    m_p[v] = x;
    std::size_t k = 0;
    for(const Corner* c = m_topo.vertex_corners_begin(v); c != m_topo.vertex_corners_end(v); ++c, ++k)
    {
      double* s = &m_samples[9 * c->hex];
      const int* dep = corner_samples_of_corner(c->local);
      for(int j = 0; j < 4; ++j) s[dep[j]] = trial[5 * k + j];
      s[8] = trial[5 * k + 4];
      m_sj[c->hex] = asj_detail::exact_minimum(s);
      m_value[c->hex] = asj_detail::soft_minimum(s, m_kappa);
    }
  }

  // the position reached from the current one by displacement d, within the
  // vertex's freedom (`normal`: the reference normal of a regular vertex)
  Vec3 candidate(std::size_t v, const Vec3& d, const Vec3& normal) const
  {
    switch(m_kind[v])
    {
    case ON_SURFACE:
      return m_target->constraint_at(v, m_p[v] + (d - dot(d, normal) * normal)).anchor;
    case ON_LINE:
    {
      // each sharp vertex keeps to its own part of the segments, at most
      // `max_slide` of the way to a neighbour's start: two neighbours on a
      // line stay at least 1 - 2 × max_slide of their start edge apart (with
      // the whole segment allowed a vertex can slide onto its neighbour: a
      // vanished edge)
      const double max_slide = 0.45;
      const Vec3 y = m_p[v] + d;
      const Vec3& o = m_start[v];
      const Vec3 a = asj_detail::closest_on_segment(y, o, o + max_slide * (m_start[m_line[v][0]] - o));
      const Vec3 b = asj_detail::closest_on_segment(y, o, o + max_slide * (m_start[m_line[v][1]] - o));
      return squared_norm(a - y) <= squared_norm(b - y) ? a : b;
    }
    default:
      return m_p[v] + d;
    }
  }

  // Built-in deviation test, against the boundary as the stage received it
  // (its error to the reference is the previous stages'): with v at x,
  //   - the midpoints of the quad edges at v, the centroids of the (0, 2)
  //     triangles containing v and the (0, 2) diagonal's midpoint when it
  //     ends at v are within `max_surface_deviation` of the start boundary
  //     quads within two rings of v (further ones are not looked at, so the
  //     test is conservative);
  //   - the start positions of v and of the vertices of its quads are within
  //     it of their quads (the start boundary stays covered).
  bool near_start(std::size_t v, const Vec3& p, double tol2) const
  {
    const auto& bf = m_topo.boundary_faces();
    for(std::size_t k = m_ring_off[v]; k < m_ring_off[v + 1]; ++k)
    {
      const auto& q = bf[m_ring[k]];
      if(asj_detail::squared_distance_to_quad(p, m_start[q[0]], m_start[q[1]], m_start[q[2]], m_start[q[3]]) <= tol2)
        return true;
    }
    return false;
  }

  bool covered(std::size_t u, std::size_t v, const Vec3& x, double tol2) const
  {
    const auto& bf = m_topo.boundary_faces();
    for(const std::size_t* k = m_topo.vertex_boundary_faces_begin(u); k != m_topo.vertex_boundary_faces_end(u); ++k)
    {
      const auto& q = bf[*k];
      const Vec3* c[4];
      for(int i = 0; i < 4; ++i) c[i] = q[i] == v ? &x : &m_p[q[i]];
      if(asj_detail::squared_distance_to_quad(m_start[u], *c[0], *c[1], *c[2], *c[3]) <= tol2)
        return true;
    }
    return false;
  }

  bool builtin_surface_test(std::size_t v, const Vec3& x, double tolerance) const
  {
    const double tol2 = tolerance * tolerance;
    const auto& bf = m_topo.boundary_faces();
    for(const std::size_t* k = m_topo.vertex_boundary_faces_begin(v); k != m_topo.vertex_boundary_faces_end(v); ++k)
    {
      const auto& q = bf[*k];
      std::array<Vec3, 4> c;
      int at = 0;
      for(int i = 0; i < 4; ++i)
      {
        c[i] = q[i] == v ? x : m_p[q[i]];
        if(q[i] == v) at = i;
      }
      // each edge at v is the "next" edge of one of its quads
      if(!near_start(v, 0.5 * (c[at] + c[(at + 1) % 4]), tol2)) return false;
      if(at != 3 && !near_start(v, (1. / 3.) * (c[0] + c[1] + c[2]), tol2)) return false;
      if(at != 1 && !near_start(v, (1. / 3.) * (c[0] + c[2] + c[3]), tol2)) return false;
      if((at == 0 || at == 2) && !near_start(v, 0.5 * (c[0] + c[2]), tol2)) return false;
    }
    if(!covered(v, v, x, tol2)) return false;
    for(const std::size_t* k = m_topo.vertex_boundary_faces_begin(v); k != m_topo.vertex_boundary_faces_end(v); ++k)
      for(std::size_t u : bf[*k])
        if(u != v && !covered(u, v, x, tol2)) return false;
    return true;
  }

  // whether v may move to x as far as the surface is concerned; `allowed`
  // caches the user measure's bound for the current visit (< 0: not yet)
  bool surface_test(std::size_t v, const Vec3& x, Surface_deviation& allowed) const
  {
    if(!m_check_surface || m_kind[v] == FREE) return true;
    if(!m_s.guard) return builtin_surface_test(v, x, m_s.max_surface_deviation);
    if(m_s.start_deviation_budget > 0. && builtin_surface_test(v, x, m_s.start_deviation_budget)) return true;
    if(allowed.to_reference < 0.) allowed = m_s.guard->bound_at(m_p, v, m_p[v], m_s.max_surface_deviation);
    return m_s.guard->allows(m_p, v, x, allowed);
  }

  // Backtracking along d: t = 1, 1/2, ... Returns the number of halvings of
  // the accepted step, or -1.
  int line_search(std::size_t v, const Vec3& d, const Vec3& normal, double& current, Surface_deviation& allowed)
  {
    double t = 1.;
    for(int halvings = 0; halvings <= m_s.max_halvings; ++halvings, t *= 0.5)
    {
      const Vec3 x = candidate(v, t * d, normal);
      const double f = evaluate(v, x);
      if(!(f > current + m_s.min_move_gain)) continue;
      if(!surface_test(v, x, allowed)) continue;
      commit(v, x);
      current = f;
      return halvings;
    }
    return -1;
  }

  // one visit of v; returns how much its objective rose (0: v did not move)
  double optimize_vertex(std::size_t v)
  {
    const Corner* b = m_topo.vertex_corners_begin(v);
    const Corner* e = m_topo.vertex_corners_end(v);
    if(b == e) return false;
    Vec3 normal{0., 0., 0.};
    if(m_kind[v] == ON_SURFACE) normal = m_target->constraint_at(v, m_p[v]).direction;
    double current = current_value(v);
    const double start = current;
    Surface_deviation allowed{-1., -1.}; // computed when first needed
    bool moved = false;
    prepare_visit(v);

    if(m_s.cuboid_targets)
    {
      Vec3 t{0., 0., 0.};
      for(const Corner* c = b; c != e; ++c)
        t = t + asj_detail::cuboid_corner(corners(c->hex), c->local);
      t = (1. / double(e - b)) * t;
      if(line_search(v, t - m_p[v], normal, current, allowed) >= 0)
      {
        moved = true;
        if(m_kind[v] == ON_SURFACE) normal = m_target->constraint_at(v, m_p[v]).direction;
      }
    }

    if(m_s.gradient_steps > 0)
    {
      // mean length of the edges at v: the unit of a step
      double len = 0.;
      int n = 0;
      for(const Corner* c = b; c != e; ++c)
        for(int k = 0; k < 3; ++k, ++n)
          len += norm(m_p[m_topo.hexes()[c->hex][hex_corner_edges[c->local][k]]] - m_p[v]);
      len /= double(n);
      for(int it = 0; it < m_s.gradient_steps; ++it)
      {
        Vec3 g{0., 0., 0.};
        for(const Corner* c = b; c != e; ++c)
          g = g + asj_detail::soft_minimum_gradient(corners(c->hex), c->local, &m_samples[9 * c->hex],
                                                    m_s.gradient_sharpness);
        if(m_kind[v] == ON_SURFACE) g = g - dot(g, normal) * normal;
        else if(m_kind[v] == ON_LINE)
        {
          const Vec3 tangent = normalized(m_start[m_line[v][1]] - m_start[m_line[v][0]]);
          g = dot(g, tangent) * tangent;
        }
        const double gn = norm(g);
        if(!(gn > 0.)) break;
        const int halvings = line_search(v, (m_step[v] * len / gn) * g, normal, current, allowed);
        if(halvings < 0)
        {
          m_step[v] = (std::max)(m_step[v] * std::pow(0.5, m_s.max_halvings + 1), 1e-3);
          break;
        }
        moved = true;
        m_step[v] = halvings == 0 ? (std::min)(1.5 * m_step[v], 0.5) : m_step[v] * std::pow(0.5, halvings);
        if(m_kind[v] == ON_SURFACE) normal = m_target->constraint_at(v, m_p[v]).direction;
      }
    }
    return moved ? current - start : 0.;
  }

  const Hex_mesh_topology& m_topo;
  const Target_surface* m_target;
  std::vector<Vec3>& m_p;
  Asj_smoothing_settings m_s;
  std::vector<Vec3> m_start;
  std::vector<unsigned char> m_kind;
  std::vector<std::array<std::size_t, 2> > m_line;
  std::vector<std::size_t> m_ring_off, m_ring;
  bool m_check_surface = false;
  double m_kappa = 0.; // current sharpness of the objective
  std::vector<double> m_samples, m_sj, m_floor, m_value, m_step;
  std::size_t m_trial_size = 0;
  // Gauss-Seidel order (see `order_vertices`): the order in effect (index
  // order without TBB), the vertices that may move, and the vertices, or
  // blocks of them, of each colour
  Asj_smoothing_settings::Visit_order m_order = Asj_smoothing_settings::Visit_order::index;
  std::vector<std::size_t> m_movable, m_block_begin;
  std::vector<std::vector<std::size_t> > m_colours;
};

/// Raises the average scaled Jacobian of a valid mesh in place (see the top
/// of this file). `target` may be null: the boundary is then fixed.
inline Asj_smoothing_report smooth_for_average_quality(const Hex_mesh_topology& topo,
                                                       const Target_surface* target,
                                                       std::vector<Vec3>& points,
                                                       const Asj_smoothing_settings& settings)
{
  Asj_smoother s(topo, target, points, settings);
  return s.run();
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SMOOTHING_ASJ_SMOOTHING_H
