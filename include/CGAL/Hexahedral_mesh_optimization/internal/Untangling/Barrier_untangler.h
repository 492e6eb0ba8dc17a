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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_UNTANGLING_BARRIER_UNTANGLER_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_UNTANGLING_BARRIER_UNTANGLER_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The foldover-free energy of Garanzha, Kaporin, Kudryavtseva, Protais, Ray,
// Sokolov ("Foldover-free maps in 50 lines of code", 2021) on the 9 Jacobian
// samples of each hex (8 corner frames and the centre frame of principal
// axes — exactly the samples of the Verdict scaled Jacobian):
//
//     f_ε(J) = |J|²_F / χ(det J, ε)^(2/3),   χ(D, ε) = (D + √(ε² + D²)) / 2,
//
// optionally plus the paper's volume term, θ (d² + 1) / χ(d, ε / s) with
// d = det J / s, s the cube of the region's mean edge length
// (`set_volume_weight`), and the boundary energy of Eq. 6 (same rows as the
// edge-angle stage), minimised by L-BFGS with a backtracking line search.
// The shape term alone does not depend on a frame's size, and while ε > 0 a
// frame much smaller than ε costs less the smaller it gets: a frame the
// shape term cannot untangle can collapse instead (see
// `Optimization_schedule::barrier_volume_weight`). The volume term makes
// that cost more than untangling it. Two uses:
//
// * `run()` — untangling: ε decreased between passes as in the reference
//   (ε → 0 as the frames become positive). The untangling guarantee is kept
//   by the caller: a region result is accepted only if it does not increase
//   its number of inverted elements.
// * `run_injective()` — from a configuration whose 9 frames per hex are all
//   positive, ε = 0: f is +∞ as soon as a frame degenerates, and the line
//   search rejects such steps, so no hex of the region can invert (the
//   frames' determinants have the sign of the Verdict scaled Jacobian
//   samples). With a strong boundary weight it pulls the boundary back
//   toward the target surface after untangling.
//
// Speed: the energy loop reads, per region hex, the 8 local indices
// precomputed once (free vertex index, or a slot of the cached fixed
// positions) — no hash lookups in the hot loop — and the frames are
// differences of the 8 corners, written out by hand. The run's time limit,
// a hard stop, ends the L-BFGS iterations (the result so far is kept: every
// accepted iterate lowers the energy).

#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Boundary_constraint.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_topology.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Untangling/Local_region.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/Time_limit.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/parallel_for_each_index.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/scaled_jacobian.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Solvers/Lbfgs_history.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

/// The median of the lengths of hex `p`'s four parallel edges along each of
/// its three directions (MEDIT order: 0-1, 0-3, 0-4): the box a hex with one
/// spoilt edge of four was meant to be.
inline void median_edge_lengths(const double p[8][3], double L[3])
{
  static const int parallel[3][4][2] = {{{0, 1}, {3, 2}, {4, 5}, {7, 6}},
                                        {{0, 3}, {1, 2}, {4, 7}, {5, 6}},
                                        {{0, 4}, {1, 5}, {2, 6}, {3, 7}}};
  for(int a = 0; a < 3; ++a)
  {
    double l[4];
    for(int e = 0; e < 4; ++e)
    {
      double q = 0.;
      for(int d = 0; d < 3; ++d)
      {
        const double t = p[parallel[a][e][1]][d] - p[parallel[a][e][0]][d];
        q += t * t;
      }
      l[e] = std::sqrt(q);
    }
    std::sort(l, l + 4);
    L[a] = 0.5 * (l[1] + l[2]);
  }
}

class Barrier_untangler
{
public:
  Barrier_untangler(const Hex_mesh_topology& topo, const Local_region& region,
                    const std::vector<Boundary_constraint>& bc, double boundary_weight)
    : m_topo(topo), m_region(region), m_bc(&bc), m_wb(boundary_weight)
  {}

