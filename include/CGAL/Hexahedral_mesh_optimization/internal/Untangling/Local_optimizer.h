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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_UNTANGLING_LOCAL_OPTIMIZER_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_UNTANGLING_LOCAL_OPTIMIZER_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Algorithm 1 of the paper: rounds of local optimisation of the regions
// around bad elements, with monotone rollback and the ξ / α / β schedule.
// The same loop serves untangling (bad = scaled Jacobian ≤ 0) and the MSJ
// stages (bad = scaled Jacobian below the stage target).
//
// One round: find the bad elements, extract the regions (2-rings, merged
// into clusters), and for every region
//   compute target edge lengths (Eq. 8, ξ clamp), factorise AᵀA once,
//   τ = 0.9; repeat `local_iterations` times:
//     solve the local-global step; v ← (1-τ) v + τ v_solution;
//     roll back if the region's number of bad elements (or of inverted
//     elements) went up — so neither ever rises (NOTES reading 6: "not
//     increased" rather than the text's "reduced", which would forbid
//     progress through a plateau);
//     τ ← 0.9 τ after an accepted step (the paper's decreasing step), but
//     τ ← 0.5 τ after a rolled-back one: the paper only decreases τ by 10 %,
//     which spends most of the solves of a hard region on repeated rollbacks.
// After a round: ξ ← ξ - 0.1; below ξ_min, α and β are halved (not below
// their floor) and ξ is reset. A round that removes no bad element makes the
// regions one ring wider next time (dense clusters of bad elements need more
// room than a 2-ring, as the paper says for the stress tests) and halves α
// and β at once: with the paper's schedule alone a stuck feature region
// waits 5 rounds per halving.
//
// Choice: the paper projects the boundary onto the surface after every
// iteration, which undoes the relaxation the untangling needs (a boundary
// vertex that must leave the surface to free an element is put back at
// once), so here a boundary vertex's anchor and normal are only refreshed at
// the start of each region solve (NOTES reading 3).

#include <CGAL/Hexahedral_mesh_optimization/internal/Untangling/Edge_angle_energy.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Untangling/Authors_edge_angle_energy.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Untangling/Target_edge_lengths.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/Time_limit.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/scaled_jacobian.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

/// Fills a constraint for every vertex from the current positions.
typedef std::function<void(const std::vector<Vec3>&, std::vector<Boundary_constraint>&)> Constraint_provider;

struct Local_optimizer_settings
{
  double target_sj = 0.;        ///< an element is bad when its SJ ≤ target (untangling: 0)
  double alpha = 1000., beta = 1000.;
  double min_alpha_beta = 1.;   ///< floor of the halving (paper: 500 in the MSJ stages)
  double xi_start = 0.6, xi_min = 0.2, xi_step = 0.1;
  int local_iterations = 20;
  int max_rounds = 60;
  int rings = 2;
  int max_rings = 6;
  /// the run's hard stop (null: none), read between regions
  const Time_limit* time_limit = nullptr;
  /// MSJ stages: a step that takes a region's minimum SJ below this floor
  /// (and below the region's current minimum) is rolled back, so the mesh's
  /// MSJ never drops under it (set it to the MSJ at the start of the stage)
  double min_sj_floor = -std::numeric_limits<double>::infinity();
  /// regions with more hexes are skipped (left to a later stage); a round
  /// in which every region is skipped ends the run. The sparse Cholesky
  /// factorisation of one region grows much faster than its size, so one
  /// large region can take most of a run.
  std::size_t max_region_hexes = std::numeric_limits<std::size_t>::max();
  /// the run ends after this many consecutive rounds that remove no bad
  /// element (a later stage takes over)
  int max_stalled_rounds = std::numeric_limits<int>::max();
  /// 0: α and β weigh the boundary rows as they are; ℓ > 0: as the authors'
  /// code weighs them, (α ℓ)² and (β ℓ)², ℓ the mean edge (their rows of
  /// Eq. 6 carry α, β unsquared beside angle rows of edge vectors divided by
  /// their length, i.e. 1/ℓ² times the length-unit rows here)
  double authors_weight_edge = 0.;
  /// the authors' loop (their `LocalMeshOpt`, read for `Method::paper`):
  /// α, β, ξ stay as given over the rounds (their scripts back off between
  /// runs), no ring growth; in a region the step τ falls by 10 % at every
  /// iteration, a step is rolled back only if the bad count rises, the
  /// target lengths after the first iteration are the current ones clamped
  /// at ξ·ē, the iterations go on past the last bad element while the
  /// region's minimum rises and end in the state before the first that does
  /// not raise it once above the target; and a vertex whose solution is more
  /// than 2ē away on an axis stays put unless `allow_big_step`
  bool authors_loop = false;
  bool allow_big_step = false;
  /// with `authors_loop`: the region's cut vertices (on hexes outside it too)
  /// slide in the tangent plane of the region's cut surface, as the boundary
  /// of the authors' local mesh does, where that surface has no crease of
  /// more than `cut_crease_degrees` (their local feature threshold); the
  /// hexes outside that share them count in the rollback
  bool slide_cut = false;
  double cut_crease_degrees = 10.;
  /// with `authors_loop`: the authors' own linearisation of the energy
  /// (Authors_edge_angle_energy.h) instead of the tripod fit, α and β unsquared
  bool authors_energy = false;
  /// with `authors_loop`: Eq. 6's v̄ is each boundary vertex's position at
  /// the iteration, as in the authors' rows (β n·x = β n·v, α x = α v), not
  /// its closest point on the target surface: the rows damp a step across
  /// the surface without pulling the vertex back onto it (the caller
  /// projects the boundary afterwards)
  bool anchor_at_current = false;
};

