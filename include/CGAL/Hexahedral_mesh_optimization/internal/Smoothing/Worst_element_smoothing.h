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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SMOOTHING_WORST_ELEMENT_SMOOTHING_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SMOOTHING_WORST_ELEMENT_SMOOTHING_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Max-min vertex smoothing of the worst elements: the second half of every
// MSJ stage (Section 3.4 runs the edge-angle optimiser with a positive target;
// what that leaves below the target is handled here).
//
// The edge-angle energy is a least-squares energy: it makes most angles
// right but it does not maximise the worst scaled Jacobian, and near the end
// of a stage it stalls on a handful of elements whose best shape is a
// compromise between neighbours. Here one vertex moves at a time to maximise
// the minimum of the scaled Jacobian samples (8 corners + centre) of the hexes
// around it, in the style of Freitag & Knupp's optimisation-based max-min
// smoothing:
//   - ascent direction: the gradient (analytic, the kernel's sample
//     gradients in scaled_jacobian.h) of a soft minimum
//     of the vertex's samples, s_min − (1/k) log Σ exp(−k (s − s_min)),
//     k = 60: the plain minimum has no gradient where two samples tie, which
//     is exactly where the optimum of a max-min problem sits;
//   - boundary vertices: without a surface guard, the direction is
//     restricted by the vertex's class (tangent plane of the reference for a
//     regular vertex, feature tangent for a sharp one, corners fixed) and the
//     vertex is projected onto its anchor after the move. With a guard
//     (Surface_guard.h), the guard is the constraint: the feature
//     classification at θ = 165° marks many spurious creases and corners on
//     coarse curved models, and a vertex held on a spurious feature line
//     fixes the worst angle of its hexes, which then bounds the MSJ. So a
//     move along the class is tried
//     first (sharp vertices), then a move in the tangent plane of the
//     reference projected back onto it, then a free move (it can cut a
//     180° boundary edge of a hex with two faces on a smooth surface, which
//     no sliding can fix); each only if the quads around the vertex stay
//     within the guard's tolerance of the reference. A real crease or
//     corner cannot move without the guard seeing the cut;
//   - backtracking from 0.3 × the vertex's mean edge length;
//   - a move is accepted only if the minimum over the hexes around the vertex
//     rises: no element ever falls below the smallest value it was compared
//     with, hence the mesh's MSJ never decreases and no element inverts.
// Sweeps visit the vertices of the elements below the current goal
// (min(target, MSJ + band)) worst first, until the MSJ stops rising. When a
// sweep stalls, the interior vertices of each element at the minimum move
// together (`improve_element`), then those of each cluster of elements near
// the minimum that share vertices (`improve_clusters`): single-vertex and
// single-element moves both stall where several elements at the minimum
// share vertices, each move lowering one of the others.
//
// Parallel and deterministic: a sweep cuts its worst-first list into
// batches of vertices that cannot see each other's moves (no shared hex; on
// the boundary, neither a vertex of a boundary quad within two rings of the
// other, which the surface tests read), each batch taken greedily from the
// first `batch_window` vertices not yet visited, in list order; the vertices
// of a batch move on all threads. A vertex left out waits for the next
// batch, so the visiting order depends on the mesh only, never on the
// number of threads, and stays close to worst first.

#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_topology.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Surface_guard.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Target_surface.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/Time_limit.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/parallel_for_each_index.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/scaled_jacobian.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <unordered_map>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

struct Worst_element_smoothing_settings
{
  double target_sj = 1.;          ///< elements at or above it are left alone
  double band = 0.05;             ///< also work on elements within `band` of the MSJ
  int max_sweeps = 200;
  int steps_per_vertex = 3;
  /// the run's hard stop (null: none), read between vertices
  const Time_limit* time_limit = nullptr;
  double min_gain = 1e-5;         ///< a sweep that raises the MSJ by less ends the run (after `patience` sweeps)
  int patience = 3;
  /// largest distance between the boundary around a moved vertex and the
  /// reference (mesh units); infinity disables the check
  double max_surface_deviation = std::numeric_limits<double>::infinity();
  /// with a guard, the guard is the boundary constraint (see the top)
  bool use_guard = true;
  /// when a sweep stalls, move the interior vertices of the worst elements
  /// together (see `improve_element`)
  bool element_moves = true;
  /// when the element moves stall too, move the interior vertices of each
  /// cluster of elements within `cluster_band` of the MSJ together, up to
  /// `cluster_steps` steps, clusters of 2 to `max_cluster_hexes` hexes (see
  /// `improve_clusters`)
  bool cluster_moves = true;
  double cluster_band = 0.005;
  int cluster_steps = 20;
  std::size_t max_cluster_hexes = 64;
  /// each batch of a sweep is taken from this many vertices at the head of
  /// the worst-first list (see the top)
  std::size_t batch_window = 256;
  /// skip the visits of settled vertices (see `m_settled`): the same moves
  /// either way; off only to test that
  bool skip_settled = true;
};

