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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_UNTANGLING_PULL_BACK_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_UNTANGLING_PULL_BACK_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The inversion-free pull-back of Section 3.3: after untangling with a
// relaxed surface the boundary vertices are off the target surface; move
// them back onto it (regular → the reference surface, sharp → its feature
// line, corner → its Ω_t position: the anchors of `Target_surface`) by a
// sequence of injective deformations, so that no accepted state ever has an
// element with a (9-point Verdict) scaled Jacobian ≤ 0.
//
// Method: SLIM (Rabinovich, Poranne, Panozzo, Sorkine-Hornung, "Scalable
// locally injective mappings", 2017) on the 9 Jacobian samples of each hex
// (the 8 corner tetrahedra and the centre frame of principal axes, i.e.
// exactly the samples of the scaled Jacobian), plus a soft boundary term,
//
//   E(x) = Σ_hex Σ_sample (1/9) f(F_s)  +  w/ℓ² Σ_boundary (x − c)ᵀ M (x − c),
//
// F_s = J_s(x) R_s⁻¹ the deformation gradient of a sample w.r.t. its rest
// frame R_s, f the symmetric Dirichlet energy |F|² + |F⁻¹|², ℓ the mean edge
// length, c the anchor and M the metric of the vertex class (Eq. 6: n nᵀ + τ I
// for a regular vertex, I − t tᵀ + τ t tᵀ for a sharp one, I for a corner;
// τ = 0.01 lets a vertex slide, gently, along its surface or line). One iteration:
// SLIM reweighting (w² = f'(σ)/(2(σ − 1)) from the closed-form
// eigen-decomposition of FᵀF, a Jacobi SVD for nearly degenerate frames,
// capped), one solve of the quadratic proxy, then a flip-avoiding line
// search: the largest step keeping every sample determinant positive
// (smallest positive root of each cubic det(J + α dJ), Smith & Schaefer
// 2015), × 0.8, halved until the energy decreases and every hex touched has
// a scaled Jacobian above the floor. Anchors (closest points) are refreshed
// at every iteration, so regular and sharp vertices slide along their
// surface / line instead of being tied to one correspondence (the paper's
// failure case, Fig. 11, blames exactly that correspondence).
//
// Choices where the paper is vague ("SLIM with the exponential AMIPS
// energy on the 8 corner tetrahedra, 20 iterations"), and why:
// - Energy: symmetric Dirichlet. AMIPS is scale invariant, so its SLIM
//   weights (which need f'(σ)/(σ − 1) > 0) are undefined; the exponential
//   symmetric Dirichlet exp(s (f − 6)) is available (`energy`) but gains no
//   surface error for a larger final max distance and more CG iterations.
// - Samples: the centre frame is included, so that finite energy ⇔ every
//   element has a positive 9-point scaled Jacobian (the 8 corner tets alone
//   do not bound the centre sample).
// - Rest shape: the ideal right-angle corner of a cube with the hex's mean
//   edge length (the energy then also improves the elements it moves). The
//   element's own initial frames (`initial_element`) reach the same surface
//   error, but a near-degenerate rest frame makes the system ill-conditioned
//   (the CG then needs an order of magnitude more iterations).
// - Linear solver: conjugate gradient with a 3×3 block-Jacobi
//   preconditioner, warm-started. Eigen's SimplicialLDLT is available
//   (`linear_solver`) but its fill-in on a 3D block makes each factorisation
//   far dearer than the few tens of warm-started CG iterations a solve needs.
// - Constraints: soft, with a weight w that starts at 1 (the interior follows
//   the boundary) and grows ×4 after every iteration that took at least a
//   quarter of the SLIM step, or after 4 iterations without a 1 % gain, up to
//   1e8. Starting high (w = 100) pulls several sharp vertices of a twisted
//   block onto the same anchor and jams it. At the end, the boundary vertices
//   are snapped exactly onto their anchors wherever that keeps the hexes
//   above the floor (all at once, else vertex by vertex).
// - SJ floor: the first target is to never lower the minimum scaled Jacobian
//   of the input; when that floor (not the energy) keeps cutting the steps,
//   it is halved, down to `min_sj_fraction` (0.5) × the input minimum.
// - Region: only the hexes within `region_rings` rings of the boundary
//   vertices farther than the tolerance are optimised (other vertices stay
//   fixed); on a stall the rings are doubled (rings < 0: the whole mesh).
// - Iterations: at most 50, until every boundary vertex is within
//   `tolerance`·ℓ of its anchor or the run stalls. When the surface cannot
//   be reached, the valid state with the smallest max + mean distance is
//   returned and `reached` is false.

#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Boundary_constraint.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_topology.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Target_surface.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/Time_limit.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/scaled_jacobian.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <Eigen/IterativeLinearSolvers>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

enum class Pull_back_energy { symmetric_dirichlet, exp_symmetric_dirichlet };
enum class Pull_back_rest_shape { ideal_cube, initial_element };
enum class Pull_back_linear_solver { conjugate_gradient, simplicial_ldlt };

