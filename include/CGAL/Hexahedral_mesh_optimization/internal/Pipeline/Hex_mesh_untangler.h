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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_HEX_MESH_UNTANGLER_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_HEX_MESH_UNTANGLER_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The untangling pipeline on flat arrays (Sections 3.1 and 3.2):
//   1. normalise the mesh (mean edge length 0.025, about its centroid) and
//      the reference surface with it, so that α = β = 1000 mean the same on
//      every model;
//   2. target surface Ω_t and feature classification (Target_surface.h);
//      ideal angles from the connectivity, with the measured dihedral angle
//      of Ω_t on feature edges (Ideal_angles.h);
//   3. stage "interior": the foldover-free energy (Barrier_untangler.h) on
//      regions around the inverted hexes with every boundary vertex fixed —
//      what the interior alone can untangle is untangled without moving the
//      surface (untangling through the relaxed edge-angle optimiser first
//      lets boundary vertices wander mean edges from home and uncover
//      creases the quality stages' guard then misses); where the hexes
//      around say the mesher meant boxes (`box_ideals`), a well-made hex
//      keeps its input shape as its ideal, an inverted one the box of its
//      edges' median lengths, so that a graded mesh stays graded;
//   4. stage "edge-angle": the local optimiser of Algorithm 1
//      (Local_optimizer.h) on what is left;
//   5. stage "barrier": on what is left, the foldover-free energy
//      (Barrier_untangler.h), region by region, each result kept only if the
//      region's inverted count does not rise;
//   6. stage "surface": the boundary pulled back toward the target surface
//      by the same energy with a true barrier (nothing can invert), see
//      pull_back_to_surface();
//   7. stage "give-back" (Give_back.h): the moved vertices of well-made
//      hexes back at their input position where the repair did not need them;
//   8. scale back; if the result is worse than the input (more inverted, or
//      as many with a lower MSJ), the input positions are kept.

#include <CGAL/Hexahedral_mesh_optimization/Optimization_result.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Untangling/Barrier_untangler.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Untangling/Local_optimizer.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/Optimization_schedule.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/Optimization_setup.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Target_surface.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/Time_limit.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/quality_statistics.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/Give_back.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/surface_distance.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <sstream>
#include <utility>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

struct Untangle_settings
{
  double sharp_angle = 165.;
  /// with a reference surface, its creases (dihedral angle below this) are
  /// recovered on the mesh boundary (Feature_recovery.h); 0: off
  double reference_feature_angle = 150.;
  double alpha = 1000., beta = 1000.;
  double xi = 0.6;
  bool relax_surface = true;
  int local_iterations = 20;
  int max_rounds = 60;
  bool barrier_fallback = true;
  /// the edge-angle stage on the whole mesh at once (the paper's global
  /// variant) instead of on the 2-ring regions of the inverted elements
  bool global_region = false;
  /// rings of hexes around the inverted ones in the edge-angle stage's regions
  int rings = 2;
  /// the edge-angle stage's steps may move a vertex by more than 2 mean edges
  /// on an axis (the authors' `allowBigStep`, with `Optimization_schedule::authors_loop`)
  bool allow_big_step = false;
  /// the run's hard stop (null: none); it is not the schedule's business
  const Time_limit* time_limit = nullptr;
  /// work caps and convergence thresholds of every stage
  Optimization_schedule schedule;
  /// optional reference surface (triangle soup, model coordinates)
  const std::vector<Vec3>* reference_points = nullptr;
  const std::vector<Tri>* reference_triangles = nullptr;
  /// edges of the reference given as creases (`edge_is_constrained_map`)
  const std::vector<std::array<std::size_t, 2> >* reference_creases = nullptr;
};