/// The authors' scripts' back-off between two runs of their loop from the
/// same start: ξ − 0.1 down to 0.2, then α and β halved and ξ back to
/// `xi_start`. Returns false when α or β falls below `alpha_floor` (no run
/// after this one).
inline bool back_off(Local_optimizer_settings& ls, double xi_start, double alpha_floor)
{
  ls.xi_start -= 0.1;
  if(ls.xi_start < 0.2 - 1e-9)
  {
    ls.alpha *= 0.5;
    ls.beta *= 0.5;
    ls.xi_start = xi_start;
  }
  return !(ls.alpha < alpha_floor || ls.beta < alpha_floor);
}

struct Local_optimizer_report
{
  std::size_t bad_before = 0, bad_after = 0;
  std::size_t inverted_before = 0, inverted_after = 0;
  int rounds = 0;
  std::size_t accepted_steps = 0, rolled_back_steps = 0;
  double final_alpha = 0., final_beta = 0.;
};

class Local_optimizer
{
public:
  Local_optimizer(const Hex_mesh_topology& topo, const Ideal_angles& ideal,
                  Constraint_provider constraints, double mean_boundary_edge_length)
    : m_topo(topo), m_ideal(ideal), m_constraints(std::move(constraints)),
      m_mean_boundary_edge(mean_boundary_edge_length)
  {}

  /// progress callback: (round, bad elements left)
  std::function<void(int, std::size_t)> on_round;
  /// optional test of a step, besides the SJ rollback: given the region, the
  /// positions of its free vertices before the step and the points after it,
  /// returns false to roll the step back (the quality stages bound the
  /// surface deviation with it)
  std::function<bool(const Local_region&, const std::vector<Vec3>&, std::vector<Vec3>&)> accept_step;