/// 3×3 block-diagonal (per vertex) preconditioner for Eigen's ConjugateGradient
class Pull_back_block_jacobi
{
public:
  typedef double Scalar;
  typedef Eigen::SparseMatrix<double> Matrix;
  Pull_back_block_jacobi() {}
  template <class M> explicit Pull_back_block_jacobi(const M& m) { compute(m); }
  template <class M> Pull_back_block_jacobi& analyzePattern(const M&) { return *this; }
  template <class M> Pull_back_block_jacobi& factorize(const M& m) { return compute(m); }
  template <class M> Pull_back_block_jacobi& compute(const M& m)
  {
    const Eigen::Index n = m.rows() / 3;
    m_inv.resize(std::size_t(n));
    for(Eigen::Index b = 0; b < n; ++b)
    {
      Eigen::Matrix3d d = Eigen::Matrix3d::Zero();
      for(int dj = 0; dj < 3; ++dj)
        for(typename M::InnerIterator it(m, 3 * b + dj); it; ++it)
          if(it.row() >= 3 * b && it.row() < 3 * b + 3) d(it.row() - 3 * b, dj) = it.value();
      m_inv[std::size_t(b)] = d.inverse();
    }
    return *this;
  }
  template <class Rhs> Eigen::VectorXd solve(const Rhs& r) const
  {
    Eigen::VectorXd x(r.size());
    for(std::size_t b = 0; b < m_inv.size(); ++b)
      x.template segment<3>(3 * Eigen::Index(b)) = m_inv[b] * r.template segment<3>(3 * Eigen::Index(b));
    return x;
  }
  Eigen::ComputationInfo info() const { return Eigen::Success; }

private:
  std::vector<Eigen::Matrix3d> m_inv;
};

/// what one accepted step did (for callbacks)
struct Pull_back_step
{
  int iteration = 0;
  double distance = 0.;  ///< max distance of a boundary vertex to its anchor after the step
  double min_sj = 0.;    ///< minimum scaled Jacobian of the optimised hexes after the step
  double weight = 0.;    ///< boundary weight w used
  double step = 0.;      ///< accepted fraction of the SLIM direction
  std::size_t free_vertices = 0;
};

struct Pull_back_settings
{
  Pull_back_energy energy = Pull_back_energy::symmetric_dirichlet;
  double exp_factor = 0.1; ///< s in exp(s (f − 6)) for the exponential energy
  Pull_back_rest_shape rest_shape = Pull_back_rest_shape::ideal_cube;
  /// the SLIM proxy system: preconditioned conjugate gradient (default) or a sparse LDLᵀ
  Pull_back_linear_solver linear_solver = Pull_back_linear_solver::conjugate_gradient;
  /// cap on the SLIM weights w² (4 at a rest frame): keeps the proxy system
  /// conditioned near degenerate frames (the line search guards validity)
  double max_slim_weight = 1e6;
  /// relative residual of the conjugate gradient
  double cg_tolerance = 1e-8;
  int max_iterations = 50;
  /// the run's hard stop (null: none), read after each iteration (the best valid state is kept)
  const Time_limit* time_limit = nullptr;
  /// reached when every boundary vertex is within tolerance × mean edge length of its anchor
  double tolerance = 1e-3;
  /// rings of hexes around the displaced boundary vertices; < 0: the whole mesh
  int region_rings = 3;
  int max_region_growths = 2;
  double initial_weight = 1.;
  double max_weight = 1e8;
  double weight_growth = 4.;
  /// the weight grows after an iteration whose accepted step is at least this fraction of the SLIM direction
  double weight_growth_min_step = 0.25;
  /// τ: tangential stiffness of regular / sharp constraints relative to the normal one
  double tangential_weight = 1e-2;
  /// No accepted state has a minimum scaled Jacobian below this fraction of
  /// the input's: the floor starts at 1 × (never lower the minimum) and is
  /// halved, down to this value, only when the run stalls above it.
  double min_sj_fraction = 0.5;
  /// snap the boundary exactly onto the anchors at the end, when valid
  bool snap = true;
  /// iterations without a 1 % gain of (max + mean) distance: the weight grows ×`weight_growth`;
  /// at `max_weight`, a stall (the region grows, else the SJ floor is relaxed, else the run ends)
  int stall_iterations = 4;
  /// called after every accepted step (never with an invalid mesh)
  std::function<void(const Pull_back_step&)> on_step;
  /// when given, each boundary vertex is pulled toward its own position in
  /// this array (held like a corner), not toward its projection onto the
  /// target surface: the paper's SLIM pull-back aims at the input's vertices
  const std::vector<Vec3>* fixed_anchors = nullptr;
};

struct Pull_back_report
{
  /// max over boundary vertices of the distance to the anchor, in the units of `points`
  double distance_before = 0., distance_after = 0.;
  double mean_edge_length = 0.;
  int iterations = 0;
  bool reached = false;
  /// minimum 9-point scaled Jacobian over the whole mesh
  double min_sj_before = 0., min_sj_after = 0.;
  std::size_t displaced_vertices = 0; ///< boundary vertices farther than the tolerance at the start
  std::size_t max_free_vertices = 0;  ///< size of the largest region optimised
  int region_growths = 0;
  bool snapped = false;
  long conjugate_gradient_iterations = 0; ///< total, over all SLIM iterations
  double seconds = 0.;
};

class Pull_back_solver
{
  typedef Eigen::Matrix3d M3;
  typedef Eigen::Vector3d V3;

public:
  Pull_back_solver(const Hex_mesh_topology& topo, const Target_surface& ts, const Pull_back_settings& s)
    : m_topo(topo), m_ts(ts), m_s(s)
  {}

