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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_REFERENCE_FIT_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_REFERENCE_FIT_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

#include <stdexcept>
#include <string>

namespace CGAL {
namespace Hexahedral_mesh_optimization {

/*!
\ingroup PkgHexahedralMeshOptimizationRef

\brief Whether a reference surface fits the boundary of a hexahedral mesh, as
computed by `hex_mesh_reference_fit()` and checked by the optimisation
functions before they move anything.

Relative values are divided by the bounding-box diagonal of the reference.
The distances are those of vertices (each boundary vertex of the mesh to the
reference surface, each reference vertex to the mesh boundary), not Hausdorff
distances: a cheap test of where the two surfaces are, not a measure of the
surface error.

- `mismatched`: the reference is clearly in another coordinate frame or of
  another object: its bounding box and the mesh boundary's do not overlap, or
  their diagonals differ by more than a factor of 2, or half the vertices of
  one surface are farther than 5 % of the diagonal from the other. The
  optimisation functions throw `Reference_mismatch` with `message`.
- `distant`: it fits, but some vertex of one surface is farther from the
  other than the surface tolerance: the optimisation will move the boundary
  onto the reference, and `message` says how far it starts (the
  optimisation functions add it to `Optimization_result::warnings`).
- `fits`: every vertex of each surface is within the tolerance of the other.
*/
struct Reference_fit
{
  enum Verdict { fits, distant, mismatched };
  Verdict verdict = fits;
  double mesh_diagonal = 0.;      ///< bounding-box diagonal of the mesh boundary, model units
  double reference_diagonal = 0.; ///< bounding-box diagonal of the reference, model units
  bool boxes_overlap = true;      ///< whether the two bounding boxes intersect
  double centre_offset = 0.;      ///< distance between the two bounding-box centres, relative
  double median_mesh_to_reference = 0., max_mesh_to_reference = 0.; ///< boundary vertices to the reference, relative
  double median_reference_to_mesh = 0., max_reference_to_mesh = 0.; ///< reference vertices to the boundary, relative
  double tolerance = 0.;          ///< the surface tolerance it was judged with, relative
  /// what does not match (`mismatched`) or how far the boundary starts
  /// (`distant`); empty when the reference fits
  std::string message;
};

/*!
\ingroup PkgHexahedralMeshOptimizationRef

\brief Thrown by `untangle_hex_mesh()`, `improve_hex_mesh_quality()` and
`optimize_hex_mesh()` when their `reference_surface` does not fit the mesh
(`Reference_fit::mismatched`); `what()` says what does not match. The mesh
is left untouched.
*/
class Reference_mismatch : public std::invalid_argument
{
public:
  explicit Reference_mismatch(const std::string& what) : std::invalid_argument(what) {}
};

} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_REFERENCE_FIT_H
