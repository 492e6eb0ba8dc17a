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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_COARSE_LEVEL_START_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_COARSE_LEVEL_START_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The coarse-level start of the quality stages: a valid mesh recognised as a
// 1→8 refinement (Refinement_hierarchy.h) is optimised at a coarse level
// first, and the fine level starts from the input moved by the coarse
// level's displacement, carried down trilinearly. On a fine mesh the
// max-min and ASJ turns end in a local optimum that a coarse level, whose
// vertex moves shift many fine layers at once, avoids (the figures are in
// benchmark/Hexahedral_mesh_optimization/RESULTS.md; `Optimization_schedule::
// coarse_level_start`).

#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Refinement_hierarchy.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/Hex_mesh_quality_improver.h>

#include <chrono>
#include <sstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

/// The levels of a recognised refinement, finest first, down to the
/// coarsest of at least `min_hexes` hexes (empty: not a refinement, or its
/// coarse level would be smaller).
inline std::vector<Refinement_level> coarse_levels(const Hex_mesh_arrays& mesh, std::size_t min_hexes,
                                                   const Time_limit* time_limit)
{
  std::vector<Refinement_level> levels;
  while(!time_limit_reached(time_limit))
  {
    Refinement_level next;
    if(!recognise_refinement(levels.empty() ? mesh : levels.back().coarse, next) || next.coarse.hexes.size() < min_hexes)
      break;
    levels.push_back(std::move(next));
  }
  return levels;
}

/// Runs the coarse level and moves `mesh` to the fine level's start when
/// `mesh` (no element inverted) is a recognised refinement, the coarse
/// level ends with nothing inverted and a higher MSJ, and the start has
/// nothing inverted and a higher MSJ than `mesh`; returns whether it did.
/// `fine_settings` is then `s` with the reference the coarse level was
/// measured against (the user's, or `mesh`'s boundary, whose triangles
/// `boundary_points` and `boundary_triangles` receive: the fine level's
/// boundary vertices have moved, their homes are their closest points on
/// it), and no surface restoration before the MSJ stages.
/// `result` receives the coarse level's stages, prefixed "coarse level: ",
/// a stage "coarse level" that says what was done, and the input's
/// quality as the "before" figures, to be followed by the fine level's run
/// (`append_run`).
template <class Visitor>
bool coarse_level_start(Hex_mesh_arrays& mesh, const Quality_settings& s, Visitor& visitor,
                        std::vector<Vec3>& boundary_points, std::vector<Tri>& boundary_triangles,
                        Quality_settings& fine_settings, Optimization_result& result)
{
  const Optimization_schedule& sc = s.schedule;
  // (the fine vertices follow the coarse level's displacement carried down:
  // with constrained vertices the stages start from the fine mesh itself)
  if(!sc.coarse_level_start || mesh.has_constrained_vertices()) return false;
  const auto start_time = std::chrono::steady_clock::now();
  const Quality_statistics q0 = quality_statistics(mesh);
  if(q0.inverted > 0) return false;
  const std::vector<Refinement_level> levels = coarse_levels(mesh, sc.coarse_level_min_hexes, s.time_limit);
  if(levels.empty() || time_limit_reached(s.time_limit)) return false;

  fine_settings = s;
  if(!s.reference_points || !s.reference_triangles)
  {
    triangulate_boundary(extract_boundary(mesh), mesh.points, Quad_split::diagonal_02, boundary_points,
                         boundary_triangles);
    fine_settings.reference_points = &boundary_points;
    fine_settings.reference_triangles = &boundary_triangles;
  }
  visitor.stage_started("coarse level", 0);
  Hex_mesh_arrays coarse = levels.back().coarse;
  const std::vector<Vec3> coarse_input = coarse.points;
  Hex_mesh_quality_improver<Visitor> improver(fine_settings, visitor);
  const Optimization_result rc = improver.run(coarse, coarse);

  Stage_report sr;
  sr.name = "coarse level";
  std::ostringstream d;
  d << "1->8 refinement recognised, " << levels.size() << (levels.size() == 1 ? " level" : " levels")
    << "; the coarsest (" << coarse.hexes.size() << " hexes) optimised: MSJ " << rc.msj_before << " -> "
    << rc.msj_after << ", surface error " << rc.surface_error;
  bool used = false;
  double start_msj = q0.msj;
  if(!time_limit_reached(s.time_limit) && rc.inverted_after == 0 && rc.msj_after > rc.msj_before)
  {
    std::vector<Vec3> displacement(coarse.points.size());
    for(std::size_t i = 0; i < coarse.points.size(); ++i) displacement[i] = coarse.points[i] - coarse_input[i];
    for(std::size_t l = levels.size(); l-- > 0;) displacement = prolongate(levels[l], displacement);
    const std::vector<Vec3> input_points = mesh.points;
    for(std::size_t v = 0; v < mesh.points.size(); ++v) mesh.points[v] = mesh.points[v] + displacement[v];
    const Quality_statistics qs = quality_statistics(mesh);
    used = qs.inverted == 0 && qs.msj > q0.msj;
    if(used)
    {
      start_msj = qs.msj;
      fine_settings.restore_before_msj_stages = false;
      d << "; the fine level starts at MSJ " << qs.msj;
    }
    else
    {
      mesh.points = input_points;
      d << "; carried down it gives MSJ " << qs.msj << " with " << qs.inverted << " inverted: not used";
    }
  }
  else
    d << ": not used";

  for(Stage_report r : rc.stages)
  {
    r.name = "coarse level: " + r.name;
    result.stages.push_back(r);
  }
  sr.msj_after = start_msj;
  sr.details = d.str();
  sr.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  result.stages.push_back(sr);
  visitor.stage_finished(sr);
  result.inverted_before = q0.inverted;
  result.msj_before = q0.msj;
  result.asj_before = q0.asj;
  result.seconds = sr.seconds;
  result.kept_input = !used; // the input as it was, unless the start was used (`append_run`)
  result.time_limit_reached = rc.time_limit_reached;
  result.interrupted = rc.interrupted;
  return used;
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_COARSE_LEVEL_START_H