  Pull_back_report run(std::vector<Vec3>& points)
  {
    const Clock::time_point start = Clock::now();
    Pull_back_report rep;
    std::vector<double> dist;
    const double tol = set_up(points, dist, rep);
    if(rep.distance_before <= tol || m_topo.hexes().empty())
    {
      rep.reached = true;
      try_snap(points, rep);
      rep.min_sj_after = global_min_sj(points);
      rep.distance_after = distances(points, dist);
      rep.seconds = seconds_since(start);
      return rep;
    }
    if(!(m_valid_min_sj > 0.)) // no valid element: nothing can be guaranteed, leave it
    {
      rep.seconds = seconds_since(start);
      return rep;
    }

    // every accepted state is valid; keep the one closest to the target
    // (score: max + mean distance, so that reachable vertices still count
    // when a few cannot reach)
    // the SJ floor starts at the input's minimum (never lower it) and is
    // relaxed towards min_sj_fraction × that minimum only when the run stalls
    Search s;
    s.fraction = (std::max)(1., m_s.min_sj_fraction);
    m_floor = (std::max)(0., s.fraction * m_valid_min_sj);
    s.best = points;
    s.best_score = rep.distance_before + m_mean_dist;
    s.w = m_s.initial_weight;
    s.rings = m_s.region_rings;
    for(;;)
    {
      build_region(points, dist, tol, s.rings);
      rep.max_free_vertices = (std::max)(rep.max_free_vertices, m_free.size());
      if(m_free.empty()) break;
      double d = rep.distance_before;
      const bool floor_stalled = descend(points, dist, tol, s, d);
      if(d <= tol || s.iteration >= m_s.max_iterations || out_of_time()) break;
      // stalled: relax the SJ floor if it is what blocks, else grow the region
      // first, then relax the floor
      const bool can_grow =
        s.rings >= 0 && s.growths < m_s.max_region_growths && m_hexes.size() < m_topo.hexes().size();
      if(floor_stalled || (!can_grow && s.fraction > m_s.min_sj_fraction))
      {
        s.fraction = (std::max)(m_s.min_sj_fraction, 0.5 * s.fraction);
        m_floor = (std::max)(0., s.fraction * m_valid_min_sj);
        continue; // same region, same weight, from the current state
      }
      if(!can_grow) break;
      s.rings = (std::max)(1, 2 * s.rings);
      ++s.growths;
      ++rep.region_growths;
      points = s.best;
      distances(points, dist);
      s.w = (std::max)(m_s.initial_weight, s.w * 1e-2);
    }
    m_snap_floor = m_floor;
    points = s.best;
    rep.iterations = s.iteration;
    try_snap(points, rep);
    rep.distance_after = distances(points, dist);
    rep.reached = rep.distance_after <= tol;
    rep.min_sj_after = global_min_sj(points);
    rep.conjugate_gradient_iterations = m_cg_iterations;
    rep.seconds = seconds_since(start);
    return rep;
  }

private:
  typedef std::chrono::steady_clock Clock;
  static double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }
  bool out_of_time() const { return time_limit_reached(m_s.time_limit); }

  /// the search's state across regions: weight, SJ floor fraction, best
  /// state and its score, region rings, iterations and region growths
  struct Search
  {
    double w = 0., fraction = 1., best_score = 0.;
    std::vector<Vec3> best;
    int rings = 0, iteration = 0, growths = 0;
  };

  /// the mean edge length, the start positions and the "before" figures of
  /// `rep`; returns the distance tolerance
  double set_up(const std::vector<Vec3>& points, std::vector<double>& dist, Pull_back_report& rep)
  {
    m_mean_edge = 0.;
    for(std::size_t e = 0; e < m_topo.number_of_edges(); ++e)
      m_mean_edge += norm(points[m_topo.edge(e)[0]] - points[m_topo.edge(e)[1]]);
    m_mean_edge /= double((std::max)(std::size_t(1), m_topo.number_of_edges()));
    rep.mean_edge_length = m_mean_edge;
    m_initial = points;
    rep.min_sj_before = global_min_sj(points);
    pin_invalid_hexes(points);
    rep.distance_before = distances(points, dist);
    rep.distance_after = rep.distance_before;
    rep.min_sj_after = rep.min_sj_before;
    const double tol = m_s.tolerance * m_mean_edge;
    for(double d : dist) if(d > tol) ++rep.displaced_vertices;
    m_snap_floor = (std::max)(0., m_valid_min_sj);
    return tol;
  }

  /// The hexes whose scaled Jacobian is not positive at the start (left
  /// inverted by the untangling) keep their vertices where they are: no
  /// region moves them, and the floors are relative to the least scaled
  /// Jacobian of the others (`m_valid_min_sj`). Without this, one such hex
  /// keeps the whole pull-back from starting (no step keeps every sample
  /// determinant positive), and the boundary stays off its surface.
  void pin_invalid_hexes(const std::vector<Vec3>& points)
  {
    m_pinned.assign(points.size(), 0);
    m_valid_min_sj = std::numeric_limits<double>::max();
    for(const Hex& h : m_topo.hexes())
    {
      const double sj = scaled_jacobian(corners(points, h));
      if(sj > 0.) m_valid_min_sj = (std::min)(m_valid_min_sj, sj);
      else for(std::size_t v : h) m_pinned[v] = 1;
    }
    // the user's constrained vertices never move either
    for(std::size_t v = 0; v < points.size(); ++v)
      if(m_topo.is_constrained(v)) m_pinned[v] = 1;
  }

  /// SLIM iterations in the current region until the target is reached, the
  /// iterations run out, the weight stalls at its maximum, or the SJ floor
  /// keeps cutting the step (returns true: relax it); `d` is the distance
  /// reached
  bool descend(std::vector<Vec3>& points, std::vector<double>& dist, double tol, Search& s, double& d)
  {
    int since_gain = 0, floor_stall = 0;
    double ref_score = s.best_score;
    while(s.iteration < m_s.max_iterations && !out_of_time())
    {
      ++s.iteration;
      double step = 0.;
      const bool moved = iterate(points, s.w, step);
      d = distances(points, dist);
      if(moved && d + m_mean_dist < s.best_score)
      {
        s.best_score = d + m_mean_dist;
        s.best = points;
      }
      if(moved && m_s.on_step)
      {
        Pull_back_step ps;
        ps.iteration = s.iteration; ps.distance = d; ps.min_sj = m_last_min_sj;
        ps.weight = s.w; ps.step = step; ps.free_vertices = m_free.size();
        m_s.on_step(ps);
      }
      if(d <= tol) return false;
      // the SJ floor, not the energy, keeps cutting the step: relax it
      floor_stall = (m_floor_blocked && step < 0.05) ? floor_stall + 1 : 0;
      if(floor_stall >= 2 && s.fraction > m_s.min_sj_fraction) return true;
      if(!moved || step >= m_s.weight_growth_min_step) s.w = (std::min)(s.w * m_s.weight_growth, m_s.max_weight);
      if(s.best_score < 0.99 * ref_score) { ref_score = s.best_score; since_gain = 0; }
      else if(++since_gain >= m_s.stall_iterations)
      { // no progress: more weight, or, at the maximal weight, a stall
        if(s.w >= m_s.max_weight) return false;
        s.w = (std::min)(s.w * m_s.weight_growth, m_s.max_weight);
        since_gain = 0;
      }
    }
    return false;
  }

