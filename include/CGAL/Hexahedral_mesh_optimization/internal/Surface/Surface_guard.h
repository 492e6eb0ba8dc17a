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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_SURFACE_GUARD_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_SURFACE_GUARD_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

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
// Sampling, not the exact local Hausdorff distance: dense enough on each quad
// that the global Hausdorff distance after a run stays close to the tolerance
// (corners and centroids alone miss the chords between them).
// The two directions are kept apart (`Surface_deviation`): a move must keep
// each within max(tolerance, its value before the move). With one number,
// a vertex next to a fold of the input's boundary (reference → mesh far
// beyond the tolerance, and nothing can fix it) would be free to take its
// quads off the reference (mesh → reference) up to that distance.
// Cost: a stage asks whether a move stays within a bound far more often
// than it needs the deviation itself, so `allows` stops at the first sample
// beyond the bound, and `bound_at` measures exactly only what exceeds the
// tolerance. Each boundary quad caches its samples' distances to the
// reference with the corners they were measured at; the distance is
// 1-Lipschitz and a sample is a convex combination of the corners, so a
// sample whose cached distance plus how far it moved is within the bound
// needs no query. The answers are those of the full measure (tested in
// test_asj_smoothing).
// The reference is the surface the error is measured against (the input's
// boundary cut along (0, 2), or the user's reference surface), not the
// target surface's both-diagonal soup: on a warped quad the two differ by
// the quad's twist, which on coarse meshes is the whole error budget.

#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_boundary.h>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

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
  // plain double arithmetic for the closest-point queries: with filtered
  // predicates the sphere-box tests of a flat (axis-aligned) boundary fall
  // back to exact arithmetic, and a distance needs no exactness
  typedef CGAL::Simple_cartesian<double> K;
  typedef std::vector<K::Triangle_3>::const_iterator Iterator;
  typedef CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_triangle_primitive<K, Iterator> > > Tree;

public:
  /// `boundary`: the boundary of the mesh being optimised; `reference`: the
  /// triangles of the surface the error is measured against; `start`: the
  /// current positions, the points that must stay covered.
  Surface_guard(const Hex_mesh_boundary& boundary, const std::vector<Vec3>& reference_points,
                const std::vector<Tri>& reference_triangles, const std::vector<Vec3>& start)
    : m_boundary(boundary), m_start(start), m_quad_cache(boundary.quads.size())
  {
    m_triangles.reserve(reference_triangles.size());
    for(const Tri& t : reference_triangles)
      m_triangles.emplace_back(point(reference_points[t[0]]), point(reference_points[t[1]]), point(reference_points[t[2]]));
    m_tree.rebuild(m_triangles.begin(), m_triangles.end());
    m_tree.accelerate_distance_queries();
    const CGAL::Bbox_3 box = m_tree.bbox();
    m_rounding = 1e-12 * std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) +
                                   CGAL::square(box.zmax() - box.zmin()));
  }

  /// From now on, a moved quad whose samples come further than `distance`
  /// from the reference is sampled again on a fine grid (see
  /// `local_deviations`); infinity (the default) turns this off.
  void set_dense_sampling_above(double distance) { m_dense_above2 = distance * distance; }

  /// From now on, the tolerance `bound_at` applies around vertex v is at
  /// most `tolerance[v]` (the `local_surface_tolerance` of thin layers)
  void set_vertex_tolerances(std::vector<double> tolerance) { m_vertex_tolerance = std::move(tolerance); }

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
    measure(points, v, x, Surface_deviation{0., 0.}, nullptr, d);
    return d;
  }

  /// `local_deviations(points, v, x).bound(tolerance)`, the same value: a
  /// direction known to be within `tolerance` is not measured exactly
  /// (with per-vertex tolerances, `tolerance` is capped by v's)
  Surface_deviation bound_at(const std::vector<Vec3>& points, std::size_t v, const Vec3& x, double tolerance) const
  {
    ++m_queries;
    if(!m_vertex_tolerance.empty()) tolerance = (std::min)(tolerance, m_vertex_tolerance[v]);
    Surface_deviation d;
    measure(points, v, x, Surface_deviation{tolerance, tolerance}, nullptr, d);
    return d;
  }

  /// whether `local_deviations(points, v, x).within(bound)`, the same
  /// answer: it stops at the first sample beyond the bound (a rejected move
  /// costs a fraction of the measure), takes, for each start sample, the
  /// first current triangle within the bound rather than the closest one,
  /// and skips the quads that the cache proves within it
  bool allows(const std::vector<Vec3>& points, std::size_t v, const Vec3& x, const Surface_deviation& bound) const
  {
    ++m_queries;
    Surface_deviation d;
    return measure(points, v, x, bound, &bound, d);
  }

  /// how many times `local_deviations`, `bound_at` and `allows` were called
  std::size_t number_of_queries() const { return m_queries.load(); }