  /// L-BFGS stops when this limit is reached (the iterate reached is kept)
  void set_time_limit(const Time_limit* limit) { m_time_limit = limit; }
  /// the boundary constraints and their weight (between passes of a pull-back)
  void set_boundary(const std::vector<Boundary_constraint>& bc, double weight) { m_bc = &bc; m_wb = weight; }
  /// weight of the sliding of a boundary vertex along its surface or feature
  /// line, away from where it was when the constraints were computed
  void set_sliding_weight(double w) { m_wt = w; }
  /// weight θ of the volume term (0, the default: the shape term alone)
  void set_volume_weight(double theta) { m_theta = theta; }
  /// Reference shapes: the frames of hex h with `use[h]` are measured
  /// against its frames at `points` (J W⁻¹, W scaled to determinant 1), so
  /// that such a hex costs least in the shape it has there (a thin box of a
  /// boundary layer stays a thin box) rather than as a cube; every other hex
  /// against the identity. Both vectors must outlive the runs; null: none.
  void set_reference_shapes(const std::vector<Vec3>* points, const std::vector<unsigned char>* use)
  {
    m_ref_points = points;
    m_ref_use = use;
  }

  /// Untangling: `passes` passes of L-BFGS on the free vertices of the region,
  /// ε shrinking as the worst frame becomes positive.
  void run(std::vector<Vec3>& points, int passes = 12, int iterations = 200)
  {
    Eigen::VectorXd x;
    setup(points, x);
    const double scale = m_scale;
    for(int pass = 0; pass < passes && !time_limit_reached(m_time_limit); ++pass)
    {
      const double min_det = minimum_determinant(x);
      // Garanzha et al.: ε large enough that the energy is finite and smooth,
      // shrinking as the worst frame becomes positive
      m_eps = (min_det < 0.) ? std::sqrt(1e-12 * scale * scale + 0.04 * min_det * min_det)
                             : 1e-3 * scale;
      lbfgs(x, iterations);
      if(min_det > 1e-3 * scale && minimum_determinant(x) > 1e-3 * scale) break;
    }
    write(x, points);
  }

  /// Injective descent (ε = 0) from positive frames; returns false, leaving
  /// `points` unchanged, if some frame of the region is not positive at the
  /// start. Otherwise every frame stays positive.
  bool run_injective(std::vector<Vec3>& points, int iterations)
  {
    Eigen::VectorXd x;
    setup(points, x);
    if(!(minimum_determinant(x) > 0.)) return false;
    m_eps = 0.;
    lbfgs(x, iterations);
    write(x, points);
    return true;
  }

  /// The energy with the region's free vertices at `points`, the given ε
  /// (0: the injective energy) and the volume term's frame size
  /// `frame_scale` (a run takes the region's mean edge length cubed at its
  /// start), and its gradient, 3 coordinates per free vertex in the order
  /// of `free_vertices` (for the tests of the analytic gradient)
  double energy_at(const std::vector<Vec3>& points, double eps, double frame_scale, Eigen::VectorXd& gradient)
  {
    Eigen::VectorXd x;
    setup(points, x);
    m_scale = frame_scale;
    m_eps = eps;
    return energy(x, &gradient);
  }

private:
  void setup(const std::vector<Vec3>& points, Eigen::VectorXd& x)
  {
    const auto& hexes = m_topo.hexes();
    const std::size_t nf = m_region.free_vertices.size();
    m_fixed.clear();
    m_idx.resize(m_region.hexes.size());
    // local index of every vertex of the region's hexes: free i >= 0, fixed
    // -1-slot (slots in order of first use). The free index of a vertex: a
    // binary search in the sorted free vertices, or for a region holding a
    // good part of the mesh, a table over all the vertices (one lookup per
    // corner instead of a search, where the table costs little more than
    // the region itself)
    const bool dense = nf > 0 && 8 * nf >= m_topo.number_of_vertices();
    std::vector<int> free_index(dense ? m_topo.number_of_vertices() : 0, absent);
    if(dense) for(std::size_t i = 0; i < nf; ++i) free_index[m_region.free_vertices[i]] = int(i);
    auto find = [&](std::size_t v) -> int {
      if(dense) return free_index[v];
      auto it = std::lower_bound(m_region.free_vertices.begin(), m_region.free_vertices.end(), v);
      return it != m_region.free_vertices.end() && *it == v ? int(it - m_region.free_vertices.begin()) : absent;
    };
    for(std::size_t r = 0; r < m_region.hexes.size(); ++r)
      for(int i = 0; i < 8; ++i)
      {
        const std::size_t v = hexes[m_region.hexes[r]][i];
        int id = find(v);
        if(id == absent)
        {
          id = -1 - int(m_fixed.size());
          m_fixed.push_back(points[v]);
        }
        m_idx[r][i] = id;
      }
    set_up_reference_frames();
    x.resize(3 * nf);
    for(std::size_t i = 0; i < nf; ++i)
      for(int d = 0; d < 3; ++d) x[3 * i + d] = points[m_region.free_vertices[i]][d];
    // scale of a frame determinant: mean edge length cubed
    double mean_edge = 0.; std::size_t ne = 0;
    for(std::size_t h : m_region.hexes)
      for(int k = 0; k < 12; ++k, ++ne)
        mean_edge += norm(points[hexes[h][hex_edges[k][0]]] - points[hexes[h][hex_edges[k][1]]]);
    mean_edge /= double((std::max)(std::size_t(1), ne));
    m_scale = mean_edge * mean_edge * mean_edge;
  }