  Local_optimizer_report run(std::vector<Vec3>& points, const Local_optimizer_settings& s) const
  {
    Local_optimizer_report rep;
    const std::size_t nh = m_topo.number_of_hexes();
    std::vector<double> sj(nh);
    for(std::size_t h = 0; h < nh; ++h) sj[h] = hex_sj(points, h);
    rep.bad_before = count_bad(sj, s.target_sj);
    rep.inverted_before = count_inverted(sj);

    double alpha = s.alpha, beta = s.beta, xi = s.xi_start;
    int rings = s.rings;
    int stalled_rounds = 0;
    std::vector<double> length(m_topo.number_of_edges(), 0.);
    std::vector<Boundary_constraint> bc;
    std::vector<char> in_region(s.authors_loop ? nh : 0, 0);
    std::size_t bad = rep.bad_before;
    for(int round = 0; round < s.max_rounds && bad > 0; ++round)
    {
      if(time_limit_reached(s.time_limit)) break;
      ++rep.rounds;
      std::vector<std::size_t> seeds;
      for(std::size_t h = 0; h < nh; ++h) if(is_bad(sj[h], s.target_sj)) seeds.push_back(h);
      m_constraints(points, bc);
      const std::vector<Local_region> regions = extract_local_regions(m_topo, seeds, rings);
      const std::size_t accepted_before = rep.accepted_steps;
      Energy_weights w;
      w.alpha = alpha; w.beta = beta;
      if(s.authors_weight_edge > 0.)
      {
        w.alpha = (alpha * s.authors_weight_edge) * (alpha * s.authors_weight_edge);
        w.beta = (beta * s.authors_weight_edge) * (beta * s.authors_weight_edge);
      }
      std::size_t optimized = 0;
      for(const Local_region& region : regions)
        if(region.hexes.size() <= s.max_region_hexes && !time_limit_reached(s.time_limit))
        {
          if(s.authors_loop) authors_region(region, points, sj, bc, w, alpha, beta, xi, s, rep, in_region);
          else optimize_region(region, points, sj, bc, w, xi, s, rep);
          ++optimized;
        }
      if(optimized == 0) break;
      const std::size_t new_bad = count_bad(sj, s.target_sj);
      if(on_round) on_round(round, new_bad);
      if(s.authors_loop)
      {
        // (a round that moved nothing would be repeated as it was)
        const bool moved = rep.accepted_steps != accepted_before;
        bad = new_bad;
        if(!moved) break;
        continue;
      }
      const bool stalled = new_bad >= bad;
      stalled_rounds = stalled ? stalled_rounds + 1 : 0;
      if(stalled) rings = (std::min)(rings + 1, s.max_rings);
      bad = new_bad;
      if(stalled_rounds >= s.max_stalled_rounds) break;
      xi -= s.xi_step;
      if(xi < s.xi_min - 1e-12 || stalled)
      {
        alpha = (std::max)(0.5 * alpha, s.min_alpha_beta);
        beta = (std::max)(0.5 * beta, s.min_alpha_beta);
        xi = s.xi_start;
      }
    }
    rep.bad_after = bad;
    rep.inverted_after = count_inverted(sj);
    rep.final_alpha = alpha; rep.final_beta = beta;
    return rep;
  }

  static bool is_bad(double sj, double target) { return sj <= target; }
  static std::size_t count_bad(const std::vector<double>& sj, double target)
  {
    std::size_t n = 0;
    for(double s : sj) if(is_bad(s, target)) ++n;
    return n;
  }
  static std::size_t count_inverted(const std::vector<double>& sj)
  {
    return std::size_t(std::count_if(sj.begin(), sj.end(), [](double s) { return is_inverted(s); }));
  }

private:
  double hex_sj(const std::vector<Vec3>& p, std::size_t h) const
  {
    std::array<Vec3, 8> c;
    for(int i = 0; i < 8; ++i) c[i] = p[m_topo.hexes()[h][i]];
    return scaled_jacobian(c);
  }

  void optimize_region(const Local_region& region, std::vector<Vec3>& points, std::vector<double>& sj,
                       const std::vector<Boundary_constraint>& bc, const Energy_weights& w, double xi,
                       const Local_optimizer_settings& s, Local_optimizer_report& rep) const
  {
    Edge_angle_energy energy(m_topo, m_ideal, region);
    if(!energy.factorize(bc, w)) return;
    std::vector<double> length(m_topo.number_of_edges(), 0.);
    compute_target_edge_lengths(m_topo, m_ideal, region, energy, points,
                                xi * m_mean_boundary_edge, length);
    auto counts = [&](const std::vector<double>& values, std::size_t& bad, std::size_t& inv, double& minsj) {
      bad = inv = 0; minsj = 2.;
      for(std::size_t i = 0; i < region.hexes.size(); ++i)
      {
        if(is_bad(values[i], s.target_sj)) ++bad;
        if(is_bad(values[i], 0.)) ++inv;
        minsj = (std::min)(minsj, values[i]);
      }
    };
    std::vector<double> cur(region.hexes.size()), trial(region.hexes.size());
    for(std::size_t i = 0; i < region.hexes.size(); ++i) cur[i] = sj[region.hexes[i]];
    std::size_t bad, inv; double minsj;
    counts(cur, bad, inv, minsj);
    std::vector<Vec3> saved(region.free_vertices.size());
    double tau = 0.9;
    for(int it = 0; it < s.local_iterations && bad > 0; ++it)
    {
      const std::vector<Vec3> sol = energy.solve(points, length);
      for(std::size_t i = 0; i < region.free_vertices.size(); ++i)
      {
        const std::size_t v = region.free_vertices[i];
        saved[i] = points[v];
        points[v] = (1. - tau) * points[v] + tau * sol[i];
      }
      for(std::size_t i = 0; i < region.hexes.size(); ++i) trial[i] = hex_sj(points, region.hexes[i]);
      std::size_t nbad, ninv; double nmin;
      counts(trial, nbad, ninv, nmin);
      // rollback: neither the bad nor the inverted count may rise, nor the
      // region's minimum fall below the stage's floor
      if(nbad > bad || ninv > inv || (nmin < s.min_sj_floor && nmin < minsj) ||
         (accept_step && !accept_step(region, saved, points)))
      {
        for(std::size_t i = 0; i < region.free_vertices.size(); ++i) points[region.free_vertices[i]] = saved[i];
        ++rep.rolled_back_steps;
        tau *= 0.5;
        continue;
      }
      ++rep.accepted_steps;
      tau *= 0.9;
      cur.swap(trial);
      bad = nbad; inv = ninv; minsj = nmin;
    }
    for(std::size_t i = 0; i < region.hexes.size(); ++i) sj[region.hexes[i]] = cur[i];
  }

