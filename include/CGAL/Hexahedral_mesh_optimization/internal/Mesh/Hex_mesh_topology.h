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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_MESH_HEX_MESH_TOPOLOGY_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_MESH_HEX_MESH_TOPOLOGY_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Connectivity the optimiser needs, computed once from the hex -> 8 vertex
// table: vertex -> hexes, unique edges, the edge valence (number of hexes
// around an edge), boundary faces / edges / vertices, and, for every vertex,
// the hexes around each of its edges in cyclic (or, on the boundary, path)
// order. The last one is what the ideal angles of the unified edge-angle
// energy (Eq. 5 of the paper) are derived from: see `Ideal_angles.h`.

#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_boundary.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/parallel_for_each_index.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/scaled_jacobian.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <utility>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {



class Hex_mesh_topology
{
public:
  /// (hex, local corner) incidence; 32-bit, half the memory of 64-bit
  /// indices (filling fresh memory is much of the set-up)
  struct Corner { std::uint32_t hex; std::int32_t local; };

  /// \pre fewer than 2^32 vertices and 2^28 hexes (12 edges each: the 32-bit indices inside)
  explicit Hex_mesh_topology(const Hex_mesh_arrays& m)
    : m_nv(m.points.size()), m_hexes(m.hexes), m_constrained(m.constrained)
  {
    if(m_nv >= (std::size_t(1) << 32) || m_hexes.size() >= (std::size_t(1) << 28))
      throw std::length_error("Hex_mesh_topology: more than 2^32 vertices or 2^28 hexahedra");
    build_vertex_hexes();
    build_edges();
    build_boundary();
  }

  std::size_t number_of_vertices() const { return m_nv; }
  std::size_t number_of_hexes() const { return m_hexes.size(); }
  std::size_t number_of_edges() const { return m_edges.size(); }
  const std::vector<Hex>& hexes() const { return m_hexes; }

  /// hexes (with the local corner index) incident to vertex v
  const Corner* vertex_corners_begin(std::size_t v) const { return m_vh.data() + m_vh_off[v]; }
  const Corner* vertex_corners_end(std::size_t v) const { return m_vh.data() + m_vh_off[v + 1]; }

  const std::array<std::size_t, 2>& edge(std::size_t e) const { return m_edges[e]; }
  /// edge id of local edge k (index into hex_edges) of hex h
  std::size_t hex_edge(std::size_t h, int k) const { return std::size_t(m_hex_edges[h][k]); }
  /// edge id between two vertices known to be adjacent
  std::size_t edge_id(std::size_t a, std::size_t b) const
  {
    const std::size_t k = sorted_edge(a, b);
    CGAL_precondition(k != std::size_t(-1));
    return std::size_t(m_edge_of_sorted[k]);
  }
  /// number of hexes around edge e
  int edge_valence(std::size_t e) const { return m_edge_valence[e]; }

  bool is_boundary_vertex(std::size_t v) const { return m_boundary_vertex[v] != 0; }
  /// whether v may not move (`Hex_mesh_arrays::constrained`, the user's
  /// `vertex_is_constrained_map`): every stage asks this
  bool is_constrained(std::size_t v) const { return !m_constrained.empty() && m_constrained[v] != 0; }
  bool has_constrained_vertices() const { return !m_constrained.empty(); }
  bool is_boundary_edge(std::size_t e) const { return m_boundary_edge[e] != 0; }
  /// boundary quads, oriented outward for positively oriented hexes, sorted
  const std::vector<std::array<std::size_t, 4> >& boundary_faces() const { return m_boundary_faces; }
  /// the boundary as `extract_boundary` gives it (the same quads, in its
  /// order, with their vertices, edges and neighbours): extracted once, for
  /// the target surface and the guards
  const Hex_mesh_boundary& boundary() const { return m_boundary; }
  /// the boundary vertices, in index order
  const std::vector<std::size_t>& boundary_vertices() const { return m_boundary_vertices; }

  /// the boundary faces around vertex v (indices into boundary_faces(); none
  /// for an interior vertex)
  const std::size_t* vertex_boundary_faces_begin(std::size_t v) const { return m_vbf.data() + m_vbf_off[v]; }
  const std::size_t* vertex_boundary_faces_end(std::size_t v) const { return m_vbf.data() + m_vbf_off[v + 1]; }

