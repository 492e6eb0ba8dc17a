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

#ifndef CGAL_IMPROVE_HEX_MESH_QUALITY_H
#define CGAL_IMPROVE_HEX_MESH_QUALITY_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

#include <CGAL/untangle_hex_mesh.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/Coarse_level_start.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/Hex_mesh_quality_improver.h>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

/// the quality settings from named parameters (the reference surface is
/// read by `read_untangle_parameters()`)
template <class NamedParameters>
void read_quality_parameters(const NamedParameters& np, const Untangle_settings& u, Quality_settings& s)
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  s.target_msj = checked_parameter("target_msj", choose_parameter(get_parameter(np, hex_mesh_internal_np::target_msj), 1.),
                                   -1., 1.);
  s.surface_tolerance = surface_tolerance_parameter(np);
  s.local_surface_tolerance = local_surface_tolerance_parameter(np);
  s.pull_back = choose_parameter(get_parameter(np, hex_mesh_internal_np::pull_back), true);
  s.asj_smoothing = choose_parameter(get_parameter(np, hex_mesh_internal_np::asj_smoothing), true);
  s.schedule = u.schedule; // the method's schedule (`read_untangle_parameters()`)
  const bool paper = choose_parameter(get_parameter(np, hex_mesh_internal_np::method), Method::package) == Method::paper;
  if(choose_parameter(get_parameter(np, hex_mesh_internal_np::edge_angle_stages), paper))
    s.schedule.msj_stage_edge_angle_passes = Optimization_schedule::paper_msj_stage_edge_angle_passes;
  else
    s.schedule.msj_stage_edge_angle_passes = 0;
  s.schedule.coarse_level_start =
    choose_parameter(get_parameter(np, hex_mesh_internal_np::coarse_level_start), s.schedule.coarse_level_start);
  s.sharp_angle = u.sharp_angle;
  s.reference_feature_angle = u.reference_feature_angle;
  s.schedule.crease_seed_angle = checked_parameter(
    "crease_seed_angle",
    choose_parameter(get_parameter(np, hex_mesh_internal_np::crease_seed_angle), s.schedule.crease_seed_angle), 0., 180.);
  s.schedule.turn_focus_band = checked_parameter(
    "turn_focus_band",
    choose_parameter(get_parameter(np, hex_mesh_internal_np::turn_focus_band), s.schedule.turn_focus_band), 0., 1.,
    true);
  s.xi = u.xi;
  s.local_iterations = u.local_iterations;
  s.alpha = (std::max)(u.alpha, 500.);
  s.beta = (std::max)(u.beta, 500.);
  if(paper) // the recipe's MSJ stages, where no named parameter is given
  {
    const Paper_recipe r = paper_recipe_parameter(np);
    s.target_msj = checked_parameter(
      "target_msj", choose_parameter(get_parameter(np, hex_mesh_internal_np::target_msj), r.target_msj), -1., 1.);
    if(r.msj_sharp_angle > 0.) s.sharp_angle = r.msj_sharp_angle;
    s.alpha = (std::max)(choose_parameter(get_parameter(np, hex_mesh_internal_np::alpha), r.msj_alpha), 500.);
    s.beta = (std::max)(choose_parameter(get_parameter(np, hex_mesh_internal_np::beta), r.msj_beta), 500.);
    s.xi = choose_parameter(get_parameter(np, hex_mesh_internal_np::xi), r.msj_xi);
    s.pull_back_to_input = true;
    s.keep_original_if_worse = true;
    s.schedule.pull_back_iterations = r.pull_back_iterations;
    if(!r.msj_in_steps && s.target_msj > 0.) // one stage, straight to the target
    {
      s.schedule.msj_stage_step = s.target_msj;
      s.schedule.msj_stage_fine_from = 2.;
    }
  }
  s.reference_points = u.reference_points;
  s.reference_triangles = u.reference_triangles;
  s.reference_creases = u.reference_creases;
}

/// `first` followed by `later` on the mesh `first` left: the stages of both,
/// the figures after `later`, the seconds of both; the input is kept only if
/// both kept theirs, and a hard stop that fired in either is said.
inline void append_run(Optimization_result& first, const Optimization_result& later)
{
  first.stages.insert(first.stages.end(), later.stages.begin(), later.stages.end());
  first.inverted_after = later.inverted_after;
  first.msj_after = later.msj_after;
  first.asj_after = later.asj_after;
  first.surface_error = later.surface_error;
  first.seconds += later.seconds;
  first.kept_input = first.kept_input && later.kept_input;
  first.success = later.success;
  first.certificate = later.certificate;
  first.time_limit_reached = first.time_limit_reached || later.time_limit_reached;
  first.interrupted = first.interrupted || later.interrupted;
}

