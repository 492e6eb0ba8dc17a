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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_UNTANGLING_IDEAL_ANGLES_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_UNTANGLING_IDEAL_ANGLES_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The ideal angles of the unified edge-angle energy (Eq. 5 of the paper),
// derived from the hex connectivity alone.
//
// The rule (the paper states it only for interior edges; this is how it is
// read and extended here):
//  * Take a vertex v and one of its edges (v,w), the "axis". The hexes around
//    the axis are ordered by walking from hex to hex through the faces that
//    contain the axis. At v, each of these hexes has two more edges; the walk
//    orders these edges into a closed cycle of n edges (interior axis of
//    valence n) or an open path of n+1 edges (axis on the boundary, n hexes).
//  * The angular step around the axis is Θ/n, with Θ = 2π for a closed cycle
//    and, for an open path, Θ = the interior dihedral angle of the target
//    surface at that edge (π on a smooth part; supplied by the caller for
//    feature edges; π/2 for an edge that has a single hex, which can only be
//    a convex feature). Two edges k+1 steps apart along the cycle / path have
//    the ideal angle (k+1)·Θ/n. For a regular interior edge (n = 4) this gives
//    π/2 between edges of different directions and π between edges of the
//    same direction, so orthogonality, straightness and the irregular-edge
//    term of the paper are one rule.
//  * Pairs one step apart always share a hex corner with the axis. They are
//    handled corner by corner: the 3 edges of a hex corner must form the
//    "ideal tripod" whose pairwise angles are the steps around the third
//    edge (for a regular corner: an orthonormal frame). Fitting a rotated
//    ideal tripod to the current corner is the local step of the
//    local-global solver (Edge_angle_energy.h); it is what lets the energy
//    tell an inverted corner from a valid one, which pairwise angles alone
//    cannot.
//  * Pairs two or more steps apart (straightness, the wider angles around an
//    irregular edge) are kept as pair terms. A pair reached from several axes
//    with different ideal angles gets the mean of their cosines (least
//    squares would average them anyway); a pair that also shares a hex corner
//    is left to the tripod.

#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_topology.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Boundary_constraint.h>

#include <cmath>
#include <map>
#include <tuple>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

/// An edge pair at a vertex with its ideal cosine (pairs 2+ steps apart).
struct Angle_pair
{
  std::size_t v, a, b; // edges (v,a) and (v,b)
  double ideal_cos;
};

/// Ideal tripod of a hex corner: unit columns t[0..2] for the edges to
/// hex_corner_edges[c][0..2], right-handed.
typedef std::array<Vec3, 3> Tripod;

/// Builds the unit tripod with pairwise angles g01, g02, g12 (right-handed).
inline Tripod make_tripod(double g01, double g02, double g12)
{
  Tripod t;
  t[0] = {1., 0., 0.};
  t[1] = {std::cos(g01), std::sin(g01), 0.};
  const double a = std::cos(g02);
  const double s = std::sin(g01);
  const double b = (std::abs(s) > 1e-12) ? (std::cos(g12) - a * std::cos(g01)) / s : 0.;
  const double c2 = 1. - a * a - b * b;
  // an infeasible triple of angles (their sum exceeds 2π) is flattened to a
  // barely positive tripod rather than rejected
  const double c = std::sqrt((std::max)(c2, 1e-4));
  const double l = std::sqrt(a * a + b * b + c * c);
  t[2] = {a / l, b / l, c / l};
  return t;
}

