// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Package: Hexahedral_mesh_optimization

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_GUARD_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_GUARD_H

// A local bound on the surface error for the per-vertex moves of the
// quality stages.
//
// Projecting a moved boundary vertex onto the reference keeps the vertex on
// the surface, not the quads around it: a vertex sliding over a curved or
// creased surface turns its quads into chords that leave the reference, or
// uncovers a bump of it. The surface error of the tables (Hausdorff distance,
// quads cut along their (0, 2) diagonal, `surface_distance.h`) sees both.
// `local_deviation(points, v, x)` measures, with v at x, both directions
// around v on sample points of the quads (corners, edge thirds and
// midpoints, the (0, 2) diagonal's midpoint, the triangle centroids):
//   - mesh → reference: samples of the boundary quads around v to the
//     reference (AABB tree);
//   - reference → mesh: samples of the same quads at their start positions
//     (on the reference when the run starts) to the current quads around v
//     and around its quad neighbours.
// Sampling, not the exact local Hausdorff distance: measured on the shared
// meshes, the global Hausdorff distance after a run stays within ~10 % of
// the tolerance (corners and centroids alone let it reach 3× the tolerance).
// The two directions are kept apart (`Surface_deviation`): a move must keep
// each within max(tolerance, its value before the move). With one number,
// a vertex next to a fold of the input's boundary (reference → mesh far
// beyond the tolerance, and nothing can fix it) was free to take its quads
// off the reference up to that distance: cap_in's error doubled (0.006 →
// 0.0103) in one max-min stage.
// The reference is the surface the error is measured against (the input's
// boundary cut along (0, 2), or the user's reference surface), not the
// target surface's both-diagonal soup: on a warped quad the two differ by
// the quad's twist, which on coarse meshes is the whole error budget.

#include <CGAL/Hexahedral_mesh_optimization/internal/Hex_mesh_boundary.h>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

/// the local surface deviation around a boundary vertex, both ways
struct Surface_deviation
{
  double to_reference = 0.;   ///< largest distance of the quads around the vertex to the reference
  double from_reference = 0.; ///< largest distance of the start quads to the current ones

  double max() const { return (std::max)(to_reference, from_reference); }
  /// the bound a move from here must respect: each direction within
  /// max(`tolerance`, its value now)
  Surface_deviation bound(double tolerance) const
  {
    return Surface_deviation{(std::max)(tolerance, to_reference), (std::max)(tolerance, from_reference)};
  }
  bool within(const Surface_deviation& b) const
  {
    return to_reference <= b.to_reference && from_reference <= b.from_reference;
  }
};

class Surface_guard
{
  typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
  typedef std::vector<K::Triangle_3>::const_iterator Iterator;
  typedef CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_triangle_primitive<K, Iterator> > > Tree;

public:
  /// `boundary`: the boundary of the mesh being optimised; `reference`: the
  /// triangles of the surface the error is measured against; `start`: the
  /// current positions, the points that must stay covered.
  Surface_guard(const Hex_mesh_boundary& boundary, const std::vector<Vec3>& reference_points,
                const std::vector<Tri>& reference_triangles, const std::vector<Vec3>& start)
    : m_boundary(boundary), m_start(start)
  {
    m_triangles.reserve(reference_triangles.size());
    for(const Tri& t : reference_triangles)
      m_triangles.emplace_back(point(reference_points[t[0]]), point(reference_points[t[1]]), point(reference_points[t[2]]));
    m_tree.rebuild(m_triangles.begin(), m_triangles.end());
    m_tree.accelerate_distance_queries();
  }

  /// From now on, a moved quad whose samples come further than `distance`
  /// from the reference is sampled again on a fine grid (see
  /// `local_deviations`); infinity (the default) turns this off.
  void set_dense_sampling_above(double distance) { m_dense_above2 = distance * distance; }

  Surface_guard(const Surface_guard&) = delete;
  Surface_guard& operator=(const Surface_guard&) = delete;

