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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_UNTANGLING_EDGE_ANGLE_ENERGY_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_UNTANGLING_EDGE_ANGLE_ENERGY_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The unified edge-angle energy (Eq. 5) plus the boundary energy (Eq. 6) on a
// local region, minimised by a local-global linearisation (Section 3.2.2).
//
// Local step. Every edge vector e = w - v at a vertex v gets target vectors:
//  * from each hex corner at v: the ideal tripod of that corner (Ideal_angles.h)
//    rotated onto the current three edges (orthogonal Procrustes with
//    det = +1); the target of edge k is L_k R t_k;
//  * from each pair term (edges 2+ steps apart around an axis): both edges
//    rotated symmetrically in their common plane until their angle is the
//    ideal one; the target of edge a is L_a a'.
// Global step. The linear least-squares problem
//     Σ |x_w - x_v - target|²  +  E_B  +  μ Σ |x - x_current|²
// over the free vertices, through its normal equations AᵀA x = Aᵀb.
//
// Choices where the paper is vague (see also ../../paper/NOTES.md):
//  * The paper freezes |e_i|, |e_j| and e_j and keeps the scalar row
//    <e_i/|e_i|, e_j/|e_j|> - â. Here the rows are vector rows in length
//    units (target edge vectors), so that the angle rows and the boundary
//    rows of Eq. 6 have the same units: with the mesh normalised to mean
//    edge length 0.025, α = β = 1000 then hold the surface firmly, and the
//    paper's halving schedule relaxes it gradually. With unitless angle rows
//    a boundary move of a whole edge costs little against them, and the
//    surface drifts.
//  * The tripod fit makes the local step orientation-aware: an inverted
//    corner has the same pairwise angles as its mirror image, but its
//    Procrustes rotation pulls it towards the positive tripod.
//  * The auxiliary variable a of the feature term of Eq. 6 is eliminated:
//    min_a α|d - a t|² + a² = α|P⊥ d|² + α/(α+1) (t·d)², so a sharp vertex
//    gets two rows of weight √α across the feature and one of weight
//    √(α/(α+1)) along it. Eq. 6's corner coefficient "a" is read as α.
//  * μ = 1e-3 (relative to the unit weight of an edge row) keeps AᵀA
//    non-singular when a free vertex has few rows (NOTES reading 7).
//  * Boundary anchors and directions are frozen during one local loop, so
//    AᵀA is factorised once per region and local loop; only Aᵀb changes.

#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Boundary_constraint.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_topology.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Untangling/Ideal_angles.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Untangling/Local_region.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <cmath>
#include <unordered_map>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

/// Orthogonal Procrustes with det = +1: the rotation R minimising
/// Σ_k |R t_k - u_k|², i.e. the rotational part of M = Σ_k u_k t_kᵀ.
/// Extracted iteratively as in Müller et al., "A robust method to extract the
/// rotational part of deformations" (MIG 2016): q is warm-started from the
/// previous solve of the same corner, which makes this much cheaper than a
/// 3x3 SVD and, unlike the SVD with a sign flip, continuous in M.
inline Eigen::Matrix3d best_rotation(const Tripod& t, const std::array<Vec3, 3>& u, Eigen::Quaterniond& q)
{
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  for(int k = 0; k < 3; ++k)
    m += Eigen::Vector3d(u[k][0], u[k][1], u[k][2]) * Eigen::Vector3d(t[k][0], t[k][1], t[k][2]).transpose();
  for(int it = 0; it < 30; ++it)
  {
    const Eigen::Matrix3d r = q.matrix();
    Eigen::Vector3d omega = r.col(0).cross(m.col(0)) + r.col(1).cross(m.col(1)) + r.col(2).cross(m.col(2));
    omega /= std::abs(r.col(0).dot(m.col(0)) + r.col(1).dot(m.col(1)) + r.col(2).dot(m.col(2))) + 1e-9;
    const double w = omega.norm();
    if(w < 1e-9) break;
    q = Eigen::Quaterniond(Eigen::AngleAxisd(w, (1. / w) * omega)) * q;
    q.normalize();
  }
  return q.matrix();
}

/// Rotates unit vectors a and b symmetrically in their plane so that their
/// angle becomes acos(ideal_cos).
inline void rotate_pair(const Vec3& a, const Vec3& b, double ideal_cos, Vec3& a2, Vec3& b2)
{
  Vec3 m = normalized(a + b), p = normalized(a - b);
  if(squared_norm(p) == 0.) // a == b: any direction across
  {
    const Vec3 any = std::abs(m[0]) < 0.9 ? Vec3{1., 0., 0.} : Vec3{0., 1., 0.};
    p = normalized(cross(m, any));
  }
  if(squared_norm(m) == 0.) // a == -b: any direction across
  {
    const Vec3 any = std::abs(p[0]) < 0.9 ? Vec3{1., 0., 0.} : Vec3{0., 1., 0.};
    m = normalized(cross(p, any));
  }
  const double half = 0.5 * std::acos((std::max)(-1., (std::min)(1., ideal_cos)));
  a2 = std::cos(half) * m + std::sin(half) * p;
  b2 = std::cos(half) * m - std::sin(half) * p;
}

