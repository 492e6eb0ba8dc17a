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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_MESH_HEX_MESH_BOUNDARY_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_MESH_HEX_MESH_BOUNDARY_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The boundary of a hexahedral mesh as flat arrays: the boundary quads (faces
// of exactly one hexahedron), the boundary vertices with a vertex -> boundary
// index map, the unique boundary edges, and the adjacencies the target
// surface and the energies need (quad across each quad edge, quads and edge
// neighbours of each boundary vertex, in CSR form). Built once per
// connectivity: the optimisation never changes it.
//
// Choices:
// - A face is on the boundary when its key (the 4 sorted vertex indices)
//   occurs exactly once among the 6·#hexes faces. Faces found 3 times or more
//   (invalid, non-manifold volume) are counted in `number_of_overshared_faces`
//   and treated as interior.
// - The faces are matched by sorting their keys rather than hashing them:
//   as fast, and the output order (by hexahedron, then by local face) is
//   deterministic.
// - A boundary edge shared by exactly two boundary quads is manifold; one
//   shared by 4 (two hexes touching along an edge only) or by an odd number
//   (impossible for a closed boundary, possible for broken input) has no
//   `quad_neighbors` entry (npos) and is flagged in `edge_is_manifold`.
// - Quads are oriented by `hex_faces` (outward for a positively oriented
//   hexahedron). The orientation is combinatorial, so it stays consistent
//   over a tangled mesh as long as the hexes are consistently numbered.

#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/face_groups.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/scaled_jacobian.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/assertions.h>

#include <boost/unordered_map.hpp>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

typedef std::array<std::size_t, 3> Tri;

struct Hex_mesh_boundary
{
  static constexpr std::size_t npos = std::size_t(-1);
  typedef std::array<std::size_t, 4> Quad;

  /// boundary quads, as mesh vertex indices, oriented outward (right-hand rule)
  std::vector<Quad> quads;
  /// the hexahedron each boundary quad belongs to, and its local face (0..5, `hex_faces`)
  std::vector<std::size_t> quad_hex;
  std::vector<std::uint8_t> quad_local_face;

  /// boundary index -> mesh vertex index (increasing mesh index)
  std::vector<std::size_t> vertices;
  /// mesh vertex index -> boundary index, `npos` for interior vertices
  std::vector<std::size_t> boundary_index;

  /// unique boundary edges as mesh vertex pairs (first < second)
  std::vector<std::array<std::size_t, 2>> edges;
  /// true when exactly two boundary quads share the edge
  std::vector<bool> edge_is_manifold;
  /// quad_edges[q][i]: the edge (quads[q][i], quads[q][(i+1)%4])
  std::vector<Quad> quad_edges;
  /// quad_neighbors[q][i]: the quad across edge i of q, npos if the edge is not manifold
  std::vector<Quad> quad_neighbors;

  /// CSR over boundary indices: the boundary quads incident to each boundary vertex
  std::vector<std::size_t> vertex_quad_offsets, vertex_quad_list;
  /// CSR over boundary indices: the boundary edges incident to each boundary vertex
  std::vector<std::size_t> vertex_edge_offsets, vertex_edge_list;

  /// faces shared by more than two hexahedra (invalid input; treated as interior)
  std::size_t number_of_overshared_faces = 0;

  std::size_t number_of_quads() const { return quads.size(); }
  std::size_t number_of_vertices() const { return vertices.size(); }
  std::size_t number_of_edges() const { return edges.size(); }
  bool is_boundary_vertex(std::size_t v) const
  {
    return v < boundary_index.size() && boundary_index[v] != npos;
  }

  /// the other end of edge `e` (mesh indices)
  std::size_t opposite(std::size_t e, std::size_t v) const
  {
    return edges[e][0] == v ? edges[e][1] : edges[e][0];
  }

  /// range [begin, end) into `vertex_quad_list` for boundary vertex `bi`
  std::pair<const std::size_t*, const std::size_t*> quads_of(std::size_t bi) const
  {
    return {vertex_quad_list.data() + vertex_quad_offsets[bi],
            vertex_quad_list.data() + vertex_quad_offsets[bi + 1]};
  }
  /// range [begin, end) into `vertex_edge_list` for boundary vertex `bi`
  std::pair<const std::size_t*, const std::size_t*> edges_of(std::size_t bi) const
  {
    return {vertex_edge_list.data() + vertex_edge_offsets[bi],
            vertex_edge_list.data() + vertex_edge_offsets[bi + 1]};
  }
  /// the quads around the corners of the quads around boundary vertex `bi`
  /// (what a move of that vertex may uncover or cover), sorted, into `out`
  void quads_near(std::size_t bi, std::vector<std::size_t>& out) const
  {
    out.clear();
    const auto around = quads_of(bi);
    for(const std::size_t* q = around.first; q != around.second; ++q)
      for(std::size_t u : quads[*q])
      {
        const auto r = quads_of(boundary_index[u]);
        out.insert(out.end(), r.first, r.second);
      }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  }
};

namespace boundary_detail {

// builds a CSR from (key, value) pairs with keys in [0, n)
inline void build_csr(std::size_t n,
                      const std::vector<std::pair<std::size_t, std::size_t>>& pairs,
                      std::vector<std::size_t>& offsets,
                      std::vector<std::size_t>& list)
{
  offsets.assign(n + 1, 0);
  for(const auto& p : pairs)
    ++offsets[p.first + 1];
  for(std::size_t i = 0; i < n; ++i)
    offsets[i + 1] += offsets[i];
  list.resize(pairs.size());
  std::vector<std::size_t> fill(offsets.begin(), offsets.end() - 1);
  for(const auto& p : pairs)
    list[fill[p.first]++] = p.second;
}

/// the faces of `hexes` that occur once, as quads with their hex and local face
inline void collect_boundary_quads(const std::vector<Hex>& hexes, std::size_t number_of_vertices,
                                   Hex_mesh_boundary& b)
{
  typedef Hex_mesh_boundary::Quad Quad;
  // one flag per face id, each written by its own group only: the groups
  // run in parallel, and the ids come out in increasing order
  enum : char { inner = 0, once = 1, overshared = 2 };
  std::vector<char> kind(6 * hexes.size(), inner);
  for_each_face_group_in_parallel(hexes, number_of_vertices, [&kind](const Quad&, const std::size_t* ids, std::size_t count) {
    if(count == 1) kind[ids[0]] = once;
    else if(count > 2) kind[ids[0]] = overshared;
  });
  std::vector<std::size_t> boundary_face_ids;
  for(std::size_t id = 0; id < kind.size(); ++id)
  {
    if(kind[id] == once) boundary_face_ids.push_back(id);
    else if(kind[id] == overshared) ++b.number_of_overshared_faces;
  }
  const std::size_t nq = boundary_face_ids.size();
  b.quads.resize(nq);
  b.quad_hex.resize(nq);
  b.quad_local_face.resize(nq);
  for(std::size_t q = 0; q < nq; ++q)
  {
    const std::size_t h = boundary_face_ids[q] / 6;
    const int f = int(boundary_face_ids[q] % 6);
    for(int i = 0; i < 4; ++i)
      b.quads[q][i] = hexes[h][hex_faces[f][i]];
    b.quad_hex[q] = h;
    b.quad_local_face[q] = std::uint8_t(f);
  }
}

/// the boundary vertices, in index order, and their boundary indices
inline void number_boundary_vertices(std::size_t number_of_vertices, Hex_mesh_boundary& b)
{
  const std::size_t npos = Hex_mesh_boundary::npos;
  b.boundary_index.assign(number_of_vertices, npos);
  for(const Hex_mesh_boundary::Quad& q : b.quads)
    for(std::size_t v : q)
      b.boundary_index[v] = 0;
  for(std::size_t v = 0; v < number_of_vertices; ++v)
    if(b.boundary_index[v] != npos)
    {
      b.boundary_index[v] = b.vertices.size();
      b.vertices.push_back(v);
    }
}

/// the edges (the 4·nq half-edges sorted by their undirected key), whether
/// each is manifold, the edges and the neighbours of each quad
inline void build_boundary_edges(Hex_mesh_boundary& b)
{
  typedef Hex_mesh_boundary::Quad Quad;
  const std::size_t npos = Hex_mesh_boundary::npos, nq = b.quads.size();
  struct Half_edge
  {
    std::array<std::size_t, 2> key;
    std::size_t id; // 4 * quad + i
    bool operator<(const Half_edge& o) const { return key < o.key || (key == o.key && id < o.id); }
  };
  std::vector<Half_edge> hes(4 * nq);
  for(std::size_t q = 0; q < nq; ++q)
    for(int i = 0; i < 4; ++i)
    {
      std::size_t a = b.quads[q][i], c = b.quads[q][(i + 1) % 4];
      if(c < a)
        std::swap(a, c);
      hes[4 * q + i] = Half_edge{{a, c}, 4 * q + i};
    }
  std::sort(hes.begin(), hes.end());

  b.quad_edges.assign(nq, Quad{npos, npos, npos, npos});
  b.quad_neighbors.assign(nq, Quad{npos, npos, npos, npos});
  for(std::size_t i = 0; i < hes.size();)
  {
    std::size_t j = i + 1;
    while(j < hes.size() && hes[j].key == hes[i].key)
      ++j;
    const std::size_t e = b.edges.size();
    b.edges.push_back(hes[i].key);
    const bool manifold = (j - i == 2);
    b.edge_is_manifold.push_back(manifold);
    for(std::size_t k = i; k < j; ++k)
      b.quad_edges[hes[k].id / 4][hes[k].id % 4] = e;
    if(manifold)
    {
      b.quad_neighbors[hes[i].id / 4][hes[i].id % 4] = hes[i + 1].id / 4;
      b.quad_neighbors[hes[i + 1].id / 4][hes[i + 1].id % 4] = hes[i].id / 4;
    }
    i = j;
  }
}

/// vertex -> quads and vertex -> edges
inline void build_boundary_incidences(Hex_mesh_boundary& b)
{
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  pairs.reserve(4 * b.quads.size());
  for(std::size_t q = 0; q < b.quads.size(); ++q)
    for(int i = 0; i < 4; ++i)
      pairs.emplace_back(b.boundary_index[b.quads[q][i]], q);
  build_csr(b.vertices.size(), pairs, b.vertex_quad_offsets, b.vertex_quad_list);
  pairs.clear();
  for(std::size_t e = 0; e < b.edges.size(); ++e)
  {
    pairs.emplace_back(b.boundary_index[b.edges[e][0]], e);
    pairs.emplace_back(b.boundary_index[b.edges[e][1]], e);
  }
  build_csr(b.vertices.size(), pairs, b.vertex_edge_offsets, b.vertex_edge_list);
}

} // namespace boundary_detail

/// Extracts the boundary of the hex mesh given by `hexes` over `number_of_vertices` vertices.
inline Hex_mesh_boundary extract_boundary(const std::vector<Hex>& hexes,
                                          std::size_t number_of_vertices)
{
  Hex_mesh_boundary b;
  boundary_detail::collect_boundary_quads(hexes, number_of_vertices, b); // faces occurring once (face_groups.h)
  boundary_detail::number_boundary_vertices(number_of_vertices, b);
  boundary_detail::build_boundary_edges(b);
  boundary_detail::build_boundary_incidences(b);
  return b;
}

inline Hex_mesh_boundary extract_boundary(const Hex_mesh_arrays& m)
{
  return extract_boundary(m.hexes, m.number_of_vertices());
}

/// The number of hexes around each boundary edge (capped at 255), indexed
/// as `b.edges`: 2 on a smooth part of a feature-aligned mesh's boundary,
/// 1 along a convex crease, 3 and more along a concave one.
inline std::vector<unsigned char> count_boundary_edge_hexes(const Hex_mesh_boundary& b, const std::vector<Hex>& hexes)
{
  std::vector<unsigned char> count(b.edges.size(), 0);
  for(const Hex& h : hexes)
    for(const auto& he : hex_edges)
    {
      const std::size_t u = h[he[0]], v = h[he[1]];
      if(!b.is_boundary_vertex(u) || !b.is_boundary_vertex(v)) continue;
      const auto er = b.edges_of(b.boundary_index[u]);
      for(const std::size_t* e = er.first; e != er.second; ++e)
        if(b.opposite(*e, u) == v)
        {
          if(count[*e] < 255) ++count[*e];
          break;
        }
    }
  return count;
}

// ------------------------------------------------------------ geometry

/// Unit normal of a (possibly non-planar) quad: the cross product of its
/// diagonals, which is the area-weighted mean normal of the bilinear patch.
/// Zero vector when the quad is degenerate.
inline Vec3 quad_normal(const std::vector<Vec3>& points, const Hex_mesh_boundary::Quad& q)
{
  const Vec3 n = cross(points[q[2]] - points[q[0]], points[q[3]] - points[q[1]]);
  const double l = norm(n);
  return l > 0. ? (1. / l) * n : Vec3{0., 0., 0.};
}

/// Mean length of the boundary edges.
inline double mean_boundary_edge_length(const Hex_mesh_boundary& b, const std::vector<Vec3>& points)
{
  if(b.edges.empty())
    return 0.;
  double s = 0.;
  for(const auto& e : b.edges)
    s += norm(points[e[1]] - points[e[0]]);
  return s / double(b.edges.size());
}

/// How a quad is cut into triangles.
enum class Quad_split
{
  /// 2 triangles along the diagonal (q[0], q[2]): a fixed rule, so that two
  /// meshes with the same connectivity are triangulated alike (the fan from
  /// the first vertex that polygon-file importers use)
  diagonal_02,
  /// 2 triangles along the shorter diagonal
  shorter_diagonal,
  /// 4 overlapping triangles (both splits), as in Section 3.1 of the paper:
  /// a projection target that does not depend on a diagonal choice
  both_diagonals
};

/// Triangulates the boundary quads into a soup over the boundary vertices:
/// `soup_points[i]` is the position of boundary vertex `i`, the triangles
/// index into it and keep the quads' (outward) orientation.
inline void triangulate_boundary(const Hex_mesh_boundary& b,
                                 const std::vector<Vec3>& points,
                                 Quad_split split,
                                 std::vector<Vec3>& soup_points,
                                 std::vector<Tri>& soup_triangles)
{
  soup_points.resize(b.vertices.size());
  for(std::size_t i = 0; i < b.vertices.size(); ++i)
    soup_points[i] = points[b.vertices[i]];
  soup_triangles.clear();
  soup_triangles.reserve((split == Quad_split::both_diagonals ? 4 : 2) * b.quads.size());
  for(const auto& q : b.quads)
  {
    const std::size_t v[4] = {b.boundary_index[q[0]], b.boundary_index[q[1]],
                              b.boundary_index[q[2]], b.boundary_index[q[3]]};
    const bool split02 = split != Quad_split::shorter_diagonal ||
      squared_norm(points[q[2]] - points[q[0]]) <= squared_norm(points[q[3]] - points[q[1]]);
    const bool split13 = split == Quad_split::both_diagonals || !split02;
    if(split02)
    {
      soup_triangles.push_back(Tri{v[0], v[1], v[2]});
      soup_triangles.push_back(Tri{v[0], v[2], v[3]});
    }
    if(split13)
    {
      soup_triangles.push_back(Tri{v[1], v[2], v[3]});
      soup_triangles.push_back(Tri{v[1], v[3], v[0]});
    }
  }
}

/// Builds a `Surface_mesh` from a triangle soup. The soup is added face by
/// face when it is already a consistently oriented combinatorial manifold
/// (the usual case for the boundary of a hex mesh); otherwise
/// `orient_polygon_soup` first duplicates non-manifold vertices and
/// reorients what it must. Degenerate triangles (a repeated index, from
/// collapsed hexes) are skipped. Returns whether face i of `out` is
/// triangle i of the soup, for every i (none skipped, no repair).
template <class Point_3>
bool soup_to_surface_mesh(const std::vector<Vec3>& soup_points,
                          const std::vector<Tri>& soup_triangles,
                          CGAL::Surface_mesh<Point_3>& out)
{
  typedef CGAL::Surface_mesh<Point_3> SM;
  typedef typename SM::Vertex_index VI;
  out.clear();
  std::vector<VI> vi;
  vi.reserve(soup_points.size());
  for(const Vec3& p : soup_points)
    vi.push_back(out.add_vertex(Point_3(p[0], p[1], p[2])));
  bool ok = true, in_order = true;
  for(const Tri& t : soup_triangles)
  {
    if(t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
    {
      in_order = false;
      continue;
    }
    if(out.add_face(vi[t[0]], vi[t[1]], vi[t[2]]) == SM::null_face())
    {
      ok = false;
      break;
    }
  }
  if(ok)
    return in_order;

  out.clear();
  std::vector<Point_3> pts;
  pts.reserve(soup_points.size());
  for(const Vec3& p : soup_points)
    pts.push_back(Point_3(p[0], p[1], p[2]));
  std::vector<std::vector<std::size_t>> polys;
  polys.reserve(soup_triangles.size());
  for(const Tri& t : soup_triangles)
    if(t[0] != t[1] && t[1] != t[2] && t[2] != t[0])
      polys.push_back({t[0], t[1], t[2]});
  CGAL::Polygon_mesh_processing::orient_polygon_soup(pts, polys);
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(pts, polys, out);
  return false;
}

/// The boundary of a hex mesh, each quad cut in 2 triangles (`split` must
/// not be `both_diagonals`, which is no manifold), as a `Surface_mesh`.
/// Returns whether its faces are the quads' triangles in order (faces 2q
/// and 2q + 1 are quad q's with `diagonal_02`; see `soup_to_surface_mesh`).
template <class Point_3>
bool boundary_to_surface_mesh(const Hex_mesh_boundary& b,
                              const std::vector<Vec3>& points,
                              CGAL::Surface_mesh<Point_3>& out,
                              Quad_split split = Quad_split::diagonal_02)
{
  CGAL_precondition(split != Quad_split::both_diagonals);
  std::vector<Vec3> sp;
  std::vector<Tri> st;
  triangulate_boundary(b, points, split, sp, st);
  return soup_to_surface_mesh(sp, st, out);
}

/// Copies a face graph into a triangle soup of `Vec3`, reading positions
/// through `vpm` with `gt`; a face of degree > 3 is cut as a fan from its
/// first vertex (callers triangulate properly beforehand when it matters).
template <class FaceGraph, class VertexPointMap, class GeomTraits>
void face_graph_to_triangle_soup(const FaceGraph& g, VertexPointMap vpm, const GeomTraits& gt,
                                 std::vector<Vec3>& soup_points,
                                 std::vector<Tri>& soup_triangles)
{
  typedef boost::graph_traits<FaceGraph> GT;
  typedef typename GT::vertex_descriptor vertex_descriptor;
  typedef typename GT::face_descriptor face_descriptor;
  soup_points.clear();
  soup_triangles.clear();
  boost::unordered_map<vertex_descriptor, std::size_t> index;
  for(vertex_descriptor v : vertices(g))
  {
    index.emplace(v, soup_points.size());
    soup_points.push_back(to_vec3(get(vpm, v), gt));
  }
  std::vector<std::size_t> f;
  for(face_descriptor fd : faces(g))
  {
    f.clear();
    for(vertex_descriptor v : vertices_around_face(halfedge(fd, g), g))
      f.push_back(index.at(v));
    for(std::size_t i = 1; i + 1 < f.size(); ++i)
      soup_triangles.push_back(Tri{f[0], f[i], f[i + 1]});
  }
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_MESH_HEX_MESH_BOUNDARY_H