  /// largest distance, either way, between the reference and the boundary
  /// quads around boundary vertex v when v is at x (0 for an interior vertex)
  double local_deviation(const std::vector<Vec3>& points, std::size_t v, const Vec3& x) const
  {
    return local_deviations(points, v, x).max();
  }

  /// the two directions of `local_deviation`
  Surface_deviation local_deviations(const std::vector<Vec3>& points, std::size_t v, const Vec3& x) const
  {
    ++m_queries;
    Surface_deviation d;
    measure(points, v, x, nullptr, d);
    return d;
  }

  /// whether `local_deviations(points, v, x).within(bound)`, the same
  /// answer: it stops at the first sample beyond the bound (a rejected move
  /// costs a fraction of the measure) and takes, for each start sample, the
  /// first current triangle within the bound rather than the closest one
  bool allows(const std::vector<Vec3>& points, std::size_t v, const Vec3& x, const Surface_deviation& bound) const
  {
    ++m_queries;
    Surface_deviation d;
    return measure(points, v, x, &bound, d);
  }

  /// how many times `local_deviations` and `allows` were called
  std::size_t number_of_queries() const { return m_queries.load(); }

private:
  /// measures `d` (see `local_deviations`); with `bound`, stops with false
  /// as soon as a sample is beyond it (then `d` is partial)
  bool measure(const std::vector<Vec3>& points, std::size_t v, const Vec3& x, const Surface_deviation* bound,
               Surface_deviation& d) const
  {
    const Hex_mesh_boundary& b = m_boundary;
    if(!b.is_boundary_vertex(v)) return true;
    const std::size_t bi = b.boundary_index[v];
    auto corners_of = [&](std::size_t q, const std::vector<Vec3>& pts, std::array<Vec3, 4>& c) {
      for(int i = 0; i < 4; ++i) c[i] = (&pts == &points && b.quads[q][i] == v) ? x : pts[b.quads[q][i]];
    };
    // quads around v first, then the quads sharing a vertex with them (which
    // may cover what v's quads no longer cover): a start sample is mostly
    // covered by its own quad, which ends its search under a bound
    // scratch, one per thread (the ASJ smoothing calls this from several)
    thread_local std::vector<std::size_t> near;
    near.clear();
    for(std::size_t k = b.vertex_quad_offsets[bi]; k < b.vertex_quad_offsets[bi + 1]; ++k)
      for(std::size_t u : b.quads[b.vertex_quad_list[k]])
      {
        const std::size_t ui = b.boundary_index[u];
        for(std::size_t j = b.vertex_quad_offsets[ui]; j < b.vertex_quad_offsets[ui + 1]; ++j)
          near.push_back(b.vertex_quad_list[j]);
      }
    std::sort(near.begin(), near.end());
    near.erase(std::unique(near.begin(), near.end()), near.end());
    auto own = [&](std::size_t q) {
      for(std::size_t k = b.vertex_quad_offsets[bi]; k < b.vertex_quad_offsets[bi + 1]; ++k)
        if(b.vertex_quad_list[k] == q) return true;
      return false;
    };
    std::stable_partition(near.begin(), near.end(), own);
    thread_local std::vector<K::Triangle_3> cover;
    cover.clear();
    std::array<Vec3, 4> c;
    for(std::size_t q : near)
    {
      corners_of(q, points, c);
      cover.emplace_back(point(c[0]), point(c[1]), point(c[2]));
      cover.emplace_back(point(c[0]), point(c[2]), point(c[3]));
    }
    // (compared as distances, not squares: the bound is often a deviation
    // measured before, which a move that leaves the worst sample alone must
    // meet exactly)
    const double to = bound ? bound->to_reference : std::numeric_limits<double>::infinity();
    const double from = bound ? bound->from_reference : std::numeric_limits<double>::infinity();
    // each query starts from the closest point of the previous sample (the
    // samples come in order along the quads): the tree then prunes with a
    // tight radius from the start and skips its nearest-neighbour search
    // (the same distances; see the manual's implementation notes)
    K::Point_3 hint = m_tree.closest_point(point(x));
    auto squared_distance_from_hint = [&](const Vec3& p) {
      const K::Point_3 q = point(p);
      hint = m_tree.closest_point(q, hint);
      return CGAL::squared_distance(q, hint);
    };
    double d2 = CGAL::squared_distance(point(x), hint), e2 = 0.;
    bool within = std::sqrt(d2) <= to;
    // mesh -> reference: the largest sample distance of a quad, false as soon
    // as one is beyond the bound
    auto mesh_to_reference = [&](const std::array<Vec3, 4>& quad, bool fine, double& q2) {
      bool ok = true;
      auto visit = [&](const Vec3& p) {
        if(!ok) return;
        q2 = (std::max)(q2, squared_distance_from_hint(p));
        ok = std::sqrt(q2) <= to;
      };
      if(fine) for_each_fine_sample(quad, visit);
      else for_each_sample(quad, visit);
      return ok;
    };
    for(std::size_t k = b.vertex_quad_offsets[bi]; k < b.vertex_quad_offsets[bi + 1] && within; ++k)
    {
      const std::size_t q = b.vertex_quad_list[k];
      // mesh -> reference: samples of the moved quad's two triangles; where
      // they come near the largest deviation allowed, a fine grid too (the
      // largest distance of a flat triangle to a curved reference can lie
      // between the coarse samples)
      corners_of(q, points, c);
      double q2 = 0.;
      within = mesh_to_reference(c, false, q2);
      if(within && q2 > m_dense_above2) within = mesh_to_reference(c, true, q2);
      d2 = (std::max)(d2, q2);
      if(!within) break;
      // reference -> mesh: samples of the quad at its start position
      corners_of(q, m_start, c);
      for_each_sample(c, [&](const Vec3& p) {
        if(!within) return;
        const K::Point_3 h = point(p);
        double best = std::numeric_limits<double>::max();
        for(const K::Triangle_3& t : cover)
        {
          best = (std::min)(best, CGAL::squared_distance(h, t));
          if(best <= e2 || (bound && std::sqrt(best) <= from)) break; // cannot raise the maximum, or within the bound
        }
        e2 = (std::max)(e2, best);
        within = std::sqrt(e2) <= from;
      });
    }
    d = Surface_deviation{std::sqrt(d2), std::sqrt(e2)};
    return within;
  }