struct Worst_element_smoothing_report
{
  double msj_before = 0., msj_after = 0.;
  int sweeps = 0;
  std::size_t moves = 0;
  std::size_t skipped_visits = 0; ///< visits of settled vertices skipped
};

class Worst_element_smoothing
{
public:
  /// `target` may be null: the boundary is then frozen; `guard` may be null:
  /// no bound on the surface deviation
  Worst_element_smoothing(const Hex_mesh_topology& topo, const Target_surface* target,
                          const Surface_guard* guard = nullptr)
    : m_topo(topo), m_target(target), m_guard(guard)
  {}

  Worst_element_smoothing_report run(std::vector<Vec3>& points, const Worst_element_smoothing_settings& s)
  {
    m_max_deviation = (m_target && m_guard) ? s.max_surface_deviation : std::numeric_limits<double>::infinity();
    m_guarded = s.use_guard && m_guard && std::isfinite(m_max_deviation);
    const std::size_t nh = m_topo.number_of_hexes();
    std::vector<double> sj(nh);
    parallel_for_each_index(nh, [&](std::size_t h) { sj[h] = hex_sj(points, h); }, 1024);
    m_settled.assign(m_topo.number_of_vertices(), 0);
    Worst_element_smoothing_report rep;
    rep.msj_before = rep.msj_after = nh ? *std::min_element(sj.begin(), sj.end()) : 1.;
    std::vector<int> mark(m_topo.number_of_vertices(), -1);
    int idle = 0;
    for(int sweep = 0; sweep < s.max_sweeps; ++sweep)
    {
      if(time_limit_reached(s.time_limit)) break;
      const double msj = *std::min_element(sj.begin(), sj.end());
      if(msj >= s.target_sj) break;
      const double goal = (std::min)(s.target_sj, msj + s.band);
      // vertices of the elements below the goal, worst element first
      std::vector<std::pair<double, std::size_t> > order;
      for(std::size_t h = 0; h < nh; ++h)
        if(sj[h] < goal)
          for(std::size_t v : m_topo.hexes()[h])
            if(mark[v] != sweep) { mark[v] = sweep; order.push_back({vertex_min(points, v, sj), v}); }
      std::sort(order.begin(), order.end());
      ++rep.sweeps;
      rep.moves += sweep_in_batches(points, order, sj, s, rep.skipped_visits);
      double now = *std::min_element(sj.begin(), sj.end());
      if(now - msj < s.min_gain && s.element_moves)
      {
        // single-vertex moves have stalled: move the interior vertices of
        // each element at the minimum together (those below the target
        // only: near the end of a run MSJ + band / 2 can be above every
        // element, and moving all of them, one at a time, would cost a pass
        // over the whole mesh at every stall)
        std::vector<std::pair<double, std::size_t> > worst;
        const double below = (std::min)(now + 0.5 * s.band, s.target_sj);
        for(std::size_t h = 0; h < nh; ++h)
          if(sj[h] < below) worst.push_back({sj[h], h});
        std::sort(worst.begin(), worst.end());
        for(const auto& w : worst)
          if(!time_limit_reached(s.time_limit) && improve_element(points, w.second, sj))
          {
            ++rep.moves;
            for(std::size_t v : m_topo.hexes()[w.second]) if(!m_topo.is_boundary_vertex(v)) unsettle_around(v);
          }
        now = *std::min_element(sj.begin(), sj.end());
      }
      if(now - msj < s.min_gain && s.cluster_moves) now = improve_clusters(points, sj, now, s, rep.moves);
      idle = (now - msj < s.min_gain) ? idle + 1 : 0;
      rep.msj_after = now;
      if(idle >= s.patience) break;
    }
    return rep;
  }

