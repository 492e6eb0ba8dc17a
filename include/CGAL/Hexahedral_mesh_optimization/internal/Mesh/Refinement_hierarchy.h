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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_MESH_REFINEMENT_HIERARCHY_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_MESH_REFINEMENT_HIERARCHY_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The 1→8 refinement of a hex mesh (every hex split by its edge midpoints,
// face centres and centre) and its inverse: recognising, from the
// connectivity alone, that a mesh is such a refinement, and the coarse mesh
// it refines. A refined mesh's vertices are of four kinds, the dimension d of
// the coarse entity they stand for: 0 a coarse corner, 1 an edge midpoint,
// 2 a face centre, 3 a cell centre. In each child hex the coarse corner sits
// at one local corner c, and local corner q is of kind |bits(q) xor
// bits(c)| (bits = the corner's (x, y, z) in the hex's own frame): one
// choice of c in a seed hex fixes the kinds of its vertices, and across a
// shared face they fix the neighbour's c. A labelling that covers every hex
// without contradiction, with 8 hexes around every cell centre, gives the
// coarse mesh: the corners of the 8 children around each cell centre.
// Used by the pipeline's coarse-level start (`coarse_level_start` in
// improve_hex_mesh_quality.h, Coarse_level_start.h says why).

#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/scaled_jacobian.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

namespace refinement_detail {

/// the (x, y, z) bits x + 2y + 4z of the local corners, MEDIT/VTK order (0-3
/// the bottom face, q + 4 above q); the permutation is its own inverse
constexpr int corner_bits[8] = {0, 1, 3, 2, 4, 5, 7, 6};

inline int bit_count(int b) { return (b & 1) + ((b >> 1) & 1) + ((b >> 2) & 1); }

/// the kind of local corner q in a child whose coarse corner is local corner c
inline int kind_of_corner(int q, int c) { return bit_count(corner_bits[q] ^ corner_bits[c]); }

struct Index_array_hash
{
  template <std::size_t N>
  std::size_t operator()(const std::array<std::size_t, N>& a) const
  {
    std::uint64_t h = 0;
    for(std::size_t v : a)
    {
      h = (h ^ std::uint64_t(v)) * 0x9e3779b97f4a7c15ull;
      h ^= h >> 29;
    }
    return std::size_t(h);
  }
};

} // namespace refinement_detail

/// Every hex split into 8 by its edge midpoints, face centres and centre (the
/// images of the parameters 0, 1/2, 1 under its trilinear map), each child in
/// its parent's frame, so orientation is kept. The new vertices shared by
/// several hexes are made once: edge midpoints keyed by the sorted vertex
/// pair, face centres by the sorted 4-tuple. The input's points keep their
/// indices.
inline Hex_mesh_arrays refine_1_to_8(const Hex_mesh_arrays& in)
{
  using refinement_detail::corner_bits;
  Hex_mesh_arrays out;
  out.points = in.points;
  out.hexes.reserve(8 * in.hexes.size());
  std::unordered_map<std::array<std::size_t, 2>, std::size_t, refinement_detail::Index_array_hash> edge_midpoint;
  std::unordered_map<std::array<std::size_t, 4>, std::size_t, refinement_detail::Index_array_hash> face_centre;
  edge_midpoint.reserve(4 * in.hexes.size());
  face_centre.reserve(4 * in.hexes.size());
  const auto bit = [](int q, int t) { return (corner_bits[q] >> t) & 1; };
  for(const Hex& h : in.hexes)
  {
    std::size_t node[3][3][3]; // lattice (0, 1/2, 1)^3 of the hex's frame
    for(int a = 0; a < 3; ++a)
      for(int b = 0; b < 3; ++b)
        for(int c = 0; c < 3; ++c)
        {
          const int abc[3] = {a, b, c};
          std::array<std::size_t, 8> corners;
          std::size_t count = 0;
          for(int q = 0; q < 8; ++q)
          {
            bool in_span = true;
            for(int t = 0; t < 3; ++t)
              if(abc[t] != 1 && abc[t] != 2 * bit(q, t)) in_span = false;
            if(in_span) corners[count++] = h[q];
          }
          const auto new_point = [&]() {
            Vec3 s{0., 0., 0.};
            for(std::size_t q = 0; q < count; ++q)
              for(int t = 0; t < 3; ++t) s[t] += in.points[corners[q]][t];
            out.points.push_back(Vec3{s[0] / double(count), s[1] / double(count), s[2] / double(count)});
            return out.points.size() - 1;
          };
          std::size_t& v = node[a][b][c];
          if(count == 1)
            v = corners[0];
          else if(count == 2)
          {
            const std::array<std::size_t, 2> key = {{(std::min)(corners[0], corners[1]), (std::max)(corners[0], corners[1])}};
            const auto it = edge_midpoint.find(key);
            v = it != edge_midpoint.end() ? it->second : (edge_midpoint[key] = new_point());
          }
          else if(count == 4)
          {
            std::array<std::size_t, 4> key = {{corners[0], corners[1], corners[2], corners[3]}};
            std::sort(key.begin(), key.end());
            const auto it = face_centre.find(key);
            v = it != face_centre.end() ? it->second : (face_centre[key] = new_point());
          }
          else
            v = new_point();
        }
    for(int a = 0; a < 2; ++a)
      for(int b = 0; b < 2; ++b)
        for(int c = 0; c < 2; ++c)
        {
          Hex child;
          for(int q = 0; q < 8; ++q) child[q] = node[a + bit(q, 0)][b + bit(q, 1)][c + bit(q, 2)];
          out.hexes.push_back(child);
        }
  }
  return out;
}

/// One level of a recognised 1→8 refinement: the coarse mesh and how a
/// field on its vertices is carried to the fine ones (`prolongate`).
struct Refinement_level
{
  Hex_mesh_arrays coarse;
  /// fine index of each coarse vertex (the fine vertices of kind 0, in increasing order)
  std::vector<std::size_t> coarse_to_fine;
  /// the fine vertices of kind 1, 2, 3, each with its neighbours of the kind
  /// below (2, 4 or 6 of them, sorted): `parents[parent_offsets[i] ..
  /// parent_offsets[i + 1])` for `children[i]`; kinds in increasing order
  std::vector<std::size_t> children;
  std::vector<std::size_t> parent_offsets;
  std::vector<std::size_t> parents;
  std::size_t number_of_fine_vertices = 0;
};

namespace refinement_detail {

/// the kinds of a refinement's vertices from one seed choice; false on a contradiction
class Labelling
{
public:
  Labelling(const Hex_mesh_arrays& m, const std::vector<std::size_t>& vh_off, const std::vector<std::size_t>& vh)
    : m_(m), vh_off_(vh_off), vh_(vh)
  {
  }

  bool run(std::size_t seed, int seed_corner)
  {
    kind.assign(m_.points.size(), no_kind);
    coarse_corner.assign(m_.hexes.size(), -1);
    std::vector<char> queued(m_.hexes.size(), 0);
    std::vector<std::size_t> queue;
    queue.reserve(m_.hexes.size());
    if(!resolve(seed, seed_corner, queue, queued)) return false;
    for(std::size_t head = 0; head < queue.size(); ++head)
    {
      const std::size_t h = queue[head];
      queued[h] = 0;
      if(coarse_corner[h] >= 0) continue;
      int found = -1, candidates = 0;
      for(int c = 0; c < 8 && candidates < 2; ++c)
      {
        bool consistent = true;
        for(int q = 0; q < 8 && consistent; ++q)
        {
          const unsigned char k = kind[m_.hexes[h][q]];
          if(k != no_kind && int(k) != kind_of_corner(q, c)) consistent = false;
        }
        if(consistent)
        {
          found = c;
          ++candidates;
        }
      }
      if(candidates == 0) return false;
      if(candidates == 1 && !resolve(h, found, queue, queued)) return false;
      // more than one: resolved later, from another neighbour
    }
    for(int c : coarse_corner)
      if(c < 0) return false; // not reached through shared faces
    return true;
  }

  static constexpr unsigned char no_kind = 255;
  std::vector<unsigned char> kind;
  /// the local corner of each hex's coarse corner
  std::vector<int> coarse_corner;

private:
  std::size_t incident_hexes(std::size_t v) const { return vh_off_[v + 1] - vh_off_[v]; }

  /// whether a vertex with this many hexes around it can be of kind k: 8
  /// children around a cell centre, 4 or 8 around a face centre (boundary or
  /// interior face), twice the coarse edge's valence around an edge midpoint
  static bool count_fits(int k, std::size_t n)
  {
    switch(k)
    {
    case 3: return n == 8;
    case 2: return n == 4 || n == 8;
    case 1: return n >= 2 && n % 2 == 0;
    default: return n >= 1;
    }
  }

  bool resolve(std::size_t h, int c, std::vector<std::size_t>& queue, std::vector<char>& queued)
  {
    coarse_corner[h] = c;
    for(int q = 0; q < 8; ++q)
    {
      const std::size_t v = m_.hexes[h][q];
      const int k = kind_of_corner(q, c);
      if(kind[v] == no_kind)
      {
        if(!count_fits(k, incident_hexes(v))) return false;
        kind[v] = static_cast<unsigned char>(k);
      }
      else if(int(kind[v]) != k)
        return false;
    }
    for(int q = 0; q < 8; ++q)
    {
      const std::size_t v = m_.hexes[h][q];
      for(std::size_t i = vh_off_[v]; i < vh_off_[v + 1]; ++i)
      {
        const std::size_t g = vh_[i];
        if(coarse_corner[g] < 0 && !queued[g])
        {
          queued[g] = 1;
          queue.push_back(g);
        }
      }
    }
    return true;
  }

  const Hex_mesh_arrays& m_;
  const std::vector<std::size_t>& vh_off_;
  const std::vector<std::size_t>& vh_;
};

/// the coarse hex of the 8 children `children_begin[0 .. 8)` around a cell
/// centre, its corners (fine indices) ordered in the frame of the first
/// child h0: child h' lies in the octant that differs from h0's along the
/// axes on which all the vertices h0 and h' share agree (a face: one axis,
/// an edge: two, the centre alone: three); false if two children claim the
/// same octant or two corners coincide
inline bool coarse_hex_around(const Hex_mesh_arrays& m, const Labelling& l, const std::size_t* children_begin,
                              Hex& coarse_hex)
{
  const std::size_t h0 = children_begin[0];
  const int c0 = l.coarse_corner[h0];
  std::array<bool, 8> filled{};
  for(int i = 0; i < 8; ++i)
  {
    const std::size_t h = children_begin[i];
    int agree = 7; // the axes on which every shared vertex's bits agree
    int first_bits = -1;
    for(int q = 0; q < 8; ++q)
      if(std::find(m.hexes[h].begin(), m.hexes[h].end(), m.hexes[h0][q]) != m.hexes[h].end())
      {
        if(first_bits < 0) first_bits = corner_bits[q];
        agree &= ~(corner_bits[q] ^ first_bits) & 7;
      }
    if(h == h0) agree = 0;
    const int slot = corner_bits[corner_bits[c0] ^ agree]; // the permutation is an involution
    if(filled[slot]) return false;
    filled[slot] = true;
    coarse_hex[slot] = m.hexes[h][l.coarse_corner[h]];
  }
  Hex sorted = coarse_hex;
  std::sort(sorted.begin(), sorted.end());
  return std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end();
}

} // namespace refinement_detail

/// Recognises `fine` as the 1→8 refinement of a coarser mesh, from its
/// connectivity alone (the points are not read): on success fills `level`
/// and returns true. A mesh whose hexes are not all reached from the seed
/// (several components), or with vertices in no hex, is not recognised.
inline bool recognise_refinement(const Hex_mesh_arrays& fine, Refinement_level& level)
{
  using namespace refinement_detail;
  const std::size_t nh = fine.hexes.size(), nv = fine.points.size();
  if(nh == 0 || nh % 8 != 0) return false;
  // vertex -> hexes, in increasing hex order
  std::vector<std::size_t> vh_off(nv + 1, 0), vh(8 * nh);
  for(const Hex& h : fine.hexes)
    for(std::size_t v : h) ++vh_off[v + 1];
  for(std::size_t v = 0; v < nv; ++v) vh_off[v + 1] += vh_off[v];
  {
    std::vector<std::size_t> fill(vh_off.begin(), vh_off.end() - 1);
    for(std::size_t h = 0; h < nh; ++h)
      for(std::size_t v : fine.hexes[h]) vh[fill[v]++] = h;
  }
  // the seed: a hex at the vertex with the fewest hexes around it (on the
  // boundary, where a wrong choice contradicts itself within a few hexes)
  std::size_t seed_vertex = nv;
  for(std::size_t v = 0; v < nv; ++v)
    if(vh_off[v + 1] > vh_off[v] && (seed_vertex == nv || vh_off[v + 1] - vh_off[v] < vh_off[seed_vertex + 1] - vh_off[seed_vertex]))
      seed_vertex = v;
  if(seed_vertex == nv) return false;
  const std::size_t seed = vh[vh_off[seed_vertex]];

  Labelling l(fine, vh_off, vh);
  for(int c = 0; c < 8; ++c)
  {
    if(!l.run(seed, c)) continue;
    Refinement_level r;
    r.number_of_fine_vertices = nv;
    std::vector<std::size_t> fine_to_coarse(nv, std::size_t(-1));
    std::size_t centres = 0;
    for(std::size_t v = 0; v < nv; ++v)
    {
      if(l.kind[v] == 0)
      {
        fine_to_coarse[v] = r.coarse_to_fine.size();
        r.coarse_to_fine.push_back(v);
        r.coarse.points.push_back(fine.points[v]);
      }
      else if(l.kind[v] == 3)
        ++centres;
    }
    if(8 * centres != nh) continue; // every hex a child of exactly one cell centre
    bool ok = true;
    r.coarse.hexes.reserve(centres);
    for(std::size_t v = 0; v < nv && ok; ++v)
    {
      if(l.kind[v] != 3) continue;
      Hex coarse_fine;
      ok = coarse_hex_around(fine, l, vh.data() + vh_off[v], coarse_fine);
      Hex ch;
      for(int q = 0; q < 8 && ok; ++q) ch[q] = fine_to_coarse[coarse_fine[q]];
      if(ok) r.coarse.hexes.push_back(ch);
    }
    if(!ok) continue;
    // parents: the neighbours one kind below, from the hexes' edges, each
    // found in several hexes (bucketed by child, then sorted and made unique
    // within the bucket); children by kind, then index
    std::vector<std::size_t> bucket_off(nv + 1, 0);
    const auto for_each_child_parent = [&](const auto& f) {
      for(const Hex& h : fine.hexes)
        for(const auto& e : hex_edges)
        {
          const std::size_t a = h[e[0]], b = h[e[1]];
          if(l.kind[b] == l.kind[a] + 1) f(b, a);
          else if(l.kind[a] == l.kind[b] + 1) f(a, b);
        }
    };
    for_each_child_parent([&](std::size_t child, std::size_t) { ++bucket_off[child + 1]; });
    for(std::size_t v = 0; v < nv; ++v) bucket_off[v + 1] += bucket_off[v];
    std::vector<std::size_t> bucket(bucket_off[nv]);
    {
      std::vector<std::size_t> fill(bucket_off.begin(), bucket_off.end() - 1);
      for_each_child_parent([&](std::size_t child, std::size_t parent) { bucket[fill[child]++] = parent; });
    }
    r.parent_offsets.push_back(0);
    for(int k = 1; k <= 3 && ok; ++k)
      for(std::size_t v = 0; v < nv && ok; ++v)
      {
        if(l.kind[v] != k) continue;
        std::size_t* b = bucket.data() + bucket_off[v];
        std::size_t* e = bucket.data() + bucket_off[v + 1];
        std::sort(b, e);
        e = std::unique(b, e);
        if(e - b != 2 * k) ok = false; // 2, 4 or 6 parents
        r.children.push_back(v);
        r.parents.insert(r.parents.end(), b, e);
        r.parent_offsets.push_back(r.parents.size());
      }
    if(!ok || r.children.size() + r.coarse_to_fine.size() != nv) continue;
    level = std::move(r);
    return true;
  }
  return false;
}

/// Carries a field on the coarse vertices (a displacement, a position) to
/// the fine vertices by the trilinear map of each coarse hex: an edge
/// midpoint takes the mean of its 2 corners, a face centre of its 4 edge
/// midpoints, a cell centre of its 6 face centres.
inline std::vector<Vec3> prolongate(const Refinement_level& level, const std::vector<Vec3>& coarse_values)
{
  std::vector<Vec3> fine(level.number_of_fine_vertices, Vec3{0., 0., 0.});
  for(std::size_t i = 0; i < level.coarse_to_fine.size(); ++i) fine[level.coarse_to_fine[i]] = coarse_values[i];
  for(std::size_t i = 0; i < level.children.size(); ++i) // by kind: the parents come first
  {
    Vec3 s{0., 0., 0.};
    const std::size_t b = level.parent_offsets[i], e = level.parent_offsets[i + 1];
    for(std::size_t j = b; j < e; ++j) s = s + fine[level.parents[j]];
    fine[level.children[i]] = (1. / double(e - b)) * s;
  }
  return fine;
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_MESH_REFINEMENT_HIERARCHY_H
