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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_ID_MAP_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_ID_MAP_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The ids of the simulation formats (gmsh tags, Abaqus and Exodus ids) are
// arbitrary positive integers: this maps them to 0-based indices, and back
// again for writing (the ids a mesh keeps, when they are usable).

#include <algorithm>
#include <cstddef>
#include <unordered_map>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {
namespace io {

/// id -> index; a dense array while the ids are small, a hash map beyond
class Id_map
{
public:
  static constexpr std::size_t none = static_cast<std::size_t>(-1);

  /// maps `id` (> 0) to `index`; false if `id` is already mapped
  bool insert(long long id, std::size_t index)
  {
    const unsigned long long u = static_cast<unsigned long long>(id);
    if(u < dense_limit())
    {
      if(u >= dense_.size())
        dense_.resize((std::max)(static_cast<std::size_t>(u) + 1, dense_.size() * 2), none);
      if(dense_[u] != none)
        return false;
      dense_[u] = index;
      ++count_;
      return true;
    }
    const bool inserted = sparse_.emplace(id, index).second;
    count_ += inserted ? 1 : 0;
    return inserted;
  }

  /// the index of `id`, `none` if unknown
  std::size_t find(long long id) const
  {
    const unsigned long long u = static_cast<unsigned long long>(id);
    if(u < dense_.size())
      return dense_[u];
    const auto it = sparse_.find(id);
    return it == sparse_.end() ? none : it->second;
  }

  std::size_t size() const { return count_; }

private:
  // the dense array never grows beyond a few times the number of ids
  std::size_t dense_limit() const { return 4 * count_ + 4096; }

  std::vector<std::size_t> dense_;
  std::unordered_map<long long, std::size_t> sparse_;
  std::size_t count_ = 0;
};

/// the ids to write for `n` items: `kept` when it holds `n` unique positive
/// ids, 1..n otherwise
inline std::vector<long long> ids_for_writing(const std::vector<long long>& kept, std::size_t n)
{
  if(kept.size() == n)
  {
    std::vector<long long> sorted(kept);
    std::sort(sorted.begin(), sorted.end());
    if(n == 0 || (sorted.front() > 0 && std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end()))
      return kept;
  }
  std::vector<long long> ids(n);
  for(std::size_t i = 0; i < n; ++i)
    ids[i] = static_cast<long long>(i + 1);
  return ids;
}

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_ID_MAP_H