/// Untangling and improvement interleaved: while elements are still inverted
/// after the quality stages (at most `untangle_again_rounds` times), the
/// untangler runs again on what they left, its boundary now pulled back
/// toward the surface, then the quality stages; a round is kept only if it
/// leaves fewer elements inverted, with the surface error within
/// max(tolerance, the error before it); a kept round is appended to `q`
/// (`append_run`). Why: once the quality stages have pulled the boundary
/// back and reshaped the neighbourhood, the untangler can free elements it
/// could not free from the input.
template <class Visitor>
void untangle_and_improve_again(Hex_mesh_arrays& arrays, const Hex_mesh_arrays& original, const Untangle_settings& u,
                                const Quality_settings& s, Visitor& visitor, Optimization_result& q)
{
  for(int round = 0; round < s.schedule.untangle_again_rounds && q.inverted_after > 0 &&
                     !time_limit_reached(s.time_limit); ++round)
  {
    Hex_mesh_arrays trial = arrays;
    Hex_mesh_untangler<Visitor> untangler(u, visitor);
    const Optimization_result r = untangler.run(trial, false);
    // a hard stop that fired in a round is said even when the round is not kept
    q.time_limit_reached = q.time_limit_reached || r.time_limit_reached;
    q.interrupted = q.interrupted || r.interrupted;
    if(r.inverted_after >= q.inverted_after) return;
    Hex_mesh_quality_improver<Visitor> improver(s, visitor);
    const Optimization_result q2 = improver.run(trial, original);
    q.time_limit_reached = q.time_limit_reached || q2.time_limit_reached;
    q.interrupted = q.interrupted || q2.interrupted;
    if(q2.inverted_after >= q.inverted_after ||
       !(q2.surface_error <= (std::max)(s.surface_tolerance, q.surface_error)))
      return;
    arrays = trial;
    append_run(q, r);
    append_run(q, q2);
  }
}

/// whether a mesh needs no work: nothing inverted, its MSJ at the aimed
/// target already, and no reference it starts away from (`warning`: the
/// reference check's)
inline bool already_at_target(const Quality_statistics& q, const Quality_settings& s, const std::string& warning)
{
  return q.inverted == 0 && q.msj >= s.aimed_msj() && warning.empty();
}

/// The result of a run with nothing to do: the input as it is, measured (its
/// certificate, its surface error), and one stage that says so.
template <class Visitor>
Optimization_result nothing_to_do(const Hex_mesh_arrays& mesh, const Quality_statistics& q, const Quality_settings& s,
                                  Visitor& visitor)
{
  Optimization_result res;
  res.inverted_before = res.inverted_after = q.inverted;
  res.msj_before = res.msj_after = q.msj;
  res.asj_before = res.asj_after = q.asj;
  res.success = true;
  res.certificate.hexes = mesh.hexes.size();
  res.certificate.not_certified = uncertified_hexes(mesh);
  res.surface_error = s.reference_points ? relative_surface_error_to(mesh, mesh, s.reference_points, s.reference_triangles)
                                         : 0.;
  Stage_report sr;
  sr.name = "at target";
  sr.msj_after = q.msj;
  sr.details = "no inverted element and the MSJ at the target already: nothing to do";
  visitor.stage_started(sr.name, 0);
  visitor.stage_finished(sr);
  res.stages.push_back(sr);
  return res;
}