  /// W⁻¹ of the 9 frames of each region hex with a reference shape, W at
  /// the reference points scaled to determinant 1 (`m_winv_of[r]` its slot,
  /// or -1: identity); a hex whose reference frames are not all positive gets none
  void set_up_reference_frames()
  {
    m_winv.clear();
    m_winv_of.assign(m_region.hexes.size(), -1);
    if(!m_ref_points || !m_ref_use) return;
    const auto& hexes = m_topo.hexes();
    for(std::size_t r = 0; r < m_region.hexes.size(); ++r)
    {
      const std::size_t h = m_region.hexes[r];
      if(!(*m_ref_use)[h]) continue;
      double p[8][3], W[9][3][3];
      for(int i = 0; i < 8; ++i) for(int d = 0; d < 3; ++d) p[i][d] = (*m_ref_points)[hexes[h][i]][d];
      if((*m_ref_use)[h] == 2) box_frames(p, W);
      else frames(p, W);
      std::array<std::array<std::array<double, 3>, 3>, 9> inv;
      bool ok = true;
      for(int s = 0; s < 9 && ok; ++s)
      {
        const double det = det3(W[s]);
        if(!(det > 0.)) { ok = false; break; }
        const double k = std::cbrt(det); // W / k has determinant 1
        const double (&w)[3][3] = W[s];
        // inverse of W / k = k · adj(W) / det
        const double f = k / det;
        inv[s][0][0] = f * (w[1][1] * w[2][2] - w[1][2] * w[2][1]);
        inv[s][0][1] = f * (w[0][2] * w[2][1] - w[0][1] * w[2][2]);
        inv[s][0][2] = f * (w[0][1] * w[1][2] - w[0][2] * w[1][1]);
        inv[s][1][0] = f * (w[1][2] * w[2][0] - w[1][0] * w[2][2]);
        inv[s][1][1] = f * (w[0][0] * w[2][2] - w[0][2] * w[2][0]);
        inv[s][1][2] = f * (w[0][2] * w[1][0] - w[0][0] * w[1][2]);
        inv[s][2][0] = f * (w[1][0] * w[2][1] - w[1][1] * w[2][0]);
        inv[s][2][1] = f * (w[0][1] * w[2][0] - w[0][0] * w[2][1]);
        inv[s][2][2] = f * (w[0][0] * w[1][1] - w[0][1] * w[1][0]);
      }
      if(!ok) continue;
      m_winv_of[r] = int(m_winv.size());
      m_winv.push_back(inv);
    }
  }

  /// the frames of the box whose edge length along each of the hex's three
  /// directions is the median of its four edges there at `p`: the ideal of a
  /// hex whose own frames are not valid (one pushed vertex spoils one edge of four)
  static void box_frames(const double p[8][3], double W[9][3][3])
  {
    double L[3];
    median_edge_lengths(p, L);
    // the direction of edge (u, v): 2 between the two faces 0-3 and 4-7,
    // else 0 for (0, 1) and (2, 3) in either face, 1 for (1, 2) and (3, 0)
    auto axis = [](int u, int v) { return (u - v == 4 || v - u == 4) ? 2 : (((u % 4) ^ (v % 4)) == 1 ? 0 : 1); };
    for(int s = 0; s < 9; ++s)
      for(int a = 0; a < 3; ++a) for(int b = 0; b < 3; ++b) W[s][a][b] = 0.;
    for(int c = 0; c < 8; ++c)
      for(int k = 0; k < 3; ++k) W[c][k][k] = L[axis(c, hex_corner_edges[c][k])];
    for(int k = 0; k < 3; ++k) W[8][k][k] = L[k];
  }

