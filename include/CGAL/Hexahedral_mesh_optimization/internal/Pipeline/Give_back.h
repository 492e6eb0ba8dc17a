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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_GIVE_BACK_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_GIVE_BACK_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The give-back (issue 49, "keep what the mesher meant"): after the stages,
// every vertex that moved is put back at its input position wherever the
// repair did not need it to move. The untangling and the smoothing spread
// their moves over regions much wider than what was broken (a region grown
// by rings, a max-min smoothing that lifts every element below its target);
// on a graded mesh each of those small moves changes the thin cells' heights
// the mesher chose. A vertex goes back when no hex around it then falls
// below min(what the stages aim at, its scaled Jacobian before) less a
// small slack, nor below the MSJ reached: the MSJ never drops, and an
// element the stages raised keeps (nearly) what it gained. A boundary vertex
// goes back only if its input position is no farther from the reference
// than where it is. Sweeps in index order: a vertex put back can let its
// neighbours go back in the next one.

#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_topology.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/scaled_jacobian.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <functional>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

struct Give_back_settings
{
  double aimed = 0.999; ///< what the stages aim at
  double floor = 0.;    ///< the MSJ reached: no hex goes below it
  double slack = 0.;    ///< how much SJ a hex may lose to a give-back (never below `floor`)
  int max_sweeps = 10;
  /// per vertex: whether it may go back (empty: every vertex)
  std::vector<unsigned char> eligible;
  /// whether boundary vertex v may go from `now` to `input` (surface check); null: never
  std::function<bool(std::size_t v, const Vec3& now, const Vec3& input)> boundary_allowed;
};

struct Give_back_report
{
  std::size_t moved_before = 0; ///< vertices off their input position before
  std::size_t given_back = 0;   ///< of those, put back
  int sweeps = 0;
};

/// whether `a` is no farther from `ts`'s reference than `b` (a boundary
/// vertex may go from `b` back to `a`)
template <typename Target_surface>
bool closer_to_reference(const Target_surface& ts, const Vec3& a, const Vec3& b)
{
  Vec3 ca, cb;
  ts.closest_on_reference(a, ca);
  ts.closest_on_reference(b, cb);
  return squared_norm(a - ca) <= squared_norm(b - cb);
}

/// Puts the vertices of `points` back at `input` where that keeps every hex
/// around them as the settings say (see above); constrained vertices never move.
inline Give_back_report give_back_to_input(const Hex_mesh_topology& topo, const std::vector<Vec3>& input,
                                           std::vector<Vec3>& points, const Give_back_settings& s)
{
  Give_back_report rep;
  const auto& hexes = topo.hexes();
  auto sj_of = [&](std::size_t h) {
    std::array<Vec3, 8> p;
    for(int i = 0; i < 8; ++i) p[i] = points[hexes[h][i]];
    return scaled_jacobian(p);
  };
  std::vector<std::size_t> off;
  for(std::size_t v = 0; v < points.size(); ++v)
    if(points[v] != input[v] && !topo.is_constrained(v) && (s.eligible.empty() || s.eligible[v])) off.push_back(v);
  rep.moved_before = off.size();
  std::vector<double> before;
  for(int sweep = 0; sweep < s.max_sweeps && !off.empty(); ++sweep)
  {
    ++rep.sweeps;
    std::vector<std::size_t> left;
    for(std::size_t v : off)
    {
      if(topo.is_boundary_vertex(v) && !(s.boundary_allowed && s.boundary_allowed(v, points[v], input[v])))
      {
        left.push_back(v);
        continue;
      }
      before.clear();
      for(auto c = topo.vertex_corners_begin(v); c != topo.vertex_corners_end(v); ++c) before.push_back(sj_of(c->hex));
      const Vec3 p = points[v];
      points[v] = input[v];
      bool ok = true;
      std::size_t i = 0;
      for(auto c = topo.vertex_corners_begin(v); c != topo.vertex_corners_end(v) && ok; ++c, ++i)
      {
        const double sj = sj_of(c->hex);
        ok = sj > 0. && sj >= s.floor && sj >= (std::min)(s.aimed, before[i]) - s.slack;
      }
      if(ok) ++rep.given_back;
      else
      {
        points[v] = p;
        left.push_back(v);
      }
    }
    const bool progress = left.size() < off.size();
    off.swap(left);
    if(!progress) break;
  }
  return rep;
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_GIVE_BACK_H
