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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_QUALITY_QUALITY_STATISTICS_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_QUALITY_QUALITY_STATISTICS_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Mesh-level quality figures (inverted count, MSJ, ASJ, histogram) computed
// from the per-element Verdict scaled Jacobian.

#include <CGAL/Hexahedral_mesh_optimization/Hex_mesh_quality.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/scaled_jacobian.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/parallel_for_each_index.h>

#include <algorithm>
#include <cstddef>
#include <limits>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

/// Quality of a hexahedral mesh: the public `CGAL::Hex_mesh_quality`
typedef CGAL::Hex_mesh_quality Quality_statistics;

/// the scaled Jacobian of every hex, on all threads (each value on its own:
/// the same on any number of threads). The drivers take the statistics
/// several times a turn, so a serial loop would add up.
inline std::vector<double> scaled_jacobians(const Hex_mesh_arrays& m)
{
  std::vector<double> sj(m.hexes.size());
  const std::size_t block = 4096;
  parallel_for_each_index((sj.size() + block - 1) / block, [&](std::size_t b) {
    const std::size_t end = (std::min)(sj.size(), (b + 1) * block);
    for(std::size_t h = b * block; h < end; ++h) sj[h] = scaled_jacobian(m, h);
  });
  return sj;
}

inline Quality_statistics quality_statistics(const std::vector<double>& sj, std::size_t vertices)
{
  Quality_statistics q;
  q.hexes = sj.size();
  q.vertices = vertices;
  if(sj.empty())
    return q;
  q.msj = std::numeric_limits<double>::max();
  double sum = 0.;
  for(double s : sj)
  {
    q.msj = (std::min)(q.msj, s);
    sum += s;
    if(is_inverted(s))
      ++q.inverted;
    int k = static_cast<int>((s + 1.) * 0.5 * Quality_statistics::histogram_bins);
    k = (std::max)(0, (std::min)(k, Quality_statistics::histogram_bins - 1));
    ++q.histogram[k];
  }
  q.asj = sum / static_cast<double>(sj.size());
  return q;
}

inline Quality_statistics quality_statistics(const Hex_mesh_arrays& m)
{
  return quality_statistics(scaled_jacobians(m), m.points.size());
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_QUALITY_QUALITY_STATISTICS_H