/// `region` without what keeps the barrier at ε = 0 from starting: the
/// vertices of its hexes whose scaled Jacobian is not positive stay where
/// they are, and the hexes left with no free vertex drop out. Without this,
/// one inverted hex left by the untangling makes every region around it
/// (regions merge: on a boundary that starts off its surface everywhere,
/// one region) refuse to move, and the boundary stays off the surface.
template <class Hex_sj>
Local_region without_nonpositive_hexes(const Local_region& region, const std::vector<Hex>& hexes, const Hex_sj& hex_sj)
{
  std::vector<std::size_t> pinned;
  for(std::size_t h : region.hexes)
    if(!(hex_sj(h) > 0.)) pinned.insert(pinned.end(), hexes[h].begin(), hexes[h].end());
  if(pinned.empty()) return region;
  std::sort(pinned.begin(), pinned.end());
  Local_region out;
  out.bad_hexes = region.bad_hexes;
  for(std::size_t v : region.free_vertices)
    if(!std::binary_search(pinned.begin(), pinned.end(), v)) out.free_vertices.push_back(v);
  std::vector<std::size_t> free_sorted = out.free_vertices;
  std::sort(free_sorted.begin(), free_sorted.end());
  for(std::size_t h : region.hexes)
  {
    bool moves = false;
    for(std::size_t v : hexes[h]) moves = moves || std::binary_search(free_sorted.begin(), free_sorted.end(), v);
    if(moves) out.hexes.push_back(h);
  }
  return out;
}

/// Stage "surface": pulls the boundary back toward the target surface after
/// untangling, without inverting anything. Around the boundary vertices
/// whose residual exceeds `tol` (normal distance to the reference for
/// regular vertices, distance to the reference for sharp ones, distance to
/// the anchor for corners), 2-ring regions are optimised with the
/// foldover-free energy at ε = 0 — a true barrier, so no Jacobian frame of
/// the region can degenerate and no hex can invert — plus the Eq. 6
/// boundary energy, whose weight starts at 100 w0 (w0: one mean edge of
/// displacement costs as much as one ideal frame) and grows ×10 per outer
/// pass while the anchors are refreshed. A region's result is kept only if
/// its largest residual did not grow and it has no more inverted hexes.
///
/// Why: Algorithm 1 halves α and β globally until the last stuck element
/// is freed, and by then the boundary of every region has drifted. Moving
/// boundary vertices back one at a time (backtracking toward the anchor,
/// each accepted only if the hexes around keep SJ > 0) gains almost
/// nothing: the whole neighbourhood has moved, so the interior must move
/// with the boundary. The pass also raises the MSJ, since the frame energy
/// shapes the hexes. The sharp residual is the distance to the reference,
/// not to Ω_t's feature polyline: on the noisy "features" of organic models
/// the chords are off the surface, and pulling onto them moves the boundary
/// off it.
/// Returns the largest residual left.
inline double pull_back_to_surface(const Hex_mesh_topology& topo, const Target_surface& ts,
                                   std::vector<Vec3>& points, double tol, int outer,
                                   const Time_limit* time_limit, std::size_t* regions_done = nullptr)
{
  const auto& hexes = topo.hexes();
  std::vector<Boundary_constraint> bc;
  auto hex_sj = [&](std::size_t h) {
    std::array<Vec3, 8> c;
    for(int i = 0; i < 8; ++i) c[i] = points[hexes[h][i]];
    return scaled_jacobian(c);
  };
  auto residual = [&](std::size_t v) {
    const Boundary_constraint& b = bc[v];
    const Vec3 d = points[v] - b.anchor;
    if(b.type == Vertex_class::regular) return std::abs(dot(d, b.direction));
    if(b.type == Vertex_class::sharp)
    {
      // off the surface, not off Ω_t's feature polyline (on noisy "features"
      // of organic models the polyline's chords are off the surface)
      Vec3 q;
      ts.closest_on_reference(points[v], q);
      return norm(points[v] - q);
    }
    return norm(d);
  };
  double worst = 0.;
  const double w0 = 1. / (0.025 * 0.025);
  for(int k = 0; k < outer; ++k)
  {
    ts.update_constraints(points, bc);
    std::vector<char> seed(hexes.size(), 0);
    worst = 0.;
    for(std::size_t v : ts.boundary().vertices)
    {
      const double r = residual(v);
      worst = (std::max)(worst, r);
      if(r > tol)
        for(auto c = topo.vertex_corners_begin(v); c != topo.vertex_corners_end(v); ++c) seed[c->hex] = 1;
    }
    std::vector<std::size_t> seeds;
    for(std::size_t h = 0; h < hexes.size(); ++h) if(seed[h]) seeds.push_back(h);
    if(seeds.empty() || time_limit_reached(time_limit)) break;
    const double w = w0 * std::pow(10., 2 + k);
    // the regions are independent (see `for_each_region`), and so are their
    // reads of the constraints and the reference tree (built by now)
    std::atomic<std::size_t> done(0);
    for_each_region(extract_local_regions(topo, seeds, 2), [&](const Local_region& whole) {
      if(time_limit_reached(time_limit)) return;
      const Local_region region = without_nonpositive_hexes(whole, hexes, hex_sj);
      if(region.free_vertices.empty()) return;
      auto region_residual = [&] {
        double m = 0.;
        for(std::size_t v : region.free_vertices) if(bc[v].type != Vertex_class::interior) m = (std::max)(m, residual(v));
        return m;
      };
      const double before = region_residual();
      std::vector<Vec3> saved(region.free_vertices.size());
      for(std::size_t i = 0; i < saved.size(); ++i) saved[i] = points[region.free_vertices[i]];
      Barrier_untangler b(topo, region, bc, w);
      b.set_time_limit(time_limit);
      std::size_t inverted_before = 0;
      for(std::size_t h : region.hexes) if(is_inverted(hex_sj(h))) ++inverted_before;
      if(!b.run_injective(points, 100)) return;
      std::size_t inverted_after = 0;
      for(std::size_t h : region.hexes) if(is_inverted(hex_sj(h))) ++inverted_after;
      if(region_residual() > before || inverted_after > inverted_before)
        for(std::size_t i = 0; i < saved.size(); ++i) points[region.free_vertices[i]] = saved[i];
      else
        ++done;
    });
    if(regions_done) *regions_done += done.load();
  }
  ts.update_constraints(points, bc);
  worst = 0.;
  for(std::size_t v : ts.boundary().vertices) worst = (std::max)(worst, residual(v));
  return worst;
}