/// Parameters of one local solve.
struct Energy_weights
{
  double alpha = 1000.;       ///< feature and corner constraint (Eq. 6)
  double beta = 1000.;        ///< tangent-plane constraint (Eq. 6)
  double pair_weight = 1.;    ///< weight of the pair terms relative to tripod rows
  double regularization = 1e-3;
};

/// The energy of one region: assembles and factorises the normal equations,
/// and solves them for the targets of the current positions.
class Edge_angle_energy
{
public:
  typedef Eigen::SparseMatrix<double> Matrix;

  Edge_angle_energy(const Hex_mesh_topology& topo, const Ideal_angles& ideal, const Local_region& region)
    : m_topo(topo), m_ideal(ideal), m_region(region)
  {
    for(std::size_t i = 0; i < region.free_vertices.size(); ++i)
      m_local.emplace(region.free_vertices[i], i);
    // pair terms at vertices of region hexes
    const auto& hexes = topo.hexes();
    std::unordered_map<std::size_t, char> vseen;
    for(std::size_t h : region.hexes)
      for(std::size_t v : hexes[h])
      {
        if(!vseen.emplace(v, 1).second) continue;
        for(auto p = ideal.pairs_of_vertex_begin(v); p != ideal.pairs_of_vertex_end(v); ++p)
        {
          const Angle_pair& ap = ideal.pairs()[*p];
          if(is_free(ap.v) || is_free(ap.a) || is_free(ap.b)) m_pairs.push_back(*p);
        }
      }
  }

  bool is_free(std::size_t v) const { return m_local.count(v) != 0; }
  std::size_t local_index(std::size_t v) const { return m_local.at(v); }

  /// Assembles AᵀA for the given boundary constraints and factorises it.
  bool factorize(const std::vector<Boundary_constraint>& bc, const Energy_weights& w)
  {
    m_weights = w;
    m_bc = &bc;
    const std::size_t n = 3 * m_region.free_vertices.size();
    std::vector<Eigen::Triplet<double> > trip;
    const auto& hexes = m_topo.hexes();
    auto add_edge_row = [&](std::size_t v, std::size_t x, double weight) {
      // row: weight (x_x - x_v), per coordinate
      const bool fv = is_free(v), fx = is_free(x);
      for(int d = 0; d < 3; ++d)
      {
        if(fv) trip.emplace_back(3 * local_index(v) + d, 3 * local_index(v) + d, weight * weight);
        if(fx) trip.emplace_back(3 * local_index(x) + d, 3 * local_index(x) + d, weight * weight);
        if(fv && fx)
        {
          trip.emplace_back(3 * local_index(v) + d, 3 * local_index(x) + d, -weight * weight);
          trip.emplace_back(3 * local_index(x) + d, 3 * local_index(v) + d, -weight * weight);
        }
      }
    };
    for(std::size_t h : m_region.hexes)
      for(int c = 0; c < 8; ++c)
        for(int k = 0; k < 3; ++k)
          add_edge_row(hexes[h][c], hexes[h][hex_corner_edges[c][k]], 1.);
    const double pw = std::sqrt(w.pair_weight);
    for(std::size_t p : m_pairs)
    {
      const Angle_pair& ap = m_ideal.pairs()[p];
      add_edge_row(ap.v, ap.a, pw);
      add_edge_row(ap.v, ap.b, pw);
    }
    for(std::size_t i = 0; i < m_region.free_vertices.size(); ++i)
    {
      const std::size_t v = m_region.free_vertices[i];
      for(int d = 0; d < 3; ++d)
        trip.emplace_back(3 * i + d, 3 * i + d, w.regularization);
      const Boundary_constraint& b = bc[v];
      for(const auto& row : boundary_rows(b))
        for(int r = 0; r < 3; ++r)
          for(int s = 0; s < 3; ++s)
            trip.emplace_back(3 * i + r, 3 * i + s, row[r] * row[s]);
    }
    Matrix ata(n, n);
    ata.setFromTriplets(trip.begin(), trip.end());
    m_solver.compute(ata);
    return m_solver.info() == Eigen::Success;
  }

