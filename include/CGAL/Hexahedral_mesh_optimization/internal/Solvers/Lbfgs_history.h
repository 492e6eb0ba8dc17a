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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SOLVERS_LBFGS_HISTORY_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SOLVERS_LBFGS_HISTORY_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The memory of L-BFGS (Nocedal & Wright, "Numerical Optimization", 2nd ed.,
// Algorithm 7.4): the last m pairs s = x_{k+1} − x_k, y = g_{k+1} − g_k, and
// the two-loop recursion that applies the inverse Hessian approximation they
// define to a gradient. The initial approximation is γ D, D a diagonal
// preconditioner (the identity when none is given) and
// γ = s·y / (y·D y) of the newest pair. Line searches stay with the callers
// (`Barrier_untangler`, `Global_asj_smoother`): what a step may break
// differs between them.

#include <Eigen/Core>

#include <cstddef>
#include <deque>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

class Lbfgs_history
{
public:
  explicit Lbfgs_history(std::size_t capacity) : m_capacity(capacity) {}

  bool empty() const { return m_s.empty(); }
  void clear() { m_s.clear(); m_y.clear(); m_ys.clear(); }

  /// adds the pair of the last step; a pair with y·s ≤ 0 (no positive
  /// curvature along s) is left out, the oldest goes beyond the capacity
  void push(Eigen::VectorXd s, Eigen::VectorXd y)
  {
    const double ys = y.dot(s);
    if(ys <= 1e-300) return;
    m_s.push_back(std::move(s));
    m_y.push_back(std::move(y));
    m_ys.push_back(ys);
    if(m_s.size() > m_capacity) { m_s.pop_front(); m_y.pop_front(); m_ys.pop_front(); }
  }

  /// H g by the two-loop recursion; D g when there is no pair yet (the
  /// caller scales the first step). `diagonal`: D, or null for the identity.
  Eigen::VectorXd inverse_hessian_times(const Eigen::VectorXd& g, const Eigen::VectorXd* diagonal = nullptr) const
  {
    Eigen::VectorXd q = g;
    std::vector<double> alpha(m_s.size());
    for(int i = static_cast<int>(m_s.size()) - 1; i >= 0; --i)
    {
      alpha[i] = m_s[i].dot(q) / m_ys[i];
      q -= alpha[i] * m_y[i];
    }
    if(diagonal) q = diagonal->cwiseProduct(q);
    if(!m_s.empty())
    {
      const double yDy = diagonal ? m_y.back().dot(diagonal->cwiseProduct(m_y.back())) : m_y.back().squaredNorm();
      q *= m_ys.back() / yDy;
    }
    for(std::size_t i = 0; i < m_s.size(); ++i)
    {
      const double beta = m_y[i].dot(q) / m_ys[i];
      q += (alpha[i] - beta) * m_s[i];
    }
    return q;
  }

private:
  std::size_t m_capacity;
  std::deque<Eigen::VectorXd> m_s, m_y;
  std::deque<double> m_ys; ///< y·s of each pair, read by both loops (each read was a pass over two vectors)
};

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SOLVERS_LBFGS_HISTORY_H