/// the surface the error is measured against: the reference soup when there
/// is one, the boundary of `input` otherwise (quads cut along (0, 2))
inline void reference_surface_of(const Hex_mesh_arrays& input, const std::vector<Vec3>* ref_points,
                                 const std::vector<Tri>* ref_tris, Triangle_surface& ref)
{
  if(!(ref_points && ref_tris))
  {
    boundary_surface(input, ref);
    return;
  }
  std::vector<Triangle_surface::Vertex_index> vi;
  for(const Vec3& p : *ref_points) vi.push_back(ref.add_vertex(Triangle_surface::Point(p[0], p[1], p[2])));
  for(const Tri& t : *ref_tris) ref.add_face(vi[t[0]], vi[t[1]], vi[t[2]]);
}

/// the surface error of `mesh` (relative to the reference's diagonal)
/// against `reference_surface_of(input, ref_points, ref_tris)`
inline double relative_surface_error_to(const Hex_mesh_arrays& mesh, const Hex_mesh_arrays& input,
                                        const std::vector<Vec3>* ref_points, const std::vector<Tri>* ref_tris)
{
  Triangle_surface ref;
  reference_surface_of(input, ref_points, ref_tris, ref);
  return relative_surface_error(mesh, ref);
}

/// `off_surface_vertices` of `mesh` against `reference_surface_of(input,
/// ref_points, ref_tris)`, with `tolerance` relative to that reference's
/// diagonal and `local` relative to the shortest edge at each vertex in
/// `input` (negative: none); adds a warning to `res` when there are any
inline void report_off_surface_vertices(const Hex_mesh_arrays& mesh, const Hex_mesh_arrays& input,
                                        const std::vector<Vec3>* ref_points, const std::vector<Tri>* ref_tris,
                                        double tolerance, double local, Optimization_result& res)
{
  Triangle_surface ref;
  reference_surface_of(input, ref_points, ref_tris, ref);
  res.off_surface = off_surface_vertices(mesh, input, ref, tolerance * diagonal(bbox_of(ref)), local);
  if(res.off_surface.empty()) return;
  const Off_surface_vertex& w = res.off_surface.front();
  std::ostringstream m;
  m << res.off_surface.size() << " boundary vertices are farther from the reference surface than the tolerance"
    << (local >= 0. ? "s allow" : " allows") << "; the farthest, vertex " << w.vertex << ", at " << w.distance << " ("
    << w.distance / w.local_length << " of its shortest edge, " << w.allowed << " allowed)";
  res.warnings.push_back(m.str());
}

