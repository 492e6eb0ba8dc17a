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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_OPTIMIZATION_SETUP_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_OPTIMIZATION_SETUP_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// What the untangler (Hex_mesh_untangler.h) and the quality improver
// (Hex_mesh_quality_improver.h) both do around their stages:
// - normalise the mesh to mean edge length 0.025 before, and back after, so
//   that α = β = 1000 mean the same on every model;
// - build the ideal angles from the connectivity, with the measured dihedral
//   angle of the target surface Ω_t on its feature edges;
// - never return a mesh worse than the input (more inverted elements, or as
//   many with a lower MSJ): the input positions are then kept.

#include <CGAL/Hexahedral_mesh_optimization/Optimization_result.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Untangling/Ideal_angles.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Target_surface.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/exact_validity.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/quality_statistics.h>

#include <algorithm>
#include <set>
#include <utility>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

/// mean edge length 0.025 about the centroid: p' = s (p - c)
struct Normalization
{
  double scale = 1.;
  Vec3 centre = {0., 0., 0.};
  Vec3 apply(const Vec3& p) const { return scale * (p - centre); }
  Vec3 undo(const Vec3& p) const { return (1. / scale) * p + centre; }
};

inline Normalization normalization(const Hex_mesh_topology& topo, const std::vector<Vec3>& points)
{
  Normalization n;
  double sum = 0.;
  for(std::size_t e = 0; e < topo.number_of_edges(); ++e)
    sum += norm(points[topo.edge(e)[0]] - points[topo.edge(e)[1]]);
  const double mean = sum / (std::max)(std::size_t(1), topo.number_of_edges());
  n.scale = mean > 0. ? 0.025 / mean : 1.;
  for(const Vec3& p : points) n.centre = n.centre + p;
  n.centre = (1. / (std::max)(std::size_t(1), points.size())) * n.centre;
  return n;
}

/// ideal angles of the mesh whose current positions are `points`, with the
/// dihedral angles of Ω_t on the feature edges of `ts`
inline Ideal_angles ideal_angles_on_target(const Hex_mesh_topology& topo, const Target_surface& ts,
                                           const std::vector<Vec3>& points)
{
  std::vector<Vec3> omega = points;
  ts.target_points(omega);
  std::set<std::pair<std::size_t, std::size_t> > sharp;
  for(std::size_t e = 0; e < ts.boundary().edges.size(); ++e)
    if(ts.sharp_edges()[e]) sharp.insert({ts.boundary().edges[e][0], ts.boundary().edges[e][1]});
  return Ideal_angles(topo, boundary_edge_angles(topo, omega, [&](std::size_t a, std::size_t b) {
                        return sharp.count(std::minmax(a, b)) != 0;
                      }));
}

/// Once the normalisation is undone (`points`): a vertex whose normalised
/// position is still its normalised input position (`normalized_input`)
/// gets its input position (`input`) back exactly, as undoing the
/// normalisation rounds it, so that only the vertices the stages moved
/// differ from the input (the caller writes back only those: the others
/// keep their exact coordinates). A constrained vertex gets its input
/// position back too: the stages never move one (they ask
/// `Hex_mesh_topology::is_constrained()`), and this makes it so whatever
/// a stage did; `keep_input_if_worse()` comes after.
inline void restore_unmoved_vertices(std::vector<Vec3>& points, const std::vector<Vec3>& normalized,
                                     const std::vector<Vec3>& normalized_input, const std::vector<Vec3>& input,
                                     const Hex_mesh_arrays& mesh)
{
  for(std::size_t v = 0; v < points.size(); ++v)
    if(normalized[v] == normalized_input[v] || mesh.is_constrained(v)) points[v] = input[v];
}

/// If `mesh` is worse than the input (positions `input_points`, the same
/// hexes: the stages never change them; quality `before`), puts the input
/// positions back and sets `res.kept_input`; fills the "after" figures and the certificate
/// of `res` either way and returns the quality of what is returned.
/// "Worse": more hexes not certified valid (exact_validity.h), more inverted
/// elements, or as many and an MSJ lower by more than
/// `msj_rounding_tolerance`: undoing the normalisation rounds the
/// coordinates, which alone can move a stuck minimum by an ulp, and must not
/// throw away what the stages gained elsewhere (a run whose MSJ stayed where
/// it was but whose ASJ rose would otherwise return the input).
inline Quality_statistics keep_input_if_worse(Hex_mesh_arrays& mesh, const std::vector<Vec3>& input_points,
                                              const Quality_statistics& before, Optimization_result& res)
{
  Quality_statistics after = quality_statistics(mesh);
  std::vector<std::size_t> uncertified = uncertified_hexes(mesh);
  constexpr double msj_rounding_tolerance = 1e-12;
  bool worse = after.inverted > before.inverted ||
               (after.inverted == before.inverted && after.msj < before.msj - msj_rounding_tolerance);
  std::vector<std::size_t> input_uncertified; // computed at most once
  bool input_certified = false;
  if(!worse && !uncertified.empty())
  {
    input_uncertified = uncertified_hexes(mesh.hexes, input_points);
    input_certified = true;
    worse = uncertified.size() > input_uncertified.size();
  }
  if(worse)
  {
    mesh.points = input_points;
    after = before;
    res.kept_input = true;
    uncertified = input_certified ? std::move(input_uncertified) : uncertified_hexes(mesh);
  }
  res.certificate.hexes = mesh.hexes.size();
  res.certificate.not_certified = std::move(uncertified);
  res.inverted_after = after.inverted; res.msj_after = after.msj; res.asj_after = after.asj;
  return after;
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_OPTIMIZATION_SETUP_H