  void corners(const Eigen::VectorXd& x, std::size_t r, double p[8][3]) const
  {
    for(int i = 0; i < 8; ++i)
    {
      const int id = m_idx[r][i];
      if(id >= 0) { p[i][0] = x[3 * id]; p[i][1] = x[3 * id + 1]; p[i][2] = x[3 * id + 2]; }
      else { const Vec3& q = m_fixed[-1 - id]; p[i][0] = q[0]; p[i][1] = q[1]; p[i][2] = q[2]; }
    }
  }

  // the 9 frames of a hex: J[s] columns k (the kernel's frames,
  // `hex_frame_coefficient`, on raw coordinates)
  static void frames(const double p[8][3], double J[9][3][3])
  {
    for(int c = 0; c < 8; ++c)
      for(int k = 0; k < 3; ++k)
      {
        const int n = hex_corner_edges[c][k];
        for(int d = 0; d < 3; ++d) J[c][d][k] = p[n][d] - p[c][d];
      }
    for(int k = 0; k < 3; ++k)
      for(int d = 0; d < 3; ++d)
      {
        double s = 0.;
        for(int i = 0; i < 4; ++i) s += p[hex_axis_plus[k][i]][d] - p[hex_axis_minus[k][i]][d];
        J[8][d][k] = 0.25 * s;
      }
  }

  static double det3(const double a[3][3])
  {
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
         + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  }

  double hex_minimum_determinant(const Eigen::VectorXd& x, std::size_t r) const
  {
    double p[8][3], J[9][3][3];
    corners(x, r, p);
    frames(p, J);
    double m = std::numeric_limits<double>::max();
    for(int s = 0; s < 9; ++s) m = (std::min)(m, det3(J[s]));
    return m;
  }

  // per hex on all threads (a small region is one task), then the minimum
  // in hex order: the same on any number of threads
  double minimum_determinant(const Eigen::VectorXd& x) const
  {
    std::vector<double> d(m_region.hexes.size());
    parallel_for_each_index(d.size(), [&](std::size_t r) { d[r] = hex_minimum_determinant(x, r); }, 1024);
    double m = std::numeric_limits<double>::max();
    for(double v : d) m = (std::min)(m, v);
    return m;
  }


  /// regions of at least this many hexes evaluate their energy on all
  /// threads, this many hexes at a time (merged regions can hold a large part
  /// of the mesh; smaller ones are not worth the threads' overhead)
  static constexpr std::size_t parallel_energy_hexes = 4096;