/// The interior dihedral angle Θ of every boundary edge for `Ideal_angles`:
/// on a sharp edge (as `is_sharp(a, b)` says) the angle measured between its
/// two boundary quads at `positions` (normally the target surface Ω_t), so
/// that the ideal angles agree with the feature the edge is held on; on other
/// boundary edges the default rule (π, or π/2 for an edge with one hex).
template <class IsSharp>
std::vector<double> boundary_edge_angles(const Hex_mesh_topology& topo, const std::vector<Vec3>& positions,
                                         const IsSharp& is_sharp)
{
  const double pi = 3.14159265358979323846;
  std::vector<double> theta(topo.number_of_edges(), pi);
  const auto& faces = topo.boundary_faces();
  auto face_normal = [&](std::size_t f) {
    const auto& q = faces[f];
    return normalized(cross(positions[q[2]] - positions[q[0]], positions[q[3]] - positions[q[1]]));
  };
  auto centroid = [&](std::size_t f) {
    const auto& q = faces[f];
    return 0.25 * (positions[q[0]] + positions[q[1]] + positions[q[2]] + positions[q[3]]);
  };
  for(std::size_t e = 0; e < topo.number_of_edges(); ++e)
  {
    if(!topo.is_boundary_edge(e)) continue;
    if(topo.edge_valence(e) == 1) theta[e] = pi / 2.;
    const auto& ed = topo.edge(e);
    const std::vector<std::size_t> f = topo.boundary_faces_of_edge(e);
    if(f.size() != 2 || !is_sharp(ed[0], ed[1])) continue;
    const Vec3 n0 = face_normal(f[0]), n1 = face_normal(f[1]);
    const double phi = std::acos((std::max)(-1., (std::min)(1., dot(n0, n1))));
    const Vec3 mid = 0.5 * (positions[ed[0]] + positions[ed[1]]);
    const bool convex = dot(n0, centroid(f[1]) - mid) < 0.;
    theta[e] = convex ? pi - phi : pi + phi;
  }
  return theta;
}

class Ideal_angles
{
public:
  /// `boundary_edge_angle[e]`: interior dihedral angle Θ of boundary edge e
  /// (ignored for interior edges); pass an empty vector for the default rule
  /// (π, or π/2 for an edge with a single hex).
  Ideal_angles(const Hex_mesh_topology& topo, const std::vector<double>& boundary_edge_angle = {})
  {
    const double pi = 3.14159265358979323846;
    const std::size_t ne = topo.number_of_edges();
    m_step.assign(ne, pi / 2.);
    for(std::size_t e = 0; e < ne; ++e)
    {
      const int n = topo.edge_valence(e);
      double theta = 2. * pi;
      if(topo.is_boundary_edge(e))
      {
        if(!boundary_edge_angle.empty()) theta = boundary_edge_angle[e];
        else theta = (n == 1) ? pi / 2. : pi;
      }
      m_step[e] = theta / n;
    }
    build_tripods(topo);
    build_pairs(topo);
  }

  /// angular step around edge e
  double step(std::size_t e) const { return m_step[e]; }
  const Tripod& tripod(std::size_t h, int corner) const { return m_tripods[8 * h + corner]; }
  /// pair terms (2+ steps apart) at vertex v
  const std::vector<Angle_pair>& pairs() const { return m_pairs; }
  const std::size_t* pairs_of_vertex_begin(std::size_t v) const { return m_pair_index.data() + m_pair_off[v]; }
  const std::size_t* pairs_of_vertex_end(std::size_t v) const { return m_pair_index.data() + m_pair_off[v + 1]; }

private:
  void build_tripods(const Hex_mesh_topology& topo)
  {
    const auto& hexes = topo.hexes();
    m_tripods.resize(8 * hexes.size());
    for(std::size_t h = 0; h < hexes.size(); ++h)
      for(int c = 0; c < 8; ++c)
      {
        std::size_t e[3];
        for(int k = 0; k < 3; ++k)
          e[k] = topo.edge_id(hexes[h][c], hexes[h][hex_corner_edges[c][k]]);
        // the angle between edges i and j is the step around the third edge
        m_tripods[8 * h + c] = make_tripod(m_step[e[2]], m_step[e[1]], m_step[e[0]]);
      }
  }

