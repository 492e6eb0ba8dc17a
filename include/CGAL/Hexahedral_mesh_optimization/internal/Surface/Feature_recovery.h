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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_FEATURE_RECOVERY_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_FEATURE_RECOVERY_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Feature recovery (issue 14, item 1): the feature curves and corners of the
// reference (Reference_features.h) matched to chains of boundary edges of
// the hex mesh, even when no mesh vertex lies on a crease.
//
// 1. Corners first: each reference corner takes the nearest free boundary
//    vertex within `match_radius` mean boundary edges, the corners in the
//    order of that distance (the closest pairs are the surest).
// 2. Then the curves, shortest first: a shortest path on the boundary edge
//    graph from the vertex of its first corner to that of its last, with
//    the cost of an edge its length × (1 + κ·(d_a² + d_b²) / (2 h²)), d the
//    distances of its ends to the curve, h the mean boundary edge and
//    κ = `off_crease_cost`: a path that keeps to the crease is cheap, one a
//    ring away costs 1 + κ times more. The path keeps within `tube_radius`
//    edges of the curve and goes through no vertex of an earlier chain or
//    corner.
//    On a feature-aligned hex mesh the creases are in the mesh's
//    connectivity as well: a boundary edge on a crease sharper than
//    `topological_crease_turn` lies on one hex (convex) or three and more
//    (concave), an edge of a smooth part on two. When most boundary edges
//    that do not lie on two hexes are near a reference crease
//    (`topological_agreement`), an edge on two hexes costs
//    1 + `topological_crease_cost` times more on such a crease, and a corner
//    goes first to the vertex whose number of such edges is that of its
//    sharp creases: positions perturbed by most of an edge no longer decide
//    alone. A closed curve (and one that starts and ends at the same
//    corner) is cut at its start and half-way round, at the nearest free
//    vertices, into two paths.
// 3. The vertices of a chain go onto their curve, spread by arc length as
//    they were spread along the chain (`spread_along_curves`), or each to
//    its closest point of the curve; a corner's vertex onto the corner.
// A curve whose corners found no vertex, or between whose vertices no path
// exists, is counted as lost; its crease is not followed.

#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_boundary.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Reference_features.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <queue>
#include <utility>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

struct Feature_recovery_parameters
{
  /// a reference corner matches a boundary vertex at most this many mean boundary edges away
  double match_radius = 2.;
  /// a chain keeps within this many mean boundary edges of its curve
  double tube_radius = 3.;
  /// κ: how much more an edge one mean edge off the crease costs than one on it
  double off_crease_cost = 8.;
  /// μ: an edge whose two quads do not lie on the two patches of the
  /// curve costs 1 + μ times more
  double off_patch_cost = 3.;
  /// a chain with a vertex farther than this many mean boundary edges from
  /// its curve is not kept (its crease is lost rather than followed by a
  /// chain that would drag the boundary across the surface), unless the
  /// hex counts are used and all its edges lie on one hex or three and more
  double max_chain_offset = 1.;
  /// τ: on a crease whose normals turn by more than `topological_crease_turn`
  /// degrees, a boundary edge on two hexes (a smooth part's) costs 1 + τ
  /// times more than one on one hex or three and more (0: the hex counts
  /// are not used). 1 lies in the middle of the range of τ over which the
  /// results do not change (RESULTS.md of the benchmark)
  double topological_crease_cost = 1.;
  double topological_crease_turn = 45.;
  /// the hex counts are used only when at least this fraction of the
  /// boundary edges not on two hexes lies within `match_radius` of a crease
  /// (a feature-aligned mesh; a staircase mesh has them everywhere)
  double topological_agreement = 0.8;
  /// a crease turning by more than this many degrees at a vertex turns at a
  /// corner there (Target_surface sets it to the `corner_turn` of
  /// Reference_features.h)
  double corner_turn = 60.;
  /// chain vertices spread along their curve (true) or each to its closest point
  bool spread_along_curves = false;
  /// rounds of Laplacian smoothing (p ← p/2 + mean of its neighbours/2)
  /// of the boundary positions used for matching only: a perturbed
  /// boundary's zigzag otherwise draws chains and quad patches off the crease
  unsigned int matching_smoothing_rounds = 1;
};