  /// the region's iterations of `authors_loop`; `cur` holds the SJ of the
  /// region's hexes at the start and is left with those at the end
  /// one solve of the authors' loop: (points, iteration, bad count now) ->
  /// the free vertices' least-squares positions (empty: failed)
  typedef std::function<std::vector<Vec3>(const std::vector<Vec3>&, int, std::size_t)> Region_solve;

  /// `authors_region_loop` with the tripod energy: the target lengths after
  /// the first iteration are the current ones clamped at ξ·ē
  void authors_region_loop(const Local_region& region, std::vector<Vec3>& points, Edge_angle_energy& energy,
                           std::vector<double>& length, double xi, const Local_optimizer_settings& s,
                           std::vector<double>& cur, std::vector<double>& trial, std::size_t bad, double minsj,
                           Local_optimizer_report& rep, const std::vector<std::size_t>& watch = {},
                           std::vector<Boundary_constraint>* current_anchors = nullptr) const
  {
    std::vector<std::size_t> edges; // the region's edges, each once
    {
      std::unordered_map<std::size_t, char> seen;
      for(std::size_t h : region.hexes)
        for(int k = 0; k < 12; ++k)
          if(seen.emplace(m_topo.hex_edge(h, k), 1).second) edges.push_back(m_topo.hex_edge(h, k));
    }
    const Region_solve solve = [&](const std::vector<Vec3>& p, int it, std::size_t) {
      if(current_anchors) anchor_at(region, p, *current_anchors);
      if(it > 0)
        for(std::size_t e : edges)
        {
          const auto& ed = m_topo.edge(e);
          length[e] = (std::max)(norm(p[ed[0]] - p[ed[1]]), xi * m_mean_boundary_edge);
        }
      return energy.solve(p, length);
    };
    authors_iterations(region, points, solve, s, cur, trial, bad, minsj, rep, watch);
  }

  /// `anchor_at_current`: the boundary rows of the region's free vertices
  /// pass through their positions `p`
  static void anchor_at(const Local_region& region, const std::vector<Vec3>& p, std::vector<Boundary_constraint>& bc)
  {
    for(std::size_t v : region.free_vertices)
      if(bc[v].type != Vertex_class::interior) bc[v].anchor = p[v];
  }

