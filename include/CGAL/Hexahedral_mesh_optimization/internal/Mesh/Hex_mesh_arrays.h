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

#include <boost/property_map/property_map.hpp>

#include <array>
#include <cmath>
#include <cstddef>
#include <type_traits>
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
  /// vertex i may not move when `constrained[i]` (CGAL's
  /// `vertex_is_constrained_map`); empty: no vertex is constrained. Every
  /// stage reads this one mask, through `is_constrained()`.
  std::vector<unsigned char> constrained = {};

  bool is_constrained(std::size_t v) const { return !constrained.empty() && constrained[v] != 0; }
  bool has_constrained_vertices() const { return !constrained.empty(); }

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

/// Whether `T` is a model of the `HexMesh` concept (doc/.../Concepts/HexMesh.h):
/// `Indexed_hex_mesh`, and in `Linear_cell_complex_hex_mesh.h` the two 3D
/// linear cell complexes.
template <class T>
struct Is_hex_mesh : std::false_type {};

template <class Point_3>
struct Is_hex_mesh<Indexed_hex_mesh<Point_3> > : std::true_type {};

/// How the algorithms read a model of `HexMesh` into flat arrays and write
/// the positions back. Specialised for `Indexed_hex_mesh` below and for the
/// linear cell complexes in `Linear_cell_complex_hex_mesh.h`. A
/// specialisation provides `Point`, `vertex_descriptor` (the key of the
/// vertex property maps), `vertices(mesh)` (vertex i of the arrays is the
/// i-th), `hexahedra(mesh, hexes)` (MEDIT/VTK order; `std::invalid_argument`
/// on a cell that is not a hexahedron) and `vertex_point_map(mesh)`, a
/// read-write property map (written only through a non-const mesh).
template <class HexMesh>
struct Hex_mesh_adapter
{
  static_assert(Is_hex_mesh<HexMesh>::value,
                "the mesh type is not a model of the HexMesh concept of Hexahedral_mesh_optimization "
                "(Indexed_hex_mesh, Linear_cell_complex_for_combinatorial_map<3,3> or "
                "Linear_cell_complex_for_generalized_map<3,3>; include "
                "CGAL/Hexahedral_mesh_optimization/Linear_cell_complex_hex_mesh.h for the latter two)");
};

/// the points of an `Indexed_hex_mesh`, by vertex index
template <class Point_3>
struct Indexed_hex_mesh_point_map
{
  typedef std::size_t key_type;
  typedef Point_3 value_type;
  typedef const Point_3& reference;
  typedef boost::read_write_property_map_tag category;
  std::vector<Point_3>* points;
  friend reference get(const Indexed_hex_mesh_point_map& m, key_type i) { return (*m.points)[i]; }
  friend void put(const Indexed_hex_mesh_point_map& m, key_type i, const value_type& p) { (*m.points)[i] = p; }
};

template <class Point_3>
struct Hex_mesh_adapter<Indexed_hex_mesh<Point_3> >
{
  typedef Indexed_hex_mesh<Point_3> Mesh;
  typedef Point_3 Point;
  typedef std::size_t vertex_descriptor;
  typedef Indexed_hex_mesh_point_map<Point_3> Default_vertex_point_map;

  static std::vector<vertex_descriptor> vertices(const Mesh& mesh)
  {
    std::vector<vertex_descriptor> v(mesh.points.size());
    for(std::size_t i = 0; i < v.size(); ++i) v[i] = i;
    return v;
  }
  static void hexahedra(const Mesh& mesh, std::vector<Hex>& hexes)
  {
    hexes.assign(mesh.hexahedra.begin(), mesh.hexahedra.end());
  }
  /// (writes only through a non-const mesh)
  static Default_vertex_point_map vertex_point_map(const Mesh& mesh)
  {
    return Default_vertex_point_map{const_cast<std::vector<Point_3>*>(&mesh.points)};
  }
};

/// the flat arrays of a model of `HexMesh`, its points read through `vpm`
/// and converted to doubles by `gt`
template <class HexMesh, class VertexPointMap, class GeomTraits>
Hex_mesh_arrays extract_hex_mesh(const HexMesh& mesh, const VertexPointMap& vpm, const GeomTraits& gt)
{
  typedef Hex_mesh_adapter<HexMesh> Adapter;
  Hex_mesh_arrays a;
  const auto vertices = Adapter::vertices(mesh);
  a.points.reserve(vertices.size());
  for(const auto& v : vertices) a.points.push_back(to_vec3(get(vpm, v), gt));
  Adapter::hexahedra(mesh, a.hexes);
  return a;
}

/// Writes back through `vpm` the positions of the vertices that moved:
/// those whose doubles differ from `before` (what `extract_hex_mesh()`
/// read). The others keep their point as it was, exactly, whatever the
/// kernel: only a moved vertex goes through `double`.
template <class HexMesh, class VertexPointMap, class GeomTraits>
void write_back_moved(const Hex_mesh_arrays& a, const std::vector<Vec3>& before, HexMesh& mesh,
                      const VertexPointMap& vpm, const GeomTraits& gt)
{
  const auto vertices = Hex_mesh_adapter<HexMesh>::vertices(mesh);
  for(std::size_t i = 0; i < vertices.size() && i < a.points.size(); ++i)
    if(a.points[i] != before[i]) put(vpm, vertices[i], to_point(a.points[i], gt));
}

/// the flat arrays of `mesh` through its own point map
template <class HexMesh, class GeomTraits>
Hex_mesh_arrays extract_hex_mesh(const HexMesh& mesh, const GeomTraits& gt)
{
  return extract_hex_mesh(mesh, Hex_mesh_adapter<HexMesh>::vertex_point_map(mesh), gt);
}

template <class Point, class GeomTraits>
Hex_mesh_arrays make_hex_mesh_arrays(const Indexed_hex_mesh<Point>& mesh, const GeomTraits& gt)
{
  return extract_hex_mesh(mesh, gt);
}

/// writes every position of `a` back through the mesh's own point map
template <class HexMesh, class GeomTraits>
void write_back_points(const Hex_mesh_arrays& a, HexMesh& mesh, const GeomTraits& gt)
{
  typedef Hex_mesh_adapter<HexMesh> Adapter;
  const auto vpm = Adapter::vertex_point_map(mesh);
  const auto vertices = Adapter::vertices(mesh);
  for(std::size_t i = 0; i < vertices.size() && i < a.points.size(); ++i)
    put(vpm, vertices[i], to_point(a.points[i], gt));
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_MESH_HEX_MESH_ARRAYS_H