private:
  /// one sample set's distances to the reference (at most: a sample not
  /// measured keeps its bound) and the corners they hold for
  struct Sample_cache
  {
    bool exact = false;           ///< every sample measured at `corners`
    std::array<Vec3, 4> corners;
    std::vector<double> distance; ///< of each sample (empty: none yet)

    void keep(const std::array<Vec3, 4>& c, const std::vector<double>& d, bool all_exact)
    {
      corners = c;
      distance = d;
      exact = all_exact;
    }
  };

  /// one entry per boundary quad (the fine samples' made when the quad
  /// first needs them), written by the visits of its corners (never two at
  /// once: a parallel sweep moves vertices that share no hex, hence no quad)
  struct Quad_cache
  {
    Sample_cache coarse, fine;
  };

  /// closest-point queries along a sequence of samples, each starting from
  /// the closest point of the previous one (the samples come in order along
  /// the quad): the tree then prunes with a tight radius from the start (the
  /// same distances, fewer nodes visited)
  struct Hinted_query
  {
    explicit Hinted_query(const Tree& t) : tree(t) {}
    const Tree& tree;
    bool have_hint = false;
    K::Point_3 hint;
    double operator()(const Vec3& p)
    {
      const K::Point_3 x = point(p);
      hint = have_hint ? tree.closest_point(x, hint) : tree.closest_point(x);
      have_hint = true;
      return std::sqrt(CGAL::squared_distance(x, hint));
    }
  };

  /// The measure of the quads around v with v at x, `d` = max(`floor`, the
  /// deviation) in each direction: what is below the floor need not be
  /// exact. With `bound`, stops with false as soon as a sample is beyond it
  /// (`d` is then partial).
  bool measure(const std::vector<Vec3>& points, std::size_t v, const Vec3& x, const Surface_deviation& floor,
               const Surface_deviation* bound, Surface_deviation& d) const
  {
    const Hex_mesh_boundary& b = m_boundary;
    d = floor;
    if(!b.is_boundary_vertex(v)) return true;
    const std::size_t bi = b.boundary_index[v];
    const std::size_t first = b.vertex_quad_offsets[bi], last = b.vertex_quad_offsets[bi + 1];
    const double to = bound ? bound->to_reference : std::numeric_limits<double>::infinity();
    bool within = true;
    std::array<Vec3, 4> c;
    for(std::size_t k = first; k < last && within; ++k)
    {
      const std::size_t q = b.vertex_quad_list[k];
      corners_of(q, points, v, x, c);
      within = quad_to_reference(q, c, floor.to_reference, to, d.to_reference);
    }
    if(within) within = start_to_quads(points, v, x, floor.from_reference, bound, d.from_reference);
    return within;
  }

  void corners_of(std::size_t q, const std::vector<Vec3>& points, std::size_t v, const Vec3& x,
                  std::array<Vec3, 4>& c) const
  {
    for(int i = 0; i < 4; ++i) c[i] = m_boundary.quads[q][i] == v ? x : points[m_boundary.quads[q][i]];
  }

  /// Mesh -> reference for quad q at corners c: raises `largest` to the
  /// quad's largest sample distance to the reference (the coarse samples;
  /// where they come near the largest deviation allowed, a fine grid too:
  /// the largest distance of a flat triangle to a curved reference can lie
  /// between the coarse samples). Returns false as soon as one is beyond
  /// `bound`. Both sets of samples go through their cache
  /// (`measure_samples`); a coarse sample is skipped only below the
  /// fine-sampling threshold too, so that the fine grid is used exactly when
  /// the full measure would use it.
  bool quad_to_reference(std::size_t q, const std::array<Vec3, 4>& c, double floor, double bound,
                         double& largest) const
  {
    Quad_cache& cache = m_quad_cache[q];
    Hinted_query query(m_tree);
    thread_local std::vector<double> coarse, fine;
    double measured = 0.; // the largest distance measured (or reused) exactly
    bool coarse_exact = true, fine_exact = true;
    auto coarse_samples = [](const std::array<Vec3, 4>& corners, auto f) { for_each_sample(corners, f); };
    auto fine_samples = [](const std::array<Vec3, 4>& corners, auto f) { for_each_fine_sample(corners, f); };
    bool ok = measure_samples(cache.coarse, c, coarse_samples, (std::min)(floor, std::sqrt(m_dense_above2)), bound, query,
                              coarse, coarse_exact, measured);
    const bool with_fine = ok && measured * measured > m_dense_above2;
    if(with_fine) ok = measure_samples(cache.fine, c, fine_samples, floor, bound, query, fine, fine_exact, measured);
    largest = (std::max)(largest, measured);
    if(ok)
    {
      cache.coarse.keep(c, coarse, coarse_exact);
      if(with_fine) cache.fine.keep(c, fine, fine_exact);
    }
    return ok;
  }

  /// The distances of one set of samples of a quad at corners c (`for_each`
  /// calls f(point, weights of the corners) for each) into `out`, with
  /// `cache`: at the corners of a measure of every sample, its distances as
  /// they are; otherwise a sample whose cached distance plus how far it
  /// moved is within `skip_below` (by `m_rounding`: a sample recomputed where
  /// it was can differ in its last bits) keeps that bound unmeasured (the
  /// distance is 1-Lipschitz and a sample is a convex combination of the
  /// corners; when one corner moved, the samples away from it did not move
  /// at all); the others are measured. Raises `measured` to the largest
  /// exact distance, and returns false as soon as it is beyond `bound`.
  /// `exact`: whether every distance in `out` is exact.
  template <class For_each_sample>
  bool measure_samples(const Sample_cache& cache, const std::array<Vec3, 4>& c, For_each_sample for_each,
                       double skip_below, double bound, Hinted_query& query, std::vector<double>& out, bool& exact,
                       double& measured) const
  {
    const bool cached = !cache.distance.empty();
    const bool unchanged = cached && cache.exact && c == cache.corners;
    std::array<Vec3, 4> moved;
    for(int i = 0; i < 4; ++i) moved[i] = cached ? c[i] - cache.corners[i] : Vec3{0., 0., 0.};
    out.clear();
    exact = true;
    bool ok = true;
    for_each(c, [&](const Vec3& p, const std::array<double, 4>& w) {
      if(!ok) return;
      const std::size_t k = out.size();
      if(!unchanged && cached)
      {
        const double most = cache.distance[k] + norm(w[0] * moved[0] + w[1] * moved[1] + w[2] * moved[2] + w[3] * moved[3]);
        if(most + m_rounding <= skip_below) { out.push_back(most); exact = false; return; }
      }
      out.push_back(unchanged ? cache.distance[k] : query(p));
      measured = (std::max)(measured, out.back());
      ok = measured <= bound;
    });
    return ok;
  }

  /// Reference -> mesh: raises `largest` to the largest distance of the
  /// samples of v's quads at their start positions to the current quads
  /// around v and around its quad neighbours (which may cover what v's quads
  /// no longer cover). A start sample within max(`largest`, `floor`) of a
  /// current triangle is settled. Returns false as soon as one is beyond
  /// `bound` (compared as distances, not squares: the bound is often a
  /// deviation measured before, which a move that leaves the worst sample
  /// alone must meet exactly).
  bool start_to_quads(const std::vector<Vec3>& points, std::size_t v, const Vec3& x, double floor,
                      const Surface_deviation* bound, double& largest) const
  {
    const Hex_mesh_boundary& b = m_boundary;
    const std::size_t bi = b.boundary_index[v];
    const std::size_t first = b.vertex_quad_offsets[bi], last = b.vertex_quad_offsets[bi + 1];
    // v's own quads first: a start sample is mostly covered by its own quad
    // (scratch, one per thread: the ASJ smoothing calls this from several)
    thread_local std::vector<std::size_t> near;
    b.quads_near(bi, near);
    auto own = [&](std::size_t q) {
      for(std::size_t k = first; k < last; ++k)
        if(b.vertex_quad_list[k] == q) return true;
      return false;
    };
    std::stable_partition(near.begin(), near.end(), own);
    thread_local std::vector<K::Triangle_3> cover;
    cover.clear();
    std::array<Vec3, 4> c;
    for(std::size_t q : near)
    {
      corners_of(q, points, v, x, c);
      cover.emplace_back(point(c[0]), point(c[1]), point(c[2]));
      cover.emplace_back(point(c[0]), point(c[2]), point(c[3]));
    }
    const double limit = bound ? bound->from_reference : std::numeric_limits<double>::infinity();
    const double settled2 = floor * floor;
    double e2 = 0.;
    bool ok = true;
    for(std::size_t k = first; k < last && ok; ++k)
    {
      for(int i = 0; i < 4; ++i) c[i] = m_start[b.quads[b.vertex_quad_list[k]][i]];
      for_each_sample(c, [&](const Vec3& p, const std::array<double, 4>&) {
        if(!ok) return;
        const K::Point_3 h = point(p);
        double best = std::numeric_limits<double>::max();
        for(const K::Triangle_3& t : cover)
        {
          best = (std::min)(best, CGAL::squared_distance(h, t));
          // cannot raise the maximum, or settled
          if(best <= e2 || (best <= settled2 && std::sqrt(best) <= floor)) break;
        }
        e2 = (std::max)(e2, best);
        ok = std::sqrt(e2) <= limit;
      });
    }
    largest = (std::max)(largest, std::sqrt(e2));
    return ok;
  }

  static K::Point_3 point(const Vec3& p) { return K::Point_3(p[0], p[1], p[2]); }

  /// The coarse samples of a quad's (0, 2) triangles, as weights of its
  /// corners: corners, the points a third and half of the way along each
  /// edge, the (0, 2) diagonal's midpoint and the triangles' centroids
  static constexpr int number_of_coarse_samples = 19;
  static constexpr double coarse_sample_weights[number_of_coarse_samples][4] = {
    {1., 0., 0., 0.}, {2. / 3., 1. / 3., 0., 0.}, {0.5, 0.5, 0., 0.}, {1. / 3., 2. / 3., 0., 0.},
    {0., 1., 0., 0.}, {0., 2. / 3., 1. / 3., 0.}, {0., 0.5, 0.5, 0.}, {0., 1. / 3., 2. / 3., 0.},
    {0., 0., 1., 0.}, {0., 0., 2. / 3., 1. / 3.}, {0., 0., 0.5, 0.5}, {0., 0., 1. / 3., 2. / 3.},
    {0., 0., 0., 1.}, {1. / 3., 0., 0., 2. / 3.}, {0.5, 0., 0., 0.5}, {2. / 3., 0., 0., 1. / 3.},
    {0.5, 0., 0.5, 0.}, {1. / 3., 1. / 3., 1. / 3., 0.}, {1. / 3., 0., 1. / 3., 1. / 3.}};

  static Vec3 coarse_sample(const std::array<Vec3, 4>& c, int k)
  {
    if(k < 16)
    {
      const double* w = coarse_sample_weights[k];
      const int i = k / 4, j = (i + 1) % 4;
      return w[i] * c[i] + w[j] * c[j];
    }
    if(k == 16) return 0.5 * (c[0] + c[2]);
    return (1. / 3.) * (k == 17 ? c[0] + c[1] + c[2] : c[0] + c[2] + c[3]);
  }

  /// f(point, weights of the corners) for each coarse sample
  template <class F>
  static void for_each_sample(const std::array<Vec3, 4>& c, F f)
  {
    for(int k = 0; k < number_of_coarse_samples; ++k)
    {
      const double* w = coarse_sample_weights[k];
      f(coarse_sample(c, k), std::array<double, 4>{w[0], w[1], w[2], w[3]});
    }
  }

  /// the points of a grid of step 1/16 on each of the quad's (0, 2) triangles
  /// (fine enough to catch a quad's overshoot between coarse samples), each
  /// with its weights of the quad's corners
  static constexpr int fine_steps = 16;
  template <class F>
  static void for_each_fine_sample(const std::array<Vec3, 4>& c, F f)
  {
    const int n = fine_steps;
    for(int t = 0; t < 2; ++t)
    {
      const Vec3& a = c[0];
      const Vec3& b = c[t == 0 ? 1 : 2];
      const Vec3& d = c[t == 0 ? 2 : 3];
      for(int i = 0; i <= n; ++i)
        for(int j = 0; i + j <= n; ++j)
        {
          const double wb = double(i) / n, wd = double(j) / n;
          const std::array<double, 4> w =
            t == 0 ? std::array<double, 4>{1. - wb - wd, wb, wd, 0.} : std::array<double, 4>{1. - wb - wd, 0., wb, wd};
          f(a + wb * (b - a) + wd * (d - a), w);
        }
    }
  }

  const Hex_mesh_boundary& m_boundary;
  std::vector<Vec3> m_start;
  mutable std::vector<Quad_cache> m_quad_cache;
  /// a cached sample is skipped only this far (1e-12 of the reference's
  /// diagonal) within the floor: a sample recomputed where it was can differ
  /// in its last bits, and a move that the full measure would refuse by such
  /// a tie is then refused all the same
  double m_rounding = 0.;
  double m_dense_above2 = std::numeric_limits<double>::infinity();
  std::vector<double> m_vertex_tolerance; ///< per vertex, normalised units (empty: none)
  mutable std::atomic<std::size_t> m_queries{0};
  std::vector<K::Triangle_3> m_triangles;
  Tree m_tree;
};

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_SURFACE_GUARD_H