  /// the region's iterations of `authors_loop`; `cur` holds the SJ of the
  /// region's hexes at the start and is left with those at the end
  void authors_iterations(const Local_region& region, std::vector<Vec3>& points, const Region_solve& solve,
                          const Local_optimizer_settings& s, std::vector<double>& cur, std::vector<double>& trial,
                          std::size_t bad, double minsj, Local_optimizer_report& rep,
                          const std::vector<std::size_t>& watch) const
  {
    // `watch`: hexes outside the region that share moved vertices: their bad
    // count joins the region's in the rollback
    for(std::size_t h : watch)
      if(is_bad(hex_sj(points, h), s.target_sj)) ++bad;
    const std::size_t nf = region.free_vertices.size();
    std::vector<Vec3> saved(nf), best(nf);
    for(std::size_t i = 0; i < nf; ++i) best[i] = points[region.free_vertices[i]];
    std::vector<double> best_sj = cur;
    const double far = 2. * m_mean_boundary_edge;
    double tau = 0.9, previous_min = -1.;
    for(int it = 0; it < s.local_iterations; ++it)
    {
      const std::vector<Vec3> sol = solve(points, it, bad);
      if(sol.size() != nf) break;
      for(std::size_t i = 0; i < nf; ++i)
      {
        const std::size_t v = region.free_vertices[i];
        saved[i] = points[v];
        const Vec3 d = sol[i] - points[v];
        if(!s.allow_big_step && (std::abs(d[0]) > far || std::abs(d[1]) > far || std::abs(d[2]) > far)) continue;
        points[v] = (1. - tau) * points[v] + tau * sol[i];
      }
      tau *= 0.9;
      std::size_t nbad = 0;
      double nmin = 2.;
      for(std::size_t i = 0; i < region.hexes.size(); ++i)
      {
        trial[i] = hex_sj(points, region.hexes[i]);
        if(is_bad(trial[i], s.target_sj)) ++nbad;
        nmin = (std::min)(nmin, trial[i]);
      }
      for(std::size_t h : watch) if(is_bad(hex_sj(points, h), s.target_sj)) ++nbad;
      if(nbad > bad || (accept_step && !accept_step(region, saved, points)))
      {
        for(std::size_t i = 0; i < nf; ++i) points[region.free_vertices[i]] = saved[i];
        ++rep.rolled_back_steps;
      }
      else
      {
        ++rep.accepted_steps;
        cur.swap(trial);
        bad = nbad; minsj = nmin;
      }
      if(previous_min > s.target_sj && !(minsj > previous_min)) break;
      previous_min = minsj;
      for(std::size_t i = 0; i < nf; ++i) best[i] = points[region.free_vertices[i]];
      best_sj = cur;
    }
    for(std::size_t i = 0; i < nf; ++i) points[region.free_vertices[i]] = best[i];
    cur = best_sj;
  }