/// Which boundary edges and vertices follow the reference's features, and
/// where on them they go; all indexed as `Hex_mesh_boundary` (edge ids,
/// boundary indices).
struct Recovered_features
{
  std::vector<unsigned char> sharp_edge; ///< edge on a recovered chain
  std::vector<unsigned char> is_corner;  ///< vertex matched to a reference corner
  std::vector<unsigned char> placed;     ///< vertex on a recovered corner or chain
  std::vector<Vec3> position;            ///< where a placed vertex goes
  std::size_t corners = 0, corners_matched = 0;
  std::size_t curves = 0, curves_recovered = 0;
  bool topological = false; ///< the hex counts of the boundary edges were used
};

namespace feature_recovery_detail {

struct Closest
{
  double arc = 0.;  // arc length of the closest point from the polyline's start
  Vec3 point = {0., 0., 0.};
  double squared_distance = std::numeric_limits<double>::max();
  std::size_t segment = 0; ///< the segment (from pts[segment] to pts[segment + 1]) it lies on
};

inline Closest closest_on_polyline(const std::vector<Vec3>& pts, const Vec3& p)
{
  Closest best;
  double arc = 0.;
  for(std::size_t i = 0; i + 1 < pts.size(); ++i)
  {
    const Vec3 ab = pts[i + 1] - pts[i];
    const double ll = squared_norm(ab), l = std::sqrt(ll);
    double t = ll > 0. ? dot(p - pts[i], ab) / ll : 0.;
    t = (std::max)(0., (std::min)(1., t));
    const Vec3 q = pts[i] + t * ab;
    const double d = squared_norm(p - q);
    if(d < best.squared_distance) best = Closest{arc + t * l, q, d, i};
    arc += l;
  }
  if(pts.size() == 1) best = Closest{0., pts[0], squared_norm(p - pts[0]), 0};
  return best;
}

inline double length_of(const std::vector<Vec3>& pts)
{
  double l = 0.;
  for(std::size_t i = 0; i + 1 < pts.size(); ++i) l += norm(pts[i + 1] - pts[i]);
  return l;
}

/// the polyline from arc length s0 to s1 (0 ≤ s0 ≤ s1 ≤ its length)
inline std::vector<Vec3> sub_polyline(const std::vector<Vec3>& pts, double s0, double s1)
{
  std::vector<Vec3> out;
  double arc = 0.;
  for(std::size_t i = 0; i + 1 < pts.size(); ++i)
  {
    const double l = norm(pts[i + 1] - pts[i]);
    const double a = arc, b = arc + l;
    arc = b;
    if(b < s0 || a > s1 || !(l > 0.)) continue;
    if(out.empty()) out.push_back(pts[i] + ((std::max)(s0, a) - a) / l * (pts[i + 1] - pts[i]));
    out.push_back(pts[i] + ((std::min)(s1, b) - a) / l * (pts[i + 1] - pts[i]));
  }
  if(out.empty() && !pts.empty()) out.push_back(pts.front());
  return out;
}

inline Vec3 point_at_arc(const std::vector<Vec3>& pts, double s)
{
  double arc = 0.;
  for(std::size_t i = 0; i + 1 < pts.size(); ++i)
  {
    const double l = norm(pts[i + 1] - pts[i]);
    if(arc + l >= s && l > 0.) return pts[i] + ((std::max)(0., s - arc) / l) * (pts[i + 1] - pts[i]);
    arc += l;
  }
  return pts.back();
}

} // namespace feature_recovery_detail