  /// one max-min move (up to `steps` ascent steps) of each of `vertices`,
  /// in turn; returns the number of steps accepted
  std::size_t raise_vertices(std::vector<Vec3>& points, const std::vector<std::size_t>& vertices, int steps = 3)
  {
    m_guarded = false; // no boundary vertex is meant to move here
    std::vector<double> sj(m_topo.number_of_hexes(), 0.); // only written: the moves read the points
    std::size_t n = 0;
    for(std::size_t v : vertices) n += improve_vertex(points, v, sj, steps);
    return n;
  }

  /// how many hexes around v are inverted with v at x
  std::size_t inverted_around(const std::vector<Vec3>& points, std::size_t v, const Vec3& x) const
  {
    std::size_t n = 0;
    for(auto c = m_topo.vertex_corners_begin(v); c != m_topo.vertex_corners_end(v); ++c)
    {
      std::array<Vec3, 8> p = corners(points, c->hex);
      p[c->local] = x;
      if(is_inverted(scaled_jacobian(p))) ++n;
    }
    return n;
  }

  /// whether v may move from where it is to x as far as quality goes: the
  /// minimum around v stays at or above `element_floor(floor, its minimum
  /// now)` (`now`), and, when a hex around v is inverted, no more are
  bool keeps_floor(const std::vector<Vec3>& points, std::size_t v, const Vec3& x, double floor, double now) const
  {
    // (written so that a NaN fails, as a zero-length edge would give)
    if(!(local_minimum(points, v, x) >= element_floor(floor, now))) return false;
    return !is_inverted(now) || inverted_around(points, v, x) <= inverted_around(points, v, points[v]);
  }

  /// the minimum scaled Jacobian of the hexes around `v` with `v` at `x`
  double local_minimum(const std::vector<Vec3>& points, std::size_t v, const Vec3& x) const
  {
    return min_scaled_jacobian_around(m_topo, points, v, x);
  }

  /// Element moves stall where the elements at the minimum form a cluster
  /// (sharing vertices) that only a joint move raises: the hexes within
  /// `cluster_band` of the MSJ `msj`, connected through their interior
  /// vertices, clusters of at most `max_cluster_hexes`, each gets up to
  /// `cluster_steps` joint steps of all its interior vertices, worst cluster
  /// first. `sj`: the scaled Jacobian of every hex, kept up to date.
  /// Returns the MSJ after them.
  double improve_clusters(std::vector<Vec3>& points, std::vector<double>& sj, double msj,
                          const Worst_element_smoothing_settings& s, std::size_t& moves)
  {
    std::vector<std::size_t> low;
    for(std::size_t h = 0; h < sj.size(); ++h)
      if(sj[h] < (std::min)(msj + s.cluster_band, s.target_sj)) low.push_back(h);
    // union-find over the low hexes, joined through shared interior vertices
    std::vector<std::size_t> parent(low.size());
    for(std::size_t i = 0; i < low.size(); ++i) parent[i] = i;
    auto root = [&parent](std::size_t i) {
      while(parent[i] != i) i = parent[i] = parent[parent[i]];
      return i;
    };
    std::unordered_map<std::size_t, std::size_t> first_at; // interior vertex -> first low hex (index) on it
    for(std::size_t i = 0; i < low.size(); ++i)
      for(std::size_t v : m_topo.hexes()[low[i]])
      {
        if(m_topo.is_boundary_vertex(v) || m_topo.is_constrained(v)) continue;
        const auto ins = first_at.emplace(v, i);
        if(!ins.second)
        {
          const std::size_t a = root(i), b = root(ins.first->second);
          if(a != b) parent[(std::max)(a, b)] = (std::min)(a, b);
        }
      }
    std::map<std::size_t, std::vector<std::size_t> > clusters; // by root, i.e. by their first low hex
    for(std::size_t i = 0; i < low.size(); ++i) clusters[root(i)].push_back(low[i]);
    std::vector<std::pair<double, std::size_t> > worst_first;
    for(const auto& c : clusters)
    {
      if(c.second.size() < 2 || c.second.size() > s.max_cluster_hexes) continue;
      double m = 2.;
      for(std::size_t h : c.second) m = (std::min)(m, sj[h]);
      worst_first.push_back({m, c.first});
    }
    std::sort(worst_first.begin(), worst_first.end());
    for(const auto& w : worst_first)
    {
      if(time_limit_reached(s.time_limit)) break;
      const std::vector<std::size_t>& hexes = clusters[w.second];
      std::vector<std::size_t> verts;
      for(std::size_t h : hexes)
        for(std::size_t v : m_topo.hexes()[h])
          if(!m_topo.is_boundary_vertex(v) && !m_topo.is_constrained(v)) verts.push_back(v);
      std::sort(verts.begin(), verts.end());
      verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
      const double length = mean_edge_length(points, hexes);
      std::size_t steps = 0;
      while(steps < std::size_t(s.cluster_steps) && move_together(points, verts, length, sj)) ++steps;
      moves += steps;
      if(steps > 0 && !m_settled.empty())
        for(std::size_t v : verts) unsettle_around(v);
    }
    return *std::min_element(sj.begin(), sj.end());
  }

private:
  using Corner = Hex_mesh_topology::Corner;
  static constexpr double softness = 60.;

