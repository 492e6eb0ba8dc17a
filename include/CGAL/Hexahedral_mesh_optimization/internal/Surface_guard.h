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
// around v:
//   - mesh → reference: the distance to the reference of the midpoints of the
//     quad edges at v, of the (0, 2) diagonals and of the triangle centroids
//     of the boundary quads around v;
//   - reference → mesh: the distance of the start positions of v and of its
//     quad neighbours (points of the reference when the run starts) to the
//     triangles of the quads around each of them.
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
#include <cmath>
#include <limits>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

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

  Surface_guard(const Surface_guard&) = delete;
  Surface_guard& operator=(const Surface_guard&) = delete;

  /// largest distance, either way, between the reference and the boundary
  /// quads around boundary vertex v when v is at x (0 for an interior vertex)
  double local_deviation(const std::vector<Vec3>& points, std::size_t v, const Vec3& x) const
  {
    const Hex_mesh_boundary& b = m_boundary;
    if(!b.is_boundary_vertex(v)) return 0.;
    const std::size_t bi = b.boundary_index[v];
    double d2 = 0.;
    auto far = [&](const Vec3& p) { d2 = (std::max)(d2, m_tree.squared_distance(point(p))); };
    std::array<std::size_t, 24> homes;
    std::size_t nhomes = 0;
    for(std::size_t k = b.vertex_quad_offsets[bi]; k < b.vertex_quad_offsets[bi + 1]; ++k)
      for(std::size_t u : b.quads[b.vertex_quad_list[k]])
        if(nhomes < homes.size() && std::find(homes.begin(), homes.begin() + nhomes, u) == homes.begin() + nhomes)
          homes[nhomes++] = u;
    auto corners_of = [&](std::size_t q, std::array<Vec3, 4>& c) {
      for(int i = 0; i < 4; ++i) c[i] = b.quads[q][i] == v ? x : points[b.quads[q][i]];
    };
    std::array<Vec3, 4> c;
    for(std::size_t k = b.vertex_quad_offsets[bi]; k < b.vertex_quad_offsets[bi + 1]; ++k)
    {
      const auto& quad = b.quads[b.vertex_quad_list[k]];
      corners_of(b.vertex_quad_list[k], c);
      const int at = int(std::find(quad.begin(), quad.end(), v) - quad.begin());
      far(0.5 * (c[at] + c[(at + 1) % 4]));
      far(0.5 * (c[at] + c[(at + 3) % 4]));
      far(0.5 * (c[0] + c[2]));
      far((1. / 3.) * (c[0] + c[1] + c[2]));
      far((1. / 3.) * (c[0] + c[2] + c[3]));
    }
    // each home must be covered by the quads around it (some of which move with v)
    for(std::size_t j = 0; j < nhomes; ++j)
    {
      const std::size_t u = homes[j], ui = b.boundary_index[u];
      const K::Point_3 h = point(m_start[u]);
      double cover = std::numeric_limits<double>::max();
      for(std::size_t k = b.vertex_quad_offsets[ui]; k < b.vertex_quad_offsets[ui + 1]; ++k)
      {
        corners_of(b.vertex_quad_list[k], c);
        cover = (std::min)(cover, (std::min)(CGAL::squared_distance(h, K::Triangle_3(point(c[0]), point(c[1]), point(c[2]))),
                                             CGAL::squared_distance(h, K::Triangle_3(point(c[0]), point(c[2]), point(c[3])))));
      }
      if(cover < std::numeric_limits<double>::max()) d2 = (std::max)(d2, cover);
    }
    return std::sqrt(d2);
  }

private:
  static K::Point_3 point(const Vec3& p) { return K::Point_3(p[0], p[1], p[2]); }

  const Hex_mesh_boundary& m_boundary;
  std::vector<Vec3> m_start;
  std::vector<K::Triangle_3> m_triangles;
  Tree m_tree;
};

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_GUARD_H
