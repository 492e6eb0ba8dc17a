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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_REFERENCE_VOLUME_REPORT_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_REFERENCE_VOLUME_REPORT_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

#include <cmath>
#include <cstddef>
#include <iomanip>
#include <limits>
#include <ostream>
#include <sstream>
#include <string>

namespace CGAL {
namespace Hexahedral_mesh_optimization {

/*!
\ingroup PkgHexahedralMeshOptimizationRef

\brief The result of `check_hex_mesh_against_reference()`: how a hexahedral
mesh fills the volume bounded by a reference surface.

Volumes and distances are in model units; relative values are divided by the
reference volume or by the bounding-box diagonal of the reference. The
report is never a bare bool: `passed()` sums it up with the thresholds it
was computed with, `summary()` (and `operator<<`) prints it in a few lines.

When the reference cannot bound a volume (empty, not closed,
self-intersecting) or TetGen fails on it, `error` says why, the fields about
the reference and the outside vertices keep their default values, and
`passed()` is `false`; the fields about the hexahedral mesh alone (its
volume, the self-intersections of its boundary) are still filled.
*/
struct Reference_volume_report
{
  static constexpr std::size_t npos = std::size_t(-1);

  /// \name Reference surface
  /// @{

  /// why the reference could not be checked, empty otherwise
  std::string error;
  /// triangles of the reference surface
  std::size_t reference_triangles = 0;
  /// edges of the reference with a single incident triangle (0 for a closed surface)
  std::size_t reference_border_edges = 0;
  /// pairs of intersecting triangles of the reference (and degenerate triangles)
  std::size_t reference_self_intersections = 0;
  /// tetrahedra of the TetGen tetrahedralisation of the reference
  std::size_t reference_tetrahedra = 0;
  /// volume bounded by the reference: the sum of the volumes of TetGen's tetrahedra
  double reference_volume = 0.;
  /// the same volume by the divergence theorem on the reference's triangles
  /// (absolute value, so independent of the orientation of the triangles)
  double reference_surface_volume = 0.;
  /// bounding-box diagonal of the reference, the unit of the relative distances
  double reference_diagonal = 0.;
  /// @}

  /// \name Hexahedral mesh
  /// @{

  /// hexahedra of the mesh
  std::size_t hexahedra = 0;
  /// vertices of the mesh
  std::size_t vertices = 0;
  /// sum of the signed volumes of the trilinear hexahedra (an inverted part counts negatively)
  double hex_mesh_volume = 0.;
  /// hexahedra whose trilinear volume is not positive
  std::size_t nonpositive_volume_hexahedra = 0;
  /// |hex_mesh_volume - reference_volume| / reference_volume (infinite without a reference volume)
  double relative_volume_difference = std::numeric_limits<double>::infinity();
  /// @}

  /// \name Boundary of the hexahedral mesh (each quadrilateral cut along its diagonal (q0, q2))
  /// @{

  /// triangles of the boundary (two per boundary quadrilateral)
  std::size_t boundary_triangles = 0;
  /// pairs of boundary triangles that intersect other than along their common edge or vertex
  std::size_t boundary_self_intersections = 0;
  /// boundary triangles with three collinear vertices (collapsed quadrilaterals)
  std::size_t degenerate_boundary_triangles = 0;
  /// @}

  /// \name Vertices outside the reference volume
  /// @{

  /// whether the point location ran (`false` when the reference has an error)
  bool outside_checked = false;
  /// vertices strictly outside the reference volume, however close to the surface
  std::size_t vertices_outside = 0;
  /// vertices outside the reference volume farther than `outside_tolerance` × `reference_diagonal` from it
  std::size_t vertices_outside_beyond_tolerance = 0;
  /// largest distance to the reference surface of a vertex outside the volume (0 if none)
  double max_outside_distance = 0.;
  /// the vertex at that distance, `npos` if none
  std::size_t farthest_outside_vertex = npos;
  /// @}

  /// \name Thresholds used by `passed()` and timing
  /// @{

  /// largest `relative_volume_difference` that `passed()` accepts
  double volume_tolerance = 0.01;
  /// largest distance outside the reference, relative to `reference_diagonal`, that `passed()` accepts
  double outside_tolerance = 0.01;
  /// time spent in TetGen, in seconds
  double tetgen_seconds = 0.;
  /// time spent in the whole check, in seconds
  double seconds = 0.;
  /// @}

  bool has_error() const { return !error.empty(); }

  bool boundary_self_intersects() const
  {
    return boundary_self_intersections > 0 || degenerate_boundary_triangles > 0;
  }

  /// `max_outside_distance` / `reference_diagonal`
  double relative_max_outside_distance() const
  {
    return reference_diagonal > 0. ? max_outside_distance / reference_diagonal : max_outside_distance;
  }

  /// the reference is valid, the volumes agree within `volume_tolerance`, no
  /// vertex is outside beyond `outside_tolerance` and the boundary of the
  /// hexahedral mesh neither self-intersects nor has degenerate triangles
  bool passed() const
  {
    return !has_error() && outside_checked && relative_volume_difference <= volume_tolerance &&
           vertices_outside_beyond_tolerance == 0 && !boundary_self_intersects();
  }

  /// a few lines of text, the last one "PASSED" or "FAILED: reasons"
  std::string summary() const
  {
    std::ostringstream o;
    o << std::setprecision(6);
    if(has_error())
      o << "reference: ERROR: " << error << "\n";
    else
      o << "reference: " << reference_triangles << " triangles, volume " << reference_volume
        << " (TetGen, " << reference_tetrahedra << " tetrahedra; divergence theorem "
        << reference_surface_volume << "), bbox diagonal " << reference_diagonal << "\n";
    o << "hex mesh: " << hexahedra << " hexahedra, " << vertices << " vertices, volume " << hex_mesh_volume;
    if(nonpositive_volume_hexahedra > 0)
      o << " (" << nonpositive_volume_hexahedra << " hexahedra of non-positive volume)";
    o << "\n";
    if(!has_error())
      o << "volume difference: " << 100. * relative_volume_difference << " % (tolerance "
        << 100. * volume_tolerance << " %)\n";
    o << "boundary: " << boundary_triangles << " triangles, " << boundary_self_intersections
      << " self-intersecting pairs, " << degenerate_boundary_triangles << " degenerate\n";
    if(outside_checked)
    {
      o << "outside the reference: " << vertices_outside << " vertices, " << vertices_outside_beyond_tolerance
        << " beyond " << outside_tolerance << " x diagonal; max distance " << max_outside_distance
        << " (" << relative_max_outside_distance() << " x diagonal";
      if(farthest_outside_vertex != npos)
        o << ", vertex " << farthest_outside_vertex;
      o << ")\n";
    }
    if(passed())
      o << "PASSED";
    else
    {
      o << "FAILED:";
      if(has_error())
        o << " invalid reference;";
      else if(!(relative_volume_difference <= volume_tolerance))
        o << " volume;";
      if(vertices_outside_beyond_tolerance > 0)
        o << " vertices outside;";
      if(boundary_self_intersects())
        o << " self-intersecting boundary;";
    }
    o << " (" << seconds << " s, TetGen " << tetgen_seconds << " s)";
    return o.str();
  }
};

/// prints `r.summary()`
inline std::ostream& operator<<(std::ostream& os, const Reference_volume_report& r)
{
  return os << r.summary();
}

} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_REFERENCE_VOLUME_REPORT_H
