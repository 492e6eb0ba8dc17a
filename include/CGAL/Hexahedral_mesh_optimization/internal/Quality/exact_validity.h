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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_QUALITY_EXACT_VALIDITY_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_QUALITY_EXACT_VALIDITY_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The exact validity certificate: the sign of each of the 9 Jacobian
// samples of a hex (scaled_jacobian.h), decided exactly on its double
// coordinates, where the scaled Jacobian itself is a rounded value whose
// sign can be wrong within a few ulps of zero.
// - Corner i: det[p_a - p_i, p_b - p_i, p_c - p_i] with {a, b, c} =
//   `hex_corner_edges[i]`, the orientation of the tetrahedron (p_i, p_a,
//   p_b, p_c): CGAL's exact predicate (`Epick`, filtered, exact fallback).
// - Centre: det of the principal axes (sums and differences of the 8
//   corners): interval arithmetic, and exact rationals when the interval
//   contains 0.
// A hex is certified valid when all 9 signs are positive: an inverted frame
// (negative) or a flat one (zero) is not.

#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/scaled_jacobian.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Exact_rational.h>
#include <CGAL/Interval_nt.h>

#include <array>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

/// the sign of det[x1 x2 x3] of the principal axes of `p`, computed in `NT`
template <class NT>
NT centre_determinant(const std::array<Vec3, 8>& p)
{
  NT x[3][3];
  for(int k = 0; k < 3; ++k)
    for(int d = 0; d < 3; ++d)
    {
      NT s(0);
      for(int j = 0; j < 4; ++j) s = s + NT(p[hex_axis_plus[k][j]][d]);
      for(int j = 0; j < 4; ++j) s = s - NT(p[hex_axis_minus[k][j]][d]);
      x[k][d] = s;
    }
  return x[0][0] * (x[1][1] * x[2][2] - x[1][2] * x[2][1])
       - x[0][1] * (x[1][0] * x[2][2] - x[1][2] * x[2][0])
       + x[0][2] * (x[1][0] * x[2][1] - x[1][1] * x[2][0]);
}

/// the exact sign of the Jacobian at the centre of the hex `p`
inline Sign exact_centre_sign(const std::array<Vec3, 8>& p)
{
  {
    Protect_FPU_rounding<true> rounding;
    const Interval_nt<false> det = centre_determinant<Interval_nt<false> >(p);
    if(det.inf() > 0.) return POSITIVE;
    if(det.sup() < 0.) return NEGATIVE;
  }
  return CGAL::sign(centre_determinant<Exact_rational>(p));
}

/// the exact sign of the Jacobian at corner `i` (0..7) of the hex `p`
inline Sign exact_corner_sign(const std::array<Vec3, 8>& p, int i)
{
  typedef Epick::Point_3 P;
  auto point = [&p](int k) { return P(p[k][0], p[k][1], p[k][2]); };
  const int* n = hex_corner_edges[i];
  return CGAL::orientation(point(i), point(n[0]), point(n[1]), point(n[2]));
}

/// whether the 9 Jacobian samples of the hex `p` are all positive, decided
/// exactly
inline bool certified_valid(const std::array<Vec3, 8>& p)
{
  for(int i = 0; i < 8; ++i)
    if(exact_corner_sign(p, i) != POSITIVE) return false;
  return exact_centre_sign(p) == POSITIVE;
}

/// the hexes of `m` that are not certified valid, in index order
inline std::vector<std::size_t> uncertified_hexes(const std::vector<Hex>& hexes, const std::vector<Vec3>& points)
{
  std::vector<std::size_t> out;
  std::array<Vec3, 8> c;
  for(std::size_t h = 0; h < hexes.size(); ++h)
  {
    for(int i = 0; i < 8; ++i) c[i] = points[hexes[h][i]];
    if(!certified_valid(c)) out.push_back(h);
  }
  return out;
}

inline std::vector<std::size_t> uncertified_hexes(const Hex_mesh_arrays& m)
{
  return uncertified_hexes(m.hexes, m.points);
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_QUALITY_EXACT_VALIDITY_H
