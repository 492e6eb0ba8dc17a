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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_UNTANGLING_AUTHORS_EDGE_ANGLE_ENERGY_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_UNTANGLING_AUTHORS_EDGE_ANGLE_ENERGY_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The edge-angle energy as the authors' public code linearises it (read for
// `Method::paper`; written here from that reading, not copied). Every row is
// a scalar cosine row between two edges e1 = (c, x1) and e2 = (c, x2) that
// share the vertex c, with e2's direction n2 = (x_c - x_2)/|x_c - x_2| frozen
// at the current positions:
//     n2 · (x_c - x_1) / l1 = b
//  * b = 0 for two edges of one face of the region (orthogonality), each
//    ordered pair once;
//  * b = -1 for two edges at a vertex that share no face of the region
//    (straightness);
//  * around an irregular edge of valence 3, b = -1/2 for two of the edges
//    across it at one vertex; of valence 5, b = cos 72° for two in one hex,
//    cos 144° otherwise, with weight 2 once the step is below 1/2, 10 once
//    nothing in the region is below the target. "Irregular": an edge on the
//    region's surface with other than 2 hexes, inside with other than 4.
// l1 is the target length of e1 at the first iteration (`first_lengths`: a
// least-squares fit of the region's lengths to the mean edge ē, the edges on
// its surface to their own lengths, parallel and consecutive edges and the
// edges across an irregular edge equal) and afterwards its current length,
// never below ξ ē. The boundary rows (Eq. 6) are β n·x = β n·v̄ on the
// tangent plane, α x = α v̄ at feature and corner vertices: their feature
// tangent carries no unit length, so its slide costs about as much as a
// corner's; α, β enter unsquared beside these rows. A regularisation μ,
// 1e-3 of a row of a mean edge, keeps the system definite. The normal
// equations are assembled and factorised at every iteration (the frozen
// directions change).

#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_topology.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Boundary_constraint.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Untangling/Local_region.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/scaled_jacobian.h>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <unordered_map>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

