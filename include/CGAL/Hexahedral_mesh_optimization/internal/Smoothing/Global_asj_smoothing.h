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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SMOOTHING_GLOBAL_ASJ_SMOOTHING_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SMOOTHING_GLOBAL_ASJ_SMOOTHING_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The interior part of the ASJ smoothing, solved for all interior vertices at
// once: maximise
//     F(x) = Σ_h softmin_k(s_h1(x), ..., s_h9(x)),
//     softmin_k(s) = −log(Σ_i exp(−k s_i)) / k,
// the sum over the hexes of a soft minimum of their 9 Verdict samples (the
// objective of the Gauss-Seidel smoothing, Asj_smoothing.h), over the
// positions x of the interior vertices, by L-BFGS with a backtracking line
// search, subject to every hex keeping a scaled Jacobian of at least
// element_floor(floor, its value at the start): a trial step that breaks it
// is retried with the free vertices of the offending hexes left in place,
// then halved like one that does not raise F enough.
//
// Gauss-Seidel moves one vertex at a time and converges slowly on this
// smooth objective (each pass still gains a little after tens of them); the
// quasi-Newton steps move every vertex together along a curvature-aware
// direction, preconditioned by the squared length of each vertex's shortest
// edge. The
// Gauss-Seidel passes that follow see to the boundary and to the vertices
// left fixed here.
//
// Free vertices: interior vertices none of whose hexes is within
// `floor_margin` of its floor; the others stay where they are, so that the
// worst elements, which bound the step of any direction that touches them,
// do not stall the line search (the max-min smoothing and the Gauss-Seidel
// passes see to them). Boundary vertices never move here.
//
// Deterministic: per-hex values and gradients are computed in parallel into
// per-hex slots, then summed in a fixed order.

#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_topology.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/Time_limit.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/parallel_for_each_index.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/scaled_jacobian.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Smoothing/Asj_smoothing.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Solvers/Lbfgs_history.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <deque>
#include <limits>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

struct Global_asj_settings
{
  /// no element ends below element_floor(min_sj_floor, its value at the start)
  double min_sj_floor = -std::numeric_limits<double>::infinity();
  /// sharpness k of the soft minimum (the Gauss-Seidel smoothing's
  /// `objective_sharpness`)
  double sharpness = 30.;
  /// interior vertices of a hex within this of its floor stay fixed
  double floor_margin = 0.02;
  /// L-BFGS iterations at most
  int max_iterations = 100;
  /// stop when the last `gain_window` iterations raised F / (number of
  /// hexes) by less than this each, on average
  double min_gain = 2e-5;
  int gain_window = 5;
  /// pairs kept by L-BFGS
  std::size_t history = 7;
  /// a trial step whose hexes break their floor is retried with the free
  /// vertices of those hexes left where they were, at most this many times,
  /// before the step is halved
  int floor_reverts = 3;
  /// the first step (steepest descent, preconditioned) moves no vertex by
  /// more than this fraction of its shortest edge
  double first_step = 1e-2;
  /// the run's hard stop (null: none), read between iterations
  const Time_limit* time_limit = nullptr;
};

struct Global_asj_report
{
  int iterations = 0;
  std::size_t free_vertices = 0;
  double objective_before = 0., objective_after = 0.; ///< F / number of hexes
};

class Global_asj_smoother
{
public:
  Global_asj_smoother(const Hex_mesh_topology& topo, std::vector<Vec3>& points, const Global_asj_settings& s)
    : m_topo(topo), m_points(points), m_s(s)
  {}

  Global_asj_report run()
  {
    Global_asj_report rep;
    select_free_vertices();
    rep.free_vertices = m_free.size();
    if(m_free.empty()) return rep;
    set_preconditioner();
    const double nh = double(m_topo.number_of_hexes());
    Eigen::VectorXd x(3 * m_free.size()), g, x_new, g_new;
    for(std::size_t j = 0; j < m_free.size(); ++j)
      for(int k = 0; k < 3; ++k) x[3 * j + k] = m_points[m_free[j]][k];
    evaluate_all(x);
    double e = energy();
    assemble_gradient(g);
    rep.objective_before = rep.objective_after = -(e + m_fixed_energy) / nh;
    if(!std::isfinite(e)) return rep; // a floor broken at the start: nothing to do safely
    Lbfgs_history history(m_s.history);
    std::deque<double> recent_gains;
    for(int it = 0; it < m_s.max_iterations && !time_limit_reached(m_s.time_limit); ++it)
    {
      Eigen::VectorXd dir = -descent_direction(history, g);
      if(!(dir.dot(g) < 0.)) { history.clear(); dir = -descent_direction(history, g); }
      double e_new = e;
      if(!line_search(x, e, g, dir, x_new, e_new, g_new)) break;
      ++rep.iterations;
      history.push(x_new - x, g_new - g);
      recent_gains.push_back((e - e_new) / nh);
      if(int(recent_gains.size()) > m_s.gain_window) recent_gains.pop_front();
      x.swap(x_new);
      g.swap(g_new);
      e = e_new;
      double window = 0.;
      for(double gain : recent_gains) window += gain;
      if(int(recent_gains.size()) == m_s.gain_window && window < m_s.min_gain * m_s.gain_window) break;
    }
    for(std::size_t j = 0; j < m_free.size(); ++j) m_points[m_free[j]] = {x[3 * j], x[3 * j + 1], x[3 * j + 2]};
    rep.objective_after = -(e + m_fixed_energy) / nh;
    return rep;
  }

private:
  // Backtracking from t = 1 (Armijo, on the step actually taken): a trial
  // whose hexes break their floor first keeps the free vertices of those
  // hexes where they were (a few times), then is halved.
  bool line_search(const Eigen::VectorXd& x, double e, const Eigen::VectorXd& g, const Eigen::VectorXd& dir,
                   Eigen::VectorXd& x_new, double& e_new, Eigen::VectorXd& g_new)
  {
    double step = 1.;
    for(int halving = 0; halving < 20; ++halving, step *= 0.5)
    {
      x_new = x + step * dir;
      evaluate_all(x_new);
      e_new = energy();
      for(int round = 0; round < m_s.floor_reverts && !std::isfinite(e_new); ++round)
      {
        keep_broken_in_place(x, x_new);
        e_new = energy();
      }
      if(e_new <= e + 1e-4 * (x_new - x).dot(g))
      {
        assemble_gradient(g_new);
        return true;
      }
    }
    return false;
  }