  /// `local_minimum` of the hexes whose corners at v are `around` with v at
  /// x if it is above `threshold`; otherwise a sample at or below it (the
  /// first found: the others are not computed)
  double local_minimum_if_above(const std::vector<Vec3>& points, const std::vector<Corner>& around, const Vec3& x,
                                double threshold) const
  {
    double m = 2.;
    for(const Corner& c : around)
    {
      std::array<Vec3, 8> p = corners(points, c.hex);
      p[c.local] = x;
      const double s = scaled_jacobian_if_above(p, threshold);
      if(!(s > threshold)) return s;
      m = (std::min)(m, s);
    }
    return m;
  }

  /// one sweep over `order` (worst first) in conflict-free batches (see the
  /// top); returns the number of steps accepted
  std::size_t sweep_in_batches(std::vector<Vec3>& points, const std::vector<std::pair<double, std::size_t> >& order,
                               std::vector<double>& sj, const Worst_element_smoothing_settings& s,
                               std::size_t& skipped)
  {
    const std::size_t nv = m_topo.number_of_vertices();
    m_hex_stamp.assign(m_topo.number_of_hexes(), 0);
    m_read_stamp.assign(nv, 0);
    m_member_stamp.assign(nv, 0);
    // pending[head ..) are the vertices not yet visited, in list order; a
    // batch looks at the first `batch_window` of them, and those it leaves
    // out are moved up, in order, to just before the rest (O(window) a batch)
    std::vector<std::size_t> pending, batch, ring;
    pending.reserve(order.size());
    for(const auto& o : order) pending.push_back(o.second);
    std::vector<std::ptrdiff_t> accepted;
    std::size_t moves = 0, stamp = 0, head = 0;
    const std::size_t window = (std::max)(std::size_t(1), s.batch_window);
    while(head < pending.size() && !time_limit_reached(s.time_limit))
    {
      ++stamp;
      batch.clear();
      const std::size_t end = (std::min)(pending.size(), head + window);
      std::size_t out = head;
      for(std::size_t k = head; k < end; ++k)
      {
        const std::size_t v = pending[k];
        if(claim(v, stamp, ring)) batch.push_back(v);
        else pending[out++] = v;
      }
      // the left-out vertices, now pending[head, out), slide up to end at `end`
      std::copy_backward(pending.begin() + std::ptrdiff_t(head), pending.begin() + std::ptrdiff_t(out),
                         pending.begin() + std::ptrdiff_t(end));
      head = end - (out - head);
      // (-1: not visited, the time limit fired; a settled vertex is not
      // visited either: it would fail again, see `m_settled`)
      accepted.assign(batch.size(), -1);
      parallel_for_each_index(batch.size(), [&](std::size_t i) {
        if(m_settled[batch[i]] && s.skip_settled) accepted[i] = 0;
        else if(!time_limit_reached(s.time_limit))
          accepted[i] = std::ptrdiff_t(improve_vertex(points, batch[i], sj, s.steps_per_vertex));
      });
      // (the members of a batch read nothing the others move: the order of
      // these updates does not matter)
      for(std::size_t i = 0; i < batch.size(); ++i)
      {
        if(m_settled[batch[i]] && s.skip_settled) ++skipped;
        if(accepted[i] == 0) m_settled[batch[i]] = 1;
        else if(accepted[i] > 0)
        {
          moves += std::size_t(accepted[i]);
          unsettle_around(batch[i]);
        }
      }
    }
    return moves;
  }

