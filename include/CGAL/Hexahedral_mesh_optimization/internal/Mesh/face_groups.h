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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_MESH_FACE_GROUPS_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_MESH_FACE_GROUPS_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The faces of a hex mesh grouped by their vertices: which hexes share a
// face, which faces are on the boundary, which are shared by more than two.
// The 6 n faces are bucketed by their smallest vertex (a counting sort, linear)
// and matched within each bucket, which holds a few faces: linear, where a
// global sort of the faces is not, and without a hash map's scattered access.

#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/parallel_for_each_index.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/scaled_jacobian.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <utility>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

namespace face_groups_detail {

typedef std::array<std::size_t, 4> Key;

/// The 6 n faces of `hexes` (ids 6 × hex + local face) bucketed by their
/// smallest vertex: bucket v is `bucketed[offset[v] .. offset[v + 1])`, ids
/// in increasing order.
template <class Hexahedra>
void bucket_faces(const Hexahedra& hexes, std::size_t number_of_vertices, std::vector<std::size_t>& offset,
                  std::vector<std::size_t>& bucketed)
{
  const std::size_t nf = 6 * hexes.size();
  auto smallest_vertex = [&](std::size_t id) {
    std::size_t m = std::size_t(hexes[id / 6][hex_faces[id % 6][0]]);
    for(int i = 1; i < 4; ++i) m = (std::min)(m, std::size_t(hexes[id / 6][hex_faces[id % 6][i]]));
    return m;
  };
  offset.assign(number_of_vertices + 1, 0);
  for(std::size_t id = 0; id < nf; ++id) ++offset[smallest_vertex(id) + 1];
  for(std::size_t v = 0; v < number_of_vertices; ++v) offset[v + 1] += offset[v];
  bucketed.resize(nf);
  std::vector<std::size_t> next(offset.begin(), offset.end() - 1);
  for(std::size_t id = 0; id < nf; ++id) bucketed[next[smallest_vertex(id)]++] = id;
}

/// `group(key, ids, count)` for each set of equal faces in bucket v, by key;
/// `faces` and `ids` are scratch space
template <class Hexahedra, class Group>
void group_bucket(const Hexahedra& hexes, const std::vector<std::size_t>& offset,
                  const std::vector<std::size_t>& bucketed, std::size_t v,
                  std::vector<std::pair<Key, std::size_t> >& faces, std::vector<std::size_t>& ids, Group& group)
{
  auto key_of = [&](std::size_t id) {
    Key k;
    for(int i = 0; i < 4; ++i) k[i] = std::size_t(hexes[id / 6][hex_faces[id % 6][i]]);
    std::sort(k.begin(), k.end());
    return k;
  };
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

} // namespace face_groups_detail

/// Calls `group(key, ids, count)` once for each set of equal faces of
/// `hexes` (array-of-8-indices hexahedra, vertex indices below
/// `number_of_vertices`): `key` is the face's four vertices sorted, `ids`
/// the faces' ids (6 × hex + local face, `hex_faces` order) in increasing
/// order. The groups come by increasing smallest vertex, then by key.
template <class Hexahedra, class Group>
void for_each_face_group(const Hexahedra& hexes, std::size_t number_of_vertices, Group group)
{
  std::vector<std::size_t> offset, bucketed;
  face_groups_detail::bucket_faces(hexes, number_of_vertices, offset, bucketed);
  std::vector<std::pair<face_groups_detail::Key, std::size_t> > faces;
  std::vector<std::size_t> ids;
  for(std::size_t v = 0; v < number_of_vertices; ++v)
    face_groups_detail::group_bucket(hexes, offset, bucketed, v, faces, ids, group);
}

/// The same groups, the buckets on TBB's threads (when linked with it): the
/// calls come in no particular order and concurrently, so `group` must only
/// write what belongs to its own faces (e.g. a flag per face id).
template <class Hexahedra, class Group>
void for_each_face_group_in_parallel(const Hexahedra& hexes, std::size_t number_of_vertices, Group group)
{
  std::vector<std::size_t> offset, bucketed;
  face_groups_detail::bucket_faces(hexes, number_of_vertices, offset, bucketed);
  const std::size_t block = 4096;
  const std::size_t blocks = (number_of_vertices + block - 1) / block;
  parallel_for_each_index(blocks, [&](std::size_t b) {
    std::vector<std::pair<face_groups_detail::Key, std::size_t> > faces;
    std::vector<std::size_t> ids;
    Group g = group;
    for(std::size_t v = b * block; v < (std::min)(number_of_vertices, (b + 1) * block); ++v)
      face_groups_detail::group_bucket(hexes, offset, bucketed, v, faces, ids, g);
  });
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_MESH_FACE_GROUPS_H
