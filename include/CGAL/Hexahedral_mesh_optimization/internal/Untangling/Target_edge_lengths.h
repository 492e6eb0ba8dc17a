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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_UNTANGLING_TARGET_EDGE_LENGTHS_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_UNTANGLING_TARGET_EDGE_LENGTHS_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Target edge lengths of a region (Eq. 8 of the paper and the ξ rule).
//
// Eq. 8 asks parallel edges to have equal lengths: the four parallel edges of
// a hex, and two edges that continue each other straight through a vertex
// (pair terms with ideal angle π). It has no anchoring term, so its minimiser
// is not unique; here every edge is also pulled to its current length with
// weight 0.1 (edges with no free end: weight 10, so the region boundary
// keeps its sizes) — NOTES reading 4. The solution is then clamped from
// below by ξ·(mean boundary edge length) (NOTES reading 2: the paper's
// "ξ‖ē‖ if ‖e‖ ≤ ξ‖ē‖" is a minimum-length clamp). Edges outside the region
// keep their current length.

#include <CGAL/Hexahedral_mesh_optimization/internal/Untangling/Edge_angle_energy.h>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <unordered_map>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

/// Fills `length[e]` for the edges of the region's hexes; other entries are
/// left as they are.
inline void compute_target_edge_lengths(const Hex_mesh_topology& topo, const Ideal_angles& ideal,
                                        const Local_region& region, const Edge_angle_energy& energy,
                                        const std::vector<Vec3>& points, double min_length,
                                        std::vector<double>& length)
{
  std::unordered_map<std::size_t, int> local;
  std::vector<std::size_t> edges;
  for(std::size_t h : region.hexes)
    for(int k = 0; k < 12; ++k)
    {
      const std::size_t e = topo.hex_edge(h, k);
      if(local.emplace(e, static_cast<int>(edges.size())).second) edges.push_back(e);
    }
  const int n = static_cast<int>(edges.size());
  std::vector<Eigen::Triplet<double> > trip;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  auto add_difference = [&](int i, int j) {
    trip.emplace_back(i, i, 1.); trip.emplace_back(j, j, 1.);
    trip.emplace_back(i, j, -1.); trip.emplace_back(j, i, -1.);
  };
  for(std::size_t h : region.hexes)
    for(const auto& g : hex_parallel_edges)
      for(int a = 0; a < 4; ++a)
        add_difference(local[topo.hex_edge(h, g[a])], local[topo.hex_edge(h, g[(a + 1) % 4])]);
  for(std::size_t v : region.free_vertices)
    for(auto p = ideal.pairs_of_vertex_begin(v); p != ideal.pairs_of_vertex_end(v); ++p)
    {
      const Angle_pair& ap = ideal.pairs()[*p];
      if(ap.ideal_cos > -0.99) continue;
      const auto ia = local.find(topo.edge_id(ap.v, ap.a)), ib = local.find(topo.edge_id(ap.v, ap.b));
      if(ia != local.end() && ib != local.end()) add_difference(ia->second, ib->second);
    }
  for(int i = 0; i < n; ++i)
  {
    const auto& ed = topo.edge(edges[i]);
    const double current = norm(points[ed[0]] - points[ed[1]]);
    const double w = (energy.is_free(ed[0]) || energy.is_free(ed[1])) ? 0.1 : 10.;
    trip.emplace_back(i, i, w);
    rhs[i] += w * current;
  }
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(trip.begin(), trip.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double> > solver(a);
  Eigen::VectorXd l = solver.solve(rhs);
  for(int i = 0; i < n; ++i)
    length[edges[i]] = (std::max)(l[i], min_length);
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_UNTANGLING_TARGET_EDGE_LENGTHS_H
