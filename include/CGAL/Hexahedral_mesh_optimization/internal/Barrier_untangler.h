// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Package: Hexahedral_mesh_optimization

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_BARRIER_UNTANGLER_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_BARRIER_UNTANGLER_H

// The second untangling stage, for regions on which the edge-angle energy
// stalls: the regularised foldover-free energy of Garanzha, Kaporin, Kudryavtseva,
// Protais, Ray, Sokolov ("Foldover-free maps in 50 lines of code", 2021) on
// the 9 Jacobian samples of each hex (8 corner frames and the centre frame
// of principal axes — exactly the samples of the Verdict scaled Jacobian):
//
//     f_ε(J) = |J|²_F / χ(det J, ε)^(2/3),   χ(D, ε) = (D + √(ε² + D²)) / 2,
//
// plus the boundary energy of Eq. 6 (same rows as the edge-angle stage), by
// L-BFGS with a backtracking line search, with ε decreased between passes
// as in the reference (ε → 0 as the frames become positive). The
// untangling guarantee is kept by the caller: a region result is accepted
// only if it does not increase its number of inverted elements.

#include <CGAL/Hexahedral_mesh_optimization/internal/Boundary_constraint.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Hex_mesh_topology.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Local_region.h>

#include <Eigen/Dense>

#include <cmath>
#include <deque>
#include <unordered_map>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

class Barrier_untangler
{
public:
  Barrier_untangler(const Hex_mesh_topology& topo, const Local_region& region,
                    const std::vector<Boundary_constraint>& bc, double boundary_weight)
    : m_topo(topo), m_region(region), m_bc(bc), m_wb(boundary_weight)
  {
    for(std::size_t i = 0; i < region.free_vertices.size(); ++i) m_local.emplace(region.free_vertices[i], i);
  }

