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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_HEX_MESH_SURFACE_DISTANCE_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_HEX_MESH_SURFACE_DISTANCE_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The distances returned by CGAL::hex_mesh_surface_distance()
// (<CGAL/hex_mesh_surface_error.h>), used inside the package as
// internal::Surface_distance.

#include <algorithm>

namespace CGAL {

/*!
\ingroup PkgHexahedralMeshOptimizationRef

\brief Distances between the boundary of a hexahedral mesh and a reference
surface, as computed by `hex_mesh_surface_distance()`. All values are in model
units.
*/
struct Hex_mesh_surface_distance
{
  /// one-sided: max over the mesh of the distance to the reference
  double mesh_to_reference = 0.;
  /// one-sided: max over the reference of the distance to the mesh
  double reference_to_mesh = 0.;
  /// bounding-box diagonal of the reference
  double reference_diagonal = 0.;
  /// metro's normaliser: the union box, enlarged by 2 % of its diagonal per side
  double metro_diagonal = 0.;

  /// the Hausdorff distance (the larger one-sided distance)
  double hausdorff() const { return (std::max)(mesh_to_reference, reference_to_mesh); }
  /// Hausdorff / reference diagonal (the package's surface error)
  double relative() const
  {
    return reference_diagonal > 0. ? hausdorff() / reference_diagonal : hausdorff();
  }
  /// Hausdorff / metro's diagonal, to compare with figures computed by metro
  double metro_relative() const
  {
    return metro_diagonal > 0. ? hausdorff() / metro_diagonal : hausdorff();
  }
};

} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_HEX_MESH_SURFACE_DISTANCE_H