template <class Visitor>
class Hex_mesh_untangler
{
  typedef std::chrono::steady_clock Clock; // for the reports' seconds only

public:
  Hex_mesh_untangler(const Untangle_settings& s, Visitor& visitor) : m_s(s), m_visitor(visitor) {}

  /// α at the end of the last edge-angle stage (its start value if none ran)
  double final_alpha() const { return m_final_alpha; }

  /// Untangles `mesh` in place. `measure_surface_error`: whether the result
  /// gets the surface error (the quality pipeline measures it itself).
  Optimization_result run(Hex_mesh_arrays& mesh, bool measure_surface_error = true)
  {
    const auto start = Clock::now();
    Optimization_result res;
    const std::vector<Vec3> input_points = mesh.points; // the hexes never change
    m_input_sj = scaled_jacobians(mesh); // the box ideals' and the give-back's view of the input
    const Quality_statistics q0 = quality_statistics(m_input_sj, mesh.points.size());
    res.inverted_before = q0.inverted; res.msj_before = q0.msj; res.asj_before = q0.asj;

    const Hex_mesh_topology topo(mesh);
    const Normalization nz = normalization(topo, mesh.points);
    for(Vec3& p : mesh.points) p = nz.apply(p);
    const std::vector<Vec3> normalized_input = mesh.points;

    Target_surface_parameters tsp;
    tsp.feature_angle = m_s.sharp_angle;
    std::unique_ptr<Target_surface> ts;
    if(m_s.reference_points && m_s.reference_triangles)
    {
      std::vector<Vec3> rp;
      rp.reserve(m_s.reference_points->size());
      for(const Vec3& p : *m_s.reference_points) rp.push_back(nz.apply(p));
      tsp.reference_feature_angle = m_s.reference_feature_angle;
      if(m_s.reference_creases) tsp.reference_creases = *m_s.reference_creases;
      ts.reset(new Target_surface(mesh, topo.boundary(), rp, *m_s.reference_triangles, tsp));
    }
    else
      ts.reset(new Target_surface(mesh, topo.boundary(), tsp));

    const Optimization_schedule& sc = m_s.schedule;
    m_inverted = count_inverted(mesh); // then kept by each stage's report
    if(ts->feature_recovery_summary().attempted)
    {
      Stage_report sr = begin_stage("feature recovery");
      sr.details = describe(ts->feature_recovery_summary());
      end_stage(sr, mesh, start, res);
    }
    if(m_s.barrier_fallback && sc.interior_stage && q0.inverted > 0 && !stopped())
      interior_stage(topo, ts->boundary(), mesh, res);
    // (what the interior stage freed needs no edge-angle stage: its set-up,
    // ideal angles and target lengths over the whole mesh, is costly on a
    // large mesh with nothing left to untangle)
    if((sc.edge_angle_stage || !m_s.barrier_fallback || !sc.barrier_stage) && m_inverted > 0 && !stopped())
      edge_angle_stage(topo, *ts, mesh, res);
    if(m_s.barrier_fallback && sc.barrier_stage && m_inverted > 0 && !stopped())
      barrier_stage(topo, *ts, mesh, res);
    if(sc.surface_stage && !stopped())
      surface_stage(topo, *ts, mesh, res);
    if(sc.give_back && !stopped())
      give_back_stage(topo, *ts, normalized_input, mesh, res);

    const std::vector<Vec3> normalized = mesh.points;
    for(Vec3& p : mesh.points) p = nz.undo(p);
    restore_unmoved_vertices(mesh.points, normalized, normalized_input, input_points, mesh);

    // ---- never make the mesh worse
    const Quality_statistics q1 = keep_input_if_worse(mesh, input_points, q0, res);
    res.success = q1.inverted == 0;
    res.time_limit_reached = m_s.time_limit && m_s.time_limit->limit_passed();
    res.interrupted = m_s.time_limit && m_s.time_limit->interrupted();
    if(measure_surface_error) res.surface_error = surface_error(mesh, Hex_mesh_arrays{input_points, mesh.hexes});
    res.seconds = since(start);
    return res;
  }

private:
  bool stopped() const { return time_limit_reached(m_s.time_limit); }
  static double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

