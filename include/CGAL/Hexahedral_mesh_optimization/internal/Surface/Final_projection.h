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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_FINAL_PROJECTION_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_FINAL_PROJECTION_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The last move of the pipeline: every boundary vertex exactly onto its
// anchor on the target surface (regular → closest point of the reference,
// sharp → closest point of its feature line, corner → its Ω_t position),
// one vertex at a time, where the hexes around it keep a scaled Jacobian at
// or above the floor (the MSJ reached), so that the projection never lowers
// the MSJ. A vertex that cannot be moved without it stays where it is and is
// counted, with its distance.

#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_topology.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/scaled_jacobian.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Target_surface.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

struct Final_projection_report
{
  std::size_t projected = 0; ///< boundary vertices moved onto their anchor
  std::size_t left = 0;      ///< boundary vertices still off it (the move would cross the floor)
  double largest_left = 0.;  ///< largest distance of those to their anchor
};

/// Moves the boundary vertices of `points` onto their anchors of `ts` where
/// every hex around the vertex keeps a scaled Jacobian ≥ `floor` (and > 0);
/// `sweeps` passes over the boundary in index order (a move can make room
/// for the next). Vertices already on their anchor are not touched.
inline Final_projection_report project_boundary_onto_target(const Hex_mesh_topology& topo, const Target_surface& ts,
                                                            std::vector<Vec3>& points, double floor, int sweeps)
{
  Final_projection_report rep;
  const std::vector<std::size_t>& bv = ts.boundary().vertices;
  std::vector<char> done(points.size(), 0);
  for(int sweep = 0; sweep < sweeps; ++sweep)
  {
    bool moved = false;
    for(std::size_t v : bv)
    {
      if(done[v]) continue;
      if(topo.is_constrained(v)) { done[v] = 1; continue; } // constrained vertices never move
      const Vec3 p = points[v];
      const Vec3 anchor = ts.constraint_at(v, p).anchor;
      if(squared_norm(anchor - p) == 0.) { done[v] = 1; continue; }
      if(!keeps_sj_floor_around(topo, points, v, anchor, floor)) continue;
      points[v] = anchor;
      done[v] = 1;
      ++rep.projected;
      moved = true;
    }
    if(!moved) break;
  }
  for(std::size_t v : bv)
    if(!done[v])
    {
      ++rep.left;
      rep.largest_left = (std::max)(rep.largest_left, std::sqrt(squared_norm(ts.constraint_at(v, points[v]).anchor - points[v])));
    }
  return rep;
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_FINAL_PROJECTION_H
