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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_PARALLEL_FOR_EACH_INDEX_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_PARALLEL_FOR_EACH_INDEX_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The package's one parallel loop: g(i) for i in [0, n) on TBB's threads when
// the package is linked with TBB, in order otherwise. Its callers make the
// iterations independent (regions that share no free vertex, vertices of one
// colour), so the result is the same on any number of threads.

#include <cstddef>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#endif

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

/// g(i) for i in [0, n), `grain` iterations at least per task
template <class G>
void parallel_for_each_index(std::size_t n, G g, std::size_t grain = 1)
{
#ifdef CGAL_LINKED_WITH_TBB
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain), [&](const tbb::blocked_range<std::size_t>& r) {
    for(std::size_t i = r.begin(); i != r.end(); ++i) g(i);
  });
#else
  (void)grain;
  for(std::size_t i = 0; i < n; ++i) g(i);
#endif
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_PIPELINE_PARALLEL_FOR_EACH_INDEX_H
