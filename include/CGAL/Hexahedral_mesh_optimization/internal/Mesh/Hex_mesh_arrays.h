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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_MESH_HEX_MESH_ARRAYS_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_MESH_HEX_MESH_ARRAYS_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The flat representation the numerical core works on: positions as plain
// doubles and the hex -> 8 vertex table. It is extracted once from the user's
// mesh (an `Indexed_hex_mesh` or a `Linear_cell_complex`) at the start of an
// algorithm and written back once at the end; nothing in the core walks a
// combinatorial structure.

#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/number_utils.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

typedef std::array<double, 3> Vec3;
typedef std::array<std::size_t, 8> Hex;

struct Hex_mesh_arrays
{
  std::vector<Vec3> points;
  std::vector<Hex> hexes;

  std::size_t number_of_vertices() const { return points.size(); }
  std::size_t number_of_hexes() const { return hexes.size(); }

  /// the 8 corner positions of hex `h`
  std::array<Vec3, 8> corners(std::size_t h) const
  {
    std::array<Vec3, 8> c;
    for(int i = 0; i < 8; ++i)
      c[i] = points[hexes[h][i]];
    return c;
  }
};

// ---------------------------------------------------------------- vectors
inline Vec3 operator-(const Vec3& a, const Vec3& b) { return {a[0]-b[0], a[1]-b[1], a[2]-b[2]}; }
inline Vec3 operator+(const Vec3& a, const Vec3& b) { return {a[0]+b[0], a[1]+b[1], a[2]+b[2]}; }
inline Vec3 operator*(double s, const Vec3& a) { return {s*a[0], s*a[1], s*a[2]}; }
inline double dot(const Vec3& a, const Vec3& b) { return a[0]*b[0] + a[1]*b[1] + a[2]*b[2]; }
inline Vec3 cross(const Vec3& a, const Vec3& b)
{
  return {a[1]*b[2] - a[2]*b[1], a[2]*b[0] - a[0]*b[2], a[0]*b[1] - a[1]*b[0]};
}
inline double squared_norm(const Vec3& a) { return dot(a, a); }
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }
/// a / |a|, or the zero vector
inline Vec3 normalized(const Vec3& a)
{
  const double l = norm(a);
  return l > 1e-300 ? (1. / l) * a : Vec3{0., 0., 0.};
}

// ------------------------------------------------------------ conversion
/// Reads the coordinates of any CGAL point through its kernel's accessors.
template <class Point, class GeomTraits>
Vec3 to_vec3(const Point& p, const GeomTraits& gt)
{
  return {CGAL::to_double(gt.compute_x_3_object()(p)),
          CGAL::to_double(gt.compute_y_3_object()(p)),
          CGAL::to_double(gt.compute_z_3_object()(p))};
}

template <class GeomTraits>
typename GeomTraits::Point_3 to_point(const Vec3& v, const GeomTraits& gt)
{
  typedef typename GeomTraits::FT FT;
  return gt.construct_point_3_object()(FT(v[0]), FT(v[1]), FT(v[2]));
}

/// How the algorithms read a mesh data structure into flat arrays and write
/// the positions back. Specialised for `Indexed_hex_mesh` below and for
/// `Linear_cell_complex_for_combinatorial_map` in `Linear_cell_complex_hex_mesh.h`.
/// A specialisation provides `Point`, `extract(mesh, gt)` and
/// `write_back(arrays, mesh, gt)`; vertex i of the arrays must be the same
/// vertex in both.
template <class HexMesh>
struct Hex_mesh_adapter;

template <class Point, class GeomTraits>
Hex_mesh_arrays make_hex_mesh_arrays(const Indexed_hex_mesh<Point>& mesh, const GeomTraits& gt)
{
  Hex_mesh_arrays a;
  a.points.reserve(mesh.points.size());
  for(const Point& p : mesh.points)
    a.points.push_back(to_vec3(p, gt));
  a.hexes.assign(mesh.hexahedra.begin(), mesh.hexahedra.end());
  return a;
}

/// writes the positions back; the connectivity is never changed by the core
template <class Point, class GeomTraits>
void write_back_points(const Hex_mesh_arrays& a, Indexed_hex_mesh<Point>& mesh, const GeomTraits& gt)
{
  for(std::size_t i = 0; i < a.points.size(); ++i)
    mesh.points[i] = to_point(a.points[i], gt);
}

template <class Point_3>
struct Hex_mesh_adapter<Indexed_hex_mesh<Point_3> >
{
  typedef Point_3 Point;

  template <class GeomTraits>
  static Hex_mesh_arrays extract(const Indexed_hex_mesh<Point_3>& mesh, const GeomTraits& gt)
  {
    return make_hex_mesh_arrays(mesh, gt);
  }

  template <class GeomTraits>
  static void write_back(const Hex_mesh_arrays& a, Indexed_hex_mesh<Point_3>& mesh, const GeomTraits& gt)
  {
    write_back_points(a, mesh, gt);
  }
};

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_MESH_HEX_MESH_ARRAYS_H