  /// starts the report of a stage and tells the visitor
  Stage_report begin_stage(const std::string& name)
  {
    Stage_report sr;
    sr.name = name;
    sr.inverted_before = m_inverted;
    m_visitor.stage_started(name, m_inverted);
    return sr;
  }

  /// completes the report of a stage and hands it to the visitor
  void end_stage(Stage_report& sr, const Hex_mesh_arrays& mesh, Clock::time_point t, Optimization_result& res)
  {
    const Quality_statistics q = quality_statistics(mesh);
    sr.inverted_after = m_inverted = q.inverted;
    sr.msj_after = q.msj;
    sr.seconds = since(t);
    res.stages.push_back(sr);
    m_visitor.stage_finished(sr);
  }

  /// stage "interior": the barrier with the boundary fixed (see `untangle_interior`)
  void interior_stage(const Hex_mesh_topology& topo, const Hex_mesh_boundary& boundary, Hex_mesh_arrays& mesh,
                      Optimization_result& res)
  {
    const auto t = Clock::now();
    Stage_report sr = begin_stage("interior");
    sr.details = untangle_interior(topo, boundary, mesh);
    sr.rounds = 1;
    end_stage(sr, mesh, t, res);
  }

  /// stage "give-back" (Give_back.h): the vertices the stages moved and
  /// whose hexes were all well made in `input` (SJ at least
  /// `barrier_input_shape_sj`) go back there wherever no hex around them
  /// then loses more than the schedule's slack of its scaled Jacobian (nor
  /// falls below the MSJ reached): the regions' energies move every vertex a
  /// little, far from what was inverted, where the repair needed none of it;
  /// where the input was poor, its positions are no better than the moves
  void give_back_stage(const Hex_mesh_topology& topo, const Target_surface& ts, const std::vector<Vec3>& input,
                       Hex_mesh_arrays& mesh, Optimization_result& res)
  {
    const auto t = Clock::now();
    Stage_report sr = begin_stage("give-back");
    Give_back_settings gs;
    gs.aimed = 1.;
    gs.floor = quality_statistics(mesh).msj;
    gs.slack = m_s.schedule.give_back_slack;
    gs.max_sweeps = m_s.schedule.give_back_sweeps;
    gs.boundary_allowed = [&ts](std::size_t, const Vec3& now, const Vec3& in) {
      return closer_to_reference(ts, in, now);
    };
    if(mesh.points != input) // (nothing to give back otherwise)
    {
      gs.eligible.assign(input.size(), 1);
      for(std::size_t h = 0; h < m_input_sj.size(); ++h)
        if(m_input_sj[h] < m_s.schedule.barrier_input_shape_sj)
          for(std::size_t v : mesh.hexes[h]) gs.eligible[v] = 0;
    }
    const Give_back_report r = give_back_to_input(topo, input, mesh.points, gs);
    std::ostringstream d;
    d << r.given_back << " of " << r.moved_before << " moved vertices back at their input position in " << r.sweeps
      << " sweeps";
    sr.details = d.str();
    sr.rounds = r.sweeps;
    end_stage(sr, mesh, t, res);
  }