  /// Appends to `out` the vertices of the boundary faces around the
  /// vertices of the boundary faces around v (two rings of faces; with
  /// repeats): what a surface test of a move of v reads.
  void append_two_ring_boundary_vertices(std::size_t v, std::vector<std::size_t>& out) const
  {
    for(const std::size_t* f = vertex_boundary_faces_begin(v); f != vertex_boundary_faces_end(v); ++f)
      for(std::size_t x : m_boundary_faces[*f])
        for(const std::size_t* g = vertex_boundary_faces_begin(x); g != vertex_boundary_faces_end(x); ++g)
          out.insert(out.end(), m_boundary_faces[*g].begin(), m_boundary_faces[*g].end());
  }

  /// the boundary faces around boundary edge e (indices into boundary_faces())
  std::vector<std::size_t> boundary_faces_of_edge(std::size_t e) const
  {
    // the boundary faces around one end in which the other end follows or
    // precedes it
    std::vector<std::size_t> r;
    const std::size_t a = m_edges[e][0], b = m_edges[e][1];
    for(const std::size_t* f = vertex_boundary_faces_begin(a); f != vertex_boundary_faces_end(a); ++f)
    {
      const std::array<std::size_t, 4>& q = m_boundary_faces[*f];
      for(int i = 0; i < 4; ++i)
        if(q[i] == a && (q[(i + 1) % 4] == b || q[(i + 3) % 4] == b)) { r.push_back(*f); break; }
    }
    return r;
  }

  /// The local corner index of vertex v in hex h, or -1.
  int local_index(std::size_t h, std::size_t v) const
  {
    for(int i = 0; i < 8; ++i) if(m_hexes[h][i] == v) return i;
    return -1;
  }

private:
  // 32-bit where there is one entry per edge or per hex edge (see `Corner`)
  typedef std::uint32_t Index;

  /// The incidence of vertices in `cells` (arrays of vertex indices), in
  /// compressed rows: vertex v's entries are list[off[v] .. off[v + 1]),
  /// entry(cell, local index) each, in cell order.
  template <class Cell, class Entry, class Make>
  void build_incidence(const std::vector<Cell>& cells, std::vector<std::size_t>& off, std::vector<Entry>& list,
                       Make entry) const
  {
    off.assign(m_nv + 1, 0);
    for(const Cell& c : cells) for(std::size_t v : c) ++off[v + 1];
    for(std::size_t v = 0; v < m_nv; ++v) off[v + 1] += off[v];
    list.resize(off[m_nv]);
    std::vector<std::size_t> fill(off.begin(), off.end() - 1);
    for(std::size_t c = 0; c < cells.size(); ++c)
      for(int i = 0; i < int(cells[c].size()); ++i) list[fill[cells[c][i]]++] = entry(c, i);
  }

  void build_vertex_hexes()
  {
    build_incidence(m_hexes, m_vh_off, m_vh, [](std::size_t h, int i) { return Corner{std::uint32_t(h), i}; });
  }

  // The edges, without hashing (a hash map of the 12 edges of every hex
  // dominates the set-up of a large mesh): the neighbours above each
  // vertex, sorted (`m_upper_off`, `m_upper`), give every edge a place
  // (a, b > a) -> its index in that list; the edge ids are then handed out in
  // the order the hexes first meet the edges. The first meeting of a place
  // is the least 12 h + k over the hex edges (h, k) there; each hex edge that
  // is a first meeting brings a new id, numbered by a prefix sum over the
  // hexes. Every pass runs over vertices or hexes in parallel and writes only
  // its own entries (or an atomic minimum): the ids do not depend on the
  // threads.
  void build_edges()
  {
    build_upper_neighbours();
    const std::vector<std::atomic<Index> > first = first_meetings();
    number_edges(first);
    count_edge_valences();
  }

  static constexpr std::size_t edge_pass_block = 4096;

  // f(v, scratch) for every vertex, by blocks of vertices on the threads,
  // with one scratch vector per block
  template <class F>
  void for_each_vertex_block(F f) const
  {
    const std::size_t block = edge_pass_block;
    parallel_for_each_index((m_nv + block - 1) / block, [&](std::size_t b) {
      std::vector<Index> scratch;
      for(std::size_t v = b * block; v < (std::min)(m_nv, (b + 1) * block); ++v) f(v, scratch);
    });
  }