/// the body of `improve_hex_mesh_quality()` (`untangle_first` false) and of
/// `optimize_hex_mesh()` (true: the untangler runs first when the mesh has
/// inverted elements, and both results are merged)
template <class HexMesh, class NamedParameters>
Optimization_result run_quality_pipeline(HexMesh& mesh, const NamedParameters& np, bool untangle_first)
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  typedef Hex_mesh_parameters<HexMesh, NamedParameters> Mesh_parameters;

  const auto start = std::chrono::steady_clock::now(); // for the result's seconds only
  Time_limit time_limit(time_limit_parameter(np));
  time_limit.watch(stop_flag_parameter(np));
  Default_optimization_visitor default_visitor;
  auto&& visitor = choose_parameter(parameters::get_parameter_reference(np, internal_np::visitor), default_visitor);
  typedef typename std::remove_reference<decltype(visitor)>::type Visitor;

  Untangle_settings u;
  std::vector<Vec3> ref_points;
  std::vector<Tri> ref_tris;
  std::vector<std::array<std::size_t, 2> > ref_creases;
  read_untangle_parameters(np, u, ref_points, ref_tris, ref_creases);
  Quality_settings s;
  read_quality_parameters(np, u, s);
  u.time_limit = s.time_limit = &time_limit; // one hard stop for the whole pipeline

  Hex_mesh_arrays arrays = Mesh_parameters::extract(mesh, np);
  const std::vector<Vec3> read = arrays.points;
  const std::string warning =
    require_reference_fit(arrays, s.reference_points, s.reference_triangles, s.surface_tolerance);
  const Hex_mesh_arrays original = arrays;
  const Quality_statistics q_input = quality_statistics(arrays);
  if(already_at_target(q_input, s, warning))
  {
    Optimization_result result = nothing_to_do(arrays, q_input, s, visitor);
    if(s.reference_points) // (the input's own boundary is its reference otherwise)
      report_off_surface_vertices(arrays, original, s.reference_points, s.reference_triangles, s.surface_tolerance,
                                  s.local_surface_tolerance, result);
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  }
  Optimization_result result;
  const bool untangle = untangle_first && q_input.inverted > 0;
  if(untangle)
  {
    Hex_mesh_untangler<Visitor> untangler(u, visitor);
    result = untangler.run(arrays, false); // the improver measures the surface error
    // the paper's recipe: the pull-back only after a surface relaxed below the recipe's α
    if(s.pull_back_to_input && !(untangler.final_alpha() < paper_recipe_parameter(np).pull_back_below_alpha))
      s.pull_back = false;
  }
  // a valid refined mesh: its coarse level first (Coarse_level_start.h)
  std::vector<Vec3> boundary_points;
  std::vector<Tri> boundary_triangles;
  Quality_settings fine_settings;
  Optimization_result coarse;
  const bool coarse_start = !untangle && coarse_level_start(arrays, s, visitor, boundary_points, boundary_triangles,
                                                            fine_settings, coarse);
  Hex_mesh_quality_improver<Visitor> improver(coarse_start ? fine_settings : s, visitor);
  Optimization_result q = improver.run(arrays, original);
  if(!coarse.stages.empty()) // the coarse level's stages first, the input's "before" figures
  {
    append_run(coarse, q);
    q = std::move(coarse);
  }
  if(untangle) untangle_and_improve_again(arrays, original, u, s, visitor, q);
  if(untangle) append_run(result, q);
  else result = q;
  if(!warning.empty()) result.warnings.insert(result.warnings.begin(), warning);
  report_off_surface_vertices(arrays, original, s.reference_points, s.reference_triangles, s.surface_tolerance,
                              s.local_surface_tolerance, result);
  if(result.inverted_after > 0) result.unresolved = unresolved_elements(arrays, result.time_limit_reached || result.interrupted);
  Mesh_parameters::write_back(arrays, read, mesh, np);
  return result;
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization

