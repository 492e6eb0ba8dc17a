// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Package: Hexahedral_mesh_optimization

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_MESH_HEX_MESH_TOPOLOGY_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_MESH_HEX_MESH_TOPOLOGY_H

// Connectivity the optimiser needs, computed once from the hex -> 8 vertex
// table: vertex -> hexes, unique edges, the edge valence (number of hexes
// around an edge), boundary faces / edges / vertices, and, for every vertex,
// the hexes around each of its edges in cyclic (or, on the boundary, path)
// order. The last one is what the ideal angles of the unified edge-angle
// energy (Eq. 5 of the paper) are derived from: see `Ideal_angles.h`.

#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_boundary.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/scaled_jacobian.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

/// key of an unordered vertex pair
inline std::uint64_t edge_key(std::size_t a, std::size_t b)
{
  if(a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint64_t>(b);
}


class Hex_mesh_topology
{
public:
  /// (hex, local corner) incidence
  struct Corner { std::size_t hex; int local; };

  explicit Hex_mesh_topology(const Hex_mesh_arrays& m)
    : m_nv(m.points.size()), m_hexes(m.hexes)
  {
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
  std::size_t hex_edge(std::size_t h, int k) const { return m_hex_edges[h][k]; }
  /// edge id between two vertices known to be adjacent
  std::size_t edge_id(std::size_t a, std::size_t b) const { return m_edge_ids.at(edge_key(a, b)); }
  /// number of hexes around edge e
  int edge_valence(std::size_t e) const { return m_edge_valence[e]; }

  bool is_boundary_vertex(std::size_t v) const { return m_boundary_vertex[v] != 0; }
  bool is_boundary_edge(std::size_t e) const { return m_boundary_edge[e] != 0; }
  /// boundary quads, oriented outward for positively oriented hexes
  const std::vector<std::array<std::size_t, 4> >& boundary_faces() const { return m_boundary_faces; }
  /// for each edge, the boundary faces containing it (two for a boundary edge of a manifold boundary)
  const std::vector<std::size_t>& boundary_vertices() const { return m_boundary_vertices; }

  /// the boundary faces around boundary edge e (indices into boundary_faces())
  std::vector<std::size_t> boundary_faces_of_edge(std::size_t e) const
  {
    std::vector<std::size_t> r;
    auto it = m_edge_bfaces.find(e);
    if(it != m_edge_bfaces.end()) r = it->second;
    return r;
  }

  /// The local corner index of vertex v in hex h, or -1.
  int local_index(std::size_t h, std::size_t v) const
  {
    for(int i = 0; i < 8; ++i) if(m_hexes[h][i] == v) return i;
    return -1;
  }

private:
  void build_vertex_hexes()
  {
    m_vh_off.assign(m_nv + 1, 0);
    for(const Hex& h : m_hexes) for(std::size_t v : h) ++m_vh_off[v + 1];
    for(std::size_t i = 0; i < m_nv; ++i) m_vh_off[i + 1] += m_vh_off[i];
    m_vh.resize(m_vh_off[m_nv]);
    std::vector<std::size_t> fill(m_vh_off.begin(), m_vh_off.end() - 1);
    for(std::size_t h = 0; h < m_hexes.size(); ++h)
      for(int i = 0; i < 8; ++i)
        m_vh[fill[m_hexes[h][i]]++] = Corner{h, i};
  }

  void build_edges()
  {
    m_hex_edges.resize(m_hexes.size());
    m_edge_ids.reserve(m_hexes.size() * 4);
    for(std::size_t h = 0; h < m_hexes.size(); ++h)
      for(int k = 0; k < 12; ++k)
      {
        const std::size_t a = m_hexes[h][hex_edges[k][0]], b = m_hexes[h][hex_edges[k][1]];
        auto ins = m_edge_ids.emplace(edge_key(a, b), m_edges.size());
        if(ins.second)
        {
          m_edges.push_back({(std::min)(a, b), (std::max)(a, b)});
          m_edge_valence.push_back(0);
        }
        m_hex_edges[h][k] = ins.first->second;
        ++m_edge_valence[ins.first->second];
      }
  }

  void build_boundary()
  {
    // the faces that occur once: the boundary structure's own face matching
    // (sorted face keys; a hash map of 6 faces per hex cost 1.5 s at 1M hexes)
    m_boundary_faces = extract_boundary(m_hexes, m_nv).quads;
    // deterministic order, independent of the hexes' order
    std::sort(m_boundary_faces.begin(), m_boundary_faces.end());
    m_boundary_vertex.assign(m_nv, 0);
    m_boundary_edge.assign(m_edges.size(), 0);
    m_edge_bfaces.clear();
    for(std::size_t fid = 0; fid < m_boundary_faces.size(); ++fid)
      for(int i = 0; i < 4; ++i)
      {
        const std::array<std::size_t, 4>& q = m_boundary_faces[fid];
        m_boundary_vertex[q[i]] = 1;
        const std::size_t e = m_edge_ids[edge_key(q[i], q[(i + 1) % 4])];
        m_boundary_edge[e] = 1;
        m_edge_bfaces[e].push_back(fid);
      }
    for(std::size_t v = 0; v < m_nv; ++v)
      if(m_boundary_vertex[v]) m_boundary_vertices.push_back(v);
  }

  std::size_t m_nv;
  std::vector<Hex> m_hexes;
  std::vector<std::size_t> m_vh_off;
  std::vector<Corner> m_vh;
  std::vector<std::array<std::size_t, 2> > m_edges;
  std::vector<int> m_edge_valence;
  std::unordered_map<std::uint64_t, std::size_t> m_edge_ids;
  std::vector<std::array<std::size_t, 12> > m_hex_edges;
  std::vector<char> m_boundary_vertex, m_boundary_edge;
  std::vector<std::array<std::size_t, 4> > m_boundary_faces;
  std::unordered_map<std::size_t, std::vector<std::size_t> > m_edge_bfaces;
  std::vector<std::size_t> m_boundary_vertices;
};

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_MESH_HEX_MESH_TOPOLOGY_H