  // the neighbours above v, sorted, in `scratch`
  void upper_neighbours(std::size_t v, std::vector<Index>& scratch) const
  {
    scratch.clear();
    for(const Corner* c = vertex_corners_begin(v); c != vertex_corners_end(v); ++c)
      for(int k = 0; k < 3; ++k)
      {
        const std::size_t w = m_hexes[c->hex][hex_corner_edges[c->local][k]];
        if(w > v) scratch.push_back(Index(w));
      }
    std::sort(scratch.begin(), scratch.end());
    scratch.erase(std::unique(scratch.begin(), scratch.end()), scratch.end());
  }

  // `m_upper_off`, `m_upper`: the places of the edges
  void build_upper_neighbours()
  {
    m_upper_off.assign(m_nv + 1, 0);
    for_each_vertex_block([&](std::size_t v, std::vector<Index>& scratch) {
      upper_neighbours(v, scratch);
      m_upper_off[v + 1] = scratch.size();
    });
    for(std::size_t v = 0; v < m_nv; ++v) m_upper_off[v + 1] += m_upper_off[v];
    m_upper.resize(m_upper_off[m_nv]);
    for_each_vertex_block([&](std::size_t v, std::vector<Index>& scratch) {
      upper_neighbours(v, scratch);
      std::copy(scratch.begin(), scratch.end(), m_upper.begin() + std::ptrdiff_t(m_upper_off[v]));
    });
  }

  // the place of every hex edge (in `m_hex_edges` for now), and the first
  // meeting 12 h + k of every place
  std::vector<std::atomic<Index> > first_meetings()
  {
    const std::size_t ne = m_upper_off[m_nv], nh = m_hexes.size();
    m_hex_edges.resize(nh);
    std::vector<std::atomic<Index> > first(ne);
    parallel_for_each_index(ne, [&](std::size_t p) { first[p].store(Index(-1), std::memory_order_relaxed); },
                            edge_pass_block);
    parallel_for_each_index(nh, [&](std::size_t h) {
      for(int k = 0; k < 12; ++k)
      {
        const std::size_t place = sorted_edge(m_hexes[h][hex_edges[k][0]], m_hexes[h][hex_edges[k][1]]);
        m_hex_edges[h][k] = Index(place);
        const Index meeting = Index(12 * h + std::size_t(k));
        Index now = first[place].load(std::memory_order_relaxed);
        while(meeting < now && !first[place].compare_exchange_weak(now, meeting, std::memory_order_relaxed)) {}
      }
    }, edge_pass_block);
    return first;
  }

  // the edge ids (`m_edges`, `m_edge_of_sorted`), the new edges of the hexes
  // before h first, and `m_hex_edges` turned from places into ids
  void number_edges(const std::vector<std::atomic<Index> >& first)
  {
    const std::size_t ne = first.size(), nh = m_hexes.size();
    auto is_first = [&](std::size_t h, int k) {
      return first[m_hex_edges[h][k]].load(std::memory_order_relaxed) == Index(12 * h + std::size_t(k));
    };
    std::vector<Index> new_before(nh + 1, 0);
    parallel_for_each_index(nh, [&](std::size_t h) {
      Index n = 0;
      for(int k = 0; k < 12; ++k) n += Index(is_first(h, k));
      new_before[h + 1] = n;
    }, edge_pass_block);
    for(std::size_t h = 0; h < nh; ++h) new_before[h + 1] += new_before[h];
    m_edges.resize(ne);
    m_edge_of_sorted.resize(ne);
    parallel_for_each_index(nh, [&](std::size_t h) {
      Index id = new_before[h];
      for(int k = 0; k < 12; ++k)
        if(is_first(h, k))
        {
          const std::size_t a = m_hexes[h][hex_edges[k][0]], b = m_hexes[h][hex_edges[k][1]];
          m_edge_of_sorted[m_hex_edges[h][k]] = id;
          m_edges[id] = {(std::min)(a, b), (std::max)(a, b)};
          ++id;
        }
    }, edge_pass_block);
    parallel_for_each_index(nh, [&](std::size_t h) {
      for(int k = 0; k < 12; ++k) m_hex_edges[h][k] = m_edge_of_sorted[m_hex_edges[h][k]];
    }, edge_pass_block);
  }

  // the valences, from the lower end of each edge (one task writes them)
  void count_edge_valences()
  {
    m_edge_valence.assign(m_edges.size(), 0);
    for_each_vertex_block([&](std::size_t v, std::vector<Index>&) {
      for(const Corner* c = vertex_corners_begin(v); c != vertex_corners_end(v); ++c)
        for(int k = 0; k < 3; ++k)
        {
          const std::size_t w = m_hexes[c->hex][hex_corner_edges[c->local][k]];
          if(w > v) ++m_edge_valence[m_edge_of_sorted[sorted_edge(v, w)]];
        }
    });
  }