  /// stage "edge-angle": the local optimiser of Algorithm 1
  void edge_angle_stage(const Hex_mesh_topology& topo, const Target_surface& ts, Hex_mesh_arrays& mesh,
                        Optimization_result& res)
  {
    const auto t = Clock::now();
    const Optimization_schedule& sc = m_s.schedule;
    const Ideal_angles ideal = ideal_angles_on_target(topo, ts, mesh.points);
    Local_optimizer opt(topo, ideal,
                        [&](const std::vector<Vec3>& p, std::vector<Boundary_constraint>& bc) {
                          ts.update_constraints(p, bc);
                        },
                        ts.mean_boundary_edge_length());
    opt.on_round = [&](int r, std::size_t left) { m_visitor.round_finished("edge-angle", r, left); };
    Local_optimizer_settings ls;
    ls.alpha = m_s.alpha; ls.beta = m_s.beta; ls.xi_start = m_s.xi;
    ls.min_alpha_beta = m_s.relax_surface ? 1. : (std::min)(m_s.alpha, m_s.beta);
    ls.local_iterations = m_s.local_iterations;
    ls.max_rounds = (std::min)(m_s.max_rounds, sc.edge_angle_rounds);
    ls.time_limit = m_s.time_limit;
    // Hand-over to the barrier stage: a region of more than
    // `edge_angle_max_region_hexes` is left to it (its factorisation grows
    // much faster than its size), and so is a plateau of
    // `edge_angle_stalled_rounds` (the barrier frees what the edge-angle
    // optimiser stalls on)
    ls.max_region_hexes = sc.edge_angle_max_region_hexes;
    ls.max_stalled_rounds = sc.edge_angle_stalled_rounds;
    // (rings past the mesh's diameter: one region, all its connected hexes)
    if(m_s.rings > ls.rings) ls.rings = ls.max_rings = m_s.rings;
    if(m_s.global_region) ls.rings = ls.max_rings = static_cast<int>(mesh.hexes.size());
    // (the global variant, the authors' MeshOpt, is still read as before:
    // its own weighting with the loop below is not followed yet)
    ls.authors_weight_edge = m_s.global_region ? 0. : sc.authors_weight_edge;
    Stage_report sr = begin_stage("edge-angle");
    Local_optimizer_report r;
    // (the global variant keeps the rounds' own schedule: one whole-mesh
    // region run again from the start at each back-off is far too slow)
    if(sc.authors_loop && !m_s.global_region)
    {
      // the scripts' back-off (`back_off`), each run from the same start;
      // the run with the fewest inverted elements is kept
      ls.authors_loop = true;
      ls.slide_cut = sc.authors_slide_cut;
      ls.authors_energy = sc.authors_energy;
      ls.allow_big_step = m_s.allow_big_step;
      ls.max_rounds = (std::min)(ls.max_rounds, sc.paper_msj_stage_rounds);
      const std::vector<Vec3> start = mesh.points;
      std::vector<Vec3> best;
      for(;;)
      {
        const Local_optimizer_report run = opt.run(mesh.points, ls);
        if(best.empty() || run.inverted_after < r.inverted_after)
        {
          r = run;
          best = mesh.points;
        }
        if(run.inverted_after == 0 || !m_s.relax_surface || stopped()) break;
        if(!back_off(ls, m_s.xi, sc.authors_untangle_alpha_floor)) break;
        mesh.points = start;
      }
      mesh.points = best;
    }
    else
      r = opt.run(mesh.points, ls);
    m_final_alpha = r.final_alpha;
    sr.rounds = r.rounds;
    std::ostringstream d;
    d << r.accepted_steps << " steps accepted, " << r.rolled_back_steps << " rolled back; alpha = "
      << r.final_alpha << ", beta = " << r.final_beta << " at the end";
    sr.details = d.str();
    end_stage(sr, mesh, t, res);
  }

  /// stage "barrier": on what is left, the foldover-free energy with the
  /// surface free to relax, strong first, weaker only for what is still
  /// inverted, each time on wider regions (weights: `Optimization_schedule`)
  void barrier_stage(const Hex_mesh_topology& topo, const Target_surface& ts, Hex_mesh_arrays& mesh,
                     Optimization_result& res)
  {
    const auto t = Clock::now();
    const Optimization_schedule& sc = m_s.schedule;
    Stage_report sr = begin_stage("barrier");
    const double w0 = 1. / (0.025 * 0.025);
    std::vector<double> weights;
    if(m_s.relax_surface) weights.assign(std::begin(sc.barrier_weights_relaxed), std::end(sc.barrier_weights_relaxed));
    else weights.assign(std::begin(sc.barrier_weights_fixed), std::end(sc.barrier_weights_fixed));
    // the passes, then (`barrier_volume_weight`) one with the volume term
    // on regions one ring wider, at the last pass's weight
    const std::size_t passes = weights.size() + (sc.barrier_volume_weight > 0. && !weights.empty() ? 1 : 0);
    bool with_volume = false;
    for(std::size_t pass = 0; pass < passes && !stopped(); ++pass)
    {
      const std::vector<std::size_t> bad = inverted_hexes(mesh);
      if(bad.empty()) break;
      ++sr.rounds;
      with_volume = pass == weights.size();
      const double w = weights[(std::min)(pass, weights.size() - 1)] * w0;
      std::vector<Boundary_constraint> bc;
      ts.update_constraints(mesh.points, bc);
      for_each_region(extract_local_regions(topo, bad, 2 + int(pass)), [&](const Local_region& region) {
        if(stopped()) return;
        Barrier_untangler b(topo, region, bc, w);
        b.set_sliding_weight(sc.barrier_sliding_fraction * w);
        if(with_volume) b.set_volume_weight(sc.barrier_volume_weight);
        b.set_time_limit(m_s.time_limit);
        run_on_region(b, region, mesh, false);
      });
      m_visitor.round_finished("barrier", int(pass), count_inverted(mesh));
    }
    sr.details = "foldover-free energy on the 8 corner frames and the centre frame";
    if(with_volume) sr.details += "; a last pass with its volume term";
    end_stage(sr, mesh, t, res);
  }

