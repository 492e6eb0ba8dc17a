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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_SURFACE_FITTING_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_SURFACE_FITTING_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Stage "surface fit": slides boundary vertices along the reference (regular
// vertices on the surface, crease vertices along their crease, corners
// fixed) to lower the two-sided surface error around them.
//
// Why: the pull-back puts every boundary vertex on the reference, but not
// the quads between them. Where the boundary started off its surface (every
// vertex perturbed, a mesh from another method), its vertices land anywhere
// on the reference, and each quad is a chord of the surface under it: over a
// curved patch, or over the kinks of a faceted reference, the quads leave
// the surface (mesh → reference) and uncover its bumps (reference → mesh).
// That chordal error alone, every vertex on the surface, can exceed the
// tolerance, and the later stages only keep what they are given.
//
// The local error of boundary vertex v at x, F_v(x), is the largest of
//   - mesh → reference: the distance to the reference of a grid of points
//     (step 1/4) on the (0, 2) triangles of the quads around v;
//   - reference → mesh: the distance of the reference's samples (its
//     vertices and a grid of at most `spacing` on its triangles) whose
//     closest quad is one of v's to the quads around v and around their
//     corners (an upper bound of the distance to the whole boundary; a
//     sample closest to another quad cannot get further from the boundary
//     when v moves).
// A vertex with F_v above `aim` takes pattern-search steps on the reference:
// from a step of `first_step` mean edges, halved `step_halvings` times, it
// tries 8 directions in the tangent plane, projected back onto the
// reference; a crease vertex tries the 2 directions along the reference's
// own crease and stays on it (the target's feature lines join the chain's
// vertices, chords of the crease: sliding along them cannot fit a chain to
// a bent crease, where the reference's own crease can). It moves to the
// best candidate that
//   - lowers E_v, the sum over the same samples of (d / aim)^8, by more than
//     `min_gain` of it, and does not raise F_v above max(aim, F_v): the
//     largest error is often shared by the vertices of one quad, and none
//     of them can lower it alone (with F_v as the only criterion, every
//     vertex of those quads was stuck);
//   - keeps every hex around v at or above min(floor, its minimum before)
//     (`Worst_element_smoothing::keeps_floor`).
// Vertices are visited worst first; the samples are assigned to their
// closest quad again before every sweep. The sweeps stop when none moved,
// when one lowered neither the largest local error (by `min_gain` of `aim`)
// nor the sum of the E_v (by `min_sweep_gain` of it: where every quad is at
// the largest error, the largest falls only once all have moved), after
// `max_sweeps`, or at the run's time limit (a hard stop). The stage
// then moves the target surface's positions to the result, so that the
// feature lines of the later stages pass through the fitted chains.

#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_topology.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/Time_limit.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/parallel_for_each_index.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Smoothing/Worst_element_smoothing.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Target_surface.h>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

struct Surface_fitting_settings
{
  /// vertices whose local error is at most this are left alone (mesh units)
  double aim = 0.;
  /// no hex may fall below min(floor, its minimum before the move)
  double floor = 0.;
  /// largest step, in mean boundary edge lengths, and how many times it is halved
  double first_step = 1.0;
  int step_halvings = 5;
  /// a move must lower E_v by more than this fraction of it; a sweep that
  /// lowers the largest error by less than this fraction of `aim` has not
  /// lowered it
  double min_gain = 1e-3;
  /// a sweep that does not lower the largest error must lower the sum of
  /// the vertices' energies by this fraction, or the sweeps stop
  double min_sweep_gain = 0.1;
  /// spacing of the reference's samples, in mean boundary edge lengths
  double spacing = 0.25;
  int max_sweeps = 8;
  /// the run's hard stop (null: none), read between vertices
  const Time_limit* time_limit = nullptr;
};

struct Surface_fitting_report
{
  double error_before = 0., error_after = 0.; ///< largest local error of a boundary vertex (mesh units)
  std::size_t moves = 0;
  int sweeps = 0;
};

class Surface_fitting
{
  typedef CGAL::Simple_cartesian<double> K;
  typedef std::vector<K::Triangle_3>::const_iterator Iterator;
  typedef CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_triangle_primitive<K, Iterator> > > Tree;

public:
  /// `reference_points`, `reference_triangles`: the surface the error is
  /// measured against (normalised like the mesh)
  Surface_fitting(const Hex_mesh_topology& topo, const Target_surface& ts, const std::vector<Vec3>& reference_points,
                  const std::vector<Tri>& reference_triangles, const Surface_fitting_settings& s)
    : m_topo(topo), m_ts(ts), m_b(ts.boundary()), m_s(s), m_probe(topo, nullptr, nullptr)
  {
    for(const Tri& t : reference_triangles)
      m_reference.emplace_back(point(reference_points[t[0]]), point(reference_points[t[1]]),
                               point(reference_points[t[2]]));
    m_reference_tree.rebuild(m_reference.begin(), m_reference.end());
    m_reference_tree.accelerate_distance_queries();
    sample_reference(reference_points, reference_triangles, s.spacing * ts.mean_boundary_edge_length());
  }

  /// Moves the boundary vertices of `points` (see the top).
  Surface_fitting_report run(std::vector<Vec3>& points)
  {
    Surface_fitting_report rep;
    std::vector<double> error(m_topo.number_of_vertices(), 0.), energy(m_topo.number_of_vertices(), 0.);
    // F_v and E_v of every boundary vertex, the samples assigned again first
    // (independent reads: in parallel, the same values); the largest F_v
    // and the sum of the E_v
    auto measure_all = [&] {
      assign_samples(points);
      parallel_for_each_index(m_b.vertices.size(), [&](std::size_t bi) {
        const std::size_t v = m_b.vertices[bi];
        const Local_measure lm = local_measure(points, v, points[v]);
        error[v] = lm.largest;
        energy[v] = lm.energy;
      }, 64);
      std::pair<double, double> largest_and_total(0., 0.);
      for(std::size_t v : m_b.vertices)
      {
        largest_and_total.first = (std::max)(largest_and_total.first, error[v]);
        largest_and_total.second += energy[v];
      }
      return largest_and_total;
    };
    std::pair<double, double> now = measure_all();
    rep.error_before = rep.error_after = now.first;
    for(int sweep = 0; sweep < m_s.max_sweeps; ++sweep)
    {
      if(time_limit_reached(m_s.time_limit)) break;
      std::vector<std::pair<double, std::size_t> > order;
      for(std::size_t v : m_b.vertices)
        if(error[v] > m_s.aim && m_ts.vertex_class(v) != Vertex_class::corner && !m_topo.is_constrained(v))
          order.push_back({-error[v], v});
      if(order.empty()) break;
      std::sort(order.begin(), order.end());
      ++rep.sweeps;
      std::size_t moved = 0;
      for(const auto& o : order)
      {
        if(time_limit_reached(m_s.time_limit)) break;
        if(improve_vertex(points, o.second)) ++moved;
      }
      rep.moves += moved;
      if(moved == 0) break;
      const std::pair<double, double> next = measure_all();
      // converged: the sweep lowered neither the largest error nor, by
      // `min_sweep_gain` of it, the energy
      const bool stalled = next.first > now.first - m_s.min_gain * m_s.aim &&
                           next.second > (1. - m_s.min_sweep_gain) * now.second;
      now = next;
      rep.error_after = now.first;
      if(stalled) break;
    }
    return rep;
  }

private:
  /// the local error and the energy Σ (d / aim)^p of the samples it is the largest of
  struct Local_measure
  {
    double largest = 0.;
    double energy = 0.;
    void add(double d2, double aim2)
    {
      largest = (std::max)(largest, d2);
      const double r = d2 / aim2;
      energy += r * r * r * r; // p = 8
    }
  };

  Local_measure local_measure(const std::vector<Vec3>& points, std::size_t v, const Vec3& x) const
  {
    Local_measure m;
    mesh_to_reference(points, v, x, m);
    reference_to_mesh(points, v, x, m);
    m.largest = std::sqrt(m.largest);
    return m;
  }

  /// pattern search on the reference from v's position (see the top)
  bool improve_vertex(std::vector<Vec3>& points, std::size_t v)
  {
    const double h = m_ts.mean_boundary_edge_length();
    Local_measure f = local_measure(points, v, points[v]);
    const double now = m_probe.local_minimum(points, v, points[v]);
    bool moved = false;
    double step = m_s.first_step * h;
    for(int k = 0; k <= m_s.step_halvings && f.largest > m_s.aim; )
    {
      // where v may go: points on the reference (on its crease for a crease
      // vertex) near x + step d, for the directions d
      std::vector<Vec3> directions;
      std::function<Vec3(const Vec3&)> project;
      const Boundary_constraint c = m_ts.constraint_at(v, points[v]);
      if(c.type == Vertex_class::sharp && !m_ts.reference_creases().empty())
      {
        const std::vector<Vec3>& crease = m_ts.reference_creases()[crease_of(v, points[v])];
        Vec3 tangent{0., 0., 0.};
        closest_on_crease(crease, points[v], &tangent);
        directions = {tangent, -1. * tangent};
        project = [&crease](const Vec3& y) { return closest_on_crease(crease, y, nullptr); };
      }
      else
      {
        if(c.type == Vertex_class::sharp)
          directions = {c.direction, -1. * c.direction};
        else
        {
          const Vec3 n = c.direction;
          const Vec3 a = std::abs(n[0]) < 0.6 ? Vec3{1., 0., 0.} : Vec3{0., 1., 0.};
          Vec3 t1 = cross(n, a);
          t1 = (1. / norm(t1)) * t1;
          const Vec3 t2 = cross(n, t1);
          const double r = std::sqrt(0.5);
          directions = {t1, t2, -1. * t1, -1. * t2, r * (t1 + t2), r * (t2 - t1), -r * (t1 + t2), r * (t1 - t2)};
        }
        project = [this, v](const Vec3& y) { return m_ts.constraint_at(v, y).anchor; };
      }
      // a move must lower the energy and may not raise the largest error above max(aim, F_v)
      const double largest_allowed = (std::max)(m_s.aim, f.largest);
      Local_measure best = f;
      best.energy *= 1. - m_s.min_gain;
      Vec3 best_x = points[v];
      for(const Vec3& d : directions)
      {
        const Vec3 y = project(points[v] + step * d);
        const Local_measure fy = local_measure(points, v, y);
        if(!(fy.energy < best.energy && fy.largest <= largest_allowed)) continue;
        if(!m_probe.keeps_floor(points, v, y, m_s.floor, now)) continue;
        best = fy;
        best_x = y;
      }
      if(best_x != points[v])
      {
        points[v] = best_x;
        f = best;
        moved = true;
      }
      else
      {
        step *= 0.5;
        ++k;
      }
    }
    return moved;
  }

  /// the reference crease closest to crease vertex v when first asked (at x)
  std::size_t crease_of(std::size_t v, const Vec3& x)
  {
    auto it = m_crease_of.find(v);
    if(it != m_crease_of.end()) return it->second;
    const auto& creases = m_ts.reference_creases();
    std::size_t best = 0;
    double d = std::numeric_limits<double>::max();
    for(std::size_t i = 0; i < creases.size(); ++i)
    {
      const double di = squared_norm(x - closest_on_crease(creases[i], x, nullptr));
      if(di < d) { d = di; best = i; }
    }
    m_crease_of.emplace(v, best);
    return best;
  }

  /// the closest point to p on polyline `crease`, and the unit tangent there
  static Vec3 closest_on_crease(const std::vector<Vec3>& crease, const Vec3& p, Vec3* tangent)
  {
    const feature_recovery_detail::Closest c = feature_recovery_detail::closest_on_polyline(crease, p);
    if(tangent && c.segment + 1 < crease.size())
    {
      const Vec3 d = crease[c.segment + 1] - crease[c.segment];
      if(squared_norm(d) > 0.) *tangent = (1. / norm(d)) * d;
    }
    return c.point;
  }

  /// largest distance to the reference of the quads around v, v at x
  void mesh_to_reference(const std::vector<Vec3>& points, std::size_t v, const Vec3& x, Local_measure& m) const
  {
    const std::size_t bi = m_b.boundary_index[v];
    const double aim2 = m_s.aim * m_s.aim;
    std::array<Vec3, 4> c;
    // each query starts from the previous sample's closest point (the
    // samples come in order): the same distances, the tree pruned sooner
    bool hinted = false;
    K::Point_3 hint;
    for(std::size_t k = m_b.vertex_quad_offsets[bi]; k < m_b.vertex_quad_offsets[bi + 1]; ++k)
    {
      corners_of(m_b.vertex_quad_list[k], points, v, x, c);
      for(int t = 0; t < 2; ++t)
      {
        const Vec3& a = c[0];
        const Vec3& b = c[t == 0 ? 1 : 2];
        const Vec3& d = c[t == 0 ? 2 : 3];
        const int n = quad_grid;
        for(int i = 0; i <= n; ++i)
          for(int j = 0; i + j <= n; ++j)
          {
            const K::Point_3 p = point(a + (double(i) / n) * (b - a) + (double(j) / n) * (d - a));
            hint = hinted ? m_reference_tree.closest_point(p, hint) : m_reference_tree.closest_point(p);
            hinted = true;
            m.add(CGAL::squared_distance(p, hint), aim2);
          }
      }
    }
  }

  /// largest distance of the reference samples assigned to v's quads to the
  /// quads around v and around their corners, v at x
  void reference_to_mesh(const std::vector<Vec3>& points, std::size_t v, const Vec3& x, Local_measure& m) const
  {
    const double aim2 = m_s.aim * m_s.aim;
    const std::size_t bi = m_b.boundary_index[v];
    std::vector<std::size_t> near;
    m_b.quads_near(bi, near);
    std::vector<K::Triangle_3> cover;
    std::array<Vec3, 4> c;
    for(std::size_t q : near)
    {
      corners_of(q, points, v, x, c);
      cover.emplace_back(point(c[0]), point(c[1]), point(c[2]));
      cover.emplace_back(point(c[0]), point(c[2]), point(c[3]));
    }
    for(std::size_t k = m_b.vertex_quad_offsets[bi]; k < m_b.vertex_quad_offsets[bi + 1]; ++k)
    {
      const std::size_t q = m_b.vertex_quad_list[k];
      for(std::size_t i = m_quad_sample_offsets[q]; i < m_quad_sample_offsets[q + 1]; ++i)
      {
        const K::Point_3& p = m_samples[m_quad_samples[i]];
        double best = std::numeric_limits<double>::max();
        for(const K::Triangle_3& t : cover) best = (std::min)(best, CGAL::squared_distance(p, t));
        m.add(best, aim2);
      }
    }
  }

  /// the reference's vertices and a barycentric grid of at most `spacing`
  /// on each triangle (at most `max_triangle_grid` steps a side)
  void sample_reference(const std::vector<Vec3>& rp, const std::vector<Tri>& rt, double spacing)
  {
    for(const Vec3& p : rp) m_samples.push_back(point(p));
    for(const Tri& t : rt)
    {
      const Vec3 &a = rp[t[0]], &b = rp[t[1]], &c = rp[t[2]];
      const double longest = (std::max)({norm(b - a), norm(c - b), norm(a - c)});
      const int n = int((std::min)(double(max_triangle_grid), std::ceil(longest / spacing)));
      for(int i = 0; i <= n; ++i)
        for(int j = 0; i + j <= n; ++j)
          if(i + j > 0 && !(i == n && j == 0) && !(i == 0 && j == n)) // not the vertices
            m_samples.push_back(point(a + (double(i) / n) * (b - a) + (double(j) / n) * (c - a)));
    }
  }

  /// each sample to its closest boundary quad at `points` (CSR by quad)
  void assign_samples(const std::vector<Vec3>& points)
  {
    std::vector<K::Triangle_3> tris;
    tris.reserve(2 * m_b.quads.size());
    for(const auto& q : m_b.quads)
    {
      tris.emplace_back(point(points[q[0]]), point(points[q[1]]), point(points[q[2]]));
      tris.emplace_back(point(points[q[0]]), point(points[q[2]]), point(points[q[3]]));
    }
    Tree tree(tris.begin(), tris.end());
    tree.accelerate_distance_queries();
    std::vector<std::size_t> quad_of(m_samples.size());
    m_quad_sample_offsets.assign(m_b.quads.size() + 1, 0);
    for(std::size_t i = 0; i < m_samples.size(); ++i)
    {
      quad_of[i] = std::size_t(tree.closest_point_and_primitive(m_samples[i]).second - tris.begin()) / 2;
      ++m_quad_sample_offsets[quad_of[i] + 1];
    }
    for(std::size_t q = 0; q < m_b.quads.size(); ++q) m_quad_sample_offsets[q + 1] += m_quad_sample_offsets[q];
    m_quad_samples.resize(m_samples.size());
    std::vector<std::size_t> fill(m_quad_sample_offsets.begin(), m_quad_sample_offsets.end() - 1);
    for(std::size_t i = 0; i < m_samples.size(); ++i) m_quad_samples[fill[quad_of[i]]++] = i;
  }

  void corners_of(std::size_t q, const std::vector<Vec3>& points, std::size_t v, const Vec3& x,
                  std::array<Vec3, 4>& c) const
  {
    for(int i = 0; i < 4; ++i) c[i] = m_b.quads[q][i] == v ? x : points[m_b.quads[q][i]];
  }

  static K::Point_3 point(const Vec3& p) { return K::Point_3(p[0], p[1], p[2]); }

  static constexpr int quad_grid = 4;          ///< steps a side of the grid on each quad triangle
  static constexpr int max_triangle_grid = 16; ///< most steps a side on a reference triangle

  const Hex_mesh_topology& m_topo;
  const Target_surface& m_ts;
  const Hex_mesh_boundary& m_b;
  Surface_fitting_settings m_s;
  Worst_element_smoothing m_probe;
  std::vector<K::Triangle_3> m_reference;
  Tree m_reference_tree;
  std::vector<K::Point_3> m_samples;
  std::vector<std::size_t> m_quad_sample_offsets, m_quad_samples;
  std::map<std::size_t, std::size_t> m_crease_of;
};

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_SURFACE_FITTING_H