  /// u moved: the vertices whose visit reads it (those of the hexes around
  /// u and, on the boundary, of the quads within two rings, which the
  /// surface tests read: the relation is symmetric) are no longer settled
  void unsettle_around(std::size_t u)
  {
    for(auto c = m_topo.vertex_corners_begin(u); c != m_topo.vertex_corners_end(u); ++c)
      for(std::size_t w : m_topo.hexes()[c->hex]) m_settled[w] = 0;
    if(!m_topo.is_boundary_vertex(u)) return;
    thread_local std::vector<std::size_t> ring;
    ring.clear();
    m_topo.append_two_ring_boundary_vertices(u, ring);
    for(std::size_t w : ring) m_settled[w] = 0;
  }

  /// Adds v to the batch `stamp` if no vertex of the batch sees its move or
  /// is seen by it: no shared hex, and for boundary vertices (their surface
  /// tests read the boundary quads within two rings) neither a vertex of
  /// the other's two rings of quads. `ring` is scratch.
  bool claim(std::size_t v, std::size_t stamp, std::vector<std::size_t>& ring)
  {
    if(m_read_stamp[v] == stamp) return false;
    for(auto c = m_topo.vertex_corners_begin(v); c != m_topo.vertex_corners_end(v); ++c)
      if(m_hex_stamp[c->hex] == stamp) return false;
    ring.clear();
    if(m_topo.is_boundary_vertex(v))
    {
      m_topo.append_two_ring_boundary_vertices(v, ring);
      for(std::size_t w : ring)
        if(m_member_stamp[w] == stamp) return false;
    }
    for(auto c = m_topo.vertex_corners_begin(v); c != m_topo.vertex_corners_end(v); ++c)
    {
      m_hex_stamp[c->hex] = stamp;
      for(std::size_t w : m_topo.hexes()[c->hex]) m_read_stamp[w] = stamp;
    }
    for(std::size_t w : ring) m_read_stamp[w] = stamp;
    m_member_stamp[v] = stamp;
    return true;
  }


  std::array<Vec3, 8> corners(const std::vector<Vec3>& points, std::size_t h) const
  {
    std::array<Vec3, 8> p;
    for(int i = 0; i < 8; ++i) p[i] = points[m_topo.hexes()[h][i]];
    return p;
  }

  double hex_sj(const std::vector<Vec3>& points, std::size_t h) const { return scaled_jacobian(corners(points, h)); }

  double vertex_min(const std::vector<Vec3>&, std::size_t v, const std::vector<double>& sj) const
  {
    double m = 2.;
    for(auto c = m_topo.vertex_corners_begin(v); c != m_topo.vertex_corners_end(v); ++c) m = (std::min)(m, sj[c->hex]);
    return m;
  }

  /// The soft minimum (sharpness `softness`) of the samples of the hexes
  /// `around`, and its gradient with respect to each of `verts` (analytic:
  /// the kernel's sample gradients, weighted as the soft minimum weighs the
  /// samples). `hard`: the exact minimum.
  double soft_minimum_gradient(const std::vector<Vec3>& points, const std::vector<std::size_t>& around,
                               const std::vector<std::size_t>& verts, std::vector<Vec3>& grad, double& hard) const
  {
    thread_local std::vector<double> s;
    s.resize(9 * around.size());
    for(std::size_t a = 0; a < around.size(); ++a) hex_samples(corners(points, around[a]), &s[9 * a]);
    hard = s.empty() ? 1. : *std::min_element(s.begin(), s.end());
    double sum = 0.;
    for(double x : s) sum += std::exp(-softness * (x - hard));
    grad.assign(verts.size(), Vec3{0., 0., 0.});
    for(std::size_t a = 0; a < around.size(); ++a)
    {
      const Hex& hx = m_topo.hexes()[around[a]];
      const std::array<Vec3, 8> p = corners(points, around[a]);
      for(int c = 0; c < 8; ++c)
      {
        const std::size_t i = std::size_t(std::find(verts.begin(), verts.end(), hx[c]) - verts.begin());
        if(i == verts.size()) continue;
        const int* dep = corner_samples_of_corner(c);
        for(int j = 0; j < 5; ++j)
        {
          const int k = j < 4 ? dep[j] : 8;
          const double x = s[9 * a + k];
          const double w = std::exp(-softness * (x - hard));
          if(w == 0.) continue;
          grad[i] = grad[i] + (w / sum) * hex_sample_gradient(p, k, c, x);
        }
      }
    }
    return hard - std::log(sum) / softness;
  }

