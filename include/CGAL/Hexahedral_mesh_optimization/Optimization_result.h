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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_OPTIMIZATION_RESULT_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_OPTIMIZATION_RESULT_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

#include <cstddef>
#include <string>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {

/*!
\ingroup PkgHexahedralMeshOptimizationRef
What one stage of an optimisation did.
*/
struct Stage_report
{
  std::string name;               ///< e.g. "edge-angle", "barrier"
  std::size_t inverted_before = 0;
  std::size_t inverted_after = 0;
  double msj_after = 0.;
  double seconds = 0.;
  int rounds = 0;                 ///< rounds (edge-angle) or passes (barrier)
  std::string details;            ///< human-readable summary (α, β reached, steps, ...)
};

/*!
\ingroup PkgHexahedralMeshOptimizationRef
An element still inverted when an optimisation gives up, and why.
*/
struct Unresolved_element
{
  std::size_t hex = 0;          ///< its index in the mesh's hexahedra
  double scaled_jacobian = 0.;  ///< its Verdict scaled Jacobian (negative)
  /// `locked`: one of its inverted corner frames has its corner and the three
  /// neighbours along its edges all on the boundary (or the centre frame is
  /// inverted and all 8 vertices are): no interior vertex can fix it, only
  /// moving the surface can (this reason comes first, whether the time
  /// limit fired or not).
  /// `region_exhausted`: it has an interior vertex in an inverted frame,
  /// and the stages' widest regions around it did not free it.
  /// `time_limit`: a hard stop (`maximum_running_time`, or `stop_flag`) fired before
  /// the stages were done.
  /// `constrained`: one of its inverted frames has every vertex constrained
  /// by the user (`vertex_is_constrained_map`) or on the boundary, at least
  /// one constrained: only moving a constrained vertex could free it (this
  /// reason comes first).
  enum Reason { locked, region_exhausted, time_limit, constrained };
  Reason reason = region_exhausted;
  std::string details;          ///< which frames are inverted, in words
};

/*!
\ingroup PkgHexahedralMeshOptimizationRef
A boundary vertex the optimisation left farther from the reference surface
than the tolerances allow: `surface_tolerance` times the reference's
bounding-box diagonal, and, when given, `local_surface_tolerance` times the
vertex's local edge length (the shortest edge at it in the input). A
vertex ends there when putting it back on the surface would invert an
element or lower the MSJ reached, or when the input already had it there.
*/
struct Off_surface_vertex
{
  std::size_t vertex = 0;     ///< its index in the mesh's vertices
  double distance = 0.;       ///< its distance to the reference surface, in model units
  double allowed = 0.;        ///< the distance the tolerances allow it, in model units
  double local_length = 0.;   ///< the shortest edge at it in the input, in model units
};

/*!
\ingroup PkgHexahedralMeshOptimizationRef
The exact validity certificate of a hexahedral mesh
(`hex_mesh_validity_certificate()`): a hexahedron is certified valid when
the Jacobian determinant is positive, decided exactly on its coordinates,
at its 8 corners (the orientation of each corner tetrahedron, by CGAL's
exact predicate) and at its centre (the principal axes: interval
arithmetic, exact rationals when the interval contains 0). These are the 9
samples of the Verdict scaled Jacobian; their rounded values can have the
wrong sign within a few ulps of zero, the certificate cannot. A hexahedron
with a zero sample (flat) is not certified either.
*/
struct Validity_certificate
{
  std::size_t hexes = 0;                  ///< the number of hexahedra examined
  std::vector<std::size_t> not_certified; ///< the indices of those not certified valid, in index order
  /// the number of hexahedra certified valid
  std::size_t certified_valid() const { return hexes - not_certified.size(); }
  /// whether every hexahedron is certified valid
  bool all_valid() const { return not_certified.empty(); }
};

/*!
\ingroup PkgHexahedralMeshOptimizationRef
The result of `untangle_hex_mesh()`: never a bare bool.

`success` is true when the mesh has no inverted element at the end (and,
for the quality functions, its MSJ reached the target). Whatever the
outcome, the mesh returned has no more inverted elements than the input and,
at equal counts, an MSJ no lower (up to 1e-12, the rounding of the
coordinates when the internal normalisation is undone): when the
optimisation could not do better, the input positions are kept (`kept_input`
is then true).

The stages end on their own criteria (convergence, work caps counted in
sweeps or iterations), never on the clock, so that the same input and
options always give the same result. The `maximum_running_time` named parameter is a
hard stop only: when it fires, every stage stops at its next safe point, the
last state that passed its checks is returned (never worse than the input),
and `time_limit_reached` is true.
*/
struct Optimization_result
{
  bool success = false;
  bool kept_input = false;
  std::size_t inverted_before = 0, inverted_after = 0;
  double msj_before = 0., msj_after = 0.;
  double asj_before = 0., asj_after = 0.;
  /// Hausdorff distance between the output boundary and the reference
  /// surface, relative to the reference's bounding-box diagonal
  double surface_error = 0.;
  /// wall-clock time of the optimisation, in seconds (a report: no stage reads it)
  double seconds = 0.;
  /// whether the `maximum_running_time` hard stop fired (the result is then the last
  /// checked state the run had reached when it stopped)
  bool time_limit_reached = false;
  /// whether the `stop_flag` hard stop fired (the result is then, as for the
  /// time limit, the last checked state the run had reached when it stopped)
  bool interrupted = false;
  /// what the caller should know and that did not stop the run, e.g. a
  /// reference surface the boundary starts far from (`Reference_fit`)
  std::vector<std::string> warnings;
  /// the elements still inverted at the end (empty when `inverted_after` is
  /// 0), in index order, each with the reason it was not freed
  std::vector<Unresolved_element> unresolved;
  /// the boundary vertices farther from the reference than the tolerances
  /// allow (`Off_surface_vertex`), farthest first relative to what they are
  /// allowed; empty when every boundary vertex is within them
  std::vector<Off_surface_vertex> off_surface;
  /// the exact validity certificate of the mesh returned; the rule "never
  /// worse than the input" also compares the numbers of hexahedra not
  /// certified valid (a result with more is replaced by the input)
  Validity_certificate certificate;
  std::vector<Stage_report> stages;
};

/*!
\ingroup PkgHexahedralMeshOptimizationRef
The default visitor: every hook does nothing. A user visitor derives from it
(or provides the same functions) to follow progress.
*/
struct Default_optimization_visitor
{
  void stage_started(const std::string& /*name*/, std::size_t /*bad_elements*/) {}
  void round_finished(const std::string& /*stage*/, int /*round*/, std::size_t /*bad_elements_left*/) {}
  void stage_finished(const Stage_report& /*report*/) {}
};

} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_OPTIMIZATION_RESULT_H
