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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_HEX_MESH_QUALITY_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_HEX_MESH_QUALITY_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The quality summary of a mesh, returned by CGAL::hex_mesh_quality()
// (<CGAL/hex_mesh_quality.h>) and used inside the package as
// internal::Quality_statistics.

#include <cstddef>
#include <vector>

namespace CGAL {

/*!
\ingroup PkgHexahedralMeshOptimizationQuality

\brief Quality summary of a hexahedral mesh, as printed by the tool and
returned by `hex_mesh_quality()`.

"Scaled Jacobian" is the Verdict definition (see `hex_scaled_jacobian()`).
The histogram has `histogram_bins` equal bins over [-1, 1]: bin `k` counts
the elements whose scaled Jacobian lies in [`bin_lower(k)`, `bin_upper(k)`),
the last bin includes 1.
*/
struct Hex_mesh_quality
{
  /// the number of bins of `histogram`
  static constexpr int histogram_bins = 20;

  /// the number of hexahedra
  std::size_t hexes = 0;
  /// the number of vertices
  std::size_t vertices = 0;
  /// the number of elements with a negative scaled Jacobian
  std::size_t inverted = 0;
  /// the minimum scaled Jacobian (0 for an empty mesh)
  double msj = 0.;
  /// the average scaled Jacobian (0 for an empty mesh)
  double asj = 0.;
  /// the number of elements in each bin
  std::vector<std::size_t> histogram = std::vector<std::size_t>(histogram_bins, 0);

  /// the lower bound of bin `k`
  static double bin_lower(int k) { return -1. + 2. * k / histogram_bins; }
  /// the upper bound of bin `k`
  static double bin_upper(int k) { return -1. + 2. * (k + 1) / histogram_bins; }
};

} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_HEX_MESH_QUALITY_H