class Authors_edge_angle_energy
{
  struct Row
  {
    std::size_t c, x1, x2; // e1 = (c, x1) carries the unknowns, e2 = (c, x2) the frozen direction
    std::size_t e1;        // local index of e1
    double b;
    int kind;              // 0 orthogonality / straightness, 1 valence-3 or valence-5 row
  };

public:
  Authors_edge_angle_energy(const Hex_mesh_topology& topo, const Local_region& region) : m_region(region)
  {
    const auto& hexes = topo.hexes();
    for(std::size_t i = 0; i < region.free_vertices.size(); ++i) m_local.emplace(region.free_vertices[i], i);
    // the region's edges and faces
    auto edge_index = [&](std::size_t a, std::size_t b) {
      const std::pair<std::size_t, std::size_t> key(std::min(a, b), std::max(a, b));
      auto it = m_edge_of.find(key);
      if(it != m_edge_of.end()) return it->second;
      const std::size_t i = m_edges.size();
      m_edge_of.emplace(key, i);
      m_edges.push_back({key.first, key.second});
      return i;
    };
    std::map<std::array<std::size_t, 4>, std::pair<std::array<std::size_t, 4>, int> > faces; // sorted -> (cyclic, count)
    std::vector<std::vector<std::size_t> > edge_cells;
    for(std::size_t h : region.hexes)
    {
      for(int f = 0; f < 6; ++f)
      {
        std::array<std::size_t, 4> q = {hexes[h][hex_faces[f][0]], hexes[h][hex_faces[f][1]], hexes[h][hex_faces[f][2]],
                                         hexes[h][hex_faces[f][3]]};
        std::array<std::size_t, 4> key = q;
        std::sort(key.begin(), key.end());
        auto it = faces.find(key);
        if(it == faces.end()) faces.emplace(key, std::make_pair(q, 1));
        else ++it->second.second;
      }
      for(int e = 0; e < 12; ++e)
      {
        const std::size_t i = edge_index(hexes[h][hex_edges[e][0]], hexes[h][hex_edges[e][1]]);
        if(edge_cells.size() <= i) edge_cells.resize(i + 1);
        edge_cells[i].push_back(h);
      }
    }
    const std::size_t ne = m_edges.size();
    edge_cells.resize(ne);
    m_on_surface.assign(ne, 0);
    std::vector<std::vector<std::array<std::size_t, 4> > > edge_faces(ne);
    for(const auto& f : faces)
    {
      const std::array<std::size_t, 4>& q = f.second.first;
      for(int k = 0; k < 4; ++k)
      {
        const std::size_t e = edge_index(q[k], q[(k + 1) % 4]);
        edge_faces[e].push_back(q);
        if(f.second.second == 1) m_on_surface[e] = 1;
        // orthogonality at corner k: the face's two edges there, each way
        const std::size_t c = q[k], a = q[(k + 1) % 4], b = q[(k + 3) % 4];
        m_rows.push_back({c, a, b, edge_index(c, a), 0., 0});
        m_rows.push_back({c, b, a, edge_index(c, b), 0., 0});
      }
    }
    // the edges at each vertex
    std::unordered_map<std::size_t, std::vector<std::size_t> > vertex_edges;
    for(std::size_t e = 0; e < ne; ++e)
      for(std::size_t v : m_edges[e]) vertex_edges[v].push_back(e);
    auto in_a_face_with = [&](std::size_t e, std::size_t g) {
      for(const auto& q : edge_faces[e])
        for(int k = 0; k < 4; ++k)
          if(edge_index(q[k], q[(k + 1) % 4]) == g) return true;
      return false;
    };
    auto other = [&](std::size_t e, std::size_t v) { return m_edges[e][0] == v ? m_edges[e][1] : m_edges[e][0]; };
    // straightness, and the consecutive pairs of the target lengths
    for(std::size_t e = 0; e < ne; ++e)
      for(std::size_t c : m_edges[e])
        for(std::size_t g : vertex_edges[c])
          if(g != e && !in_a_face_with(e, g))
          {
            m_rows.push_back({c, other(e, c), other(g, c), e, -1., 0});
            m_equal.push_back({e, g});
          }
    // the irregular edges of valence 3 and 5
    for(std::size_t s = 0; s < ne; ++s)
    {
      const std::size_t n = edge_cells[s].size();
      const bool irregular = m_on_surface[s] ? n != 2 : n != 4;
      if(!irregular || (n != 3 && n != 5)) continue;
      std::vector<std::size_t> across; // the edges of its faces at one of its ends
      for(const auto& q : edge_faces[s])
        for(int k = 0; k < 4; ++k)
        {
          const std::size_t g = edge_index(q[k], q[(k + 1) % 4]);
          if(g == s) continue;
          const bool a = q[k] == m_edges[s][0] || q[k] == m_edges[s][1];
          const bool b = q[(k + 1) % 4] == m_edges[s][0] || q[(k + 1) % 4] == m_edges[s][1];
          if(a != b) across.push_back(g);
        }
      std::sort(across.begin(), across.end());
      across.erase(std::unique(across.begin(), across.end()), across.end());
      for(std::size_t i : across)
        for(std::size_t j : across)
        {
          if(i == j) continue;
          std::size_t c = m_edges[i][0];
          if(c != m_edges[j][0] && c != m_edges[j][1]) c = m_edges[i][1];
          if(c != m_edges[j][0] && c != m_edges[j][1]) continue;
          double b = -0.5;
          if(n == 5)
          {
            bool same_cell = false;
            for(std::size_t h : edge_cells[s])
            {
              const auto& hx = hexes[h];
              auto has = [&](std::size_t e) {
                return std::find(hx.begin(), hx.end(), m_edges[e][0]) != hx.end() &&
                       std::find(hx.begin(), hx.end(), m_edges[e][1]) != hx.end();
              };
              if(has(i) && has(j)) { same_cell = true; break; }
            }
            b = same_cell ? 0.309 : -0.809;
          }
          m_rows.push_back({c, other(i, c), other(j, c), i, b, 1});
          m_equal.push_back({i, j});
        }
    }
    // parallel edges of each hex, for the target lengths
    for(std::size_t h : region.hexes)
      for(const auto& g : hex_parallel_edges)
        for(int a = 0; a < 4; ++a)
          m_equal.push_back({edge_index(hexes[h][hex_edges[g[a]][0]], hexes[h][hex_edges[g[a]][1]]),
                             edge_index(hexes[h][hex_edges[g[(a + 1) % 4]][0]], hexes[h][hex_edges[g[(a + 1) % 4]][1]])});
  }

  /// mean length of the edges on the region's surface (ē)
  double mean_surface_edge(const std::vector<Vec3>& p) const
  {
    double sum = 0.;
    std::size_t n = 0;
    for(std::size_t e = 0; e < m_edges.size(); ++e)
      if(m_on_surface[e]) { sum += norm(p[m_edges[e][0]] - p[m_edges[e][1]]); ++n; }
    return n ? sum / double(n) : 1.;
  }