  /// Joint move of the interior vertices of hex h: ascent on the soft minimum
  /// of the samples of every hex around them (analytic gradient in all
  /// their coordinates), accepted only if the minimum over those hexes rises.
  /// Single-vertex max-min stalls where several elements at the minimum
  /// share vertices and each move of one vertex lowers one of them.
  std::size_t improve_element(std::vector<Vec3>& points, std::size_t h, std::vector<double>& sj) const
  {
    std::vector<std::size_t> verts;
    for(std::size_t v : m_topo.hexes()[h])
      if(!m_topo.is_boundary_vertex(v) && !m_topo.is_constrained(v)) verts.push_back(v);
    return move_together(points, verts, mean_edge_length(points, std::vector<std::size_t>(1, h)), sj);
  }

  /// the mean edge length of `hexes`
  double mean_edge_length(const std::vector<Vec3>& points, const std::vector<std::size_t>& hexes) const
  {
    double length = 0.;
    for(std::size_t k : hexes)
      for(int e = 0; e < 12; ++e)
        length += norm(points[m_topo.hexes()[k][hex_edges[e][0]]] - points[m_topo.hexes()[k][hex_edges[e][1]]]);
    return length / (12. * double(hexes.size()));
  }

  /// One ascent step of the vertices `verts` (interior, distinct) together
  /// on the soft minimum of the hexes around them, accepted only if the
  /// minimum over those hexes rises; the trial steps start at 0.3 `length`.
  /// Returns 1 if accepted, else 0.
  std::size_t move_together(std::vector<Vec3>& points, const std::vector<std::size_t>& verts, double length,
                            std::vector<double>& sj) const
  {
    if(verts.empty()) return 0;
    std::vector<std::size_t> around;
    for(std::size_t v : verts)
      for(auto c = m_topo.vertex_corners_begin(v); c != m_topo.vertex_corners_end(v); ++c) around.push_back(c->hex);
    std::sort(around.begin(), around.end());
    around.erase(std::unique(around.begin(), around.end()), around.end());
    auto hard_minimum = [&] {
      double m = std::numeric_limits<double>::max();
      for(std::size_t k : around) m = (std::min)(m, hex_sj(points, k));
      return m;
    };
    if(!(length > 0.)) return 0;
    double f0 = 0.;
    std::vector<Vec3> g;
    soft_minimum_gradient(points, around, verts, g, f0);
    double gn = 0.;
    for(const Vec3& gi : g) gn += squared_norm(gi);
    gn = std::sqrt(gn);
    if(!(gn > 0.)) return 0;
    std::vector<Vec3> x0(verts.size());
    for(std::size_t i = 0; i < verts.size(); ++i) x0[i] = points[verts[i]];
    // with an inverted hex around, the rise of the minimum does not keep the
    // valid ones valid: their count may not rise (see `element_floor`)
    auto inverted = [&] {
      std::size_t n = 0;
      for(std::size_t k : around) if(is_inverted(hex_sj(points, k))) ++n;
      return n;
    };
    const double hard0 = hard_minimum();
    const std::size_t inverted_before = is_inverted(hard0) ? inverted() : 0;
    // the trials stop at the first sample that does not beat hard0: the
    // hexes worst first
    std::vector<std::size_t> worst_first = around;
    std::stable_sort(worst_first.begin(), worst_first.end(),
                     [&sj](std::size_t a, std::size_t b) { return sj[a] < sj[b]; });
    auto rises = [&] {
      for(std::size_t k : worst_first)
        if(!(scaled_jacobian_if_above(corners(points, k), hard0 + 1e-9) > hard0 + 1e-9)) return false;
      return true;
    };
    for(double t = 0.3 * length; t > 1e-4 * length; t *= 0.5)
    {
      for(std::size_t i = 0; i < verts.size(); ++i) points[verts[i]] = x0[i] + (t / gn) * g[i];
      if(rises() && (inverted_before == 0 || inverted() <= inverted_before))
      {
        for(std::size_t k : around) sj[k] = hex_sj(points, k);
        return 1;
      }
    }
    for(std::size_t i = 0; i < verts.size(); ++i) points[verts[i]] = x0[i];
    return 0;
  }

