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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_OPTIMIZATION_SCHEDULE_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_OPTIMIZATION_SCHEDULE_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The schedule of the two drivers (Hex_mesh_untangler.h and
// Hex_mesh_quality_improver.h): how much work each stage may do and when it
// has converged. Every stage ends when it reaches its target, when it
// converges (its minimum, or its energy, improved by less than the ε below
// over the number of sweeps below), or at a work cap counted in rounds,
// sweeps, passes, iterations or turns. Nothing here is a time: the run's time
// limit is a hard stop only (Time_limit.h), so the same input and options
// give the same output on any machine and under any load.
//
// The values were chosen on the shared meshes and the benchmark's stress
// set; the measurements behind them are in
// benchmark/Hexahedral_mesh_optimization/RESULTS.md.

#include <cstddef>
#include <limits>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

struct Optimization_schedule
{
  // ---- which stages run (the paper's method runs fewer, see `paper()`)

  /// untangling: the barrier with the boundary fixed before the edge-angle
  /// stage, the barrier on what that leaves, and the barrier pull-back of
  /// the boundary ("surface")
  bool interior_stage = true;
  /// untangling: the paper's edge-angle optimiser (Algorithm 1) between the
  /// two barrier stages; it also runs whenever the barrier stages are off
  /// (named parameter `barrier_fallback`)
  bool edge_angle_stage = true;
  bool barrier_stage = true;
  bool surface_stage = true;
  /// quality: the surface restoration before and after the MSJ stages
  bool restoration = true;
  /// quality: the surface fit after the pull-back, when the error is above
  /// the tolerance (Surface_fitting.h)
  bool surface_fitting = true;
  /// quality: the max-min smoothing in each MSJ stage
  bool msj_stage_max_min = true;
  /// quality: the boundary exactly onto the target surface at the end,
  /// vertex by vertex, where that keeps the MSJ (Final_projection.h)
  bool final_projection = true;
  /// sweeps of that projection over the boundary (a move can make room for the next)
  int final_projection_sweeps = 3;

  // ---- untangling (Hex_mesh_untangler.h)

  /// rings of hexes around the inverted ones in the regions of the stage
  /// "interior" (the barrier with every boundary vertex fixed)
  int interior_rings = 3;
  /// a hex whose input SJ is at least this is well made: the stage "interior"
  /// may keep its input shape as the barrier's ideal, and the untangler's
  /// give-back may put its vertices back (> 1: never)
  double barrier_input_shape_sj = 0.99;
  /// ... and an inverted hex whose median edge lengths along its three
  /// directions have at least this aspect gets that box as ideal
  double barrier_box_min_aspect = 2.;
  /// ... where at least this share of the hexes sharing a vertex with it are
  /// well-made elongated boxes (the mesher meant boxes there)
  double barrier_box_evidence = 0.5;
  /// the edge-angle stage (Algorithm 1): at most this many rounds (its first
  /// rounds relax the surface where the barrier alone would leave it locked;
  /// the barrier frees the rest far faster), ended earlier by this many
  /// consecutive rounds that free nothing, and regions above this many hexes
  /// are left to the barrier (their sparse Cholesky factorisation grows much
  /// faster than their size)
  int edge_angle_rounds = 4;
  int edge_angle_stalled_rounds = 8;
  std::size_t edge_angle_max_region_hexes = 3000;
  /// the stage "barrier": one pass per weight, in units of w0 (moving a
  /// vertex one mean edge off its anchor costs as much as one well-shaped
  /// frame), each on regions one ring wider than the previous; sliding along
  /// the surface costs `barrier_sliding_fraction` of the weight
  double barrier_weights_relaxed[4] = {100., 10., 1., 1.};
  double barrier_weights_fixed[2] = {1000., 1000.};
  double barrier_sliding_fraction = 0.1;
  /// what the passes of the stage "barrier" leave inverted gets one more
  /// pass, on regions one ring wider than the last, with the volume term of
  /// the foldover-free energy at this weight (`Barrier_untangler`, 0: no
  /// such pass). The shape term alone lets a frame it cannot untangle
  /// collapse into a sliver that no later stage can free; the volume term
  /// keeps it open. It runs in a last pass only: in every pass it changes
  /// the turns' path on inputs that need no such help.
  double barrier_volume_weight = 0.1;
  /// `optimize_hex_mesh()`: how many times the untangler and the quality
  /// stages run again while elements are still inverted
  /// (`untangle_and_improve_again`)
  int untangle_again_rounds = 2;
  /// the stage "surface": outer passes, and the residual (in mean edges)
  /// under which a boundary vertex is on the target surface
  int surface_passes = 4;
  double surface_residual_edges = 0.1;

  // ---- quality (Hex_mesh_quality_improver.h)

  /// The coarse-level start (Coarse_level_start.h): a mesh without inverted
  /// elements that its connectivity shows to be a 1→8 refinement
  /// (Refinement_hierarchy.h), once or more, is first optimised at its
  /// coarsest level of at least `coarse_level_min_hexes` hexes, and the
  /// fine level starts from the input moved by that level's displacement,
  /// carried down trilinearly. On a fine mesh the turns end in a local
  /// optimum that a coarse vertex's move, many fine layers at once, avoids.
  /// Below that size a coarse level is too coarse to shape the fine one.
  bool coarse_level_start = true;
  std::size_t coarse_level_min_hexes = 4096;

  /// The MSJ stages, the turns and `success` aim at min(target_msj, this):
  /// a mesh whose every element is above it is as good as a hex mesh gets,
  /// and aiming at 1 itself would make every element of a nearly regular
  /// mesh "below the target", so a stage would visit the whole mesh: the
  /// cost would grow with the mesh, not with its bad elements.
  double excellent_msj = 0.999;

  /// the quality stages' creases (Target_surface.h): only the boundary
  /// edges whose dihedral angle is below this start one, and the edges below
  /// the sharp angle θ then only continue them
  /// (`Target_surface_parameters::feature_seed_angle`, the named parameter
  /// `crease_seed_angle`). Default 180: every edge below θ is a crease, as in
  /// the paper and in the untangling stages. 150 gains on some inputs and
  /// loses on others (RESULTS.md, "Crease seeds"), so it is not the default.
  double crease_seed_angle = 180.;

  /// the repair region (Repair_region.h): the quality stages move only the
  /// vertices within `repair_region_rings` rings of a hex below the aimed MSJ that
  /// was inverted, got worse, or had an input SJ below `repair_region_kept_sj`
  bool repair_region = true;
  int repair_region_rings = 2;
  double repair_region_kept_sj = 0.99;

  /// the give-back at the end (Give_back.h): moved vertices back at their
  /// input position where no hex around falls below min(aimed MSJ, its SJ) less
  /// `give_back_slack` nor below the MSJ reached; at most `give_back_sweeps` sweeps
  bool give_back = true;
  double give_back_slack = 0.002;
  int give_back_sweeps = 10;

  /// SLIM iterations of the pull-back
  int pull_back_iterations = 40;
  /// sweeps of the surface restoration
  int restoration_sweeps = 8;
  /// the surface fit: vertices whose local two-sided error is above
  /// `surface_fit_aim` of the tolerance slide along the reference, at most
  /// `surface_fit_sweeps` sweeps (Surface_fitting.h)
  double surface_fit_aim = 0.8;
  /// the fit is kept only if it removes at least this fraction of the
  /// surface error's excess over the tolerance (a fit that gets nowhere
  /// near the tolerance only costs quality)
  double surface_fit_min_excess_cut = 0.5;
  int surface_fit_sweeps = 8;
  /// the MSJ stages: targets 0, `msj_stage_step`, 2 × that, … ; in each,
  /// after the max-min smoothing, the edge-angle passes (Algorithm 1) go on
  /// while one raises the MSJ by at least `msj_stage_min_gain` or frees an
  /// element below the stage's target, at most
  /// `msj_stage_edge_angle_passes` times, each of at most `msj_stage_rounds`
  /// rounds. Default 0: the turns below raise the MSJ as high or higher in
  /// less time; the paper's method runs them.
  double msj_stage_step = 0.1;
  /// above this target the MSJ stages step by `msj_stage_fine_step` (the
  /// paper's scripts: 0.1 … 0.4, then 0.45, 0.5, …); 2: never
  double msj_stage_fine_from = 2.;
  double msj_stage_fine_step = 0.05;
  double msj_stage_min_gain = 0.005;
  int msj_stage_edge_angle_passes = 0;
  /// the passes of the paper's schedule, and of `edge_angle_stages(true)`
  static constexpr int paper_msj_stage_edge_angle_passes = 8;
  int msj_stage_rounds = 3;
  /// the projection after an edge-angle pass keeps every element at or above
  /// the stage's target, not only above the MSJ (the paper's steps accept a
  /// state only above their target: a projection that pushes elements back
  /// under it undoes the pass)
  bool msj_stage_projection_at_target = false;
  /// the edge-angle passes of the MSJ stages may go below the MSJ they
  /// started from (never below 0) and end in the best state of their rounds,
  /// as the authors' optimiser keeps its best iteration; false: every step
  /// that lowers a region's minimum under the stage's MSJ is rolled back
  bool msj_stage_keep_best = false;
  /// the rounds of the paper's schedule: the outer iterations of its scripts
  static constexpr int paper_msj_stage_rounds = 20;
  /// the edge-angle optimiser's boundary weights: 0, α and β as they are;
  /// ℓ > 0, (α ℓ)² and (β ℓ)² as in the authors' code (Local_optimizer.h)
  double authors_weight_edge = 0.;
  /// the edge-angle optimiser runs the authors' loop (`Local_optimizer_settings::
  /// authors_loop`), and its callers back off between runs from the same
  /// start as the authors' scripts do (ξ − 0.1 down to 0.2, then α, β halved
  /// and ξ back to its start), the MSJ stages while α ≥ their α floor
  bool authors_loop = false;
  /// with `authors_loop`, the untangler's back-off stops when α or β falls
  /// below this (the scripts halve them while elements stay inverted)
  double authors_untangle_alpha_floor = 1.;
  /// with it, the regions' cut vertices slide on the cut surface (`Local_optimizer_settings::slide_cut`)
  bool authors_slide_cut = false;
  /// with it, the authors' linearisation of the energy (`Local_optimizer_settings::authors_energy`)
  bool authors_energy = false;
  /// in the MSJ stages, with `authors_loop`: the authors' linearisation of
  /// the energy (whatever `authors_energy` says for the untangling), and
  /// the boundary rows through the vertices' current positions
  /// (`Local_optimizer_settings::anchor_at_current`)
  bool msj_authors_energy = false;
  bool msj_anchor_at_current = false;
  /// the surface guard's bound in the MSJ stages, relative to the tolerance;
  /// while a run ends above the tolerance, at most `msj_guard_retries` runs
  /// again, each with the bound times `msj_guard_retry_factor` (0.9, 0.75,
  /// 0.625); the quads whose samples come within `msj_dense_sampling` of the
  /// tolerance are sampled on a fine grid too
  double msj_guard_margin = 0.9;
  int msj_guard_retries = 2;
  double msj_guard_retry_factor = 0.8333;
  double msj_dense_sampling = 0.7;
  /// the precision of the surface error measured by the quality stages'
  /// checks, relative to the reference's diagonal: a check may read the
  /// error up to this much low, so a state this close above the tolerance
  /// can pass it; with 1e-4 a state just over the tolerance could be kept,
  /// hence 1e-6.
  double surface_check_precision = 1e-6;
  /// the max-min smoothing (Worst_element_smoothing.h): at most this many
  /// sweeps; `max_min_patience` sweeps in a row that raise the MSJ by less
  /// than `max_min_min_gain` end it
  int max_min_sweeps = 200;
  int max_min_patience = 3;
  double max_min_min_gain = 1e-5;
  /// the turns (one focused ASJ pass near the elements below MSJ +
  /// `turn_focus_band`, its floor the MSJ minus a drop, then the max-min
  /// smoothing toward the target): at most `max_turns`. The drops are 0,
  /// `turn_floor_drop`, and its halves down to `min_turn_floor_drop`
  /// (0, 0.03, 0.015, 0.0075). A turn that raises the MSJ by more than
  /// `turn_min_kept_gain` gets a surface check and is kept within the
  /// bound; the others are undone without one (the check is the dearest
  /// part of a turn). A turn that is not kept, or gains less than
  /// `turn_min_gain`, moves on to the next drop, cyclically; a turn kept with
  /// at least `turn_min_gain` keeps its drop. The turns end when every drop
  /// has failed in a row. The guard of the turns and of the final
  /// smoothing starts at `turn_guard` of the tolerance and is halved after a
  /// turn undone for its surface error (the turns end below
  /// `min_turn_guard`) and after a turn kept only thanks to a surface
  /// restoration (not below `min_turn_guard`): with the guard unchanged, a
  /// turn can go over the bound again and again, each time brought back by
  /// a restoration.
  /// Why so: the turns' gains are erratic, and which turn stalls first
  /// depends on the rounding of sums; ending on the second unproductive
  /// turn, or undoing small gains unchecked, made the result depend on that
  /// rounding (one small kept gain can let later turns go much further).
  /// `turn_min_gain` 0.005, not less: a turn costs a focused ASJ pass, a
  /// max-min run and a surface check.
  /// The turns' ASJ pass visits the vertices in index order within blocks
  /// of `turn_block_size` vertices close in space, the blocks that do not
  /// touch on all threads (`Asj_smoothing_settings::Visit_order`): faster
  /// than one vertex at a time, and unlike plain colour order it does not
  /// stall the turns. The size changes the turns' path, not their quality
  /// on the whole. The blocks and their colours are set up once, from the
  /// positions at the first turn (`Asj_smoother::restart`).
  /// The focus band trades MSJ for time: 0.15 meets the package's time
  /// bounds on the published rows with every row above its published MSJ
  /// and ASJ; a wider band (named parameter `turn_focus_band`) reaches a
  /// higher MSJ in more time (RESULTS.md, "The turns' focus band 0.15").
  std::size_t turn_block_size = 256;
  int max_turns = 40;
  double turn_focus_band = 0.15;
  double turn_min_gain = 0.005;
  double turn_min_kept_gain = 0.;
  double turn_floor_drop = 0.03;
  double min_turn_floor_drop = 0.0075;
  double turn_guard = 0.7;
  double min_turn_guard = 0.15;
  double turn_dense_sampling = 0.5;
  /// the final ASJ smoothing starts with all the interior vertices at once
  /// (Global_asj_smoothing.h): at most this many L-BFGS iterations (0: none),
  /// ending when 5 iterations in a row gain less than `..._min_gain` each
  /// (mean soft minimum per hex); interior vertices of the hexes within
  /// `..._floor_margin` of the MSJ stay for the Gauss-Seidel passes.
  /// Gauss-Seidel alone converges slowly on this smooth objective; the
  /// L-BFGS start reaches a higher ASJ in less time. The margin saves time
  /// in the passes after the L-BFGS at no measurable cost in ASJ.
  int final_asj_global_iterations = 100;
  double final_asj_global_min_gain = 2e-5;
  double final_asj_global_floor_margin = 0.02;
  /// the final ASJ smoothing: at most this many Gauss-Seidel passes; a pass
  /// that raises the ASJ by less than `asj_min_gain` ends it. 5e-4, not
  /// 1e-4: on large meshes the passes otherwise run to their cap for gains
  /// of a few 1e-4 each, at a small ASJ cost on the published rows.
  int asj_passes = 30;
  double asj_min_gain = 5e-4;
  /// in the final ASJ smoothing, a vertex whose visit raised its objective
  /// (a sum of soft minima over its hexes) by at most this does not make
  /// the vertices around it active for the next pass: with 0 every vertex
  /// moves in every pass; with 1e-4 the active set shrinks at no cost in
  /// MSJ or ASJ; with 1e-3 it shrinks further but the ASJ falls.
  double asj_reactivation_gain = 1e-4;
  /// whether the final ASJ smoothing moves boundary vertices (guarded, and
  /// undone if the surface check fails) before a run with the boundary
  /// fixed. Default: the boundary fixed only (no guard query, no surface
  /// check: much faster, for a small loss of ASJ).
  bool final_asj_moves_boundary = false;

  /// the target of MSJ stage k (0, 1, …): k steps, the fine ones past
  /// `msj_stage_fine_from`
  double msj_stage_target(int k) const
  {
    const double coarse = k * msj_stage_step;
    if(!(coarse > msj_stage_fine_from)) return coarse;
    const int last_coarse = static_cast<int>(msj_stage_fine_from / msj_stage_step + 1e-9);
    return last_coarse * msj_stage_step + (k - last_coarse) * msj_stage_fine_step;
  }

  /// The method of Xu & Chen (2018) alone: edge-angle untangling with
  /// relaxation (Algorithm 1, no hand-over to the barrier), the SLIM
  /// pull-back, MSJ stages by the edge-angle optimiser with the boundary
  /// projected back, the final ASJ smoothing and the projection of the
  /// boundary that keeps the MSJ (their scripts end so); none of the package's
  /// additions (barrier stages, restoration, max-min smoothing, turns, the
  /// L-BFGS start of the ASJ smoothing).
  static Optimization_schedule paper()
  {
    Optimization_schedule s;
    s.interior_stage = s.barrier_stage = s.surface_stage = false;
    s.edge_angle_stage = true;
    s.restoration = false;
    s.surface_fitting = false;
    s.msj_stage_max_min = false;
    s.final_projection = true; // the scripts' last SmoothMap: the boundary onto the surface, quality kept
    s.repair_region = false;
    s.barrier_input_shape_sj = 2.;
    s.give_back = false;
    s.edge_angle_rounds = 60;      // the paper's untangling to its end: no barrier takes over
    s.edge_angle_stalled_rounds = std::numeric_limits<int>::max();
    s.edge_angle_max_region_hexes = std::numeric_limits<std::size_t>::max();
    s.msj_stage_edge_angle_passes = paper_msj_stage_edge_angle_passes;
    s.max_turns = 0;
    s.final_asj_global_iterations = 0;
    s.crease_seed_angle = 180.;
    s.coarse_level_start = false;
    s.msj_stage_fine_from = 0.4;
    s.msj_stage_rounds = paper_msj_stage_rounds;
    s.msj_stage_projection_at_target = true;
    s.msj_stage_keep_best = true;
    s.authors_weight_edge = 0.025; // the authors' weighting, at the normalised mean edge 0.025
    s.authors_loop = true;         // the authors' region loop and their scripts' back-off
    s.authors_slide_cut = true;    // their local mesh's boundary: the cut slides too
    // (authors_energy: off, the tripod fit is kept while untangling)
    s.msj_authors_energy = true;    // their energy raises a boundary element the tripod fit lowers
    s.msj_anchor_at_current = true; // their rows do not pull the boundary back onto the surface
    return s;
  }
};

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_OPTIMIZATION_SCHEDULE_H