  /// `slide_cut`: the region with its cut vertices that may slide, each held
  /// to the tangent plane of the cut surface at its position (β), the
  /// hexes outside that share them watched, then the authors' loop
  void authors_region(const Local_region& region, std::vector<Vec3>& points, std::vector<double>& sj,
                      std::vector<Boundary_constraint>& bc, const Energy_weights& w, double alpha, double beta,
                      double xi, const Local_optimizer_settings& s, Local_optimizer_report& rep,
                      std::vector<char>& in_region) const
  {
    const auto& hexes = m_topo.hexes();
    for(std::size_t h : region.hexes) in_region[h] = 1;
    const double crease_cos = std::cos(s.cut_crease_degrees * 3.14159265358979323846 / 180.);
    std::vector<std::size_t> cut, watch;
    {
      std::vector<std::size_t> candidates;
      for(std::size_t h : region.hexes) candidates.insert(candidates.end(), hexes[h].begin(), hexes[h].end());
      std::sort(candidates.begin(), candidates.end());
      candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
      std::vector<std::size_t> outside;
      for(std::size_t v : candidates)
      {
        if(!s.slide_cut) break;
        if(std::binary_search(region.free_vertices.begin(), region.free_vertices.end(), v)) continue;
        if(m_topo.is_constrained(v) || m_topo.is_boundary_vertex(v) || bc[v].type != Vertex_class::interior) continue;
        // the region's faces at v that hexes outside it share: the cut surface
        std::vector<std::pair<std::array<std::size_t, 4>, Vec3> > faces; // sorted key, outward normal
        std::vector<std::array<std::size_t, 4> > outside_faces;
        for(auto c = m_topo.vertex_corners_begin(v); c != m_topo.vertex_corners_end(v); ++c)
          for(int f = 0; f < 6; ++f)
          {
            const auto& hx = hexes[c->hex];
            std::array<std::size_t, 4> key = {hx[hex_faces[f][0]], hx[hex_faces[f][1]], hx[hex_faces[f][2]],
                                              hx[hex_faces[f][3]]};
            if(std::find(key.begin(), key.end(), v) == key.end()) continue;
            if(!in_region[c->hex])
            {
              std::sort(key.begin(), key.end());
              outside_faces.push_back(key);
              continue;
            }
            const Vec3 p0 = points[key[0]], p1 = points[key[1]], p2 = points[key[2]], p3 = points[key[3]];
            Vec3 n = cross(p2 - p0, p3 - p1);
            Vec3 hc = {0., 0., 0.};
            for(std::size_t x : hx) hc = hc + 0.125 * points[x];
            if(dot(n, 0.25 * (p0 + p1 + p2 + p3) - hc) < 0.) n = -1. * n;
            std::sort(key.begin(), key.end());
            faces.push_back({key, normalized(n)});
          }
        std::vector<Vec3> normals;
        for(const auto& f : faces)
          if(std::find(outside_faces.begin(), outside_faces.end(), f.first) != outside_faces.end())
            normals.push_back(f.second);
        if(normals.empty()) continue;
        bool flat = true;
        Vec3 sum = {0., 0., 0.};
        for(std::size_t i = 0; i < normals.size() && flat; ++i)
        {
          sum = sum + normals[i];
          for(std::size_t j = i + 1; j < normals.size() && flat; ++j) flat = dot(normals[i], normals[j]) >= crease_cos;
        }
        if(!flat || squared_norm(sum) == 0.) continue;
        cut.push_back(v);
        Boundary_constraint& b = bc[v];
        b.type = Vertex_class::regular;
        b.anchor = points[v];
        b.direction = normalized(sum);
        for(auto c = m_topo.vertex_corners_begin(v); c != m_topo.vertex_corners_end(v); ++c)
          if(!in_region[c->hex]) outside.push_back(c->hex);
      }
      std::sort(outside.begin(), outside.end());
      outside.erase(std::unique(outside.begin(), outside.end()), outside.end());
      watch.swap(outside);
    }
    for(std::size_t h : region.hexes) in_region[h] = 0;
    Local_region grown = region;
    grown.free_vertices.insert(grown.free_vertices.end(), cut.begin(), cut.end());
    std::sort(grown.free_vertices.begin(), grown.free_vertices.end());
    std::vector<double> cur(region.hexes.size()), trial(region.hexes.size());
    std::size_t bad = 0;
    double minsj = 2.;
    for(std::size_t i = 0; i < region.hexes.size(); ++i)
    {
      cur[i] = sj[region.hexes[i]];
      if(is_bad(cur[i], s.target_sj)) ++bad;
      minsj = (std::min)(minsj, cur[i]);
    }
    if(s.authors_energy)
    {
      const Authors_edge_angle_energy energy(m_topo, grown);
      const double mean = energy.mean_surface_edge(points);
      const Region_solve solve = [&](const std::vector<Vec3>& p, int it, std::size_t bad_now) {
        std::vector<Vec3> out;
        if(s.anchor_at_current) anchor_at(grown, p, bc);
        // (the irregular-edge rows: weight 2 once the step is below 1/2, 10 once nothing is bad)
        const double singular = bad_now == 0 ? 10. : (std::pow(0.9, it + 1) < 0.5 ? 2. : 1.);
        if(!energy.solve(p, bc, alpha, beta, it == 0 ? energy.first_lengths(p, mean) : std::vector<double>(),
                         xi * mean, singular, mean, out))
          out.clear();
        return out;
      };
      authors_iterations(grown, points, solve, s, cur, trial, bad, minsj, rep, watch);
      for(std::size_t i = 0; i < region.hexes.size(); ++i) sj[region.hexes[i]] = cur[i];
      for(std::size_t h : watch) sj[h] = hex_sj(points, h);
    }
    else
    {
      Edge_angle_energy energy(m_topo, m_ideal, grown);
      if(energy.factorize(bc, w))
      {
        std::vector<double> length(m_topo.number_of_edges(), 0.);
        compute_target_edge_lengths(m_topo, m_ideal, grown, energy, points, xi * m_mean_boundary_edge, length);
        authors_region_loop(grown, points, energy, length, xi, s, cur, trial, bad, minsj, rep, watch,
                            s.anchor_at_current ? &bc : nullptr);
        for(std::size_t i = 0; i < region.hexes.size(); ++i) sj[region.hexes[i]] = cur[i];
        for(std::size_t h : watch) sj[h] = hex_sj(points, h);
      }
    }
    for(std::size_t v : cut) bc[v] = Boundary_constraint();
  }

  const Hex_mesh_topology& m_topo;
  const Ideal_angles& m_ideal;
  Constraint_provider m_constraints;
  double m_mean_boundary_edge;
};

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_UNTANGLING_LOCAL_OPTIMIZER_H