  /// the kinds of move at a vertex, tried in turn until one is accepted:
  /// along its class (on the surface, along its feature line), on the
  /// reference whatever its class, or free (only under the surface guard)
  enum Move { along_class, on_reference, free_move };

  static std::vector<Move> moves_for(Vertex_class cls, bool guarded)
  {
    if(cls == Vertex_class::interior) return {free_move};
    if(!guarded) return {along_class};
    if(cls == Vertex_class::sharp) return {along_class, on_reference, free_move};
    return {on_reference, free_move};
  }

  /// the ascent direction `g` at x0 restricted to the freedom of move `m`
  Vec3 restricted(std::size_t v, const Vec3& x0, const Vec3& g, Move m, Vertex_class cls) const
  {
    if(m == along_class)
    {
      const Boundary_constraint bc = m_target->constraint_at(v, x0);
      return cls == Vertex_class::regular ? g - dot(g, bc.direction) * bc.direction
                                          : dot(g, bc.direction) * bc.direction;
    }
    if(m == on_reference)
    {
      Vec3 anchor, normal;
      m_target->closest_on_reference(x0, anchor, &normal);
      return g - dot(g, normal) * normal;
    }
    return g;
  }

  /// x brought back to the freedom of move `m`
  Vec3 constrained(std::size_t v, const Vec3& x, Move m) const
  {
    if(m == along_class) return m_target->constraint_at(v, x).anchor;
    if(m == on_reference)
    {
      Vec3 y;
      m_target->closest_on_reference(x, y);
      return y;
    }
    return x;
  }

  /// the mean length of the edges at v
  double mean_edge_length_at(const std::vector<Vec3>& points, std::size_t v) const
  {
    double length = 0.;
    int ne = 0;
    for(auto c = m_topo.vertex_corners_begin(v); c != m_topo.vertex_corners_end(v); ++c)
      for(int k = 0; k < 3; ++k, ++ne)
        length += norm(points[m_topo.hexes()[c->hex][hex_corner_edges[c->local][k]]] - points[v]);
    return length / (std::max)(ne, 1);
  }

  /// the minimum of the samples of the hexes around v (`local_minimum`),
  /// and that of the samples v does not move (of each hex, the 4 corners
  /// away from v): while the latter is not above the former, no move of v
  /// can raise the minimum (most vertices of a hex at the minimum are in
  /// that case)
  void minimum_around(const std::vector<Vec3>& points, std::size_t v, double& all, double& unmoved) const
  {
    for(auto c = m_topo.vertex_corners_begin(v); c != m_topo.vertex_corners_end(v); ++c)
    {
      double samples[9];
      hex_samples(corners(points, c->hex), samples);
      bool moves_with_v[9] = {false, false, false, false, false, false, false, false, true};
      for(int j = 0; j < 4; ++j) moves_with_v[corner_samples_of_corner(c->local)[j]] = true;
      for(int i = 0; i < 9; ++i)
      {
        all = (std::min)(all, samples[i]);
        if(!moves_with_v[i]) unmoved = (std::min)(unmoved, samples[i]);
      }
    }
  }

