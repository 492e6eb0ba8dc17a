// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Package: Hexahedral_mesh_optimization

#ifndef CGAL_IMPROVE_HEX_MESH_QUALITY_H
#define CGAL_IMPROVE_HEX_MESH_QUALITY_H

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
    s.schedule.pull_back_iterations = r.pull_back_iterations;
    if(!r.msj_in_steps && s.target_msj > 0.) // one stage, straight to the target
    {
      s.schedule.msj_stage_step = s.target_msj;
      s.schedule.msj_stage_fine_from = 2.;
    }
  }
  s.reference_points = u.reference_points;
  s.reference_triangles = u.reference_triangles;
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
  typedef Hex_mesh_adapter<HexMesh> Adapter;
  typedef typename Kernel_traits<typename Adapter::Point>::Kernel Default_traits;

  const auto start = std::chrono::steady_clock::now(); // for the result's seconds only
  Time_limit time_limit(time_limit_parameter(np));
  time_limit.watch(stop_flag_parameter(np));
  const auto gt = choose_parameter(get_parameter(np, internal_np::geom_traits), Default_traits());
  Default_optimization_visitor default_visitor;
  auto&& visitor = choose_parameter(parameters::get_parameter_reference(np, internal_np::visitor), default_visitor);
  typedef typename std::remove_reference<decltype(visitor)>::type Visitor;

  Untangle_settings u;
  std::vector<Vec3> ref_points;
  std::vector<Tri> ref_tris;
  read_untangle_parameters(np, gt, u, ref_points, ref_tris);
  Quality_settings s;
  read_quality_parameters(np, u, s);
  u.time_limit = s.time_limit = &time_limit; // one hard stop for the whole pipeline

  Hex_mesh_arrays arrays = Adapter::extract(mesh, gt);
  const std::string warning =
    require_reference_fit(arrays, s.reference_points, s.reference_triangles, s.surface_tolerance);
  const Hex_mesh_arrays original = arrays;
  const Quality_statistics q_input = quality_statistics(arrays);
  if(already_at_target(q_input, s, warning))
  {
    Optimization_result result = nothing_to_do(arrays, q_input, s, visitor);
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
  if(result.inverted_after > 0) result.unresolved = unresolved_elements(arrays, result.time_limit_reached || result.interrupted);
  Adapter::write_back(arrays, mesh, gt);
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

\tparam HexMesh `Indexed_hex_mesh` or `Linear_cell_complex_for_combinatorial_map<3,3>`

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
  \cgalParamNBegin{crease_seed_angle}
    \cgalParamDescription{in the quality stages, a crease starts only at a boundary edge whose dihedral angle is below this; an edge below `sharp_angle` only continues a crease from its end (hysteresis), so that the many edges just below `sharp_angle` of a coarse curved boundary make no short creases meeting in spurious corners. 180 or `sharp_angle`: every edge below `sharp_angle` is a crease. It is off by default because its gains and losses are spread over the published rows and the stress set (the benchmark's RESULTS.md has both); in [0, 180] (`std::invalid_argument` otherwise)}
    \cgalParamType{`double`}
    \cgalParamDefault{180}
  \cgalParamNEnd
  \cgalParamNBegin{turn_focus_band}
    \cgalParamDescription{the turns of max-min and ASJ smoothing before the final ASJ smoothing: each turn's ASJ pass reshapes the neighbourhood of the elements below the MSJ plus this band, in (0, 1] (`std::invalid_argument` otherwise). The default meets the package's time targets on the published rows; 0.2 reaches a higher MSJ for more time (the benchmark's RESULTS.md has the published rows with both)}
    \cgalParamType{`double`}
    \cgalParamDefault{0.15}
  \cgalParamNEnd
  \cgalParamNBegin{alpha}
    \cgalParamDescription{weight of the feature and corner constraints in the edge-angle stages (a value below 500 counts as 500); in [0, 1e12] (`std::invalid_argument` otherwise)}
    \cgalParamType{`double`}
    \cgalParamDefault{1000}
  \cgalParamNEnd
  \cgalParamNBegin{beta}
    \cgalParamDescription{weight of the tangent-plane constraint in the edge-angle stages (a value below 500 counts as 500); in [0, 1e12] (`std::invalid_argument` otherwise)}
    \cgalParamType{`double`}
    \cgalParamDefault{1000}
  \cgalParamNEnd
  \cgalParamNBegin{method}
    \cgalParamDescription{`Hexahedral_mesh_optimization::Method::package`: the package's pipeline; `Method::paper`: the method of Xu & Chen alone (edge-angle untangling with relaxation, SLIM pull-back, MSJ stages by the edge-angle optimiser, ASJ smoothing), for reproducing the paper}
    \cgalParamType{`Hexahedral_mesh_optimization::Method`}
    \cgalParamDefault{`Method::package`}
  \cgalParamNEnd
  \cgalParamNBegin{edge_angle_stages}
    \cgalParamDescription{whether each MSJ stage runs the edge-angle optimiser (up to 8 passes while they raise the MSJ by 0.005) where the max-min smoothing falls short}
    \cgalParamType{`bool`}
    \cgalParamDefault{`false`, `true` with `Method::paper`}
  \cgalParamNEnd
  \cgalParamNBegin{pull_back}
    \cgalParamDescription{whether the pull-back runs when the surface error exceeds the tolerance (its result is kept only if it lowers the surface error)}
    \cgalParamType{`bool`}
    \cgalParamDefault{`true`}
  \cgalParamNEnd
  \cgalParamNBegin{coarse_level_start}
    \cgalParamDescription{whether a mesh without inverted elements that its connectivity shows to be a 1→8 refinement (every hex split into 8, once or more) is optimised at its coarsest level of at least 4096 hexes first, the stages then starting from that level's displacement carried down trilinearly: on a finely refined mesh the turns end in a local optimum that a coarse vertex's move, which shifts many fine layers at once, avoids}
    \cgalParamType{`bool`}
    \cgalParamDefault{`true`, `false` with `Method::paper`}
  \cgalParamNEnd
  \cgalParamNBegin{asj_smoothing}
    \cgalParamDescription{whether the ASJ smoothing runs: at the end, and in turn with the MSJ stages while that raises the MSJ}
    \cgalParamType{`bool`}
    \cgalParamDefault{`true`}
  \cgalParamNEnd
  \cgalParamNBegin{time_limit}
    \cgalParamDescription{a hard stop, in seconds of wall-clock time from the call: when it is reached every stage stops at its next safe point, the mesh returned is the last state that passed its surface check (never worse than the input) and the result's `time_limit_reached` is true. It decides nothing else: without it (the default) every stage runs to convergence or to its work cap, and the same input gives the same output on any machine. It is at least 0 (`std::invalid_argument` otherwise).}
    \cgalParamType{`double`}
    \cgalParamDefault{none}
  \cgalParamNEnd
  \cgalParamNBegin{stop_flag}
    \cgalParamDescription{a flag another thread or a signal handler may set to stop the run: it is then a hard stop like `time_limit` (every stage stops at its next safe point, the mesh returned is the last state that passed its checks, never worse than the input), and the result's `interrupted` is true}
    \cgalParamType{`const std::atomic<bool>*`}
    \cgalParamDefault{none}
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

It takes the named parameters of both functions; `time_limit` is a hard stop
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
