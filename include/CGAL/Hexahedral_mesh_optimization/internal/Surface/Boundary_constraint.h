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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_BOUNDARY_CONSTRAINT_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_BOUNDARY_CONSTRAINT_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// What the optimiser needs to know about a boundary vertex (Eq. 6 of the
// paper): its class, its reference position v̄ on the target surface and the
// direction attached to v̄ (the surface normal of a regular vertex, the
// feature tangent of a sharp-edge vertex). The target surface
// (Target_surface.h) fills these; the energy (Edge_angle_energy.h) reads them.

#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>

#include <cstdint>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

enum class Vertex_class : std::uint8_t
{
  interior = 0, ///< not on the boundary: free
  regular,      ///< on a smooth part of the boundary: moves in the tangent plane
  sharp,        ///< on a feature line: moves along its tangent
  corner        ///< where more than 2 feature edges meet: stays near its anchor
};

struct Boundary_constraint
{
  Vertex_class type = Vertex_class::interior;
  Vec3 anchor = {0., 0., 0.};    ///< v̄: the closest point on the target surface / feature / corner
  Vec3 direction = {0., 0., 0.}; ///< unit normal (regular) or unit tangent (sharp); unused otherwise
};

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_BOUNDARY_CONSTRAINT_H
