// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Package: Hexahedral_mesh_optimization

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_MESH_FACE_GROUPS_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_MESH_FACE_GROUPS_H

// The faces of a hex mesh grouped by their vertices: which hexes share a
// face, which faces are on the boundary, which are shared by more than two.
// The 6 n faces are bucketed by their smallest vertex (a counting sort, linear)
// and matched within each bucket, which holds a few faces: a global sort of
// the faces, or a hash map of them, took seconds on a 1M-hex mesh.

#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/scaled_jacobian.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <utility>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

/// Calls `group(key, ids, count)` once for each set of equal faces of
/// `hexes` (array-of-8-indices hexahedra, vertex indices below
/// `number_of_vertices`): `key` is the face's four vertices sorted, `ids`
/// the faces' ids (6 × hex + local face, `hex_faces` order) in increasing
/// order. The groups come by increasing smallest vertex, then by key.
template <class Hexahedra, class Group>
void for_each_face_group(const Hexahedra& hexes, std::size_t number_of_vertices, Group group)
{
  typedef std::array<std::size_t, 4> Key;
  const std::size_t nf = 6 * hexes.size();
  auto key_of = [&](std::size_t id) {
    Key k;
    for(int i = 0; i < 4; ++i) k[i] = std::size_t(hexes[id / 6][hex_faces[id % 6][i]]);
    std::sort(k.begin(), k.end());
    return k;
  };
  auto smallest_vertex = [&](std::size_t id) {
    std::size_t m = std::size_t(hexes[id / 6][hex_faces[id % 6][0]]);
    for(int i = 1; i < 4; ++i) m = (std::min)(m, std::size_t(hexes[id / 6][hex_faces[id % 6][i]]));
    return m;
  };
  std::vector<std::size_t> offset(number_of_vertices + 1, 0);
  for(std::size_t id = 0; id < nf; ++id) ++offset[smallest_vertex(id) + 1];
  for(std::size_t v = 0; v < number_of_vertices; ++v) offset[v + 1] += offset[v];
  std::vector<std::size_t> bucketed(nf);
  {
    std::vector<std::size_t> next(offset.begin(), offset.end() - 1);
    for(std::size_t id = 0; id < nf; ++id) bucketed[next[smallest_vertex(id)]++] = id;
  }
  std::vector<std::pair<Key, std::size_t> > faces;
  std::vector<std::size_t> ids;
  for(std::size_t v = 0; v < number_of_vertices; ++v)
  {
    faces.clear();
    for(std::size_t k = offset[v]; k < offset[v + 1]; ++k) faces.push_back({key_of(bucketed[k]), bucketed[k]});
    std::sort(faces.begin(), faces.end());
    for(std::size_t i = 0; i < faces.size();)
    {
      std::size_t j = i + 1;
      while(j < faces.size() && faces[j].first == faces[i].first) ++j;
      ids.clear();
      for(std::size_t k = i; k < j; ++k) ids.push_back(faces[k].second);
      group(faces[i].first, ids.data(), ids.size());
      i = j;
    }
  }
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_MESH_FACE_GROUPS_H
