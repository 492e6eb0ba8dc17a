// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Structured hex meshes the tests build for themselves: the connectivity of
// a structured vertex grid, a box grid and a closed cylinder on flat arrays.

#ifndef HMO_TEST_MESHES_H
#define HMO_TEST_MESHES_H

#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/number_type_config.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace hmo_test {

/// the hexes of a structured grid of (nx+1)×(ny+1)×(nz+1) vertices numbered
/// i + (nx+1) (j + (ny+1) k), in MEDIT order (0-3 bottom face, i+4 above i)
inline std::vector<std::array<std::size_t, 8> > structured_hexes(std::size_t nx, std::size_t ny, std::size_t nz)
{
  auto id = [&](std::size_t i, std::size_t j, std::size_t k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  std::vector<std::array<std::size_t, 8> > hexes;
  for(std::size_t k = 0; k < nz; ++k)
    for(std::size_t j = 0; j < ny; ++j)
      for(std::size_t i = 0; i < nx; ++i)
        hexes.push_back({{id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k),
                          id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)}});
  return hexes;
}

namespace HMOI = CGAL::Hexahedral_mesh_optimization::internal;

/// nx × ny × nz grid spanning [0,sx]×[0,sy]×[0,sz], MEDIT order
inline HMOI::Hex_mesh_arrays grid(std::size_t nx, std::size_t ny, std::size_t nz,
                                  double sx = 1., double sy = 1., double sz = 1.)
{
  HMOI::Hex_mesh_arrays m;
  for(std::size_t k = 0; k <= nz; ++k)
    for(std::size_t j = 0; j <= ny; ++j)
      for(std::size_t i = 0; i <= nx; ++i)
        m.points.push_back(HMOI::Vec3{sx * double(i) / double(nx), sy * double(j) / double(ny), sz * double(k) / double(nz)});
  m.hexes = structured_hexes(nx, ny, nz);
  return m;
}

/// a grid whose square cross-section [-1,1]² is mapped onto the unit disk
/// ring by ring (uniform angle along each square ring): a closed cylinder
inline HMOI::Hex_mesh_arrays cylinder(std::size_t n, std::size_t nz, double height)
{
  HMOI::Hex_mesh_arrays m = grid(n, n, nz, 2., 2., height);
  for(HMOI::Vec3& p : m.points)
  {
    const double x = p[0] - 1., y = p[1] - 1.;
    const double r = (std::max)(std::abs(x), std::abs(y));
    if(r < 1e-12)
    {
      p[0] = p[1] = 0.;
      continue;
    }
    // arc-length parameter along the square ring of half-side r, in [0, 8r)
    double s;
    if(x >= r - 1e-12)        s = y + r;             // right side, y from -r to r
    else if(y >= r - 1e-12)   s = 2 * r + (r - x);   // top side
    else if(x <= -r + 1e-12)  s = 4 * r + (r - y);   // left side
    else                      s = 6 * r + (x + r);   // bottom side
    const double a = s / (8. * r) * 2. * CGAL_PI - CGAL_PI / 4.;
    p[0] = r * std::cos(a);
    p[1] = r * std::sin(a);
  }
  return m;
}

} // namespace hmo_test

#endif // HMO_TEST_MESHES_H
