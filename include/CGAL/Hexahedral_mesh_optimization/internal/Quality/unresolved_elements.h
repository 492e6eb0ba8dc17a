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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_QUALITY_UNRESOLVED_ELEMENTS_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_QUALITY_UNRESOLVED_ELEMENTS_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// What is still inverted when an optimisation ends, and why
// (`Optimization_result::unresolved`): a user whose solver refuses the mesh
// needs the element ids and whether the surface itself is the obstacle.
//
// A frame (corner or centre sample of the scaled Jacobian) depends on 4
// vertices (a corner and its three edge neighbours) or on all 8 (the
// centre). An inverted frame whose vertices are all on the boundary is
// "locked": the interior vertices cannot change it, only a move of the
// surface can, and the stages hold the surface within the tolerance. One
// whose vertices are all constrained by the user or on the boundary, one at
// least constrained, is "constrained": only moving a vertex the user
// constrained could change it.

#include <CGAL/Hexahedral_mesh_optimization/Optimization_result.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_boundary.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/scaled_jacobian.h>

#include <sstream>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

/// The inverted elements of `mesh`, in index order, with their reason;
/// `time_limit_fired`: the run was stopped by its time limit (the reason of
/// every element that is not locked).
inline std::vector<Unresolved_element> unresolved_elements(const Hex_mesh_arrays& mesh, bool time_limit_fired)
{
  std::vector<Unresolved_element> out;
  std::vector<std::size_t> bad;
  for(std::size_t h = 0; h < mesh.hexes.size(); ++h)
    if(is_inverted(scaled_jacobian(mesh, h))) bad.push_back(h);
  if(bad.empty()) return out;
  const Hex_mesh_boundary boundary = extract_boundary(mesh);
  for(std::size_t h : bad)
  {
    const std::array<Vec3, 8> p = mesh.corners(h);
    const Hex& hx = mesh.hexes[h];
    double s[9];
    hex_samples(p, s);
    Unresolved_element e;
    e.hex = h;
    e.scaled_jacobian = scaled_jacobian(p);
    std::ostringstream frames, locked_frames, constrained_frames;
    int locked = 0, constrained = 0;
    for(int i = 0; i < 9; ++i)
    {
      if(!is_inverted(s[i])) continue;
      // the vertices of the frame: a corner and its three edge neighbours, or all 8
      std::vector<std::size_t> frame;
      if(i < 8)
      {
        frame.push_back(hx[i]);
        for(int k = 0; k < 3; ++k) frame.push_back(hx[hex_corner_edges[i][k]]);
      }
      else
        frame.assign(hx.begin(), hx.end());
      bool all_on_boundary = true, all_held = true, any_constrained = false;
      for(std::size_t v : frame)
      {
        all_on_boundary = all_on_boundary && boundary.is_boundary_vertex(v);
        all_held = all_held && (boundary.is_boundary_vertex(v) || mesh.is_constrained(v));
        any_constrained = any_constrained || mesh.is_constrained(v);
      }
      std::ostringstream name;
      if(i < 8) name << "corner " << i << " (vertex " << hx[i] << ")";
      else name << "centre";
      frames << (frames.tellp() > 0 ? ", " : "") << name.str() << " " << s[i];
      if(all_held && any_constrained)
      {
        constrained_frames << (constrained ? ", " : "") << name.str();
        ++constrained;
      }
      else if(all_on_boundary)
      {
        locked_frames << (locked ? ", " : "") << name.str();
        ++locked;
      }
    }
    if(constrained > 0)
    {
      e.reason = Unresolved_element::constrained;
      e.details = "constrained: the inverted frame of " + constrained_frames.str() +
                  " has all its vertices constrained or on the boundary: only moving a constrained vertex can free it"
                  "; inverted frames: " + frames.str();
    }
    else if(locked > 0)
    {
      e.reason = Unresolved_element::locked;
      e.details = "locked: the inverted frame of " + locked_frames.str() +
                  " has all its vertices on the boundary: only moving the surface can free it" +
                  (time_limit_fired ? " (and the time limit fired before the stages were done)" : "") +
                  "; inverted frames: " + frames.str();
    }
    else
    {
      e.reason = time_limit_fired ? Unresolved_element::time_limit : Unresolved_element::region_exhausted;
      e.details = std::string(time_limit_fired ? "the time limit fired before it was freed"
                                               : "region exhausted: the widest regions of the stages did not free it") +
                  "; inverted frames: " + frames.str();
    }
    out.push_back(e);
  }
  return out;
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_QUALITY_UNRESOLVED_ELEMENTS_H