/*!
\ingroup PkgHexahedralMeshOptimizationRef

\brief Raises the minimum scaled Jacobian (MSJ) of a hexahedral mesh in
stages, then its average (ASJ), keeping the boundary on a reference surface.

Sections 3.3 and 3.4 of Xu & Chen (2018) and the final smoothing:
- a mesh without inverted elements that its connectivity shows to be a 1→8
  refinement (every hex split into 8, once or more) is optimised at its
  coarsest level of at least 4096 hexes first, and the stages below start
  from its displacement carried down trilinearly (not with `Method::paper`;
  see the manual, "Quality Improvement");
- when the boundary is farther from the reference than `surface_tolerance`
  (after an untangling that relaxed it), an inversion-free pull-back brings it
  back (SLIM on the 9 Jacobian samples of each hex, flip-avoiding line search);
- MSJ stages with targets 0.1, 0.2, … up to `target_msj`: each runs the
  edge-angle local optimiser on the regions of the elements below the target
  (α, β ≥ 500, rollback whenever an element would fall under the MSJ the stage
  started from), projects the boundary back onto the target surface, then a
  max-min smoothing of the vertices of the elements still below the target,
  whose boundary moves stay within `surface_tolerance` of the reference. The
  first stage that misses its target ends the schedule;
- an ASJ smoothing that raises the mean without lowering any element under
  the MSJ reached.

The mesh returned never has a lower MSJ (nor more inverted elements) than the
input: when nothing better is found the input is returned as it was.

\tparam HexMesh a model of `HexMesh`

\param mesh the mesh, optimised in place
\param np an optional sequence of named parameters among the ones listed below

\cgalNamedParamsBegin
  \cgalParamNBegin{target_msj}
    \cgalParamDescription{the MSJ to reach, in [-1, 1] (`std::invalid_argument` otherwise); the stages stop there}
    \cgalParamType{`double`}
    \cgalParamDefault{1 (as high as the method gets it)}
  \cgalParamNEnd
  \cgalParamNBegin{surface_tolerance}
    \cgalParamDescription{largest surface error, relative to the reference's bounding-box diagonal, that the boundary moves of the quality stages may cause; in [0, 1] (`std::invalid_argument` otherwise)}
    \cgalParamType{`double`}
    \cgalParamDefault{0.005}
  \cgalParamNEnd
  \cgalParamNBegin{local_surface_tolerance}
    \cgalParamDescription{a fraction of the local edge length: the boundary moves of the quality stages also keep the boundary around each vertex within this fraction of the shortest edge at the vertex in the input, so that the tolerance means something for a boundary layer's thin first cells; the boundary vertices left farther from the reference than the tolerances allow are listed in `Optimization_result::off_surface`, with a warning; a negative value: none; NaN throws `std::invalid_argument`}
    \cgalParamType{`double`}
    \cgalParamDefault{none (`surface_tolerance` alone)}
  \cgalParamNEnd
  \cgalParamNBegin{reference_surface}
    \cgalParamDescription{a triangle (or polygon) mesh the boundary must stay on. It is checked against the mesh boundary before anything moves (`hex_mesh_reference_fit()`): one in another coordinate frame or of another object throws `Hexahedral_mesh_optimization::Reference_mismatch`, the mesh untouched; one the boundary starts farther from than `surface_tolerance` adds a warning to the result}
    \cgalParamType{a model of `FaceListGraph` with an internal vertex point map, e.g. `Surface_mesh`}
    \cgalParamDefault{the boundary of the input mesh}
  \cgalParamNEnd
  \cgalParamNBegin{sharp_angle}
    \cgalParamDescription{θ in degrees: boundary edges whose dihedral angle is below it are features; in [0, 180] (`std::invalid_argument` otherwise)}
    \cgalParamType{`double`}
    \cgalParamDefault{165}
  \cgalParamNEnd
  \cgalParamNBegin{reference_feature_angle}
    \cgalParamDescription{with `reference_surface`: the reference's edges with a dihedral angle below this, in degrees, are its creases; chains of boundary edges are matched to them and to their corners, and follow them (feature recovery), in place of the features found with `sharp_angle`. A reference without clear creases (fewer than half of the edges below this angle are also below it minus 30 degrees, as on a faceted organic surface) keeps the classification by `sharp_angle`. 0 turns recovery off; in [0, 180] (`std::invalid_argument` otherwise)}
    \cgalParamType{`double`}
    \cgalParamDefault{150}
  \cgalParamNEnd
  \cgalParamNBegin{method}
    \cgalParamDescription{`Hexahedral_mesh_optimization::Method::package`: the package's pipeline; `Method::paper`: the method of Xu & Chen alone (edge-angle untangling with relaxation, SLIM pull-back, MSJ stages by the edge-angle optimiser, ASJ smoothing), for reproducing the paper}
    \cgalParamType{`Hexahedral_mesh_optimization::Method`}
    \cgalParamDefault{`Method::package`}
  \cgalParamNEnd
  \cgalParamNBegin{maximum_running_time}
    \cgalParamDescription{a hard stop, in seconds of wall-clock time from the call: when it is reached every stage stops at its next safe point, the mesh returned is the last state that passed its surface check (never worse than the input) and the result's `time_limit_reached` is true. It decides nothing else: without it (the default) every stage runs to convergence or to its work cap, and the same input gives the same output on any machine. It is at least 0 (`std::invalid_argument` otherwise). It is CGAL's own named parameter `CGAL::parameters::maximum_running_time` (the package declares no `time_limit`: CGAL 5.5's Mesh_3 headers declare `CGAL::parameters::time_limit` as a Boost.Parameter keyword; from CGAL 5.6 on, CGAL's `time_limit` is another name of the same parameter).}
    \cgalParamType{`double`}
    \cgalParamDefault{none}
  \cgalParamNEnd
  \cgalParamNBegin{stop_flag}
    \cgalParamDescription{a flag another thread or a signal handler may set to stop the run: it is then a hard stop like `maximum_running_time` (every stage stops at its next safe point, the mesh returned is the last state that passed its checks, never worse than the input), and the result's `interrupted` is true}
    \cgalParamType{`const std::atomic<bool>*`}
    \cgalParamDefault{none}
  \cgalParamNEnd
  \cgalParamNBegin{vertex_point_map}
    \cgalParamDescription{a property map associating points to the vertices of `mesh`; only the vertices that moved are written back (`put()`), the others keep their points exactly, whatever the kernel}
    \cgalParamType{a model of `ReadWritePropertyMap` whose key type is the vertex descriptor of `HexMesh` and whose value type is the `Point_3` of `geom_traits`}
    \cgalParamDefault{the points of the mesh}
  \cgalParamNEnd
  \cgalParamNBegin{vertex_is_constrained_map}
    \cgalParamDescription{a property map saying which vertices are constrained: a constrained vertex never moves, in any stage (untangling, surface pull-back, smoothing); an inverted hexahedron that only moving constrained vertices could free is reported in `Optimization_result::unresolved` with the reason `constrained`}
    \cgalParamType{a model of `ReadablePropertyMap` whose key type is the vertex descriptor of `HexMesh` and whose value type is `bool`}
    \cgalParamDefault{no vertex is constrained}
  \cgalParamNEnd
  \cgalParamNBegin{reference_vertex_point_map}
    \cgalParamDescription{with `reference_surface`: the points of its vertices}
    \cgalParamType{a model of `ReadablePropertyMap` whose key type is the vertex descriptor of the reference surface and whose value type is a point of a CGAL kernel}
    \cgalParamDefault{`get_const_property_map(CGAL::vertex_point, reference)`}
  \cgalParamNEnd
  \cgalParamNBegin{edge_is_constrained_map}
    \cgalParamDescription{with `reference_surface` and feature recovery (`reference_feature_angle` above 0): edges of the reference that are creases whatever their dihedral angle, added to those detected; the mesh boundary recovers them as it recovers the detected ones}
    \cgalParamType{a model of `ReadablePropertyMap` whose key type is the edge descriptor of the reference surface and whose value type is `bool`}
    \cgalParamDefault{no edge is given}
  \cgalParamNEnd
  \cgalParamNBegin{visitor}
    \cgalParamDescription{an object notified of stages and rounds}
    \cgalParamType{a class with the functions of `Hexahedral_mesh_optimization::Default_optimization_visitor`}
    \cgalParamDefault{`Hexahedral_mesh_optimization::Default_optimization_visitor`}
  \cgalParamNEnd
  \cgalParamNBegin{geom_traits}
    \cgalParamDescription{an instance of a geometric traits class}
    \cgalParamType{a model of `HexMeshOptimizationTraits`}
    \cgalParamDefault{the kernel of the mesh's point type}
  \cgalParamNEnd
\cgalNamedParamsEnd

\returns MSJ, ASJ and inverted count before and after, surface error against
  the reference, time and a report per stage; `success` is true when the mesh
  has no inverted element and reached `target_msj`. The elements still
  inverted, if any, are listed with the reason each was not freed
  (`Optimization_result::unresolved`).
*/
template <class HexMesh, class CGAL_NP_TEMPLATE_PARAMETERS>
Hexahedral_mesh_optimization::Optimization_result
improve_hex_mesh_quality(HexMesh& mesh, const CGAL_NP_CLASS& np = parameters::default_values())
{
  return Hexahedral_mesh_optimization::internal::run_quality_pipeline(mesh, np, false);
}

/*!
\ingroup PkgHexahedralMeshOptimizationRef

\brief The whole pipeline: untangles the mesh (`untangle_hex_mesh()`, only
when it has inverted elements), then improves it (`improve_hex_mesh_quality()`:
pull-back, MSJ stages, ASJ smoothing), the surface error being measured
against the input's boundary (or the reference surface) throughout.

It takes the named parameters of both functions; `maximum_running_time` is a hard stop
for the whole pipeline (default: none). The result's stages list both parts
in order.
*/
template <class HexMesh, class CGAL_NP_TEMPLATE_PARAMETERS>
Hexahedral_mesh_optimization::Optimization_result
optimize_hex_mesh(HexMesh& mesh, const CGAL_NP_CLASS& np = parameters::default_values())
{
  return Hexahedral_mesh_optimization::internal::run_quality_pipeline(mesh, np, true);
}

} // namespace CGAL

#endif // CGAL_IMPROVE_HEX_MESH_QUALITY_H