  /// up to `steps` ascent steps on vertex v; returns the number accepted
  std::size_t improve_vertex(std::vector<Vec3>& points, std::size_t v, std::vector<double>& sj, int steps) const
  {
    if(m_topo.is_constrained(v)) return 0; // the user's constrained vertices never move
    const Vertex_class cls = m_target ? m_target->vertex_class(v)
                                      : (m_topo.is_boundary_vertex(v) ? Vertex_class::corner : Vertex_class::interior);
    const bool guarded = cls != Vertex_class::interior && m_guarded;
    if(cls == Vertex_class::corner && !guarded) return 0;
    const double length = mean_edge_length_at(points, v);
    if(!(length > 0.)) return 0;
    // a step must beat f0, which it cannot once `unmoved` is not above it
    double f0 = 2., unmoved = 2.;
    minimum_around(points, v, f0, unmoved);
    if(!(unmoved > f0 + 1e-9)) return 0;

    // the hexes around v, for the soft minimum's gradient, and their
    // corners at v worst first, for the trials (the worst hex is the one most
    // likely to fail a trial, which then stops there)
    std::vector<std::size_t> around;
    for(auto c = m_topo.vertex_corners_begin(v); c != m_topo.vertex_corners_end(v); ++c) around.push_back(c->hex);
    std::vector<Corner> worst_first(m_topo.vertex_corners_begin(v), m_topo.vertex_corners_end(v));
    std::stable_sort(worst_first.begin(), worst_first.end(),
                     [&sj](const Corner& a, const Corner& b) { return sj[a.hex] < sj[b.hex]; });
    const std::vector<std::size_t> single(1, v);
    std::vector<Vec3> gradient;
    std::size_t accepted = 0;
    // the guard's bound for this visit, measured where v starts, when a
    // trial first raises the minimum (most visits of a stalled vertex
    // raise nothing and need no closest-point query)
    bool have_allowed = false;
    Surface_deviation allowed;
    const Vec3 start = points[v];
    auto guard_allows = [&](const Vec3& x) {
      if(!have_allowed)
      {
        allowed = m_guard->bound_at(points, v, start, m_max_deviation);
        have_allowed = true;
      }
      return m_guard->allows(points, v, x, allowed);
    };
    const std::vector<Move> moves = moves_for(cls, guarded);
    for(int step = 0; step < steps; ++step)
    {
      if(!(unmoved > f0 + 1e-9)) break;
      const Vec3 x0 = points[v];
      double hard = 0.;
      soft_minimum_gradient(points, around, single, gradient, hard);
      bool moved = false;
      for(std::size_t m = 0; m < moves.size() && !moved; ++m)
      {
        const Vec3 g = restricted(v, x0, gradient[0], moves[m], cls);
        const double gn = norm(g);
        if(!(gn > 0.)) continue;
        const Vec3 dir = (1. / gn) * g;
        for(double t = 0.3 * length; t > 1e-4 * length; t *= 0.5)
        {
          const Vec3 x = constrained(v, x0 + t * dir, moves[m]);
          const double f = local_minimum_if_above(points, worst_first, x, f0 + 1e-9);
          // (a rise of the minimum keeps every valid hex valid unless one
          // around v is inverted: then their count may not rise)
          if(f > f0 + 1e-9 && (!is_inverted(f0) || inverted_around(points, v, x) <= inverted_around(points, v, x0)) &&
             (!guarded || guard_allows(x)))
          {
            points[v] = x;
            f0 = f;
            moved = true;
            break;
          }
        }
      }
      if(!moved) break;
      ++accepted;
    }
    if(accepted)
      for(auto c = m_topo.vertex_corners_begin(v); c != m_topo.vertex_corners_end(v); ++c) sj[c->hex] = hex_sj(points, c->hex);
    return accepted;
  }

  const Hex_mesh_topology& m_topo;
  const Target_surface* m_target;
  const Surface_guard* m_guard;
  double m_max_deviation = std::numeric_limits<double>::infinity();
  bool m_guarded = false;
  // the batches of a sweep (`sweep_in_batches`): the batch that last
  // claimed each hex, read each vertex and moved each vertex
  std::vector<std::size_t> m_hex_stamp, m_read_stamp, m_member_stamp;
  // A visit of a vertex depends only on the positions of the vertices it
  // reads (those of its hexes and, on the boundary, of its two rings of
  // quads): a vertex whose visit moved nothing, and around which nothing has
  // moved since, would fail again. Such a vertex is settled (1) and its
  // visits are skipped until a move around it clears the flag
  // (`unsettle_around`): same moves, same bytes, without the trials of
  // the stalled sweeps.
  std::vector<unsigned char> m_settled;
};

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SMOOTHING_WORST_ELEMENT_SMOOTHING_H