class Feature_recovery
{
  static constexpr std::size_t npos = Hex_mesh_boundary::npos;

public:
  /// `points`: the boundary vertices' positions (boundary indices), on or
  /// near the reference; `h`: their mean boundary edge length
  /// `quad_patch`: the reference patch each boundary quad lies on
  /// (`Reference_features::triangle_patch` of the triangle closest to its centre);
  /// `edge_hexes`: the number of hexes around each boundary edge
  /// (`count_boundary_edge_hexes`)
  Feature_recovery(const Hex_mesh_boundary& boundary, const std::vector<Vec3>& points, double h,
                   const std::vector<std::size_t>& quad_patch, const std::vector<unsigned char>& edge_hexes,
                   const Feature_recovery_parameters& param = Feature_recovery_parameters())
    : b_(boundary), P_(points), h_(h), quad_patch_(quad_patch), edge_hexes_(edge_hexes), param_(param)
  {
    edge_quads_.assign(b_.edges.size(), {{npos, npos}});
    for(std::size_t q = 0; q < b_.quads.size(); ++q)
      for(int i = 0; i < 4; ++i)
      {
        std::array<std::size_t, 2>& eq = edge_quads_[b_.quad_edges[q][i]];
        (eq[0] == npos ? eq[0] : eq[1]) = q;
      }
  }

  Recovered_features run(const Reference_features& rf)
  {
    const std::size_t nb = b_.vertices.size();
    r_ = Recovered_features();
    r_.sharp_edge.assign(b_.edges.size(), 0);
    r_.is_corner.assign(nb, 0);
    r_.placed.assign(nb, 0);
    r_.position.assign(nb, Vec3{0., 0., 0.});
    r_.corners = rf.corners.size();
    r_.curves = rf.curves.size();
    r_.topological = feature_aligned(rf);
    sharp_curves_at_corner_.assign(rf.corners.size(), 0);
    for(const Reference_feature_curve& c : rf.curves)
      if(!c.closed && c.normal_turn > param_.topological_crease_turn)
      {
        ++sharp_curves_at_corner_[c.first_corner];
        ++sharp_curves_at_corner_[c.last_corner];
      }
    distance_.assign(nb, -1.);
    cost_.assign(nb, std::numeric_limits<double>::max());
    prev_edge_.assign(nb, npos);

    const std::vector<std::size_t> corner_vertex = match_corners(rf);
    std::vector<std::size_t> order(rf.curves.size());
    std::vector<double> length(rf.curves.size());
    for(std::size_t c = 0; c < order.size(); ++c)
    {
      order[c] = c;
      length[c] = feature_recovery_detail::length_of(rf.curves[c].points);
    }
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return length[a] < length[b]; });
    for(std::size_t c : order)
      if(recover_curve(rf.curves[c], corner_vertex)) ++r_.curves_recovered;
    return r_;
  }

