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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_REPAIR_REGION_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_REPAIR_REGION_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The repair region of the quality stages (issue 49, "keep what the mesher
// meant"): the quality stages move only the vertices of the hexes within a
// few rings of a hex that is a reason to move anything; every other vertex
// stays exactly where it is, as if the user had constrained it.
//
// A hex is a reason when its scaled Jacobian now is below what the stages
// aim at and
//   - it was inverted (SJ <= 0) in the input: it was broken; or
//   - it is lower now than in the input: the repair (the untangling) made it
//     worse; or
//   - its input SJ is below `kept_sj`: the input itself was poor there.
// A hex the mesher made well (input SJ >= `kept_sj`) and that nothing made
// worse is not a reason: a 1000:1 box of a boundary layer has SJ 1, and a
// slightly wedged cell of a curved wall stays as the mesher shaped it. The
// region is fixed once, before the stages: the max-min and ASJ smoothing
// then cannot spread the repair ring after ring over the whole mesh (each
// move leaves its neighbours a little below the target, which made them
// the next stage's reasons). On an input whose poor elements are spread
// everywhere the region is the whole mesh and nothing changes.

#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_topology.h>

#include <cstddef>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

struct Repair_region
{
  /// per vertex: 1 if it must stay (outside the region, or constrained by the user)
  std::vector<unsigned char> constrained;
  std::size_t reasons = 0;       ///< hexes that are a reason to move
  std::size_t free_vertices = 0; ///< vertices the stages may move
  bool whole_mesh = false;       ///< every vertex not constrained by the user is free
};

/// The region around the reasons (see above), `rings` rings of hexes
/// sharing a vertex; `sj_now` and `sj_input` per hex; `user` the user's
/// constrained mask (empty: none), kept in the result.
inline Repair_region repair_region(const Hex_mesh_topology& topo, const std::vector<double>& sj_now,
                                   const std::vector<double>& sj_input, const std::vector<unsigned char>& user,
                                   double aimed, double kept_sj, int rings)
{
  const std::size_t nh = topo.number_of_hexes(), nv = topo.number_of_vertices();
  const auto& hexes = topo.hexes();
  std::vector<unsigned char> in_region(nh, 0), vertex_in(nv, 0);
  std::vector<std::size_t> front;
  Repair_region r;
  for(std::size_t h = 0; h < nh; ++h)
  {
    const bool below = sj_now[h] < aimed;
    const bool reason = below && (sj_input[h] <= 0. || sj_now[h] < sj_input[h] || sj_input[h] < kept_sj);
    if(!reason) continue;
    in_region[h] = 1;
    front.push_back(h);
    ++r.reasons;
  }
  for(int k = 0; k < rings && !front.empty(); ++k)
  {
    std::vector<std::size_t> next;
    for(std::size_t h : front)
      for(std::size_t v : hexes[h])
        for(auto c = topo.vertex_corners_begin(v); c != topo.vertex_corners_end(v); ++c)
          if(!in_region[c->hex]) { in_region[c->hex] = 1; next.push_back(c->hex); }
    front.swap(next);
  }
  for(std::size_t h = 0; h < nh; ++h)
    if(in_region[h])
      for(std::size_t v : hexes[h]) vertex_in[v] = 1;
  r.constrained.assign(nv, 0);
  r.whole_mesh = true;
  for(std::size_t v = 0; v < nv; ++v)
  {
    const bool by_user = !user.empty() && user[v] != 0;
    r.constrained[v] = (by_user || !vertex_in[v]) ? 1 : 0;
    if(!vertex_in[v] && !by_user) r.whole_mesh = false;
    if(!r.constrained[v]) ++r.free_vertices;
  }
  return r;
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_REPAIR_REGION_H