  /// Runs `passes` passes of L-BFGS on the free vertices of the region.
  void run(std::vector<Vec3>& points, int passes = 12, int iterations = 200)
  {
    const std::size_t n = 3 * m_region.free_vertices.size();
    Eigen::VectorXd x(n);
    for(std::size_t i = 0; i < m_region.free_vertices.size(); ++i)
      for(int d = 0; d < 3; ++d) x[3 * i + d] = points[m_region.free_vertices[i]][d];
    m_points = &points;
    // scale of a frame determinant: mean edge length cubed
    double mean_edge = 0.; std::size_t ne = 0;
    for(std::size_t h : m_region.hexes)
      for(int k = 0; k < 12; ++k, ++ne)
        mean_edge += norm(points[m_topo.hexes()[h][hex_edges[k][0]]] - points[m_topo.hexes()[h][hex_edges[k][1]]]);
    mean_edge /= (std::max)(std::size_t(1), ne);
    const double scale = mean_edge * mean_edge * mean_edge;
    for(int pass = 0; pass < passes; ++pass)
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

private:
  template <class F>
  void for_each_sample(const Eigen::VectorXd& x, F f) const
  {
    const auto& hexes = m_topo.hexes();
    for(std::size_t h : m_region.hexes)
    {
      std::array<Vec3, 8> p;
      for(int i = 0; i < 8; ++i) p[i] = position(x, hexes[h][i]);
      for(int c = 0; c < 8; ++c)
      {
        // corner frame: columns p[n_k] - p[c]; weights (+1 at n_k, -1 at c)
        std::array<std::array<double, 8>, 3> w{};
        for(int k = 0; k < 3; ++k) { w[k][hex_corner_edges[c][k]] += 1.; w[k][c] -= 1.; }
        f(h, p, w);
      }
      // centre frame: principal axes / 4
      static const int plus[3][4] = {{1, 2, 5, 6}, {2, 3, 6, 7}, {4, 5, 6, 7}};
      static const int minus[3][4] = {{0, 3, 4, 7}, {0, 1, 4, 5}, {0, 1, 2, 3}};
      std::array<std::array<double, 8>, 3> w{};
      for(int k = 0; k < 3; ++k)
        for(int i = 0; i < 4; ++i) { w[k][plus[k][i]] += 0.25; w[k][minus[k][i]] -= 0.25; }
      f(h, p, w);
    }
  }

  static Eigen::Matrix3d frame(const std::array<Vec3, 8>& p, const std::array<std::array<double, 8>, 3>& w)
  {
    Eigen::Matrix3d j = Eigen::Matrix3d::Zero();
    for(int k = 0; k < 3; ++k)
      for(int i = 0; i < 8; ++i)
        if(w[k][i] != 0.)
          for(int d = 0; d < 3; ++d) j(d, k) += w[k][i] * p[i][d];
    return j;
  }

  double minimum_determinant(const Eigen::VectorXd& x) const
  {
    double m = std::numeric_limits<double>::max();
    for_each_sample(x, [&](std::size_t, const std::array<Vec3, 8>& p, const std::array<std::array<double, 8>, 3>& w) {
      m = (std::min)(m, frame(p, w).determinant());
    });
    return m;
  }

  Vec3 position(const Eigen::VectorXd& x, std::size_t v) const
  {
    auto it = m_local.find(v);
    if(it == m_local.end()) return (*m_points)[v];
    return {x[3 * it->second], x[3 * it->second + 1], x[3 * it->second + 2]};
  }

  double energy(const Eigen::VectorXd& x, Eigen::VectorXd* grad) const
  {
    if(grad) grad->setZero(x.size());
    double e = 0.;
    const auto& hexes = m_topo.hexes();
    for_each_sample(x, [&](std::size_t h, const std::array<Vec3, 8>& p, const std::array<std::array<double, 8>, 3>& w) {
      const Eigen::Matrix3d j = frame(p, w);
      const double det = j.determinant();
      const double root = std::sqrt(m_eps * m_eps + det * det);
      const double chi = 0.5 * (det + root);
      const double f2 = j.squaredNorm();
      const double c23 = std::pow(chi, -2. / 3.);
      e += f2 * c23;
      if(!grad) return;
      const double dchi = 0.5 * (1. + det / root);
      Eigen::Matrix3d cof;
      cof.col(0) = j.col(1).cross(j.col(2));
      cof.col(1) = j.col(2).cross(j.col(0));
      cof.col(2) = j.col(0).cross(j.col(1));
      const Eigen::Matrix3d g = 2. * c23 * j - (2. / 3.) * f2 * c23 / chi * dchi * cof;
      for(int i = 0; i < 8; ++i)
      {
        auto it = m_local.find(hexes[h][i]);
        if(it == m_local.end()) continue;
        for(int k = 0; k < 3; ++k)
          if(w[k][i] != 0.)
            for(int d = 0; d < 3; ++d) (*grad)[3 * it->second + d] += w[k][i] * g(d, k);
      }
    });
    // boundary energy (Eq. 6), weighted relative to the frame energy's scale
    for(std::size_t i = 0; i < m_region.free_vertices.size(); ++i)
    {
      const Boundary_constraint& b = m_bc[m_region.free_vertices[i]];
      if(b.type == Vertex_class::interior) continue;
      const Vec3 d = Vec3{x[3 * i], x[3 * i + 1], x[3 * i + 2]} - b.anchor;
      Vec3 r = d; // corner: the whole displacement
      if(b.type == Vertex_class::regular) r = dot(d, b.direction) * b.direction;
      else if(b.type == Vertex_class::sharp) r = d - dot(d, b.direction) * b.direction;
      e += m_wb * squared_norm(r);
      if(grad) for(int k = 0; k < 3; ++k) (*grad)[3 * i + k] += 2. * m_wb * r[k];
    }
    return e;
  }

  void lbfgs(Eigen::VectorXd& x, int iterations) const
  {
    std::deque<Eigen::VectorXd> s_hist, y_hist;
    Eigen::VectorXd g, g_new;
    double e = energy(x, &g);
    for(int it = 0; it < iterations; ++it)
    {
      // two-loop recursion
      Eigen::VectorXd q = g;
      std::vector<double> alpha(s_hist.size());
      for(int i = static_cast<int>(s_hist.size()) - 1; i >= 0; --i)
      {
        alpha[i] = s_hist[i].dot(q) / y_hist[i].dot(s_hist[i]);
        q -= alpha[i] * y_hist[i];
      }
      if(!s_hist.empty()) q *= s_hist.back().dot(y_hist.back()) / y_hist.back().squaredNorm();
      else q *= 1e-4 / (std::max)(g.norm(), 1e-300) ;
      for(std::size_t i = 0; i < s_hist.size(); ++i)
      {
        const double beta = y_hist[i].dot(q) / y_hist[i].dot(s_hist[i]);
        q += (alpha[i] - beta) * s_hist[i];
      }
      Eigen::VectorXd dir = -q;
      if(dir.dot(g) >= 0.) dir = -g * 1e-4 / (std::max)(g.norm(), 1e-300);
      double step = 1., e_new = 0.;
      Eigen::VectorXd x_new;
      bool ok = false;
      for(int ls = 0; ls < 30; ++ls, step *= 0.5)
      {
        x_new = x + step * dir;
        e_new = energy(x_new, &g_new);
        if(std::isfinite(e_new) && e_new <= e + 1e-4 * step * dir.dot(g)) { ok = true; break; }
      }
      if(!ok) break;
      s_hist.push_back(x_new - x); y_hist.push_back(g_new - g);
      if(y_hist.back().dot(s_hist.back()) <= 1e-300) { s_hist.pop_back(); y_hist.pop_back(); }
      if(s_hist.size() > 7) { s_hist.pop_front(); y_hist.pop_front(); }
      const double de = e - e_new;
      x = x_new; g = g_new; e = e_new;
      if(de < 1e-12 * (std::abs(e) + 1.)) break;
    }
  }

  void write(const Eigen::VectorXd& x, std::vector<Vec3>& points) const
  {
    for(std::size_t i = 0; i < m_region.free_vertices.size(); ++i)
      points[m_region.free_vertices[i]] = {x[3 * i], x[3 * i + 1], x[3 * i + 2]};
  }

  const Hex_mesh_topology& m_topo;
  const Local_region& m_region;
  const std::vector<Boundary_constraint>& m_bc;
  double m_wb;
  double m_eps = 1.;
  std::unordered_map<std::size_t, std::size_t> m_local;
  const std::vector<Vec3>* m_points = nullptr;
};

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_BARRIER_UNTANGLER_H