private:
  struct Path_task
  {
    std::size_t from, to;
    std::vector<Vec3> curve; // from the place of `from` to that of `to`
    std::array<std::size_t, 2> patches;
    bool sharp; // its normals turn by more than `topological_crease_turn`
  };

  /// the boundary edge e lies on two hexes, as an edge of a smooth part
  bool on_two_hexes(std::size_t e) const { return edge_hexes_[e] == 2; }

  /// do most boundary edges not on two hexes lie near a crease of the reference
  bool feature_aligned(const Reference_features& rf) const
  {
    if(param_.topological_crease_cost <= 0.) return false;
    std::size_t off_two = 0, far = 0;
    for(std::size_t e = 0; e < b_.edges.size(); ++e)
      if(!on_two_hexes(e)) ++off_two;
    // stops at the first edge past the fraction allowed off the creases
    const double far_allowed = (1. - param_.topological_agreement) * double(off_two);
    const double r2 = CGAL::square(param_.match_radius * h_);
    std::vector<std::vector<Vec3>> polylines;
    for(const Reference_feature_curve& c : rf.curves) polylines.push_back(c.polyline());
    for(std::size_t e = 0; e < b_.edges.size() && double(far) <= far_allowed; ++e)
    {
      if(on_two_hexes(e)) continue;
      bool near = false;
      const Vec3 m = 0.5 * (P_[b_.boundary_index[b_.edges[e][0]]] + P_[b_.boundary_index[b_.edges[e][1]]]);
      for(const std::vector<Vec3>& pts : polylines)
        if(feature_recovery_detail::closest_on_polyline(pts, m).squared_distance <= r2) { near = true; break; }
      if(!near) ++far;
    }
    return off_two > 0 && double(far) <= far_allowed;
  }

  /// how far boundary vertex bi is from being, in the mesh's connectivity, a
  /// corner where `ns` sharp creases meet: the difference between ns and its
  /// number of edges not on two hexes, plus one where two such edges meet
  /// without turning by `corner_turn` (a vertex along a crease, not at its turn)
  std::size_t topological_mismatch(std::size_t bi, std::size_t ns) const
  {
    const std::size_t td = topological_crease_degree(bi);
    std::size_t mismatch = td > ns ? td - ns : ns - td;
    if(td == 2 && ns == 2)
    {
      Vec3 out[2];
      int k = 0;
      const auto er = b_.edges_of(bi);
      for(const std::size_t* e = er.first; e != er.second; ++e)
        if(!on_two_hexes(*e)) out[k++] = P_[b_.boundary_index[b_.opposite(*e, b_.vertices[bi])]] - P_[bi];
      const double l = norm(out[0]) * norm(out[1]);
      // outward edges of a straight crease point apart (cosine −1)
      if(!(l > 0.) || dot(out[0], out[1]) / l < -std::cos(param_.corner_turn * CGAL_PI / 180.)) ++mismatch;
    }
    return mismatch;
  }

  /// the number of boundary edges at bi that do not lie on two hexes
  std::size_t topological_crease_degree(std::size_t bi) const
  {
    std::size_t k = 0;
    const auto er = b_.edges_of(bi);
    for(const std::size_t* e = er.first; e != er.second; ++e)
      if(!on_two_hexes(*e)) ++k;
    return k;
  }

  /// does boundary edge e lie between the two patches of the task's curve
  bool between_patches(std::size_t e, const Path_task& t) const
  {
    const std::array<std::size_t, 2>& q = edge_quads_[e];
    if(q[1] == npos) return true; // a border edge
    const std::size_t a = quad_patch_[q[0]], b = quad_patch_[q[1]];
    return (a == t.patches[0] && b == t.patches[1]) || (a == t.patches[1] && b == t.patches[0]);
  }

  /// the nearest free boundary vertex to p within the match radius, or npos
  std::size_t nearest_free_vertex(const Vec3& p) const
  {
    std::size_t best = npos;
    double bd = CGAL::square(param_.match_radius * h_);
    for(std::size_t bi = 0; bi < P_.size(); ++bi)
    {
      const double d = squared_norm(P_[bi] - p);
      if(!r_.placed[bi] && d <= bd && (best == npos || d < bd)) { best = bi; bd = d; }
    }
    return best;
  }

  void place(std::size_t bi, const Vec3& p)
  {
    r_.placed[bi] = 1;
    r_.position[bi] = p;
  }

  /// how many of `patches` the quads around boundary vertex bi lie on
  std::size_t patches_around(std::size_t bi, const std::vector<std::size_t>& patches) const
  {
    std::size_t k = 0;
    const auto qr = b_.quads_of(bi);
    for(std::size_t p : patches)
      for(const std::size_t* q = qr.first; q != qr.second; ++q)
        if(quad_patch_[*q] == p) { ++k; break; }
    return k;
  }

  /// the vertex for reference corner c: among the free vertices within the
  /// match radius, with the hex counts the one with as many edges not on two
  /// hexes as the corner has sharp creases, then the one whose quads lie on
  /// most of the corner's patches (a vertex next to the corner, on one of
  /// its creases, lies on fewer), then the nearest; npos if none
  std::size_t corner_candidate(const Reference_features& rf, std::size_t c) const
  {
    std::size_t best = npos, best_patches = 0, best_mismatch = 0;
    double bd = 0.;
    const double radius2 = CGAL::square(param_.match_radius * h_);
    for(std::size_t bi = 0; bi < P_.size(); ++bi)
    {
      const double d = squared_norm(P_[bi] - rf.corners[c]);
      if(r_.placed[bi] || d > radius2) continue;
      const std::size_t k = patches_around(bi, rf.corner_patches[c]);
      const std::size_t mismatch = r_.topological ? topological_mismatch(bi, sharp_curves_at_corner_[c]) : 0;
      if(best == npos || mismatch < best_mismatch
         || (mismatch == best_mismatch && (k > best_patches || (k == best_patches && d < bd))))
      { best = bi; best_patches = k; best_mismatch = mismatch; bd = d; }
    }
    return best;
  }

  std::vector<std::size_t> match_corners(const Reference_features& rf)
  {
    const std::size_t nc = rf.corners.size();
    std::vector<std::pair<double, std::size_t>> by_distance;
    for(std::size_t c = 0; c < nc; ++c)
    {
      const std::size_t v = corner_candidate(rf, c);
      if(v != npos) by_distance.emplace_back(squared_norm(P_[v] - rf.corners[c]), c);
    }
    std::sort(by_distance.begin(), by_distance.end());
    std::vector<std::size_t> corner_vertex(nc, npos);
    for(const auto& dc : by_distance)
    {
      const std::size_t c = dc.second, v = corner_candidate(rf, c);
      if(v == npos) continue;
      corner_vertex[c] = v;
      place(v, rf.corners[c]);
      r_.is_corner[v] = 1;
      ++r_.corners_matched;
    }
    return corner_vertex;
  }

  /// one curve as one or two paths; false when it is lost
  bool recover_curve(const Reference_feature_curve& curve, const std::vector<std::size_t>& corner_vertex)
  {
    using namespace feature_recovery_detail;
    const std::vector<Vec3> pts = curve.polyline();
    std::size_t from = npos, to = npos;
    const bool sharp = r_.topological && curve.normal_turn > param_.topological_crease_turn;
    if(curve.closed)
    {
      from = to = nearest_free_vertex(pts.front());
      if(from != npos) place(from, pts.front());
    }
    else
    {
      from = corner_vertex[curve.first_corner];
      to = corner_vertex[curve.last_corner];
    }
    if(from == npos || to == npos) return false;
    if(from != to)
      return route(Path_task{from, to, pts, curve.patches, sharp});
    // a loop: cut half-way round
    const double L = length_of(pts);
    const Vec3 half = point_at_arc(pts, 0.5 * L);
    const std::size_t mid = nearest_free_vertex(half);
    if(mid == npos) return false;
    place(mid, half);
    return route(Path_task{from, mid, sub_polyline(pts, 0., 0.5 * L), curve.patches, sharp})
        && route(Path_task{mid, to, sub_polyline(pts, 0.5 * L, L), curve.patches, sharp});
  }

  /// distance of boundary vertex bi to the task's curve (cached per task)
  double off_crease(std::size_t bi, const Path_task& t)
  {
    if(distance_[bi] < 0.)
    {
      distance_[bi] = std::sqrt(feature_recovery_detail::closest_on_polyline(t.curve, P_[bi]).squared_distance);
      touched_.push_back(bi);
    }
    return distance_[bi];
  }

  /// the cheapest path from t.from to t.to (Dijkstra; ties by vertex index);
  /// false when there is none
  bool shortest_path(const Path_task& t, std::vector<std::size_t>& path_edges)
  {
    typedef std::pair<double, std::size_t> Entry;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
    const double tube = param_.tube_radius * h_, h2 = h_ * h_;
    cost_[t.from] = 0.;
    touched_.push_back(t.from);
    queue.emplace(0., t.from);
    while(!queue.empty())
    {
      const Entry top = queue.top();
      queue.pop();
      const std::size_t u = top.second;
      if(top.first > cost_[u]) continue;
      if(u == t.to) break;
      const double du = off_crease(u, t);
      const auto er = b_.edges_of(u);
      for(const std::size_t* e = er.first; e != er.second; ++e)
      {
        if(r_.sharp_edge[*e]) continue;
        const std::size_t w = b_.boundary_index[b_.opposite(*e, b_.vertices[u])];
        if(w != t.to && (r_.placed[w] || off_crease(w, t) > tube)) continue;
        const double dw = off_crease(w, t);
        const double c = top.first + norm(P_[w] - P_[u]) * (1. + param_.off_crease_cost * (du * du + dw * dw) / (2. * h2))
                                                         * (between_patches(*e, t) ? 1. : 1. + param_.off_patch_cost)
                                                         * (t.sharp && on_two_hexes(*e) ? 1. + param_.topological_crease_cost : 1.);
        if(c < cost_[w])
        {
          if(cost_[w] == std::numeric_limits<double>::max()) touched_.push_back(w);
          cost_[w] = c;
          prev_edge_[w] = *e;
          queue.emplace(c, w);
        }
      }
    }
    const bool found = cost_[t.to] < std::numeric_limits<double>::max();
    path_edges.clear();
    for(std::size_t v = t.to; found && v != t.from;)
    {
      path_edges.push_back(prev_edge_[v]);
      v = b_.boundary_index[b_.opposite(prev_edge_[v], b_.vertices[v])];
    }
    std::reverse(path_edges.begin(), path_edges.end());
    for(std::size_t v : touched_)
    {
      distance_[v] = -1.;
      cost_[v] = std::numeric_limits<double>::max();
      prev_edge_[v] = npos;
    }
    touched_.clear();
    return found && !path_edges.empty();
  }

  /// the path of one task, its edges marked and its vertices placed on the curve
  bool route(const Path_task& t)
  {
    using namespace feature_recovery_detail;
    std::vector<std::size_t> edges;
    if(!shortest_path(t, edges)) return false;
    // a chain along the mesh's own crease edges is kept however far the
    // perturbed positions put it from its curve
    const bool along_mesh_crease = t.sharp && std::none_of(edges.begin(), edges.end(),
                                                           [this](std::size_t e) { return on_two_hexes(e); });
    if(!along_mesh_crease)
    {
      std::size_t v = t.from;
      for(std::size_t e : edges)
      {
        v = b_.boundary_index[b_.opposite(e, b_.vertices[v])];
        if(closest_on_polyline(t.curve, P_[v]).squared_distance > CGAL::square(param_.max_chain_offset * h_))
          return false;
      }
    }
    std::vector<std::size_t> chain{t.from};
    std::vector<double> arc{0.};
    for(std::size_t e : edges)
    {
      const std::size_t w = b_.boundary_index[b_.opposite(e, b_.vertices[chain.back()])];
      arc.push_back(arc.back() + norm(P_[w] - P_[chain.back()]));
      chain.push_back(w);
      r_.sharp_edge[e] = 1;
    }
    const double L = length_of(t.curve);
    for(std::size_t i = 1; i + 1 < chain.size(); ++i)
      place(chain[i], param_.spread_along_curves && arc.back() > 0.
                        ? point_at_arc(t.curve, L * arc[i] / arc.back())
                        : closest_on_polyline(t.curve, P_[chain[i]]).point);
    return true;
  }

  const Hex_mesh_boundary& b_;
  const std::vector<Vec3>& P_;
  double h_;
  const std::vector<std::size_t>& quad_patch_;
  const std::vector<unsigned char>& edge_hexes_;
  Feature_recovery_parameters param_;
  std::vector<std::size_t> sharp_curves_at_corner_;
  std::vector<std::array<std::size_t, 2>> edge_quads_;
  Recovered_features r_;
  std::vector<double> distance_, cost_;
  std::vector<std::size_t> prev_edge_, touched_;
};

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_FEATURE_RECOVERY_H