  /// stage "surface": the boundary back toward the target surface
  void surface_stage(const Hex_mesh_topology& topo, const Target_surface& ts, Hex_mesh_arrays& mesh,
                     Optimization_result& res)
  {
    const auto t = Clock::now();
    const Optimization_schedule& sc = m_s.schedule;
    Stage_report sr = begin_stage("surface");
    std::size_t regions = 0;
    const double worst = pull_back_to_surface(topo, ts, mesh.points, sc.surface_residual_edges * 0.025,
                                              sc.surface_passes, m_s.time_limit, &regions);
    sr.details = std::to_string(regions) + " regions, largest residual " + std::to_string(worst / 0.025) + " edges";
    end_stage(sr, mesh, t, res);
  }

  /// The foldover-free energy on regions of 3 rings around the inverted
  /// hexes with every boundary vertex fixed: whatever the interior alone can
  /// untangle is untangled without moving the surface. A region's result is
  /// kept only if it lowers its inverted count: where the interior cannot
  /// help, the next stages start from the input as it was.
  /// Returns what it did, for the stage's report.
  std::string untangle_interior(const Hex_mesh_topology& topo, const Hex_mesh_boundary& boundary,
                                Hex_mesh_arrays& mesh) const
  {
    const std::vector<Boundary_constraint> no_constraints(mesh.points.size());
    std::vector<Local_region> regions = extract_local_regions(topo, inverted_hexes(mesh), m_s.schedule.interior_rings);
    for(Local_region& region : regions)
    {
      std::vector<std::size_t> interior;
      for(std::size_t v : region.free_vertices) if(!boundary.is_boundary_vertex(v)) interior.push_back(v);
      region.free_vertices.swap(interior);
    }
    const double shape_sj = m_s.schedule.barrier_input_shape_sj;
    const std::vector<Vec3> reference = mesh.points;
    const std::vector<unsigned char> use_reference =
      shape_sj <= 1. ? box_ideals(topo, mesh, m_input_sj) : std::vector<unsigned char>(mesh.hexes.size(), 0);
    for_each_region(regions, [&](const Local_region& region) {
      if(region.free_vertices.empty() || stopped()) return;
      Barrier_untangler b(topo, region, no_constraints, 0.);
      if(shape_sj <= 1.) b.set_reference_shapes(&reference, &use_reference);
      b.set_time_limit(m_s.time_limit);
      run_on_region(b, region, mesh, true);
    });
    std::size_t largest = 0;
    for(const Local_region& region : regions) largest = (std::max)(largest, region.hexes.size());
    std::ostringstream d;
    d << "foldover-free energy, interior vertices only; " << regions.size() << " regions, the largest of "
      << largest << " hexes";
    return d.str();
  }