  /// the frame energy of region hex r (infinity when injective and a frame
  /// is not positive) and, with `gp`, its gradient at the hex's 8 corners
  double hex_energy(const Eigen::VectorXd& x, std::size_t r, std::array<std::array<double, 3>, 8>* gp) const
  {
    double p[8][3], J[9][3][3];
    const bool injective = m_eps == 0.;
    double e = 0.;
    if(gp) for(auto& c : *gp) c = {0., 0., 0.};
    corners(x, r, p);
    frames(p, J);
    const int ref = m_winv_of.empty() ? -1 : m_winv_of[r];
    for(int s = 0; s < 9; ++s)
    {
      double jw[3][3]; // J W⁻¹ with a reference shape (the determinant is the same: det W⁻¹ = 1)
      if(ref >= 0)
      {
        const auto& wi = m_winv[std::size_t(ref)][s];
        for(int a = 0; a < 3; ++a)
          for(int b = 0; b < 3; ++b) jw[a][b] = J[s][a][0] * wi[0][b] + J[s][a][1] * wi[1][b] + J[s][a][2] * wi[2][b];
      }
      const double (&j)[3][3] = ref >= 0 ? jw : J[s];
      const double det = det3(j);
      double chi, dchi;
      if(injective)
      {
        if(!(det > 0.)) return std::numeric_limits<double>::infinity();
        chi = det; dchi = 1.;
      }
      else
      {
        const double root = std::sqrt(m_eps * m_eps + det * det);
        chi = 0.5 * (det + root);
        dchi = 0.5 * (1. + det / root);
      }
      double f2 = 0.;
      for(int a = 0; a < 3; ++a) for(int b = 0; b < 3; ++b) f2 += j[a][b] * j[a][b];
      const double c23 = 1. / std::cbrt(chi * chi); // chi^(-2/3), cheaper than std::pow on this hot path
      e += f2 * c23;
      // the volume term, in units of the region's frame size s = m_scale
      if(m_theta > 0.)
      {
        const double d = det / m_scale, cs = chi / m_scale;
        e += m_theta * (d * d + 1.) / cs;
      }
      if(!gp) continue;
      // cofactor matrix: d det / d J
      double cof[3][3];
      cof[0][0] = j[1][1] * j[2][2] - j[1][2] * j[2][1];
      cof[0][1] = j[1][2] * j[2][0] - j[1][0] * j[2][2];
      cof[0][2] = j[1][0] * j[2][1] - j[1][1] * j[2][0];
      cof[1][0] = j[0][2] * j[2][1] - j[0][1] * j[2][2];
      cof[1][1] = j[0][0] * j[2][2] - j[0][2] * j[2][0];
      cof[1][2] = j[0][1] * j[2][0] - j[0][0] * j[2][1];
      cof[2][0] = j[0][1] * j[1][2] - j[0][2] * j[1][1];
      cof[2][1] = j[0][2] * j[1][0] - j[0][0] * j[1][2];
      cof[2][2] = j[0][0] * j[1][1] - j[0][1] * j[1][0];
      const double a1 = 2. * c23;
      double a2 = (2. / 3.) * f2 * c23 / chi * dchi; // −∂e/∂det so far
      if(m_theta > 0.)
      {
        const double d = det / m_scale, cs = chi / m_scale;
        a2 -= m_theta * (2. * d / cs - (d * d + 1.) * dchi / (cs * cs)) / m_scale;
      }
      double g[3][3];
      for(int a = 0; a < 3; ++a) for(int b = 0; b < 3; ++b) g[a][b] = a1 * j[a][b] - a2 * cof[a][b];
      if(ref >= 0)
      {
        // ∂e/∂J = ∂e/∂(J W⁻¹) W⁻ᵀ
        const auto& wi = m_winv[std::size_t(ref)][s];
        double gj[3][3];
        for(int a = 0; a < 3; ++a)
          for(int b = 0; b < 3; ++b) gj[a][b] = g[a][0] * wi[b][0] + g[a][1] * wi[b][1] + g[a][2] * wi[b][2];
        for(int a = 0; a < 3; ++a) for(int b = 0; b < 3; ++b) g[a][b] = gj[a][b];
      }
      if(s < 8)
      {
        for(int k = 0; k < 3; ++k)
        {
          const int n = hex_corner_edges[s][k];
          for(int d = 0; d < 3; ++d) { (*gp)[n][d] += g[d][k]; (*gp)[s][d] -= g[d][k]; }
        }
      }
      else
      {
        for(int k = 0; k < 3; ++k)
          for(int i = 0; i < 4; ++i)
            for(int d = 0; d < 3; ++d)
            {
              (*gp)[hex_axis_plus[k][i]][d] += 0.25 * g[d][k];
              (*gp)[hex_axis_minus[k][i]][d] -= 0.25 * g[d][k];
            }
      }
    }
    return e;
  }

  double energy(const Eigen::VectorXd& x, Eigen::VectorXd* grad) const
  {
    if(grad) grad->setZero(x.size());
    double e = 0.;
    std::array<std::array<double, 3>, 8> gp;
    auto add = [&](std::size_t r, double term, const std::array<std::array<double, 3>, 8>& g) {
      e += term;
      if(!grad) return;
      for(int i = 0; i < 8; ++i)
      {
        const int id = m_idx[r][i];
        if(id < 0) continue;
        for(int d = 0; d < 3; ++d) (*grad)[3 * id + d] += g[i][d];
      }
    };
    const std::size_t n = m_region.hexes.size();
    if(n < parallel_energy_hexes)
    {
      // a small region, one of many run side by side: on its own thread
      for(std::size_t r = 0; r < n; ++r)
      {
        add(r, hex_energy(x, r, grad ? &gp : nullptr), gp);
        if(!std::isfinite(e)) return std::numeric_limits<double>::infinity();
      }
    }
    else
    {
      // in blocks: a block's hexes on all threads, then added in hex order
      // (the same sum whatever the number of threads)
      std::vector<double> term(parallel_energy_hexes);
      std::vector<std::array<std::array<double, 3>, 8> > gradient(grad ? parallel_energy_hexes : 0);
      for(std::size_t first = 0; first < n; first += parallel_energy_hexes)
      {
        const std::size_t count = (std::min)(parallel_energy_hexes, n - first);
        parallel_for_each_index(count, [&](std::size_t k) {
          term[k] = hex_energy(x, first + k, grad ? &gradient[k] : nullptr);
        }, 256);
        for(std::size_t k = 0; k < count; ++k) add(first + k, term[k], grad ? gradient[k] : gp);
        if(!std::isfinite(e)) return std::numeric_limits<double>::infinity();
      }
    }
    // boundary energy (Eq. 6), weighted relative to the frame energy's scale
    const std::vector<Boundary_constraint>& bcs = *m_bc;
    for(std::size_t i = 0; i < m_region.free_vertices.size(); ++i)
    {
      const Boundary_constraint& b = bcs[m_region.free_vertices[i]];
      if(b.type == Vertex_class::interior) continue;
      const Vec3 d = Vec3{x[3 * i], x[3 * i + 1], x[3 * i + 2]} - b.anchor;
      Vec3 r = d; // corner: the whole displacement
      if(b.type == Vertex_class::regular) r = dot(d, b.direction) * b.direction;
      else if(b.type == Vertex_class::sharp) r = d - dot(d, b.direction) * b.direction;
      const Vec3 t = d - r; // the sliding along the surface or the feature
      e += m_wb * squared_norm(r) + m_wt * squared_norm(t);
      if(grad) for(int k = 0; k < 3; ++k) (*grad)[3 * i + k] += 2. * (m_wb * r[k] + m_wt * t[k]);
    }
    return e;
  }