  // the free vertices of the hexes below their floor go back to `x`; the
  // hexes around them are evaluated again
  void keep_broken_in_place(const Eigen::VectorXd& x, Eigen::VectorXd& x_new)
  {
    std::vector<std::size_t>& again = m_again;
    again.clear();
    for(std::size_t i = 0; i < m_active.size(); ++i)
    {
      if(!m_broken[i]) continue;
      for(std::size_t v : m_topo.hexes()[m_active[i]])
      {
        const long j = m_index[v];
        if(j < 0 || (x_new[3 * j] == x[3 * j] && x_new[3 * j + 1] == x[3 * j + 1] && x_new[3 * j + 2] == x[3 * j + 2]))
          continue;
        for(int k = 0; k < 3; ++k) x_new[3 * j + k] = x[3 * j + k];
        for(auto c = m_topo.vertex_corners_begin(v); c != m_topo.vertex_corners_end(v); ++c)
          again.push_back(m_slot[c->hex]);
      }
    }
    std::sort(again.begin(), again.end());
    again.erase(std::unique(again.begin(), again.end()), again.end());
    parallel_for_each_index(again.size(), [&](std::size_t k) { evaluate_hex(x_new, again[k]); }, 64);
  }

  // −H g; the first step moves no vertex by more than `first_step` of its
  // shortest edge
  Eigen::VectorXd descent_direction(const Lbfgs_history& history, const Eigen::VectorXd& g) const
  {
    Eigen::VectorXd q = history.inverse_hessian_times(g, &m_diagonal);
    if(history.empty())
    {
      double largest = 0.; // the largest move relative to the vertex's shortest edge
      for(Eigen::Index i = 0; i < q.size(); ++i) largest = (std::max)(largest, std::abs(q[i]) / std::sqrt(m_diagonal[i]));
      q *= m_s.first_step / (std::max)(largest, 1e-300);
    }
    return q;
  }

  // the free vertices (interior, every hex around at least `floor_margin`
  // above its floor), the hexes they move, the floors, and the constant part
  // of the energy (the hexes that do not move)
  void select_free_vertices()
  {
    const std::size_t nh = m_topo.number_of_hexes(), nv = m_topo.number_of_vertices();
    m_floor.resize(nh);
    std::vector<unsigned char> near_floor(nh, 0);
    std::vector<double> soft_minimum_of(nh, 0.);
    parallel_for_each_index(nh, [&](std::size_t h) {
      double f[9];
      hex_samples(corners(h), f);
      const double sj = asj_detail::exact_minimum(f);
      m_floor[h] = element_floor(m_s.min_sj_floor, sj);
      near_floor[h] = sj < m_floor[h] + m_s.floor_margin;
      soft_minimum_of[h] = asj_detail::soft_minimum(f, m_s.sharpness);
    }, 256);
    m_index.assign(nv, -1);
    m_free.clear();
    for(std::size_t v = 0; v < nv; ++v)
    {
      if(m_topo.is_boundary_vertex(v) || m_topo.is_constrained(v)) continue;
      bool free = true;
      for(auto c = m_topo.vertex_corners_begin(v); c != m_topo.vertex_corners_end(v) && free; ++c)
        free = !near_floor[c->hex];
      if(!free) continue;
      m_index[v] = static_cast<long>(m_free.size());
      m_free.push_back(v);
    }
    std::vector<unsigned char> moving(nh, 0);
    for(std::size_t v : m_free)
      for(auto c = m_topo.vertex_corners_begin(v); c != m_topo.vertex_corners_end(v); ++c) moving[c->hex] = 1;
    m_active.clear();
    m_fixed_energy = 0.;
    m_slot.assign(nh, 0);
    for(std::size_t h = 0; h < nh; ++h)
    {
      if(!moving[h]) { m_fixed_energy -= soft_minimum_of[h]; continue; }
      m_slot[h] = m_active.size();
      m_active.push_back(h);
    }
    m_value.resize(m_active.size());
    m_gradient.resize(m_active.size());
    m_broken.resize(m_active.size());
  }

