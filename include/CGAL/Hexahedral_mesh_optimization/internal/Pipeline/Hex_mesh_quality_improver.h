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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_HEX_MESH_QUALITY_IMPROVER_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_HEX_MESH_QUALITY_IMPROVER_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Quality improvement after untangling (Sections 3.3 and 3.4 and the final
// smoothing), on flat arrays. The driver `run` calls one method per stage:
//   0. `limit_to_repair_region` (Repair_region.h): the vertices away from
//      what is broken, got worse or was poor in the input are constrained
//      for every later stage;
//   1. `set_up`: normalise (mean edge 0.025, as the untangler), target
//      surface Ω_t of the reference (the original input's boundary, or the
//      user's surface); the ideal angles are made when an edge-angle pass
//      first needs them;
//   2. `pull_back_stage` (Pull_back.h), only when the surface error exceeds
//      the tolerance (after an untangling that relaxed the surface), and kept
//      only if it lowers the surface error;
//   3. `surface_guard_set_up`, then `restoration_stage`
//      (Boundary_restoration.h): boundary vertices back toward their home on
//      the reference wherever the MSJ allows;
//   4. `msj_stages_with_retry`: stages "msj>=t" for t = 0 (only if something
//      is inverted), 0.1, 0.2, … up to the target, each on what is below t —
//      max-min smoothing (Worst_element_smoothing.h), boundary moves bounded
//      by the surface guard (Surface_guard.h), then, while it falls short,
//      edge-angle passes of Algorithm 1 (Local_optimizer.h) with the
//      boundary projected back; then the restoration at the MSJ reached;
//   5. `turns`: one focused ASJ pass and a max-min smoothing in turn while
//      the MSJ rises, each turn checked against the surface bound;
//   6. `final_asj_smoothing` (Asj_smoothing.h): raises the mean without
//      lowering any element below the MSJ reached;
//   6b. `give_back_stage` (Give_back.h): moved vertices back at their
//      input position where the repair did not need them moved;
//   6c. `final_projection_stage` (Final_projection.h): the boundary exactly
//      onto the target surface where that keeps the MSJ;
//   7. undo the normalisation; if the MSJ (or the inverted count) is worse
//      than the input's, the input is returned.
// Every stage ends on its own convergence test or work cap, all in
// Optimization_schedule.h; the time limit is a hard stop only (Time_limit.h).
// A turn or final smoothing stopped by it before its surface check is undone,
// so the result is always a checked state. The measurements behind this
// order and these values: benchmark/Hexahedral_mesh_optimization/RESULTS.md.
//
// The surface tolerance: the paper bounds nothing and reports the error it
// got; here the user gives a tolerance (relative to the reference's
// bounding-box diagonal) that no boundary move of the max-min and ASJ
// smoothing may exceed locally. The edge-angle passes keep the paper's soft
// constraints (α, β ≥ 500) and the projection at the end of each pass is
// refused where it would lower an element under the stage's floor, so the
// measured error can end slightly above the tolerance: it is reported, not
// hidden.

#include <CGAL/Hexahedral_mesh_optimization/Optimization_result.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Smoothing/Asj_smoothing.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Smoothing/Global_asj_smoothing.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Boundary_restoration.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Final_projection.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Untangling/Local_optimizer.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/Optimization_schedule.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/Optimization_setup.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/Repair_region.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/Give_back.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Untangling/Pull_back.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Surface_guard.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Surface_fitting.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Target_surface.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/Time_limit.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Smoothing/Worst_element_smoothing.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/quality_statistics.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/surface_distance.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <sstream>
#include <utility>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

struct Quality_settings
{
  /// the MSJ aimed at; ≥ 1 means as high as the method gets it
  double target_msj = 1.;
  double sharp_angle = 165.;
  /// as `Untangle_settings::reference_feature_angle`
  double reference_feature_angle = 150.;
  double alpha = 1000., beta = 1000.;
  double min_alpha_beta = 500.;
  double xi = 0.6;
  int local_iterations = 20;
  bool pull_back = true;
  /// the paper's recipe: the pull-back runs whatever the surface error and
  /// pulls the boundary toward the input's own vertices, as the authors'
  /// SLIM step does (without a reference surface only); its result is kept
  bool pull_back_to_input = false;
  /// the paper's recipe: the result is given up for `original` (not for the
  /// untangled mesh this run starts from) when its MSJ is not above it, as
  /// the scripts return their input
  bool keep_original_if_worse = false;
  bool asj_smoothing = true;
  /// largest surface error allowed to the boundary moves of the quality
  /// stages, relative to the reference's bounding-box diagonal
  double surface_tolerance = 0.005;
  /// with a value ≥ 0, the boundary moves of the quality stages also keep
  /// the quads around a boundary vertex within this fraction of the
  /// shortest edge at it in `original` (thin layers); negative: none
  double local_surface_tolerance = -1.;
  /// the run's hard stop (null: none); it is not the schedule's business
  const Time_limit* time_limit = nullptr;
  /// work caps and convergence thresholds of every stage
  Optimization_schedule schedule;
  /// whether the surface restoration runs before the MSJ stages too (not
  /// after a coarse-level start, whose boundary the coarse level already
  /// kept within the tolerance: there the restoration only costs time)
  bool restore_before_msj_stages = true;
  /// optional reference surface (model coordinates); default: the boundary of `original`
  const std::vector<Vec3>* reference_points = nullptr;
  const std::vector<Tri>* reference_triangles = nullptr;
  /// edges of the reference given as creases (`edge_is_constrained_map`)
  const std::vector<std::array<std::size_t, 2> >* reference_creases = nullptr;

  /// the MSJ the stages aim at: the target, but never above
  /// `Optimization_schedule::excellent_msj`
  double aimed_msj() const { return (std::min)(target_msj, schedule.excellent_msj); }
};

template <class Visitor>
class Hex_mesh_quality_improver
{
  typedef std::chrono::steady_clock Clock; // for the reports' seconds only

  /// what the stages share: the normalised mesh, its reference, target
  /// surface, guard, the boundary vertices' homes, and the surface error of
  /// the current state when known
  struct Run_state
  {
    Run_state(Hex_mesh_arrays& m, Optimization_result& r) : mesh(m), res(r) {}
    Hex_mesh_arrays& mesh;
    Optimization_result& res;
    std::unique_ptr<Hex_mesh_topology> topo;
    Normalization nz;
    /// the reference, model coordinates, cut along (0, 2) as the surface error is measured
    Triangle_surface reference;
    /// `reference` set up for the checks after each change (built at the first)
    std::unique_ptr<Reference_distance_index> reference_index;
    /// what the surface checks since the start learnt (`surface_error_after_change`)
    Surface_error_bounds error_bounds;
    /// the surface tolerance in normalised mesh units
    double tolerance = 0.;
    double diagonal = 0.;
    std::unique_ptr<Target_surface> ts;
    std::unique_ptr<Ideal_angles> ideal;
    std::unique_ptr<Surface_guard> guard;
    /// home of each boundary vertex on the reference
    std::vector<Vec3> home;
    /// surface error of the current state (it depends on the boundary
    /// vertices only and is measured only when they moved); negative: unknown
    double current_error = -1.;
    /// whether `current_error` may be an upper bound (`measure_error_since`)
    /// rather than a measure: the result's error is then measured at the end
    bool error_may_be_bound = false;
    /// what the turns and the final smoothing may take the error to
    double error_bound = 0.;
  };

public:
  Hex_mesh_quality_improver(const Quality_settings& s, Visitor& visitor) : m_s(s), m_visitor(visitor) {}

  /// Improves `mesh` in place. `original` is the mesh the surface error is
  /// measured against when no reference surface is given (the untangler's
  /// input in the whole pipeline; `mesh` itself otherwise).
  Optimization_result run(Hex_mesh_arrays& mesh, const Hex_mesh_arrays& original)
  {
    const auto start = Clock::now();
    Optimization_result res;
    const std::vector<Vec3> input_points = mesh.points; // the hexes never change
    const Quality_statistics q0 = quality_statistics(mesh);
    res.inverted_before = q0.inverted; res.msj_before = q0.msj; res.asj_before = q0.asj;

    Run_state st(mesh, res);
    const std::vector<unsigned char> user_constrained = mesh.constrained;
    std::string region; // reported once the mesh is normalised, as every later event
    if(m_s.schedule.repair_region) region = limit_to_repair_region(st, original);
    set_up(st, original);
    if(!region.empty()) report_event(st, "repair region", region, false);
    const std::vector<Vec3> normalized_input = mesh.points;
    if(m_s.pull_back && !stopped()) pull_back_stage(st, original); // around what is inverted, if anything (see Pull_back.h)
    if(m_s.schedule.surface_fitting && !stopped()) surface_fit_stage(st);
    if(!stopped()) surface_guard_set_up(st, original);
    if(m_s.restore_before_msj_stages && !stopped() && restoration_stage(st) > 0) st.current_error = -1.;
    if(!stopped()) msj_stages_with_retry(st);
    if(m_s.asj_smoothing && !stopped()) turns(st);
    if(m_s.asj_smoothing && !stopped()) final_asj_smoothing(st);
    std::vector<Vec3> normalized_original;
    if(m_s.schedule.give_back && !stopped()) normalized_original = give_back_stage(st, original);
    if(m_s.schedule.final_projection && !stopped()) final_projection_stage(st);

    const std::vector<Vec3> normalized = mesh.points;
    for(Vec3& p : mesh.points) p = st.nz.undo(p);
    restore_unmoved_vertices(mesh.points, normalized, normalized_input, input_points, mesh);
    // the vertices the give-back put back get their exact input coordinates
    for(std::size_t v = 0; v < normalized_original.size(); ++v)
      if(normalized[v] == normalized_original[v]) mesh.points[v] = original.points[v];
    mesh.constrained = user_constrained;

    // ---- never make the mesh worse
    const Quality_statistics q1 =
      m_s.keep_original_if_worse && original.points.size() == input_points.size()
        ? keep_input_if_worse(mesh, original.points, quality_statistics(original), res)
        : keep_input_if_worse(mesh, input_points, q0, res);
    res.success = q1.inverted == 0 && q1.msj >= aimed_msj() - 1e-12;
    res.surface_error = (st.current_error >= 0. && !st.error_may_be_bound && !res.kept_input)
                          ? st.current_error
                          : surface_distance(mesh, st.reference, m_s.schedule.surface_check_precision).relative();
    res.time_limit_reached = m_s.time_limit && m_s.time_limit->limit_passed();
    res.interrupted = m_s.time_limit && m_s.time_limit->interrupted();
    res.seconds = seconds_since(start);
    return res;
  }

private:
  bool stopped() const { return time_limit_reached(m_s.time_limit); }

  double aimed_msj() const { return m_s.aimed_msj(); }

  /// Stage "repair region" (Repair_region.h): the vertices outside the
  /// region around what is broken, got worse or was poor in `original` are
  /// constrained for every later stage (the user's mask is put back at the
  /// end); returns the stage's description
  std::string limit_to_repair_region(Run_state& st, const Hex_mesh_arrays& original)
  {
    const Optimization_schedule& sc = m_s.schedule;
    const Hex_mesh_topology topo(st.mesh);
    const Repair_region r = repair_region(topo, scaled_jacobians(st.mesh), scaled_jacobians(original), st.mesh.constrained,
                                          aimed_msj(), sc.repair_region_kept_sj, sc.repair_region_rings);
    std::ostringstream d;
    d << r.reasons << " hexes to repair, " << r.free_vertices << " of " << st.mesh.points.size()
      << " vertices free" << (r.whole_mesh ? " (the whole mesh)" : "");
    if(!r.whole_mesh) st.mesh.constrained = r.constrained;
    return d.str();
  }

  /// the reference surface, the normalisation and Ω_t
  void set_up(Run_state& st, const Hex_mesh_arrays& original)
  {
    // reference surface (model coordinates): for the guard cut along (0, 2)
    // as the surface error is measured; for Ω_t both ways
    if(user_reference())
    {
      m_guard_points = m_target_points = *m_s.reference_points;
      m_guard_tris = m_target_tris = *m_s.reference_triangles;
    }
    else
    {
      const Hex_mesh_boundary ob = extract_boundary(original);
      triangulate_boundary(ob, original.points, Quad_split::diagonal_02, m_guard_points, m_guard_tris);
      triangulate_boundary(ob, original.points, Quad_split::both_diagonals, m_target_points, m_target_tris);
    }
    {
      std::vector<Triangle_surface::Vertex_index> vi;
      for(const Vec3& p : m_guard_points) vi.push_back(st.reference.add_vertex(Triangle_surface::Point(p[0], p[1], p[2])));
      for(const Tri& t : m_guard_tris) st.reference.add_face(vi[t[0]], vi[t[1]], vi[t[2]]);
    }
    st.diagonal = internal::diagonal(bbox_of(st.reference));

    // normalise
    st.topo.reset(new Hex_mesh_topology(st.mesh));
    st.nz = normalization(*st.topo, st.mesh.points);
    for(Vec3& p : st.mesh.points) p = st.nz.apply(p);
    for(Vec3& p : m_guard_points) p = st.nz.apply(p);
    for(Vec3& p : m_target_points) p = st.nz.apply(p);
    st.tolerance = m_s.surface_tolerance * st.diagonal * st.nz.scale;

    Target_surface_parameters tsp;
    tsp.feature_angle = m_s.sharp_angle;
    tsp.feature_seed_angle = m_s.schedule.crease_seed_angle;
    // Ω_t = the boundary projected onto the reference, not smoothed: the
    // untangler smoothed what needed it, and smoothing a valid boundary only
    // moves the anchors of its corners and feature vertices away from it
    tsp.smoothing_iterations = 0;
    if(user_reference())
    {
      tsp.reference_feature_angle = m_s.reference_feature_angle;
      if(m_s.reference_creases) tsp.reference_creases = *m_s.reference_creases;
    }
    st.ts.reset(new Target_surface(st.mesh, st.topo->boundary(), m_target_points, m_target_tris, tsp));
    if(st.ts->feature_recovery_summary().attempted)
      report_event(st, "feature recovery", describe(st.ts->feature_recovery_summary()), true);
  }

  bool user_reference() const { return m_s.reference_points && m_s.reference_triangles; }

  /// the home of each boundary vertex on the reference (its input position
  /// when the reference is the input's boundary, its projection otherwise)
  /// and the surface guard every later stage shares
  void surface_guard_set_up(Run_state& st, const Hex_mesh_arrays& original)
  {
    st.home.assign(st.mesh.points.size(), Vec3{0., 0., 0.});
    for(std::size_t v : st.ts->boundary().vertices)
    {
      if(user_reference()) st.ts->closest_on_reference(st.mesh.points[v], st.home[v]);
      else st.home[v] = st.nz.apply(original.points[v]);
    }
    // what the boundary must keep covering: the input's boundary itself, or
    // (with a user's reference, which the guard checks directly) the
    // boundary as it is now
    const std::vector<Vec3> guard_start = user_reference() ? st.mesh.points : st.home;
    st.guard.reset(new Surface_guard(st.ts->boundary(), m_guard_points, m_guard_tris, guard_start));
    if(m_s.local_surface_tolerance >= 0.)
    {
      const bool same = original.points.size() == st.mesh.points.size(); // (not on a coarse level)
      std::vector<double> tolerance = shortest_edge_at_vertices(same ? original : st.mesh);
      for(double& t : tolerance) t *= m_s.local_surface_tolerance * (same ? st.nz.scale : 1.);
      st.guard->set_vertex_tolerances(std::move(tolerance));
    }
  }

  /// measures the surface error of the current state
  double measure_error(Run_state& st) const
  {
    st.current_error = scaled_error(st.mesh, st.reference, st.nz, m_s.schedule.surface_check_precision);
    return st.current_error;
  }

  /// Measures the surface error after a change from `before`, whose error
  /// was `error_before` (< 0: unknown, measured in full): only the quads
  /// that moved and the reference near them are measured, less what the
  /// bounds kept from the previous checks (`st.error_bounds`) clear
  /// (`surface_error_after_change`). The value is an upper bound, exact
  /// whenever the error grew beyond `error_before`.
  double measure_error_since(Run_state& st, const std::vector<Vec3>& before, double error_before) const
  {
    if(error_before < 0.) return measure_error(st);
    if(!st.reference_index) st.reference_index.reset(new Reference_distance_index(st.reference));
    const Normalization& nz = st.nz;
    st.current_error =
      surface_error_after_change(st.ts->boundary(), before, st.mesh.points, *st.reference_index, error_before * st.diagonal,
                                 [&nz](const Vec3& p) { return nz.undo(p); }, m_s.schedule.surface_check_precision,
                                 &st.error_bounds) /
      st.diagonal;
    st.error_may_be_bound = true;
    return st.current_error;
  }

  /// The MSJ stages, their guard keeping a margin (`msj_guard_margin` of the
  /// tolerance, fine sampling from `msj_dense_sampling`), then the
  /// restoration at the MSJ reached. While the error measured after them is
  /// above the tolerance, they run again from where they started with the
  /// guard's bound times `msj_guard_retry_factor`, at most
  /// `msj_guard_retries` times; the first run within the tolerance is kept,
  /// or else the mesh as the stages received it. The margin, the fine sampling and
  /// the runs again apply only when the error before the stages is within
  /// the tolerance (after an untangling that left the boundary off the
  /// surface they cannot cause an excess, and only hold the stages back).
  void msj_stages_with_retry(Run_state& st)
  {
    const Optimization_schedule& sc = m_s.schedule;
    if(st.current_error < 0.) measure_error(st);
    const bool within_before = st.current_error <= m_s.surface_tolerance;
    if(within_before) st.guard->set_dense_sampling_above(sc.msj_dense_sampling * st.tolerance);
    auto run_msj_stages = [&](double margin) {
      msj_stages(st, margin * st.tolerance);
      restoration_stage(st);
      measure_error(st);
    };
    const std::vector<Vec3> before = st.mesh.points;
    double margin = within_before ? sc.msj_guard_margin : 1.;
    run_msj_stages(margin);
    if(!within_before || st.current_error <= m_s.surface_tolerance || stopped()) return;
    // runs again: `best` is the run with the lowest error so far (the state
    // in `st.mesh` when `best_is_current`)
    std::vector<Vec3> best = st.mesh.points;
    double best_error = st.current_error;
    bool best_is_current = true;
    for(int retry = 0; retry < sc.msj_guard_retries && best_error > m_s.surface_tolerance && !stopped(); ++retry)
    {
      margin *= sc.msj_guard_retry_factor;
      report_check(st, "the MSJ stages", "surface error " + std::to_string(st.current_error) +
                    " above the tolerance; run again with the guard at " + std::to_string(margin) +
                    " of it (an earlier run is kept if this one is not better)");
      st.mesh.points = before;
      run_msj_stages(margin);
      best_is_current = !stopped() && st.current_error < best_error;
      if(best_is_current)
      {
        best = st.mesh.points;
        best_error = st.current_error;
      }
    }
    if(best_error > m_s.surface_tolerance && !stopped())
    {
      // no run within the tolerance: the tolerance binds and the MSJ is
      // only aimed at, so the mesh as the stages received it (within) is kept
      st.mesh.points = before;
      measure_error(st);
      report_check(st, "the runs again of the MSJ stages",
                   "none within the tolerance: the mesh before the MSJ stages kept");
      return;
    }
    if(!best_is_current)
    {
      st.mesh.points = std::move(best);
      st.current_error = best_error;
      report_check(st, "the runs again of the MSJ stages",
                   stopped() ? "time limit reached" : "the run with the lowest surface error kept");
    }
  }

  /// What the surface error may still grow by (mesh units, × `factor`): an
  /// ASJ move whose quads stay that close to the boundary as its stage
  /// received it skips the guard's AABB queries
  /// (`Asj_smoothing_settings::start_deviation_budget`); 0 while the error
  /// of the current state is unknown.
  double error_budget(const Run_state& st, double factor) const
  {
    return st.current_error >= 0.
             ? factor * (std::max)(0., st.error_bound - st.current_error) * st.diagonal * st.nz.scale
             : 0.;
  }

  /// Checks the surface error after a turn or the final smoothing: within
  /// `error_bound` it is kept; otherwise (`restore`) the surface restoration
  /// runs first, and if the error is still above, or the time limit was
  /// reached before the check, the state `saved` (of error `saved_error`) is
  /// put back and a "check" stage says why.
  bool within_bound(Run_state& st, const std::vector<Vec3>& saved, double saved_error, const char* what, bool restore,
                    bool* restored = nullptr)
  {
    double e = -1.;
    if(restored) *restored = false;
    if(!stopped())
    {
      e = measure_error_since(st, saved, saved_error);
      if(e <= st.error_bound) return true;
      if(restore && !stopped())
      {
        if(restored) *restored = true;
        restoration_stage(st);
        e = measure_error(st);
        if(e <= st.error_bound && !stopped()) return true;
      }
    }
    st.mesh.points = saved;
    st.current_error = saved_error;
    std::ostringstream d;
    if(e < 0. || stopped()) d << "time limit reached before its surface check";
    else d << "surface error " << e << " above " << st.error_bound;
    report_check(st, what, d.str());
    return false;
  }

  /// ASJ smoothing and max-min smoothing in turn while the MSJ rises: the
  /// ASJ pass reshapes the neighbourhood of the worst elements, which frees
  /// elements the max-min smoothing had stalled on. The ASJ pass may take
  /// elements down to its floor, the MSJ minus a drop: 0, then
  /// `turn_floor_drop`, halved down to `min_turn_floor_drop`, then 0 again.
  /// A turn that raised the MSJ (by more than `turn_min_kept_gain`) is kept
  /// if its surface error stays within max(tolerance, the error before the
  /// turns), after a restoration if need be (the guard is then halved, not
  /// below `min_turn_guard`; once a restoration has failed to bring a turn
  /// within the bound, the later turns get none); otherwise it is undone (and the guard halved;
  /// below `min_turn_guard` the turns end). A turn that raised nothing is
  /// undone without a surface check. A turn kept with a gain of at least
  /// `turn_min_gain` keeps its drop; any other moves on to the next drop.
  /// The turns end when every drop has failed in a row, or after
  /// `max_turns` (see `Optimization_schedule` for why).
  void turns(Run_state& st)
  {
    const Optimization_schedule& sc = m_s.schedule;
    // from here on the error bound is strict (a turn over it is undone): the
    // guard samples the quads that come near the tolerance on a fine grid too
    st.guard->set_dense_sampling_above(sc.turn_dense_sampling * st.tolerance);
    if(st.current_error < 0.) measure_error(st);
    st.error_bound = (std::max)(m_s.surface_tolerance, st.current_error);
    std::vector<double> drops(1, 0.);
    for(double d = sc.turn_floor_drop; d >= sc.min_turn_floor_drop && d > 0.; d *= 0.5) drops.push_back(d);
    std::size_t mode = 0;       // the drop in use
    std::size_t unproductive = 0; // turns in a row not productive
    m_turn_guard = sc.turn_guard;
    // one smoother for all the turns: its vertex order and colours are set
    // up once (see `Asj_smoother::restart`)
    std::unique_ptr<Asj_smoother> smoother;
    Quality_statistics now = quality_statistics(st.mesh);
    // a turn over the bound gets a surface restoration until one fails to
    // bring a turn back within it; the later ones are undone at once
    bool restoration_helps = true;
    for(int turn = 0; turn < sc.max_turns && !stopped(); ++turn)
    {
      const std::vector<Vec3> saved = st.mesh.points;
      const double saved_error = st.current_error;
      const Quality_statistics saved_quality = now;
      const double before = now.msj;
      if(before >= aimed_msj()) break;
      Asj_smoothing_settings one_focused_pass;
      one_focused_pass.max_passes = 1;
      one_focused_pass.focus_below = before + sc.turn_focus_band;
      one_focused_pass.order = Asj_smoothing_settings::Visit_order::index_blocks;
      one_focused_pass.block_size = sc.turn_block_size;
      one_focused_pass.start_deviation_budget = error_budget(st, m_turn_guard);
      now = asj_stage(st, now, m_turn_guard * st.tolerance, one_focused_pass, drops[mode], &smoother);
      now = max_min_stage(st, now, m_turn_guard * st.tolerance);
      const double after = now.msj;
      // a turn worth its surface check is kept within the bound; the others
      // are undone unchecked
      const bool worth = after > before + sc.turn_min_kept_gain;
      bool restored = false;
      const bool kept = worth && within_bound(st, saved, saved_error, "the last ASJ + max-min turn", restoration_helps, &restored);
      if(restored && !kept) restoration_helps = false;
      if(!kept) now = saved_quality;
      else if(restored)
      {
        now = quality_statistics(st.mesh);
        m_turn_guard = (std::max)(0.5 * m_turn_guard, sc.min_turn_guard);
      }
      if(!worth)
      {
        st.mesh.points = saved;
        st.current_error = saved_error;
        std::ostringstream why;
        why << "MSJ " << before << " -> " << after << " with the floor " << drops[mode] << " below it";
        report_check(st, "the last ASJ + max-min turn", why.str());
      }
      else if(!kept)
      {
        m_turn_guard *= 0.5; // undone for its surface error
        if(m_turn_guard < sc.min_turn_guard) break;
      }
      const bool productive = kept && after >= before + sc.turn_min_gain;
      if(productive) unproductive = 0;
      else
      {
        if(++unproductive >= drops.size()) break;
        mode = (mode + 1) % drops.size();
      }
    }
  }

  /// The final ASJ smoothing, never below the MSJ reached, its guard as the
  /// turns'. If its surface check undoes it, it runs again with the boundary
  /// fixed, which cannot change the surface error (the restoration would
  /// move the boundary back and lose much of the ASJ gained).
  void final_asj_smoothing(Run_state& st)
  {
    const Optimization_schedule& sc = m_s.schedule;
    Quality_statistics q = quality_statistics(st.mesh);
    if(sc.final_asj_global_iterations > 0) q = interior_asj_stage(st, q);
    if(stopped()) return;
    Asj_smoothing_settings settings;
    settings.max_passes = sc.asj_passes;
    settings.min_asj_gain = sc.asj_min_gain;
    settings.min_reactivating_gain = sc.asj_reactivation_gain;
    if(sc.final_asj_moves_boundary)
    {
      if(st.current_error < 0.) measure_error(st);
      st.error_bound = (std::max)(m_s.surface_tolerance, st.current_error);
      const std::vector<Vec3> saved = st.mesh.points;
      const double saved_error = st.current_error;
      settings.start_deviation_budget = error_budget(st, m_turn_guard);
      asj_stage(st, q, m_turn_guard * st.tolerance, settings);
      if(within_bound(st, saved, saved_error, "the final ASJ smoothing", false) || stopped()) return;
    }
    const double error = st.current_error;
    settings.move_boundary = false;
    settings.start_deviation_budget = 0.;
    asj_stage(st, quality_statistics(st.mesh), m_turn_guard * st.tolerance, settings);
    st.current_error = error; // the boundary did not move
  }

  /// stage "projection": the boundary exactly onto the target surface
  /// wherever that keeps the MSJ reached (Final_projection.h); undone if the
  /// surface error grew past the tolerance or the error it had
  void final_projection_stage(Run_state& st)
  {
    const auto t = Clock::now();
    m_visitor.stage_started("projection", 0);
    std::vector<Vec3> saved = st.mesh.points;
    const Quality_statistics q = quality_statistics(st.mesh);
    const Final_projection_report r =
      project_boundary_onto_target(*st.topo, *st.ts, st.mesh.points, q.msj, m_s.schedule.final_projection_sweeps);
    if(r.projected > 0 && st.current_error < 0.) // the error before, for the bound: measured only when needed
    {
      std::swap(st.mesh.points, saved);
      measure_error(st);
      std::swap(st.mesh.points, saved);
    }
    const double saved_error = st.current_error;
    std::ostringstream d;
    d << r.projected << " boundary vertices moved onto the target surface, " << r.left
      << " left off it (the move would lower the MSJ; largest distance "
      << r.largest_left / st.ts->mean_boundary_edge_length() << " mean edge lengths)";
    report_stage(st, "projection", q, t, 1, d.str());
    st.error_bound = (std::max)(m_s.surface_tolerance, saved_error);
    if(r.projected > 0) within_bound(st, saved, saved_error, "the projection", false);
  }

  /// stage "give-back" (Give_back.h): the moved vertices back at their
  /// position in `original` where the repair did not need them moved; undone
  /// if the surface error grew past the tolerance or the error it had.
  /// Returns `original`'s points normalised (empty if undone).
  std::vector<Vec3> give_back_stage(Run_state& st, const Hex_mesh_arrays& original)
  {
    const Optimization_schedule& sc = m_s.schedule;
    const auto t = Clock::now();
    m_visitor.stage_started("give-back", 0);
    if(st.current_error < 0.) measure_error(st);
    const std::vector<Vec3> saved = st.mesh.points;
    const double saved_error = st.current_error;
    const Quality_statistics q = quality_statistics(st.mesh);
    std::vector<Vec3> input;
    input.reserve(original.points.size());
    for(const Vec3& p : original.points) input.push_back(st.nz.apply(p));
    const Target_surface& ts = *st.ts;
    Give_back_settings gs;
    gs.aimed = aimed_msj();
    gs.floor = q.msj;
    gs.slack = sc.give_back_slack;
    gs.max_sweeps = sc.give_back_sweeps;
    gs.boundary_allowed = [&ts](std::size_t, const Vec3& now, const Vec3& in) {
      return closer_to_reference(ts, in, now);
    };
    const Give_back_report r = give_back_to_input(*st.topo, input, st.mesh.points, gs);
    std::ostringstream d;
    d << r.given_back << " of " << r.moved_before << " moved vertices back at their input position in " << r.sweeps
      << " sweeps";
    report_stage(st, "give-back", q, t, r.sweeps, d.str());
    st.error_bound = (std::max)(m_s.surface_tolerance, saved_error);
    if(r.given_back > 0 && !within_bound(st, saved, saved_error, "the give-back", false)) return {};
    return input;
  }

  /// The interior vertices all at once (Global_asj_smoothing.h), never below
  /// the MSJ reached; the boundary does not move, so the surface error stays.
  Quality_statistics interior_asj_stage(Run_state& st, const Quality_statistics& q)
  {
    const Optimization_schedule& sc = m_s.schedule;
    const auto t = Clock::now();
    m_visitor.stage_started("asj-interior", 0);
    Global_asj_settings gs;
    gs.min_sj_floor = q.msj;
    gs.max_iterations = sc.final_asj_global_iterations;
    gs.min_gain = sc.final_asj_global_min_gain;
    gs.floor_margin = sc.final_asj_global_floor_margin;
    gs.time_limit = m_s.time_limit;
    const Global_asj_report gr = smooth_interior_for_average_quality(*st.topo, st.mesh.points, gs);
    std::ostringstream d;
    d << "L-BFGS on " << gr.free_vertices << " interior vertices, " << gr.iterations
      << " iterations, mean soft minimum " << gr.objective_before << " -> " << gr.objective_after;
    return report_stage(st, "asj-interior", q, t, gr.iterations, d.str());
  }

  /// a "check" stage: `what` was undone, and why
  void report_check(Run_state& st, const std::string& what, const std::string& why)
  {
    report_event(st, "check", what + " undone: " + why, false);
  }

  /// a stage that moved nothing, reported with the mesh's quality as it is
  /// (the visitor is told the inverted count at its start if `with_count`)
  void report_event(Run_state& st, const std::string& name, const std::string& details, bool with_count)
  {
    Stage_report sr;
    sr.name = name;
    const Quality_statistics q = quality_statistics(st.mesh);
    sr.inverted_before = sr.inverted_after = q.inverted;
    sr.msj_after = q.msj;
    sr.details = details;
    st.res.stages.push_back(sr);
    m_visitor.stage_started(sr.name, with_count ? q.inverted : 0);
    m_visitor.stage_finished(sr);
  }

  /// an ASJ smoothing from the state of quality `q`; `as` brings the
  /// caller's choices (passes, focus, fixed boundary), the floor (the MSJ −
  /// `floor_drop`) and guard are set here. With `keep`, the smoother is kept
  /// there and restarted by the next call. Returns the quality after.
  Quality_statistics asj_stage(Run_state& st, const Quality_statistics& q, double guard_tolerance,
                               Asj_smoothing_settings as, double floor_drop = 0.,
                               std::unique_ptr<Asj_smoother>* keep = nullptr)
  {
    const auto t = Clock::now();
    m_visitor.stage_started("asj", 0);
    as.min_sj_floor = q.msj - floor_drop;
    as.max_surface_deviation = guard_tolerance;
    const Surface_guard& guard = *st.guard;
    as.guard = &guard;
    as.time_limit = m_s.time_limit;
    Asj_smoothing_report ar;
    if(!keep) ar = smooth_for_average_quality(*st.topo, st.ts.get(), st.mesh.points, as);
    else
    {
      if(*keep) (*keep)->restart(as);
      else keep->reset(new Asj_smoother(*st.topo, st.ts.get(), st.mesh.points, as));
      ar = (*keep)->run();
    }
    std::ostringstream d;
    d << "ASJ " << ar.asj_before << " -> " << ar.asj_after << " in " << ar.passes << " passes, MSJ kept at "
      << ar.msj_after;
    return report_stage(st, "asj", q, t, ar.passes, d.str());
  }

  /// the max-min smoothing settings of the schedule, toward `target`
  Worst_element_smoothing_settings max_min_settings(double target, double guard_tolerance) const
  {
    const Optimization_schedule& sc = m_s.schedule;
    Worst_element_smoothing_settings ws;
    ws.target_sj = target;
    ws.max_surface_deviation = guard_tolerance;
    ws.max_sweeps = sc.max_min_sweeps;
    ws.patience = sc.max_min_patience;
    ws.min_gain = sc.max_min_min_gain;
    ws.time_limit = m_s.time_limit;
    return ws;
  }

  /// The max-min smoothing of the turns: toward the target itself rather
  /// than the next staged one, so that the elements within the band above the
  /// MSJ are worked on however close the next stage's value is (aimed at a
  /// value just above the MSJ, a turn can stall a hair below it on the few
  /// elements left there, and that ends the turns).
  Quality_statistics max_min_stage(Run_state& st, const Quality_statistics& q, double guard_tolerance)
  {
    const auto t = Clock::now();
    m_visitor.stage_started("max-min", count_below(st.mesh, q.msj + 0.05));
    Worst_element_smoothing polish(*st.topo, st.ts.get(), st.guard.get());
    const Worst_element_smoothing_report wr =
      polish.run(st.mesh.points, max_min_settings(aimed_msj(), guard_tolerance));
    std::ostringstream d;
    d << wr.moves << " moves in " << wr.sweeps << " sweeps, MSJ " << wr.msj_before << " -> " << wr.msj_after;
    return report_stage(st, "max-min", q, t, wr.sweeps, d.str());
  }

  /// completes the report of a stage that inverts nothing and hands it to the visitor
  Quality_statistics report_stage(Run_state& st, const std::string& name, const Quality_statistics& before,
                                  Clock::time_point t, int rounds, const std::string& details)
  {
    Stage_report sr;
    sr.name = name;
    const Quality_statistics after = quality_statistics(st.mesh);
    sr.inverted_before = before.inverted;
    sr.inverted_after = after.inverted;
    sr.msj_after = after.msj;
    sr.seconds = seconds_since(t);
    sr.rounds = rounds;
    sr.details = details;
    st.res.stages.push_back(sr);
    m_visitor.stage_finished(sr);
    return after;
  }

  /// the surface restoration; returns the number of boundary moves it made
  std::size_t restoration_stage(Run_state& st)
  {
    if(!m_s.schedule.restoration) return 0;
    const auto t = Clock::now();
    m_visitor.stage_started("surface restoration", 0);
    Boundary_restoration_settings bs;
    const Quality_statistics q = quality_statistics(st.mesh);
    bs.floor = q.msj;
    bs.home_distance = 1e-9; // mesh units, normalised: a mean edge is 0.025
    bs.max_sweeps = m_s.schedule.restoration_sweeps;
    bs.time_limit = m_s.time_limit;
    const Boundary_restoration_report br =
      restore_boundary(*st.topo, *st.guard, st.ts->boundary().vertices, st.home, st.mesh.points, bs);
    std::ostringstream d;
    d << br.moves << " boundary moves toward the reference in " << br.sweeps
      << " sweeps, largest distance of a boundary vertex to its home " << br.distance_before / 0.025 << " -> "
      << br.distance_after / 0.025 << " mean edge lengths";
    report_stage(st, "surface restoration", q, t, br.sweeps, d.str());
    return br.moves;
  }

  /// Stage "surface fit" (Surface_fitting.h), with a user's reference,
  /// when the surface error is above the tolerance: kept only if it brings
  /// the error close to the tolerance (see below). With the input's own boundary as the reference the
  /// restoration moves the boundary vertices to their input positions,
  /// where the error is 0, so the fit is not run.
  void surface_fit_stage(Run_state& st)
  {
    if(!user_reference()) return;
    const double error_before = st.current_error >= 0. ? st.current_error : measure_error(st);
    if(error_before <= m_s.surface_tolerance) return;
    const auto t = Clock::now();
    m_visitor.stage_started("surface fit", 0);
    const Quality_statistics q = quality_statistics(st.mesh);
    Surface_fitting_settings fs;
    fs.aim = m_s.schedule.surface_fit_aim * st.tolerance;
    fs.floor = q.msj;
    fs.max_sweeps = m_s.schedule.surface_fit_sweeps;
    fs.time_limit = m_s.time_limit;
    const std::vector<Vec3> before = st.mesh.points;
    Surface_fitting fit(*st.topo, *st.ts, m_guard_points, m_guard_tris, fs);
    const Surface_fitting_report fr = fit.run(st.mesh.points);
    const double error_after = measure_error(st);
    // kept when it removes at least `surface_fit_min_excess_cut` of the
    // error's excess over the tolerance: a fit that gets nowhere near the
    // tolerance only takes the quality down, one that gets close lets the
    // later stages finish the job
    const double tol = m_s.surface_tolerance;
    const bool kept = error_after < error_before &&
                      error_after - tol <= (1. - m_s.schedule.surface_fit_min_excess_cut) * (error_before - tol);
    if(!kept)
    {
      st.mesh.points = before;
      st.current_error = error_before;
    }
    else
      st.ts->move_target_to(st.mesh.points);
    std::ostringstream d;
    d << fr.moves << " boundary moves along the reference in " << fr.sweeps
      << " sweeps, largest local error " << fr.error_before / st.tolerance << " -> " << fr.error_after / st.tolerance
      << " tolerances; surface error " << error_before << " -> " << error_after
      << (kept ? "" : ": not close enough to the tolerance, the mesh before the fit is kept");
    report_stage(st, "surface fit", q, t, fr.sweeps, d.str());
  }

  static double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

  /// surface error of the normalised mesh against the model-space reference,
  /// to `precision` (relative to the reference's diagonal)
  static double scaled_error(const Hex_mesh_arrays& mesh, const Triangle_surface& reference, const Normalization& nz,
                             double precision)
  {
    Hex_mesh_arrays m = mesh;
    for(Vec3& p : m.points) p = nz.undo(p);
    return surface_distance(m, reference, precision).relative();
  }

  /// The pull-back, when the boundary is off the target surface by more
  /// than the tolerance, kept only if it lowers the surface error: Ω_t's
  /// anchors are projections of the boundary as the untangler left it, and
  /// on a mesh whose boundary slid along a curved surface, or whose feature
  /// classification is noisy, reaching them can raise the Hausdorff
  /// distance to the reference.
  void pull_back_stage(Run_state& st, const Hex_mesh_arrays& original)
  {
    const double error_before = measure_error(st);
    const bool to_input = m_s.pull_back_to_input && !user_reference();
    if(error_before <= m_s.surface_tolerance && !to_input) return;
    const auto t = Clock::now();
    std::vector<Boundary_constraint> bc;
    st.ts->update_constraints(st.mesh.points, bc);
    std::vector<Vec3> input_anchors;
    if(to_input)
    {
      input_anchors.reserve(original.points.size());
      for(const Vec3& p : original.points) input_anchors.push_back(st.nz.apply(p));
      for(std::size_t v : st.ts->boundary().vertices) bc[v].anchor = input_anchors[v];
    }
    double far = 0.;
    for(std::size_t v : st.ts->boundary().vertices) far = (std::max)(far, norm(st.mesh.points[v] - bc[v].anchor));
    if(!(far > 0.01 * 0.025)) return;
    m_visitor.stage_started("pull-back", 0);
    Pull_back_settings ps;
    ps.max_iterations = m_s.schedule.pull_back_iterations;
    ps.time_limit = m_s.time_limit;
    if(to_input) ps.fixed_anchors = &input_anchors;
    const std::vector<Vec3> before = st.mesh.points;
    const Pull_back_report pr = pull_back_to_target(*st.topo, *st.ts, st.mesh.points, ps);
    const double error_after = measure_error(st);
    const bool kept = error_after < error_before || to_input;
    if(!kept)
    {
      st.mesh.points = before;
      st.current_error = error_before;
    }
    Stage_report sr;
    sr.name = "pull-back";
    const Quality_statistics q = quality_statistics(st.mesh);
    sr.inverted_before = sr.inverted_after = q.inverted; // what it pins stays as it is
    sr.msj_after = q.msj;
    sr.seconds = seconds_since(t);
    sr.rounds = pr.iterations;
    std::ostringstream d;
    d << "largest distance of a boundary vertex to the target surface " << pr.distance_before / 0.025 << " -> "
      << pr.distance_after / 0.025 << " mean edge lengths"
      << (pr.reached ? "" : " (target not reached: the best valid state is kept)") << "; surface error "
      << error_before << " -> " << error_after
      << (kept ? "" : ": not lower, the mesh before the pull-back is kept");
    sr.details = d.str();
    st.res.stages.push_back(sr);
    m_visitor.stage_finished(sr);
  }

  /// Stages "msj>=t" for t = 0 (only if something is inverted), then
  /// `msj_stage_step`, 2 × that, … up to the target, each on what is below
  /// t: max-min smoothing first (one vertex at a time, far cheaper than a
  /// global edge-angle solve for the same rise of the MSJ), then, while
  /// it falls short of t, edge-angle passes (Algorithm 1 with α, β ≥ 500,
  /// rollback under the stage's starting MSJ or beyond the guard), the
  /// boundary projected back, and max-min again, while a pass raises the MSJ
  /// by at least `msj_stage_min_gain`. A stage that does not reach its t
  /// ends the schedule: the MSJ is then as high as this method gets it.
  void msj_stages(Run_state& st, double guard_tolerance)
  {
    const Optimization_schedule& sc = m_s.schedule;
    const double target = aimed_msj();
    double msj = quality_statistics(st.mesh).msj;
    for(int k = 0; !stopped(); ++k)
    {
      double t = sc.msj_stage_target(k);
      if(t > target) t = target;
      if(msj > t && t < target) continue;
      const auto t0 = Clock::now();
      std::ostringstream name;
      name << "msj>=" << t;
      m_visitor.stage_started(name.str(), count_below(st.mesh, t));
      Stage_report sr;
      sr.name = name.str();
      sr.inverted_before = quality_statistics(st.mesh).inverted;
      std::ostringstream d;
      Worst_element_smoothing polish(*st.topo, st.ts.get(), st.guard.get());
      const Worst_element_smoothing_settings ws = max_min_settings(t, guard_tolerance);
      auto smooth = [&] {
        if(!sc.msj_stage_max_min)
        {
          msj = quality_statistics(st.mesh).msj;
          return;
        }
        const Worst_element_smoothing_report wr = polish.run(st.mesh.points, ws);
        const double now = quality_statistics(st.mesh).msj;
        d << "max-min smoothing: " << wr.moves << " moves in " << wr.sweeps << " sweeps, MSJ " << msj << " -> " << now;
        msj = now;
      };
      smooth();
      // (even for a handful of elements: an edge-angle pass that does not
      // lift the last element below t can still open room for the max-min
      // smoothing after it)
      for(int pass = 0; msj < t && pass < sc.msj_stage_edge_angle_passes && !stopped(); ++pass)
      {
        const double msj_pass = msj;
        const Local_optimizer_report r = edge_angle_pass(st, t, msj, guard_tolerance, sr.name);
        sr.rounds += r.rounds;
        const std::size_t projected =
          project_boundary(st, guard_tolerance, sc.msj_stage_projection_at_target ? t : msj);
        d << "; edge-angle: below " << t << " " << r.bad_before << " -> " << r.bad_after << " in " << r.rounds
          << " rounds, " << projected << " boundary vertices projected back; ";
        smooth();
        // on while the pass raises the MSJ or frees elements (Algorithm 1
        // clears the elements below t one region at a time: the MSJ rises
        // only when the last is freed)
        if(msj - msj_pass < sc.msj_stage_min_gain && r.bad_after >= r.bad_before) break;
      }
      sr.inverted_after = quality_statistics(st.mesh).inverted;
      sr.msj_after = msj;
      sr.seconds = seconds_since(t0);
      sr.details = d.str();
      st.res.stages.push_back(sr);
      m_visitor.stage_finished(sr);
      if(msj < t || t >= target) break;
    }
  }

  /// one pass of the edge-angle local optimiser toward `t`, no element below `floor`
  Local_optimizer_report edge_angle_pass(Run_state& st, double t, double floor, double guard_tolerance,
                                         const std::string& stage)
  {
    const Target_surface& ts = *st.ts;
    const Surface_guard& guard = *st.guard;
    // the ideal angles, when a pass first needs them (their boundary part,
    // the dihedral angles of Ω_t, does not change: the same whenever made;
    // they cost a pass over the whole mesh, which a run may not need)
    if(!st.ideal) st.ideal.reset(new Ideal_angles(ideal_angles_on_target(*st.topo, ts, st.mesh.points)));
    Local_optimizer opt(*st.topo, *st.ideal,
                        [&](const std::vector<Vec3>& p, std::vector<Boundary_constraint>& bc) {
                          ts.update_constraints(p, bc);
                        },
                        ts.mean_boundary_edge_length());
    // (the paper's schedule: the rounds may go below the MSJ they started
    // from, and the pass ends in the best state of its rounds)
    const bool keep_best = m_s.schedule.msj_stage_keep_best;
    std::vector<Vec3> best;
    double best_msj = floor;
    if(keep_best) best = st.mesh.points;
    opt.on_round = [&](int r, std::size_t left) {
      m_visitor.round_finished(stage, r, left);
      if(!keep_best) return;
      const double now = quality_statistics(st.mesh).msj;
      if(now > best_msj)
      {
        best_msj = now;
        best = st.mesh.points;
      }
    };
    opt.accept_step = [&](const Local_region& region, const std::vector<Vec3>& before, std::vector<Vec3>& p) {
      return surface_kept(ts.boundary(), guard, guard_tolerance, region, before, p);
    };
    Local_optimizer_settings ls;
    ls.target_sj = t;
    ls.alpha = m_s.alpha; ls.beta = m_s.beta;
    ls.min_alpha_beta = m_s.min_alpha_beta;
    ls.xi_start = m_s.xi;
    ls.local_iterations = m_s.local_iterations;
    ls.max_rounds = m_s.schedule.msj_stage_rounds;
    ls.time_limit = m_s.time_limit;
    ls.min_sj_floor = keep_best ? 0. : floor;
    ls.authors_weight_edge = m_s.schedule.authors_weight_edge;
    if(!m_s.schedule.authors_loop)
    {
      const Local_optimizer_report r = opt.run(st.mesh.points, ls);
      if(keep_best) st.mesh.points = best;
      return r;
    }
    // the scripts' back-off (`back_off`, α and β at or above their floor),
    // each run from the same start; the first run that leaves nothing below
    // t ends it
    ls.authors_loop = true;
    ls.slide_cut = m_s.schedule.authors_slide_cut;
    ls.authors_energy = m_s.schedule.authors_energy || m_s.schedule.msj_authors_energy;
    ls.anchor_at_current = m_s.schedule.msj_anchor_at_current;
    ls.min_sj_floor = -std::numeric_limits<double>::infinity();
    const std::vector<Vec3> start = st.mesh.points;
    Local_optimizer_report r;
    for(bool first = true;; first = false)
    {
      const Local_optimizer_report run = opt.run(st.mesh.points, ls);
      if(first) r = run;
      else
      {
        r.rounds += run.rounds;
        r.accepted_steps += run.accepted_steps;
        r.rolled_back_steps += run.rolled_back_steps;
        r.bad_after = run.bad_after;
      }
      if(run.bad_after == 0 || stopped()) break;
      if(!back_off(ls, m_s.xi, m_s.min_alpha_beta)) break;
      st.mesh.points = start;
    }
    if(keep_best) st.mesh.points = best;
    return r;
  }

  /// whether a step of the edge-angle optimiser on `region` (free vertices
  /// at `before`, now at `points`) keeps every boundary vertex within the
  /// tolerance, or at least no further from the reference than it was
  static bool surface_kept(const Hex_mesh_boundary& boundary, const Surface_guard& guard, double tolerance,
                           const Local_region& region, const std::vector<Vec3>& before, std::vector<Vec3>& points)
  {
    std::vector<std::pair<std::size_t, Surface_deviation> > over; // (free index, deviation after)
    for(std::size_t i = 0; i < region.free_vertices.size(); ++i)
    {
      const std::size_t v = region.free_vertices[i];
      if(!boundary.is_boundary_vertex(v)) continue;
      const Surface_deviation d = guard.local_deviations(points, v, points[v]);
      if(d.max() > tolerance) over.push_back({i, d});
    }
    if(over.empty()) return true;
    bool ok = true;
    std::vector<Vec3> after(region.free_vertices.size());
    for(std::size_t i = 0; i < after.size(); ++i)
    {
      after[i] = points[region.free_vertices[i]];
      points[region.free_vertices[i]] = before[i];
    }
    for(const auto& o : over)
    {
      const std::size_t v = region.free_vertices[o.first];
      if(!o.second.within(guard.bound_at(points, v, points[v], tolerance))) { ok = false; break; }
    }
    for(std::size_t i = 0; i < after.size(); ++i) points[region.free_vertices[i]] = after[i];
    return ok;
  }

  /// projects boundary vertices onto their anchors, each only if no hex
  /// around it falls below `floor` and the guard allows it; returns how many
  std::size_t project_boundary(Run_state& st, double tolerance, double floor) const
  {
    const Target_surface& ts = *st.ts;
    const Surface_guard& guard = *st.guard;
    std::vector<Vec3>& points = st.mesh.points;
    std::size_t n = 0;
    const Worst_element_smoothing probe(*st.topo, &ts, nullptr);
    for(std::size_t v : ts.boundary().vertices)
    {
      const Vec3 a = ts.constraint_at(v, points[v]).anchor;
      if(squared_norm(a - points[v]) == 0.) continue;
      const double now = probe.local_minimum(points, v, points[v]);
      if(!probe.keeps_floor(points, v, a, floor, now)) continue;
      const Surface_deviation allowed = guard.bound_at(points, v, points[v], tolerance);
      if(!guard.allows(points, v, a, allowed)) continue;
      points[v] = a;
      ++n;
    }
    return n;
  }

  static std::size_t count_below(const Hex_mesh_arrays& m, double t)
  {
    const std::vector<double> sj = scaled_jacobians(m);
    return std::size_t(std::count_if(sj.begin(), sj.end(), [t](double x) { return x <= t; }));
  }

  Quality_settings m_s;
  Visitor& m_visitor;
  /// the reference surface in normalised mesh units: for the guard, cut
  /// along (0, 2) as the surface error is measured; for Ω_t both ways
  std::vector<Vec3> m_guard_points, m_target_points;
  std::vector<Tri> m_guard_tris, m_target_tris;
  /// the guard of the turns and of the final smoothing, relative to the tolerance
  double m_turn_guard = 0.7;
};

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_HEX_MESH_QUALITY_IMPROVER_H