public:
  double global_min_sj(const std::vector<Vec3>& points) const
  {
    double m = std::numeric_limits<double>::max();
    for(const Hex& h : m_topo.hexes()) m = (std::min)(m, scaled_jacobian(corners(points, h)));
    return m;
  }

private:
  // ---------------------------------------------------------------- samples
  // sample s < 8: corner frame (columns p[n_k] − p[s]); s = 8: principal axes / 4 (scaled_jacobian.h)
  struct Sample_table
  {
    double g[9][8][3];
    Sample_table()
    {
      for(int s = 0; s < 9; ++s) for(int i = 0; i < 8; ++i) for(int k = 0; k < 3; ++k) g[s][i][k] = hex_frame_coefficient(s, i, k);
    }
  };
  static const Sample_table& table() { static const Sample_table t; return t; }

  static std::array<Vec3, 8> corners(const std::vector<Vec3>& p, const Hex& h)
  {
    std::array<Vec3, 8> c;
    for(int i = 0; i < 8; ++i) c[i] = p[h[i]];
    return c;
  }

  static M3 frame(const std::array<Vec3, 8>& p, int s)
  {
    const Sample_table& t = table();
    M3 j = M3::Zero();
    for(int i = 0; i < 8; ++i)
      for(int k = 0; k < 3; ++k)
      {
        const double g = t.g[s][i][k];
        if(g != 0.) for(int d = 0; d < 3; ++d) j(d, k) += g * p[i][d];
      }
    return j;
  }

  // ---------------------------------------------------------------- targets
  // distance of every boundary vertex to its anchor (0 for interior ones); returns the max
  double distances(const std::vector<Vec3>& points, std::vector<double>& dist)
  {
    update_anchors(points);
    dist.assign(points.size(), 0.);
    double m = 0., sum = 0.;
    for(std::size_t v : m_ts.boundary().vertices)
    {
      dist[v] = norm(points[v] - m_bc[v].anchor);
      m = (std::max)(m, dist[v]);
      sum += dist[v];
    }
    m_mean_dist = sum / double((std::max)(std::size_t(1), m_ts.boundary().vertices.size()));
    return m;
  }

  /// the boundary constraints at `points`: the target surface's, or the
  /// fixed anchors (`Pull_back_settings::fixed_anchors`)
  void update_anchors(const std::vector<Vec3>& points)
  {
    m_ts.update_constraints(points, m_bc);
    if(!m_s.fixed_anchors) return;
    for(std::size_t v : m_ts.boundary().vertices)
    {
      m_bc[v].type = Vertex_class::corner;
      m_bc[v].anchor = (*m_s.fixed_anchors)[v];
    }
  }

  M3 constraint_metric(const Boundary_constraint& c) const
  {
    const double tau = m_s.tangential_weight;
    const V3 d(c.direction[0], c.direction[1], c.direction[2]);
    switch(c.type)
    {
    case Vertex_class::regular: return d * d.transpose() + tau * M3::Identity();
    case Vertex_class::sharp: return M3::Identity() - (1. - tau) * d * d.transpose();
    default: return M3::Identity();
    }
  }

  // ---------------------------------------------------------------- region
  /// the region: the hexes within `rings` of the boundary vertices farther
  /// than `tol` from the target (all when rings < 0), its free vertices
  /// (all their hexes in it), their rest frames and the sparse pattern
  void build_region(const std::vector<Vec3>& points, const std::vector<double>& dist, double tol, int rings)
  {
    select_region(points, dist, tol, rings);
    compute_rest_frames();
    build_sparse_pattern();
    if(m_s.linear_solver == Pull_back_linear_solver::simplicial_ldlt)
      m_solver.analyzePattern(m_H);
  }

  void select_region(const std::vector<Vec3>& points, const std::vector<double>& dist, double tol, int rings)
  {
    const std::size_t nv = points.size(), nh = m_topo.number_of_hexes();
    const auto& hexes = m_topo.hexes();
    std::vector<char> in(nh, 0);
    if(rings < 0) std::fill(in.begin(), in.end(), 1);
    else
    {
      std::vector<char> seed(nv, 0);
      for(std::size_t v : m_ts.boundary().vertices) if(dist[v] > tol) seed[v] = 1;
      for(int r = 0; r <= rings; ++r)
      {
        for(std::size_t v = 0; v < nv; ++v)
          if(seed[v])
            for(auto c = m_topo.vertex_corners_begin(v); c != m_topo.vertex_corners_end(v); ++c) in[c->hex] = 1;
        for(std::size_t h = 0; h < nh; ++h) if(in[h]) for(std::size_t v : hexes[h]) seed[v] = 1;
      }
    }
    m_local.assign(nv, -1);
    m_free.clear();
    for(std::size_t v = 0; v < nv; ++v)
    {
      bool all = m_topo.vertex_corners_begin(v) != m_topo.vertex_corners_end(v) && !m_pinned[v];
      for(auto c = m_topo.vertex_corners_begin(v); c != m_topo.vertex_corners_end(v) && all; ++c) all = in[c->hex] != 0;
      if(all) { m_local[v] = int(m_free.size()); m_free.push_back(v); }
    }
    m_hexes.clear();
    for(std::size_t h = 0; h < nh; ++h)
    {
      if(!in[h]) continue;
      bool any = false;
      for(std::size_t v : hexes[h]) any = any || m_local[v] >= 0;
      if(any) m_hexes.push_back(h);
    }
  }

  /// rest frames (inverse), from the positions at the start of the pull-back
  void compute_rest_frames()
  {
    const auto& hexes = m_topo.hexes();
    m_rinv.resize(m_hexes.size());
    for(std::size_t i = 0; i < m_hexes.size(); ++i)
    {
      const std::array<Vec3, 8> p = corners(m_initial, hexes[m_hexes[i]]);
      if(m_s.rest_shape == Pull_back_rest_shape::ideal_cube)
      {
        double l = 0.;
        for(int k = 0; k < 12; ++k) l += norm(p[hex_edges[k][0]] - p[hex_edges[k][1]]);
        l /= 12.;
        for(int s = 0; s < 9; ++s) m_rinv[i][s] = (1. / l) * M3::Identity();
      }
      else
        for(int s = 0; s < 9; ++s) m_rinv[i][s] = frame(p, s).inverse();
    }
  }

  /// sparse pattern: 3×3 blocks between free vertices sharing a hex, and
  /// where each hex's vertex pairs go in it (m_block)
  void build_sparse_pattern()
  {
    const auto& hexes = m_topo.hexes();
    const std::size_t m = m_free.size();
    std::vector<std::vector<int> > nb(m);
    for(std::size_t h : m_hexes)
      for(std::size_t a : hexes[h])
        if(m_local[a] >= 0)
          for(std::size_t b : hexes[h])
            if(m_local[b] >= 0) nb[m_local[a]].push_back(m_local[b]);
    std::size_t nnz = 0;
    for(auto& l : nb) { std::sort(l.begin(), l.end()); l.erase(std::unique(l.begin(), l.end()), l.end()); nnz += 9 * l.size(); }
    m_H.resize(int(3 * m), int(3 * m));
    m_H.resizeNonZeros(Eigen::Index(nnz));
    int* outer = m_H.outerIndexPtr();
    int* inner = m_H.innerIndexPtr();
    int pos = 0;
    for(std::size_t j = 0; j < m; ++j)
      for(int dj = 0; dj < 3; ++dj)
      {
        outer[3 * j + dj] = pos;
        for(int i : nb[j]) for(int di = 0; di < 3; ++di) inner[pos++] = 3 * i + di;
      }
    outer[3 * m] = pos;
    std::fill(m_H.valuePtr(), m_H.valuePtr() + nnz, 0.);
    m_block.assign(m_hexes.size(), std::array<int, 64>());
    for(std::size_t i = 0; i < m_hexes.size(); ++i)
    {
      const Hex& hx = hexes[m_hexes[i]];
      for(int a = 0; a < 8; ++a)
        for(int b = 0; b < 8; ++b)
        {
          const int la = m_local[hx[a]], lb = m_local[hx[b]];
          if(la < 0 || lb < 0) { m_block[i][8 * a + b] = -1; continue; }
          // entry (3 la + di, 3 lb + dj) = outer[3 lb + dj] + 3 k + di, k = rank of la among lb's neighbours
          const auto& l = nb[lb];
          m_block[i][8 * a + b] = int(std::lower_bound(l.begin(), l.end(), la) - l.begin());
        }
    }
  }

  // ---------------------------------------------------------------- energy
  double sample_energy(const M3& f) const
  {
    const double det = f.determinant();
    if(!(det > 0.)) return std::numeric_limits<double>::infinity();
    const double sd = f.squaredNorm() + f.inverse().squaredNorm();
    if(m_s.energy == Pull_back_energy::symmetric_dirichlet) return sd;
    return std::exp(m_s.exp_factor * (sd - 6.));
  }

  // energy of the region at positions x of the free vertices (others from points)
  double energy(const std::vector<Vec3>& pts) const
  {
    const auto& hexes = m_topo.hexes();
    double e = 0.;
    for(std::size_t i = 0; i < m_hexes.size(); ++i)
    {
      const std::array<Vec3, 8> p = corners(pts, hexes[m_hexes[i]]);
      for(int s = 0; s < 9; ++s)
      {
        e += sample_energy(frame(p, s) * m_rinv[i][s]) / 9.;
        if(!std::isfinite(e)) return e;
      }
    }
    const double wl = m_w / (m_mean_edge * m_mean_edge);
    for(std::size_t v : m_free)
    {
      const Boundary_constraint& c = m_bc[v];
      if(c.type == Vertex_class::interior) continue;
      const Vec3 r3 = pts[v] - c.anchor;
      const V3 r(r3[0], r3[1], r3[2]);
      e += wl * r.dot(constraint_metric(c) * r);
    }
    return e;
  }

  // one SLIM iteration; false when no step could be taken
  bool iterate(std::vector<Vec3>& points, double w, double& step)
  {
    m_floor_blocked = false;
    m_w = w;
    Eigen::VectorXd rhs;
    assemble(points, w, rhs);
    Eigen::VectorXd xs;
    if(!solve(points, rhs, xs)) return false;
    std::vector<Vec3> dir(points.size(), Vec3{0., 0., 0.});
    for(std::size_t l = 0; l < m_free.size(); ++l)
    {
      const Vec3& x = points[m_free[l]];
      dir[m_free[l]] = Vec3{xs[3 * l] - x[0], xs[3 * l + 1] - x[1], xs[3 * l + 2] - x[2]};
    }
    return line_search(points, dir, step);
  }

  /// SLIM's weights of a frame F (reference frame already applied): WᵀW and
  /// WᵀW R, from the eigen-decomposition FᵀF = V Σ² Vᵀ (closed form, no SVD):
  /// with U Σ = F V, WᵀW = U diag(w²) Uᵀ = F V diag(w²/σ²) Vᵀ Fᵀ and
  /// WᵀW R = U diag(w²) Vᵀ = F V diag(w²/σ) Vᵀ, R = U Vᵀ the closest rotation
  /// (a nearly degenerate F, whose small σ the closed form loses, goes
  /// through a Jacobi SVD instead)
  struct Slim_weights
  {
    M3 ww;  ///< WᵀW
    M3 wwr; ///< WᵀW R
  };

  // (GCC 12 warns, wrongly, that Eigen's JacobiSVD of a 3×3 matrix may read
  // uninitialised singular values once inlined here)
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
  Slim_weights slim_weights(const M3& f) const
  {
    Eigen::SelfAdjointEigenSolver<M3> es;
    es.computeDirect(f.transpose() * f);
    M3 vv = es.eigenvectors();
    V3 sig;
    if(es.eigenvalues()[0] > 1e-6 * es.eigenvalues()[2])
      for(int k = 0; k < 3; ++k) sig[k] = std::sqrt(es.eigenvalues()[k]);
    else
    {
      Eigen::JacobiSVD<M3> svd(f, Eigen::ComputeFullV);
      vv = svd.matrixV();
      sig = svd.singularValues();
    }
    double scale = 1.;
    if(m_s.energy == Pull_back_energy::exp_symmetric_dirichlet)
    {
      const double sd = f.squaredNorm() + f.inverse().squaredNorm();
      scale = m_s.exp_factor * std::exp(m_s.exp_factor * (sd - 6.));
    }
    V3 a, b;
    for(int k = 0; k < 3; ++k)
    {
      const double x = (std::max)(sig[k], 1e-12);
      const double w2 = (std::min)(m_s.max_slim_weight, scale * (x + 1.) * (x * x + 1.) / (x * x * x));
      a[k] = w2 / (x * x);
      b[k] = w2 / x;
    }
    const M3 fv = f * vv;
    const M3 ww = fv * a.asDiagonal() * fv.transpose();
    const M3 wwr = fv * b.asDiagonal() * vv.transpose();
    return {ww, wwr};
  }
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

  /// the local step's system: the SLIM quadratic of every sample of the
  /// region's hexes (into m_H's values and `rhs`; fixed vertices to the
  /// right-hand side), plus the boundary constraints with weight w
  void assemble(const std::vector<Vec3>& points, double w, Eigen::VectorXd& rhs)
  {
    // m_bc holds the anchors of the current positions (distances() was called last)
    const auto& hexes = m_topo.hexes();
    const std::size_t m = m_free.size();
    double* val = m_H.valuePtr();
    std::fill(val, val + m_H.nonZeros(), 0.);
    const int* outer = m_H.outerIndexPtr();
    rhs = Eigen::VectorXd::Zero(Eigen::Index(3 * m));
    const Sample_table& t = table();
    for(std::size_t i = 0; i < m_hexes.size(); ++i)
    {
      const Hex& hx = hexes[m_hexes[i]];
      const std::array<Vec3, 8> p = corners(points, hx);
      for(int s = 0; s < 9; ++s)
      {
        const M3 f = frame(p, s) * m_rinv[i][s];
        const Slim_weights sw = slim_weights(f);
        const M3& ww = sw.ww;
        const M3& wwr = sw.wwr;
        // D = G R⁻¹ (8×3)
        Eigen::Matrix<double, 8, 3> g;
        for(int a = 0; a < 8; ++a) for(int k = 0; k < 3; ++k) g(a, k) = t.g[s][a][k];
        const Eigen::Matrix<double, 8, 3> dm = g * m_rinv[i][s];
        const double vol = 1. / 9.;
        for(int a = 0; a < 8; ++a)
        {
          if(dm.row(a).squaredNorm() == 0.) continue;
          const int la = m_local[hx[a]];
          if(la < 0) continue;
          rhs.segment<3>(3 * la) += vol * wwr * dm.row(a).transpose();
          for(int b = 0; b < 8; ++b)
          {
            const double c = vol * dm.row(a).dot(dm.row(b));
            if(c == 0.) continue;
            const int k = m_block[i][8 * a + b];
            if(k < 0)
            { // b fixed: to the right-hand side
              const Vec3& xb = p[b];
              rhs.segment<3>(3 * la) -= c * (ww * V3(xb[0], xb[1], xb[2]));
              continue;
            }
            const int lb = m_local[hx[b]];
            for(int dj = 0; dj < 3; ++dj)
            {
              double* col = val + outer[3 * lb + dj] + 3 * k;
              for(int di = 0; di < 3; ++di) col[di] += c * ww(di, dj);
            }
          }
        }
      }
    }
    const double wl = w / (m_mean_edge * m_mean_edge);
    for(std::size_t l = 0; l < m; ++l)
    {
      const Boundary_constraint& c = m_bc[m_free[l]];
      if(c.type == Vertex_class::interior) continue;
      const M3 mm = wl * constraint_metric(c);
      const int k = diagonal_rank(l);
      for(int dj = 0; dj < 3; ++dj)
      {
        double* col = val + outer[3 * l + dj] + 3 * k;
        for(int di = 0; di < 3; ++di) col[di] += mm(di, dj);
      }
      rhs.segment<3>(3 * l) += mm * V3(c.anchor[0], c.anchor[1], c.anchor[2]);
    }
  }

  /// solves m_H xs = rhs (sparse LDLᵀ, or conjugate gradients from the
  /// current positions); false when it fails or gives a non-finite value
  bool solve(const std::vector<Vec3>& points, const Eigen::VectorXd& rhs, Eigen::VectorXd& xs)
  {
    if(m_s.linear_solver == Pull_back_linear_solver::simplicial_ldlt)
    {
      m_solver.factorize(m_H);
      if(m_solver.info() != Eigen::Success) return false;
      xs = m_solver.solve(rhs);
      if(m_solver.info() != Eigen::Success) return false;
    }
    else
    {
      const std::size_t m = m_free.size();
      Eigen::VectorXd x0(Eigen::Index(3 * m));
      for(std::size_t l = 0; l < m; ++l)
        for(int d = 0; d < 3; ++d) x0[Eigen::Index(3 * l + d)] = points[m_free[l]][d];
      m_cg.setTolerance(m_s.cg_tolerance);
      m_cg.setMaxIterations(Eigen::Index(2000));
      m_cg.compute(m_H);
      xs = m_cg.solveWithGuess(rhs, x0);
      m_cg_iterations += long(m_cg.iterations());
    }
    return xs.allFinite();
  }

  /// the flip-avoiding step along `dir` (at most 0.8 of the first
  /// inversion, then halved) that lowers the energy and keeps every hex of
  /// the region above the SJ floor; sets `step` and returns true if found
  bool line_search(std::vector<Vec3>& points, const std::vector<Vec3>& dir, double& step)
  {
    const auto& hexes = m_topo.hexes();
    double amax = 1.25;
    for(std::size_t i = 0; i < m_hexes.size(); ++i)
    {
      const Hex& hx = hexes[m_hexes[i]];
      const std::array<Vec3, 8> p = corners(points, hx), d = corners(dir, hx);
      for(int s = 0; s < 9; ++s) amax = (std::min)(amax, first_root(frame(p, s), frame(d, s), amax));
    }
    double alpha = (std::min)(1., 0.8 * amax);
    const double e0 = energy(points);
    std::vector<Vec3> trial = points;
    for(int ls = 0; ls < 30; ++ls, alpha *= 0.5)
    {
      for(std::size_t v : m_free) trial[v] = points[v] + alpha * dir[v];
      const double e1 = energy(trial);
      if(!(e1 < e0)) continue;
      double msj = std::numeric_limits<double>::max();
      for(std::size_t h : m_hexes) msj = (std::min)(msj, scaled_jacobian(corners(trial, hexes[h])));
      if(!(msj >= m_floor) || !(msj > 0.)) { m_floor_blocked = true; continue; }
      for(std::size_t v : m_free) points[v] = trial[v];
      step = alpha;
      m_last_min_sj = msj;
      return true;
    }
    return false;
  }


  int diagonal_rank(std::size_t l) const
  {
    const int* outer = m_H.outerIndexPtr();
    const int* inner = m_H.innerIndexPtr();
    const int* b = inner + outer[3 * l];
    const int* e = inner + outer[3 * l + 1];
    return int(std::lower_bound(b, e, int(3 * l)) - b) / 3;
  }

  // the smallest α in (0, cap) with det(J + α D) = 0, or cap; det J > 0
  static double first_root(const M3& j, const M3& d, double cap)
  {
    const V3 j0 = j.col(0), j1 = j.col(1), j2 = j.col(2), d0 = d.col(0), d1 = d.col(1), d2 = d.col(2);
    const double c0 = j0.dot(j1.cross(j2));
    const double c1 = d0.dot(j1.cross(j2)) + j0.dot(d1.cross(j2)) + j0.dot(j1.cross(d2));
    const double c2 = j0.dot(d1.cross(d2)) + d0.dot(j1.cross(d2)) + d0.dot(d1.cross(j2));
    const double c3 = d0.dot(d1.cross(d2));
    auto p = [&](double a) { return ((c3 * a + c2) * a + c1) * a + c0; };
    if(!(c0 > 0.)) return 0.;
    // breakpoints: critical points of p in (0, cap)
    double pts[4];
    int n = 0;
    pts[n++] = 0.;
    const double qa = 3. * c3, qb = 2. * c2, qc = c1;
    double r[2];
    int nr = 0;
    if(std::abs(qa) > 1e-300)
    {
      const double disc = qb * qb - 4. * qa * qc;
      if(disc >= 0.)
      {
        const double sq = std::sqrt(disc);
        const double q = -0.5 * (qb + (qb >= 0. ? sq : -sq));
        r[nr++] = q / qa;
        if(q != 0.) r[nr++] = qc / q;
      }
    }
    else if(std::abs(qb) > 1e-300)
      r[nr++] = -qc / qb;
    if(nr == 2 && r[0] > r[1]) std::swap(r[0], r[1]);
    for(int k = 0; k < nr; ++k) if(r[k] > 0. && r[k] < cap) pts[n++] = r[k];
    pts[n++] = cap;
    for(int k = 0; k + 1 < n; ++k)
    {
      if(p(pts[k + 1]) > 0.) continue;
      double lo = pts[k], hi = pts[k + 1];
      for(int it = 0; it < 60 && hi - lo > 1e-6 * hi; ++it)
      {
        const double mid = 0.5 * (lo + hi);
        (p(mid) > 0. ? lo : hi) = mid;
      }
      return lo;
    }
    return cap;
  }

  // ---------------------------------------------------------------- snap
  // Moves the boundary vertices exactly onto their anchors where that keeps
  // every hex above the floor: all at once if possible, else vertex by vertex
  // (a few sweeps, full move then half, quarter).
  void try_snap(std::vector<Vec3>& points, Pull_back_report& rep)
  {
    if(!m_s.snap) return;
    const double floor = m_snap_floor;
    auto local_ok = [&](std::size_t v) { return keeps_sj_floor_around(m_topo, points, v, points[v], floor); };
    update_anchors(points);
    const std::vector<std::size_t>& bv = m_ts.boundary().vertices;
    {
      const std::vector<Vec3> saved = points;
      for(std::size_t v : bv) points[v] = m_bc[v].anchor;
      bool ok = true;
      for(std::size_t v : bv) if(!(ok = local_ok(v))) break;
      if(ok) { rep.snapped = true; return; }
      points = saved;
    }
    for(int sweep = 0; sweep < 3; ++sweep)
    {
      update_anchors(points);
      bool all = true;
      for(std::size_t v : bv)
      {
        const Vec3 p = points[v];
        if(squared_norm(p - m_bc[v].anchor) == 0.) continue;
        bool done = false;
        for(double a = 1.; a > 0.2 && !done; a *= 0.5)
        {
          points[v] = p + a * (m_bc[v].anchor - p);
          done = local_ok(v);
          if(done && a < 1.) all = false;
        }
        if(!done) { points[v] = p; all = false; }
      }
      if(all) { rep.snapped = true; return; }
    }
  }

  const Hex_mesh_topology& m_topo;
  const Target_surface& m_ts;
  Pull_back_settings m_s;
  std::vector<Vec3> m_initial;
  double m_mean_edge = 1.;
  std::vector<Boundary_constraint> m_bc;
  std::vector<int> m_local;
  std::vector<std::size_t> m_free, m_hexes;
  std::vector<std::array<M3, 9> > m_rinv;
  std::vector<std::array<int, 64> > m_block;
  Eigen::SparseMatrix<double> m_H;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double> > m_solver;
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper, Pull_back_block_jacobi> m_cg;
  long m_cg_iterations = 0;
  bool m_floor_blocked = false;
  double m_floor = 0., m_snap_floor = 0., m_w = 1., m_last_min_sj = 0., m_mean_dist = 0.;
  double m_valid_min_sj = 0.;        // least scaled Jacobian of the hexes not pinned
  std::vector<char> m_pinned;        // per vertex: a vertex of a hex invalid at the start
};

/// Pulls the boundary of a valid hex mesh back onto the target surface
/// (Section 3.3) without ever inverting an element; see the comment at the
/// top of this file. `points` (the mesh vertices, in the coordinates of
/// `target`) is modified in place and always stays valid.
inline Pull_back_report pull_back_to_target(const Hex_mesh_topology& topo,
                                            const Target_surface& target,
                                            std::vector<Vec3>& points,
                                            const Pull_back_settings& settings = Pull_back_settings())
{
  Pull_back_solver solver(topo, target, settings);
  return solver.run(points);
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_UNTANGLING_PULL_BACK_H