  /// One local-global step from `points`; returns the least-squares positions
  /// of the free vertices (in region order). `length` gives the target length
  /// of each edge (by edge id).
  std::vector<Vec3> solve(const std::vector<Vec3>& points, const std::vector<double>& length)
  {
    if(m_rotations.size() != 8 * m_region.hexes.size())
      m_rotations.assign(8 * m_region.hexes.size(), Eigen::Quaterniond::Identity());
    const std::size_t nf = m_region.free_vertices.size();
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(3 * nf);
    const auto& hexes = m_topo.hexes();
    // row weight*(x_x - x_v) = weight*target: Aᵀb gets +w²·target at x and
    // -w²·target at v; fixed vertices move to the right-hand side.
    auto add_edge_target = [&](std::size_t v, std::size_t x, const Vec3& target, double w2) {
      const bool fv = is_free(v), fx = is_free(x);
      Vec3 t = target;
      if(!fx) t = t - points[x];           // x fixed: row is -x_v = t - x_x
      if(!fv) t = t + points[v];           // v fixed: row is x_x = t + x_v
      for(int d = 0; d < 3; ++d)
      {
        if(fx) rhs[3 * local_index(x) + d] += w2 * t[d];
        if(fv) rhs[3 * local_index(v) + d] -= w2 * t[d];
      }
    };
    for(std::size_t ri = 0; ri < m_region.hexes.size(); ++ri)
      for(int c = 0; c < 8; ++c)
      {
        const std::size_t h = m_region.hexes[ri];
        const std::size_t v = hexes[h][c];
        std::array<Vec3, 3> u;
        std::array<std::size_t, 3> nb;
        for(int k = 0; k < 3; ++k)
        {
          nb[k] = hexes[h][hex_corner_edges[c][k]];
          u[k] = normalized(points[nb[k]] - points[v]);
        }
        const Tripod& t = m_ideal.tripod(h, c);
        const Eigen::Matrix3d r = best_rotation(t, u, m_rotations[8 * ri + c]);
        for(int k = 0; k < 3; ++k)
        {
          const Eigen::Vector3d d = r * Eigen::Vector3d(t[k][0], t[k][1], t[k][2]);
          const double l = length[m_topo.hex_edge(h, edge_index(c, k))];
          add_edge_target(v, nb[k], Vec3{l * d[0], l * d[1], l * d[2]}, 1.);
        }
      }
    for(std::size_t p : m_pairs)
    {
      const Angle_pair& ap = m_ideal.pairs()[p];
      Vec3 a2, b2;
      rotate_pair(normalized(points[ap.a] - points[ap.v]), normalized(points[ap.b] - points[ap.v]),
                  ap.ideal_cos, a2, b2);
      add_edge_target(ap.v, ap.a, length[m_topo.edge_id(ap.v, ap.a)] * a2, m_weights.pair_weight);
      add_edge_target(ap.v, ap.b, length[m_topo.edge_id(ap.v, ap.b)] * b2, m_weights.pair_weight);
    }
    for(std::size_t i = 0; i < nf; ++i)
    {
      const std::size_t v = m_region.free_vertices[i];
      for(int d = 0; d < 3; ++d)
        rhs[3 * i + d] += m_weights.regularization * points[v][d];
      const Boundary_constraint& b = (*m_bc)[v];
      for(const auto& row : boundary_rows(b))
      {
        const double target = dot(row, b.anchor);
        for(int d = 0; d < 3; ++d)
          rhs[3 * i + d] += row[d] * target;
      }
    }
    const Eigen::VectorXd x = m_solver.solve(rhs);
    std::vector<Vec3> out(nf);
    for(std::size_t i = 0; i < nf; ++i)
      out[i] = {x[3 * i], x[3 * i + 1], x[3 * i + 2]};
    return out;
  }

private:
  /// local edge index (into hex_edges) of the edge from corner c to its k-th neighbour
  static int edge_index(int c, int k)
  {
    const int w = hex_corner_edges[c][k];
    for(int e = 0; e < 12; ++e)
      if((hex_edges[e][0] == c && hex_edges[e][1] == w) || (hex_edges[e][0] == w && hex_edges[e][1] == c))
        return e;
    return 0;
  }

  /// the rows of Eq. 6 for one vertex: unit directions scaled by √weight;
  /// each row reads row·x = row·anchor
  std::vector<Vec3> boundary_rows(const Boundary_constraint& b) const
  {
    std::vector<Vec3> rows;
    const double sa = std::sqrt(m_weights.alpha), sb = std::sqrt(m_weights.beta);
    switch(b.type)
    {
    case Vertex_class::interior: break;
    case Vertex_class::regular:
      rows.emplace_back(sb * b.direction);
      break;
    case Vertex_class::sharp:
    {
      const Vec3 t = normalized(b.direction);
      const Vec3 any = std::abs(t[0]) < 0.9 ? Vec3{1., 0., 0.} : Vec3{0., 1., 0.};
      const Vec3 u1 = normalized(cross(t, any)), u2 = cross(t, u1);
      rows.emplace_back(sa * u1);
      rows.emplace_back(sa * u2);
      rows.emplace_back(std::sqrt(m_weights.alpha / (m_weights.alpha + 1.)) * t);
      break;
    }
    case Vertex_class::corner:
      rows.push_back(Vec3{sa, 0., 0.});
      rows.push_back(Vec3{0., sa, 0.});
      rows.push_back(Vec3{0., 0., sa});
      break;
    }
    return rows;
  }

  const Hex_mesh_topology& m_topo;
  const Ideal_angles& m_ideal;
  const Local_region& m_region;
  std::unordered_map<std::size_t, std::size_t> m_local;
  std::vector<std::size_t> m_pairs;
  Energy_weights m_weights;
  const std::vector<Boundary_constraint>* m_bc = nullptr;
  Eigen::SimplicialLDLT<Matrix> m_solver;
  std::vector<Eigen::Quaterniond> m_rotations; // warm starts, one per region hex corner
};

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_UNTANGLING_EDGE_ANGLE_ENERGY_H