  static K::Point_3 point(const Vec3& p) { return K::Point_3(p[0], p[1], p[2]); }

  const Hex_mesh_boundary& m_boundary;
  /// points of the quad's (0, 2) triangles: corners, edge and diagonal
  /// midpoints, centroids and the points a third of the way along each edge
  template <class F>
  static void for_each_sample(const std::array<Vec3, 4>& c, F f)
  {
    for(int i = 0; i < 4; ++i)
    {
      f(c[i]);
      const Vec3& a = c[i];
      const Vec3& e = c[(i + 1) % 4];
      f((2. / 3.) * a + (1. / 3.) * e);
      f(0.5 * (a + e));
      f((1. / 3.) * a + (2. / 3.) * e);
    }
    f(0.5 * (c[0] + c[2]));
    f((1. / 3.) * (c[0] + c[1] + c[2]));
    f((1. / 3.) * (c[0] + c[2] + c[3]));
  }

  /// the points of a grid of step 1/16 on each of the quad's (0, 2) triangles
  /// (a 1/8 grid still missed fertility_gregson11's overshoot)
  template <class F>
  static void for_each_fine_sample(const std::array<Vec3, 4>& c, F f)
  {
    const int n = 16;
    for(int t = 0; t < 2; ++t)
    {
      const Vec3& a = c[0];
      const Vec3& b = c[t == 0 ? 1 : 2];
      const Vec3& d = c[t == 0 ? 2 : 3];
      for(int i = 0; i <= n; ++i)
        for(int j = 0; i + j <= n; ++j)
          f(a + (double(i) / n) * (b - a) + (double(j) / n) * (d - a));
    }
  }

  std::vector<Vec3> m_start;
  double m_dense_above2 = std::numeric_limits<double>::infinity();
  mutable std::atomic<std::size_t> m_queries{0};
  std::vector<K::Triangle_3> m_triangles;
  Tree m_tree;
};

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_GUARD_H