  // the place of edge (a, b) among the neighbours above min(a, b), or -1
  std::size_t sorted_edge(std::size_t a, std::size_t b) const
  {
    if(a > b) std::swap(a, b);
    const auto first = m_upper.begin() + std::ptrdiff_t(m_upper_off[a]),
               last = m_upper.begin() + std::ptrdiff_t(m_upper_off[a + 1]);
    const auto it = std::lower_bound(first, last, b);
    return it != last && *it == Index(b) ? std::size_t(it - m_upper.begin()) : std::size_t(-1);
  }

  void build_boundary()
  {
    // the faces that occur once: the boundary structure's own face matching
    // (sorted face keys, cheaper than a hash map of 6 faces per hex)
    m_boundary = extract_boundary(m_hexes, m_nv);
    m_boundary_faces = m_boundary.quads;
    // deterministic order, independent of the hexes' order
    std::sort(m_boundary_faces.begin(), m_boundary_faces.end());
    m_boundary_vertex.assign(m_nv, 0);
    m_boundary_edge.assign(m_edges.size(), 0);
    for(std::size_t fid = 0; fid < m_boundary_faces.size(); ++fid)
      for(int i = 0; i < 4; ++i)
      {
        const std::array<std::size_t, 4>& q = m_boundary_faces[fid];
        m_boundary_vertex[q[i]] = 1;
        const std::size_t e = edge_id(q[i], q[(i + 1) % 4]);
        m_boundary_edge[e] = 1;
      }
    for(std::size_t v = 0; v < m_nv; ++v)
      if(m_boundary_vertex[v]) m_boundary_vertices.push_back(v);
    build_incidence(m_boundary_faces, m_vbf_off, m_vbf, [](std::size_t f, int) { return f; });
  }

  std::size_t m_nv;
  std::vector<Hex> m_hexes;
  std::vector<unsigned char> m_constrained;
  std::vector<std::size_t> m_vh_off;
  std::vector<Corner> m_vh;
  std::vector<std::array<std::size_t, 2> > m_edges;
  std::vector<int> m_edge_valence;
  std::vector<std::size_t> m_upper_off; // see build_edges
  std::vector<Index> m_upper, m_edge_of_sorted;
  std::vector<std::array<Index, 12> > m_hex_edges;
  std::vector<char> m_boundary_vertex, m_boundary_edge;
  Hex_mesh_boundary m_boundary;
  std::vector<std::array<std::size_t, 4> > m_boundary_faces;
  std::vector<std::size_t> m_boundary_vertices;
  std::vector<std::size_t> m_vbf_off, m_vbf; // boundary faces around each vertex
};

/// The minimum scaled Jacobian of the hexes around vertex `v` with `v` at
/// `x` (the other vertices at `points`): the local test of every one-vertex
/// move that must keep an SJ floor (max-min smoothing, snaps, projections).
/// A NaN value (a zero-length edge) is returned as it is, so that every
/// comparison with a floor fails (std::min would drop it).
inline double min_scaled_jacobian_around(const Hex_mesh_topology& topo, const std::vector<Vec3>& points,
                                         std::size_t v, const Vec3& x)
{
  double m = 2.;
  for(auto c = topo.vertex_corners_begin(v); c != topo.vertex_corners_end(v); ++c)
  {
    std::array<Vec3, 8> p;
    for(int i = 0; i < 8; ++i) p[i] = points[topo.hexes()[c->hex][i]];
    p[c->local] = x;
    const double sj = scaled_jacobian(p);
    if(std::isnan(sj)) return sj;
    m = (std::min)(m, sj);
  }
  return m;
}

/// whether the hexes around `v`, with `v` at `x`, keep a scaled Jacobian
/// at or above `floor` and above 0 (false on NaN, as a zero-length edge gives)
inline bool keeps_sj_floor_around(const Hex_mesh_topology& topo, const std::vector<Vec3>& points, std::size_t v,
                                  const Vec3& x, double floor)
{
  const double m = min_scaled_jacobian_around(topo, points, v, x);
  return m >= floor && m > 0.;
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_MESH_HEX_MESH_TOPOLOGY_H