  void lbfgs(Eigen::VectorXd& x, int iterations) const
  {
    Lbfgs_history history(7);
    Eigen::VectorXd g, g_new, x_new;
    double e = energy(x, &g);
    if(!std::isfinite(e)) return;
    for(int it = 0; it < iterations; ++it)
    {
      if((it & 7) == 7 && time_limit_reached(m_time_limit)) break;
      Eigen::VectorXd q = history.inverse_hessian_times(g);
      if(history.empty()) q *= 1e-4 / (std::max)(g.norm(), 1e-300);
      Eigen::VectorXd dir = -q;
      if(dir.dot(g) >= 0.) dir = -g * 1e-4 / (std::max)(g.norm(), 1e-300);
      const double slope = dir.dot(g);
      double step = 1., e_new = 0.;
      bool ok = false;
      for(int ls = 0; ls < 30; ++ls, step *= 0.5)
      {
        x_new = x + step * dir;
        e_new = energy(x_new, &g_new);
        if(std::isfinite(e_new) && e_new <= e + 1e-4 * step * slope) { ok = true; break; }
      }
      if(!ok) break;
      history.push(x_new - x, g_new - g);
      const double de = e - e_new;
      x.swap(x_new); g.swap(g_new); e = e_new;
      // converged: the energy fell by less than this (relative). A large
      // region (see `parallel_energy_hexes`) stops at 1e-8: its last
      // iterations are long and untangle nothing more. Small regions keep
      // 1e-9: they are cheap, and the positions they end at are where the
      // quality stages start, so stopping them early costs MSJ later
      const double converged = m_region.hexes.size() < parallel_energy_hexes ? 1e-9 : 1e-8;
      if(de < converged * (std::abs(e) + 1.)) break;
    }
  }

  void write(const Eigen::VectorXd& x, std::vector<Vec3>& points) const
  {
    for(std::size_t i = 0; i < m_region.free_vertices.size(); ++i)
      points[m_region.free_vertices[i]] = {x[3 * i], x[3 * i + 1], x[3 * i + 2]};
  }

  const Hex_mesh_topology& m_topo;
  const Local_region& m_region;
  const std::vector<Boundary_constraint>* m_bc;
  double m_wb;
  double m_wt = 0.;
  double m_theta = 0.;
  double m_eps = 1.;
  double m_scale = 1.;
  const Time_limit* m_time_limit = nullptr;
  static constexpr int absent = std::numeric_limits<int>::min();
  std::vector<std::array<int, 8> > m_idx; // per region hex: free index, or -1-slot in m_fixed
  std::vector<Vec3> m_fixed;
  const std::vector<Vec3>* m_ref_points = nullptr;
  const std::vector<unsigned char>* m_ref_use = nullptr;
  std::vector<int> m_winv_of; // per region hex: slot in m_winv, or -1
  std::vector<std::array<std::array<std::array<double, 3>, 3>, 9> > m_winv;
};

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_UNTANGLING_BARRIER_UNTANGLER_H