  /// the first iteration's target lengths (see the file's comment)
  std::vector<double> first_lengths(const std::vector<Vec3>& p, double mean) const
  {
    const std::size_t ne = m_edges.size();
    std::vector<Eigen::Triplet<double> > t;
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(ne);
    for(std::size_t e = 0; e < ne; ++e)
    {
      t.emplace_back(e, e, 1.);
      rhs[e] = m_on_surface[e] ? norm(p[m_edges[e][0]] - p[m_edges[e][1]]) : mean;
    }
    for(const auto& q : m_equal)
    {
      t.emplace_back(q[0], q[0], 1.); t.emplace_back(q[1], q[1], 1.);
      t.emplace_back(q[0], q[1], -1.); t.emplace_back(q[1], q[0], -1.);
    }
    Eigen::SparseMatrix<double> a(ne, ne);
    a.setFromTriplets(t.begin(), t.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double> > solver(a);
    const Eigen::VectorXd l = solver.solve(rhs);
    return std::vector<double>(l.data(), l.data() + ne);
  }

  /// One iteration: the least-squares positions of the free vertices (in
  /// region order) for the rows at `p`. `lengths`: the first iteration's
  /// target lengths, or empty for the current ones clamped at `min_length`.
  /// `singular_weight` weighs the valence-3 and valence-5 rows. Returns
  /// false if the factorisation fails.
  bool solve(const std::vector<Vec3>& p, const std::vector<Boundary_constraint>& bc, double alpha, double beta,
             const std::vector<double>& lengths, double min_length, double singular_weight, double mean,
             std::vector<Vec3>& out) const
  {
    const std::size_t nf = m_region.free_vertices.size();
    std::vector<Eigen::Triplet<double> > t;
    t.reserve(m_rows.size() * 18 + nf * 9);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(3 * nf);
    auto local = [&](std::size_t v) -> long {
      auto it = m_local.find(v);
      return it == m_local.end() ? -1 : long(it->second);
    };
    for(const Row& r : m_rows)
    {
      const long ic = local(r.c), i1 = local(r.x1);
      if(ic < 0 && i1 < 0) continue;
      Vec3 n2 = p[r.c] - p[r.x2];
      const double l2 = norm(n2);
      if(!(l2 > 0.)) continue;
      n2 = (1. / l2) * n2;
      double l1 = lengths.empty() ? (std::max)(norm(p[r.c] - p[r.x1]), min_length) : lengths[r.e1];
      if(!(l1 > 0.)) l1 = min_length > 0. ? min_length : mean;
      const double w = r.kind == 1 ? singular_weight : 1.;
      const Vec3 a = (w / l1) * n2;
      double target = w * r.b; // a·x_c - a·x_1 = target, fixed ends to the right
      if(ic < 0) target -= dot(a, p[r.c]);
      if(i1 < 0) target += dot(a, p[r.x1]);
      for(int d = 0; d < 3; ++d)
        for(int k = 0; k < 3; ++k)
        {
          const double aa = a[d] * a[k];
          if(ic >= 0) t.emplace_back(3 * ic + d, 3 * ic + k, aa);
          if(i1 >= 0) t.emplace_back(3 * i1 + d, 3 * i1 + k, aa);
          if(ic >= 0 && i1 >= 0)
          {
            t.emplace_back(3 * ic + d, 3 * i1 + k, -aa);
            t.emplace_back(3 * i1 + d, 3 * ic + k, -aa);
          }
        }
      for(int d = 0; d < 3; ++d)
      {
        if(ic >= 0) rhs[3 * ic + d] += a[d] * target;
        if(i1 >= 0) rhs[3 * i1 + d] -= a[d] * target;
      }
    }
    const double mu = 1e-3 / (mean * mean);
    for(std::size_t i = 0; i < nf; ++i)
    {
      const std::size_t v = m_region.free_vertices[i];
      for(int d = 0; d < 3; ++d)
      {
        t.emplace_back(3 * i + d, 3 * i + d, mu);
        rhs[3 * i + d] += mu * p[v][d];
      }
      const Boundary_constraint& b = bc[v];
      if(b.type == Vertex_class::regular)
      {
        const Vec3 n = b.direction;
        const double rn = dot(n, b.anchor);
        for(int d = 0; d < 3; ++d)
        {
          for(int k = 0; k < 3; ++k) t.emplace_back(3 * i + d, 3 * i + k, beta * beta * n[d] * n[k]);
          rhs[3 * i + d] += beta * beta * n[d] * rn;
        }
      }
      else if(b.type == Vertex_class::sharp || b.type == Vertex_class::corner)
        for(int d = 0; d < 3; ++d)
        {
          t.emplace_back(3 * i + d, 3 * i + d, alpha * alpha);
          rhs[3 * i + d] += alpha * alpha * b.anchor[d];
        }
    }
    Eigen::SparseMatrix<double> a(3 * nf, 3 * nf);
    a.setFromTriplets(t.begin(), t.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double> > solver(a);
    if(solver.info() != Eigen::Success) return false;
    const Eigen::VectorXd x = solver.solve(rhs);
    out.resize(nf);
    for(std::size_t i = 0; i < nf; ++i) out[i] = {x[3 * i], x[3 * i + 1], x[3 * i + 2]};
    return true;
  }

private:
  const Local_region& m_region;
  std::unordered_map<std::size_t, std::size_t> m_local;
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> m_edge_of;
  std::vector<std::array<std::size_t, 2> > m_edges;
  std::vector<char> m_on_surface;
  std::vector<Row> m_rows;
  std::vector<std::array<std::size_t, 2> > m_equal;
};

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_UNTANGLING_AUTHORS_EDGE_ANGLE_ENERGY_H