  /// Which hexes keep a box as the barrier's ideal (`Barrier_untangler::set_reference_shapes`):
  /// 1 its input shape, 2 the box of its median edge lengths (an inverted
  /// hex), 0 a cube. A hex keeps a box where the mesher evidently meant
  /// boxes (a boundary layer): it is elongated (`box_aspect` at least
  /// `barrier_box_min_aspect`) and at least `barrier_box_evidence` of the
  /// hexes sharing a vertex with it are elongated and well made (SJ at least
  /// `barrier_input_shape_sj`). Scattered inverted or elongated hexes, as a
  /// perturbation leaves them, aim at a cube.
  /// (`sj`: the scaled Jacobians of `mesh`'s hexes)
  std::vector<unsigned char> box_ideals(const Hex_mesh_topology& topo, const Hex_mesh_arrays& mesh,
                                        const std::vector<double>& sj) const
  {
    const Optimization_schedule& sc = m_s.schedule;
    const std::size_t nh = mesh.hexes.size();
    std::vector<unsigned char> elongated(nh, 0), well_made_box(nh, 0), use(nh, 0);
    for(std::size_t h = 0; h < nh; ++h)
    {
      elongated[h] = box_aspect(mesh, h) >= sc.barrier_box_min_aspect;
      well_made_box[h] = elongated[h] && sj[h] >= sc.barrier_input_shape_sj;
    }
    std::vector<std::size_t> ring;
    for(std::size_t h = 0; h < nh; ++h)
    {
      if(!elongated[h] || !(well_made_box[h] || is_inverted(sj[h]))) continue;
      ring.clear();
      for(std::size_t v : mesh.hexes[h])
        for(auto c = topo.vertex_corners_begin(v); c != topo.vertex_corners_end(v); ++c)
          if(c->hex != h) ring.push_back(c->hex);
      std::sort(ring.begin(), ring.end());
      ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
      std::size_t boxes = 0;
      for(std::size_t n : ring) boxes += well_made_box[n];
      if(!ring.empty() && double(boxes) >= sc.barrier_box_evidence * double(ring.size()))
        use[h] = is_inverted(sj[h]) ? 2 : 1;
    }
    return use;
  }

  /// the largest ratio of the median lengths of hex h's edges along its
  /// three directions (`median_edge_lengths`)
  static double box_aspect(const Hex_mesh_arrays& mesh, std::size_t h)
  {
    double p[8][3], L[3];
    for(int i = 0; i < 8; ++i) for(int d = 0; d < 3; ++d) p[i][d] = mesh.points[mesh.hexes[h][i]][d];
    median_edge_lengths(p, L);
    const double lo = (std::min)({L[0], L[1], L[2]}), hi = (std::max)({L[0], L[1], L[2]});
    return lo > 0. ? hi / lo : 0.;
  }

  /// Untangling by `b` on `region`, undone unless the region's inverted
  /// count falls (`must_fall`) or at least does not rise; nothing is done
  /// on a region with nothing inverted.
  static void run_on_region(Barrier_untangler& b, const Local_region& region, Hex_mesh_arrays& mesh, bool must_fall)
  {
    auto count = [&] { // on all threads (a small region is one task)
      std::vector<unsigned char> inverted(region.hexes.size());
      parallel_for_each_index(region.hexes.size(), [&](std::size_t i) {
        inverted[i] = is_inverted(scaled_jacobian(mesh, region.hexes[i])) ? 1 : 0;
      }, 1024);
      return std::size_t(std::count(inverted.begin(), inverted.end(), 1));
    };
    const std::size_t before = count();
    if(before == 0) return;
    std::vector<Vec3> saved(region.free_vertices.size());
    for(std::size_t i = 0; i < saved.size(); ++i) saved[i] = mesh.points[region.free_vertices[i]];
    b.run(mesh.points);
    const std::size_t after = count();
    if(must_fall ? after >= before : after > before)
      for(std::size_t i = 0; i < saved.size(); ++i) mesh.points[region.free_vertices[i]] = saved[i];
  }

  static std::vector<std::size_t> inverted_hexes(const Hex_mesh_arrays& m)
  {
    const std::vector<double> sj = scaled_jacobians(m); // on all threads
    std::vector<std::size_t> bad;
    for(std::size_t h = 0; h < sj.size(); ++h) if(is_inverted(sj[h])) bad.push_back(h);
    return bad;
  }

  static std::size_t count_inverted(const Hex_mesh_arrays& m) { return inverted_hexes(m).size(); }

  double surface_error(const Hex_mesh_arrays& mesh, const Hex_mesh_arrays& input) const
  {
    return relative_surface_error_to(mesh, input, m_s.reference_points, m_s.reference_triangles);
  }

  Untangle_settings m_s;
  Visitor& m_visitor;
  /// the inverted count of the current state, from the last count or stage report
  std::size_t m_inverted = 0;
  double m_final_alpha = m_s.alpha;
  /// the scaled Jacobians of the input's hexes, computed once per run
  std::vector<double> m_input_sj;
};

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_HEX_MESH_UNTANGLER_H