  // D: per free vertex, the squared length of its shortest edge (the
  // objective's Hessian scales as 1 / length², and the edges of one mesh can
  // span orders of magnitude)
  void set_preconditioner()
  {
    m_diagonal.resize(3 * m_free.size());
    for(std::size_t j = 0; j < m_free.size(); ++j)
    {
      const std::size_t v = m_free[j];
      double shortest = std::numeric_limits<double>::infinity();
      for(auto c = m_topo.vertex_corners_begin(v); c != m_topo.vertex_corners_end(v); ++c)
        for(int k = 0; k < 3; ++k)
          shortest = (std::min)(shortest, squared_norm(m_points[m_topo.hexes()[c->hex][hex_corner_edges[c->local][k]]] -
                                                       m_points[v]));
      for(int k = 0; k < 3; ++k) m_diagonal[3 * j + k] = shortest;
    }
  }

  std::array<Vec3, 8> corners(std::size_t h) const
  {
    std::array<Vec3, 8> p;
    for(int c = 0; c < 8; ++c) p[c] = m_points[m_topo.hexes()[h][c]];
    return p;
  }

  // value, gradient and floor test of active hex i with the free vertices at x
  void evaluate_hex(const Eigen::VectorXd& x, std::size_t i)
  {
    const std::size_t h = m_active[i];
    std::array<Vec3, 8> p;
    for(int c = 0; c < 8; ++c)
    {
      const std::size_t v = m_topo.hexes()[h][c];
      const long j = m_index[v];
      p[c] = j < 0 ? m_points[v] : Vec3{x[3 * j], x[3 * j + 1], x[3 * j + 2]};
    }
    double f[9], w[9];
    hex_samples(p, f);
    const double m = asj_detail::exact_minimum(f);
    m_broken[i] = !(m >= m_floor[h]);
    double sum = 0.;
    for(int s = 0; s < 9; ++s) sum += (w[s] = asj_detail::exp_minus(m_s.sharpness * (f[s] - m)));
    m_value[i] = m - std::log(sum) / m_s.sharpness;
    for(int s = 0; s < 9; ++s) w[s] /= sum;
    for(Vec3& gc : m_gradient[i]) gc = Vec3{0., 0., 0.};
    add_weighted_sample_gradients(p, f, w, m_gradient[i]);
  }

  void evaluate_all(const Eigen::VectorXd& x)
  {
    parallel_for_each_index(m_active.size(), [&](std::size_t i) { evaluate_hex(x, i); }, 128);
  }

  // E = −Σ over the moving hexes of their soft minima as last evaluated, +∞
  // when one of them is below its floor (`m_broken` says which)
  double energy() const
  {
    double e = 0.;
    bool broken = false;
    for(std::size_t i = 0; i < m_active.size(); ++i) { e -= m_value[i]; broken = broken || m_broken[i]; }
    return broken ? std::numeric_limits<double>::infinity() : e;
  }

  // ∂E/∂x from the per-hex gradients as last evaluated
  void assemble_gradient(Eigen::VectorXd& grad) const
  {
    grad.resize(3 * m_free.size());
    parallel_for_each_index(m_free.size(), [&](std::size_t j) {
      Vec3 gv{0., 0., 0.};
      const std::size_t v = m_free[j];
      for(auto c = m_topo.vertex_corners_begin(v); c != m_topo.vertex_corners_end(v); ++c)
        gv = gv - m_gradient[m_slot[c->hex]][c->local];
      for(int k = 0; k < 3; ++k) grad[3 * j + k] = gv[k];
    }, 256);
  }

  const Hex_mesh_topology& m_topo;
  std::vector<Vec3>& m_points;
  Global_asj_settings m_s;
  std::vector<std::size_t> m_free;    // free vertex j -> mesh vertex
  std::vector<long> m_index;          // mesh vertex -> free index, or -1
  std::vector<std::size_t> m_active;  // the hexes with a free vertex
  std::vector<std::size_t> m_slot;    // hex -> its place in m_active
  std::vector<double> m_floor;        // per hex
  std::vector<double> m_value;        // per active hex: its soft minimum
  std::vector<std::array<Vec3, 8> > m_gradient; // per active hex: ∂(soft minimum)/∂(corner)
  std::vector<unsigned char> m_broken; // per active hex: below its floor in the last evaluation
  Eigen::VectorXd m_diagonal;
  double m_fixed_energy = 0.;
  std::vector<std::size_t> m_again;
};

/// raises the ASJ of the interior (see the file's comment); the boundary does not move
inline Global_asj_report smooth_interior_for_average_quality(const Hex_mesh_topology& topo,
                                                             std::vector<Vec3>& points,
                                                             const Global_asj_settings& s)
{
  Global_asj_smoother smoother(topo, points, s);
  return smoother.run();
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SMOOTHING_GLOBAL_ASJ_SMOOTHING_H