  void build_pairs(const Hex_mesh_topology& topo)
  {
    const auto& hexes = topo.hexes();
    const std::size_t nv = topo.number_of_vertices();
    m_pair_off.assign(nv + 1, 0);
    for(std::size_t v = 0; v < nv; ++v)
    {
      // the hex corners at v, and for each neighbour w, the links (a,b)
      std::map<std::size_t, std::vector<std::pair<std::size_t, std::size_t> > > links;
      std::map<std::pair<std::size_t, std::size_t>, bool> corner_pair;
      for(auto c = topo.vertex_corners_begin(v); c != topo.vertex_corners_end(v); ++c)
      {
        const int* n = hex_corner_edges[c->local];
        const std::size_t w[3] = {hexes[c->hex][n[0]], hexes[c->hex][n[1]], hexes[c->hex][n[2]]};
        for(int k = 0; k < 3; ++k)
        {
          const std::size_t a = w[(k + 1) % 3], b = w[(k + 2) % 3];
          links[w[k]].emplace_back(a, b);
          corner_pair[std::minmax(a, b)] = true;
        }
      }
      std::map<std::pair<std::size_t, std::size_t>, std::pair<double, int> > acc;
      for(const auto& axis : links)
      {
        const std::vector<std::size_t> order = walk(axis.second);
        if(order.empty()) continue; // non-manifold fan: no ideal angles there
        const bool closed = order.size() == axis.second.size();
        const double step = m_step[topo.edge_id(v, axis.first)];
        const std::size_t m = order.size();
        for(std::size_t i = 0; i < m; ++i)
          for(std::size_t j = i + 1; j < m; ++j)
          {
            std::size_t d = j - i;
            if(closed) d = (std::min)(d, m - d);
            if(d < 2) continue;
            const auto key = std::minmax(order[i], order[j]);
            if(corner_pair.count(key)) continue;
            auto& s = acc[key];
            s.first += std::cos(d * step);
            s.second += 1;
          }
      }
      for(const auto& p : acc)
      {
        m_pairs.push_back(Angle_pair{v, p.first.first, p.first.second, p.second.first / p.second.second});
        ++m_pair_off[v + 1];
      }
    }
    for(std::size_t v = 0; v < nv; ++v) m_pair_off[v + 1] += m_pair_off[v];
    // pairs are appended vertex by vertex, so the index is the identity
    m_pair_index.resize(m_pairs.size());
    for(std::size_t i = 0; i < m_pairs.size(); ++i) m_pair_index[i] = i;
  }

  /// Orders the edges linked by the hexes around an axis into a cycle or a
  /// path; returns an empty vector when the links do not form one chain.
  static std::vector<std::size_t> walk(const std::vector<std::pair<std::size_t, std::size_t> >& links)
  {
    std::map<std::size_t, std::vector<std::size_t> > adj;
    for(const auto& l : links) { adj[l.first].push_back(l.second); adj[l.second].push_back(l.first); }
    std::size_t start = adj.begin()->first;
    for(const auto& a : adj)
    {
      if(a.second.size() > 2) return {};
      if(a.second.size() == 1) { start = a.first; break; }
    }
    std::vector<std::size_t> order{start};
    std::size_t prev = start, cur = start;
    while(true)
    {
      const auto& nb = adj[cur];
      std::size_t next = nb[0];
      if(next == prev && nb.size() == 2) next = nb[1];
      if(order.size() > 1 && next == prev) break; // path end
      if(next == start) break;                    // cycle closed
      if(order.size() > adj.size()) return {};
      order.push_back(next);
      prev = cur; cur = next;
      if(adj[cur].size() == 1) break;
    }
    if(order.size() != adj.size()) return {};
    return order;
  }

  std::vector<double> m_step;
  std::vector<Tripod> m_tripods;
  std::vector<Angle_pair> m_pairs;
  std::vector<std::size_t> m_pair_off, m_pair_index;
};

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_UNTANGLING_IDEAL_ANGLES_H
