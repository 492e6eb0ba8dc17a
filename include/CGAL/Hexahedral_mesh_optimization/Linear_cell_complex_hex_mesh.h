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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_LINEAR_CELL_COMPLEX_HEX_MESH_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_LINEAR_CELL_COMPLEX_HEX_MESH_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Conversions between `Indexed_hex_mesh` and a 3D linear cell complex based on
// a combinatorial map, and the adapter that lets every function of the
// package (`hex_mesh_quality()`, ...) take such a linear cell complex.
//
// Layout of a hexahedron made by `make_hexahedron(p0, ..., p7)` (CGAL's
// picture: 0-3 bottom, p5 above p0, p6 above p1, p7 above p2, p4 above p3):
// its six faces, as cycles of darts along beta1 (a dart's vertex is its
// origin), are
//   F1 = (p0 p5 p6 p1)  the dart returned by make_hexahedron
//   F2 = (p1 p6 p7 p2)  = beta2(beta1(beta1(F1)))
//   F3 = (p2 p7 p4 p3)  = beta2(beta1(beta1(F2)))
//   F4 = (p3 p4 p5 p0)  = beta1(beta1(beta2(F1)))
//   F5 = (p0 p1 p2 p3)  = beta2(beta0(F1))
//   F6 = (p5 p4 p7 p6)  = beta1(beta2(beta1(F1)))
// With MEDIT/VTK vertices m0..m7 (0-3 bottom, m(i+4) above m(i)) the
// hexahedron is make_hexahedron(m0, m1, m2, m3, m7, m4, m5, m6), so that
// p0..p3 = m0..m3, p5 = m4, p6 = m5, p7 = m6, p4 = m7: the geometry is the same
// hexahedron, vertex for vertex. The orientation-preserving symmetries of a
// cube act simply transitively on its 24 darts, so the walk above started
// from ANY dart of a combinatorial hexahedron gives a valid MEDIT order with
// the same orientation.

#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>

#include <CGAL/Kernel_traits.h>
#include <CGAL/Linear_cell_complex_for_combinatorial_map.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

/// The faces F1..F6 of `make_hexahedron(m0, m1, m2, m3, m7, m4, m5, m6)` as
/// MEDIT local vertex indices, in the beta1 order of their darts.
constexpr int lcc_hex_faces[6][4] = {
  {0, 4, 5, 1}, {1, 5, 6, 2}, {2, 6, 7, 3},
  {3, 7, 4, 0}, {0, 1, 2, 3}, {4, 7, 6, 5}
};

/// The six face darts F1..F6 of the combinatorial hexahedron whose F1 is `d`
/// (see the layout at the top of this file). Valid only for a combinatorial
/// hexahedron; `lcc_hexahedron_faces_checked()` verifies it.
template <class LCC, class Dart>
std::array<Dart, 6> lcc_hexahedron_faces(LCC& lcc, Dart d)
{
  std::array<Dart, 6> f;
  f[0] = d;
  f[1] = lcc.beta(d, 1, 1, 2);
  f[2] = lcc.beta(f[1], 1, 1, 2);
  f[3] = lcc.beta(d, 2, 1, 1);
  f[4] = lcc.beta(d, 0, 2);
  f[5] = lcc.beta(d, 1, 2, 1);
  return f;
}

/// Same as `lcc_hexahedron_faces()`, but checks on the way that the volume
/// of `d` is a combinatorial hexahedron: six quadrilaterals glued by beta2 as
/// `make_hexahedron()` glues them. Marks the 24 darts with `mark` (a dart
/// already marked means the volume is not a hexahedron). Returns false when
/// it is not one.
template <class LCC, class Dart>
bool lcc_hexahedron_faces_checked(const LCC& lcc, Dart d, std::array<Dart, 6>& f,
                                  typename LCC::size_type mark)
{
  auto free2 = [&lcc](Dart x) { return lcc.template is_free<2>(x); };
  auto is_quad = [&lcc](Dart x) {
    return !lcc.template is_free<1>(x) && !lcc.template is_free<1>(lcc.beta(x, 1)) &&
           !lcc.template is_free<1>(lcc.beta(x, 1, 1)) &&
           !lcc.template is_free<1>(lcc.beta(x, 1, 1, 1)) &&
           lcc.beta(x, 1, 1, 1, 1) == x;
  };
  if(!is_quad(d))
    return false;
  // F2, F4, F5, F6 through the beta2 links of F1, then F3
  if(free2(d) || free2(lcc.beta(d, 1)) || free2(lcc.beta(d, 1, 1)) || free2(lcc.beta(d, 0)))
    return false;
  f[0] = d;
  f[1] = lcc.beta(d, 1, 1, 2);
  f[3] = lcc.beta(d, 2, 1, 1);
  f[4] = lcc.beta(d, 0, 2);
  f[5] = lcc.beta(d, 1, 2, 1);
  for(int i : {1, 3, 4, 5})
    if(!is_quad(f[i]))
      return false;
  if(free2(lcc.beta(f[1], 1, 1)))
    return false;
  f[2] = lcc.beta(f[1], 1, 1, 2);
  if(!is_quad(f[2]))
    return false;
  // the remaining beta2 links of make_combinatorial_hexahedron
  if(lcc.beta(f[2], 2) != lcc.beta(f[1], 1, 1) ||
     lcc.beta(f[2], 1, 2) != lcc.beta(f[5], 1) ||
     lcc.beta(f[2], 1, 1, 2) != f[3] ||
     lcc.beta(f[2], 0, 2) != lcc.beta(f[4], 1, 1) ||
     lcc.beta(f[5], 2) != lcc.beta(f[3], 1) ||
     lcc.beta(f[5], 1, 1, 2) != lcc.beta(f[1], 1) ||
     lcc.beta(f[4], 0, 2) != lcc.beta(f[3], 0) ||
     lcc.beta(f[4], 1, 2) != lcc.beta(f[1], 0))
    return false;
  // 24 distinct darts
  for(int i = 0; i < 6; ++i)
  {
    Dart x = f[i];
    for(int k = 0; k < 4; ++k, x = lcc.beta(x, 1))
    {
      if(lcc.is_marked(x, mark))
        return false;
      lcc.mark(x, mark);
    }
  }
  return true;
}

/// Walks every 3-cell of `lcc` once, in the order of
/// `lcc.one_dart_per_cell<3>()` (the order of the first dart of each cell in
/// `lcc.darts()`), calls `fun(faces)` with the six face darts (F1..F6) of each.
/// Returns false, with a message, when a 3-cell is not a hexahedron.
template <class LCC, class Function>
bool for_each_lcc_hexahedron(const LCC& lcc, Function fun, std::string* message)
{
  typedef typename LCC::Dart_const_handle Dart;
  const typename LCC::size_type mark = lcc.get_new_mark();
  bool ok = true;
  std::size_t h = 0;
  std::array<Dart, 6> faces;
  for(auto it = lcc.darts().begin(), end = lcc.darts().end(); it != end; ++it)
  {
    Dart d = it;
    if(lcc.is_marked(d, mark))
      continue;
    if(!lcc_hexahedron_faces_checked(lcc, d, faces, mark))
    {
      if(message)
      {
        std::ostringstream s;
        s << "3-cell " << h << " of the linear cell complex is not a hexahedron";
        *message = s.str();
      }
      ok = false;
      break;
    }
    fun(faces);
    ++h;
  }
  lcc.unmark_all(mark);
  lcc.free_mark(mark);
  return ok;
}

/// vertex attribute -> its position in `lcc.vertex_attributes()`
template <class LCC>
std::unordered_map<typename LCC::Vertex_attribute_const_handle, std::size_t>
lcc_vertex_index_map(const LCC& lcc)
{
  std::unordered_map<typename LCC::Vertex_attribute_const_handle, std::size_t> index;
  index.reserve(lcc.vertex_attributes().size());
  std::size_t i = 0;
  for(auto it = lcc.vertex_attributes().begin(), end = lcc.vertex_attributes().end(); it != end; ++it)
    index.emplace(it, i++);
  return index;
}

/// The hexahedra of `lcc` as MEDIT/VTK-ordered vertex indices (vertex i is
/// the i-th vertex attribute), in 3-cell order.
template <class LCC>
bool lcc_hexahedra(const LCC& lcc, std::vector<std::array<std::size_t, 8> >& hexes,
                   std::string* message)
{
  typedef typename LCC::Dart_const_handle Dart;
  const auto index = lcc_vertex_index_map(lcc);
  hexes.clear();
  hexes.reserve(lcc.number_of_darts() / 24);
  bool missing = false;
  auto vertex = [&](Dart x) -> std::size_t {
    auto found = index.find(lcc.vertex_attribute(x));
    if(found == index.end())
    {
      missing = true;
      return 0;
    }
    return found->second;
  };
  const bool ok = for_each_lcc_hexahedron(lcc, [&](const std::array<Dart, 6>& f) {
    // m0 = p0, m1 = p1, m2 = p2, m3 = p3, m4 = p5, m5 = p6, m6 = p7, m7 = p4
    hexes.push_back({vertex(f[0]), vertex(lcc.beta(f[0], 0)), vertex(lcc.beta(f[1], 0)),
                     vertex(lcc.beta(f[4], 0)), vertex(lcc.beta(f[0], 1)),
                     vertex(lcc.beta(f[0], 1, 1)), vertex(lcc.beta(f[1], 1, 1)),
                     vertex(lcc.beta(f[5], 1))});
  }, message);
  if(ok && missing)
  {
    if(message)
      *message = "a dart of the linear cell complex has no vertex attribute";
    return false;
  }
  return ok;
}

template <class Point, class GeomTraits>
Point convert_point(const Point& p, const GeomTraits&) { return p; }

template <class Point, class Other, class GeomTraits>
Point convert_point(const Other& p, const GeomTraits& gt,
                    typename std::enable_if<!std::is_same<Point, Other>::value>::type* = nullptr)
{
  typedef typename Kernel_traits<Other>::Kernel Other_kernel;
  return to_point(to_vec3(p, Other_kernel()), gt);
}

/// Reads a 3D linear cell complex (combinatorial map based) into flat
/// arrays: vertex i is the i-th vertex attribute, hexahedra in 3-cell order.
/// Throws `std::invalid_argument` when a 3-cell is not a hexahedron.
template <class LCC, class GeomTraits>
Hex_mesh_arrays lcc_to_arrays(const LCC& lcc, const GeomTraits& gt)
{
  Hex_mesh_arrays a;
  a.points.reserve(lcc.vertex_attributes().size());
  for(auto it = lcc.vertex_attributes().begin(), end = lcc.vertex_attributes().end(); it != end; ++it)
    a.points.push_back(to_vec3(lcc.point_of_vertex_attribute(it), gt));
  std::string message;
  if(!lcc_hexahedra(lcc, a.hexes, &message))
    throw std::invalid_argument(message);
  return a;
}

/// One face of a hexahedron of `build_linear_cell_complex()`: its vertices
/// sorted (to find its twin), along beta1 from its dart, its hexahedron.
template <class LCC>
struct Lcc_face_record
{
  std::array<std::size_t, 4> key;   // sorted vertex indices
  std::array<std::size_t, 4> cycle; // vertex indices along beta1 from `dart`
  std::size_t hex;
  typename LCC::Dart_handle dart;
  bool operator<(const Lcc_face_record& o) const { return key < o.key || (key == o.key && hex < o.hex); }
};

/// Makes one volume of `lcc` per hexahedron (`vertices`: the vertex
/// attributes of the mesh's points) and the records of their faces; false,
/// with `message`, on a vertex index out of range.
template <class Hexahedra, class LCC>
bool make_lcc_hexahedra(const Hexahedra& hexahedra,
                        const std::vector<typename LCC::Vertex_attribute_handle>& vertices, LCC& lcc,
                        std::vector<Lcc_face_record<LCC> >& faces, std::string& message)
{
  typedef typename LCC::Dart_handle Dart;
  faces.reserve(6 * hexahedra.size());
  for(std::size_t h = 0; h < hexahedra.size(); ++h)
  {
    const auto& m = hexahedra[h];
    for(int i = 0; i < 8; ++i)
      if(m[i] >= vertices.size())
      {
        std::ostringstream s;
        s << "hexahedron " << h << " refers to vertex " << m[i] << " but the mesh has only "
          << vertices.size() << " vertices";
        message = s.str();
        return false;
      }
    const Dart d = lcc.make_hexahedron(vertices[m[0]], vertices[m[1]], vertices[m[2]], vertices[m[3]],
                                       vertices[m[7]], vertices[m[4]], vertices[m[5]], vertices[m[6]]);
    const std::array<Dart, 6> f = lcc_hexahedron_faces(lcc, d);
    for(int k = 0; k < 6; ++k)
    {
      Lcc_face_record<LCC> face;
      Dart x = f[k];
      for(int j = 0; j < 4; ++j, x = lcc.beta(x, 1))
      {
        face.cycle[j] = m[lcc_hex_faces[k][j]];
        if(lcc.vertex_attribute(x) != vertices[face.cycle[j]])
        {
          message = "internal error: unexpected dart layout of make_hexahedron()";
          return false;
        }
      }
      face.key = face.cycle;
      std::sort(face.key.begin(), face.key.end());
      face.hex = h;
      face.dart = f[k];
      faces.push_back(face);
    }
  }
  return true;
}

/// Sews the faces [i, j) of the sorted `faces`, which share one vertex set:
/// nothing to do for a boundary face, the 3-sewing of a pair, and false,
/// with `message`, for a non-manifold face, a face repeated in one
/// hexahedron or a pair with inconsistent orientations.
template <class LCC>
bool sew_lcc_faces(const std::vector<Lcc_face_record<LCC> >& faces, std::size_t i, std::size_t j, LCC& lcc,
                   std::string& message)
{
  typedef typename LCC::Dart_handle Dart;
  const std::array<std::size_t, 4>& k = faces[i].key;
  std::ostringstream s;
  s << "face (" << k[0] << " " << k[1] << " " << k[2] << " " << k[3] << ") ";
  if(j - i > 2)
  {
    s << "is shared by " << (j - i) << " hexahedra (" << faces[i].hex << ", "
      << faces[i + 1].hex << ", " << faces[i + 2].hex << (j - i > 3 ? ", ...": "")
      << "): the mesh is not manifold";
    message = s.str();
    return false;
  }
  if(j - i < 2)
    return true;
  const Lcc_face_record<LCC>& a = faces[i];
  const Lcc_face_record<LCC>& b = faces[i + 1];
  if(a.hex == b.hex)
  {
    s << "appears twice in hexahedron " << a.hex;
    message = s.str();
    return false;
  }
  // b's dart that goes from a.cycle[1] to a.cycle[0], b's cycle being the reverse of a's
  int r = -1;
  for(int t = 0; t < 4 && r < 0; ++t)
    if(b.cycle[t] == a.cycle[1] && b.cycle[(t + 1) % 4] == a.cycle[0] &&
       b.cycle[(t + 2) % 4] == a.cycle[3] && b.cycle[(t + 3) % 4] == a.cycle[2])
      r = t;
  if(r < 0)
  {
    s << "of hexahedra " << a.hex << " and " << b.hex
      << " is not traversed in opposite directions by them (inconsistent orientation)";
    message = s.str();
    return false;
  }
  Dart e = b.dart;
  for(int t = 0; t < r; ++t)
    e = lcc.beta(e, 1);
  if(!lcc.template is_sewable<3>(a.dart, e))
  {
    s << "of hexahedra " << a.hex << " and " << b.hex << " cannot be 3-sewn";
    message = s.str();
    return false;
  }
  // the vertex attributes are already shared: sew the darts only
  lcc.template topo_sew<3>(a.dart, e);
  return true;
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization

/*!
\ingroup PkgHexahedralMeshOptimizationRef

\brief Builds a 3D linear cell complex from an indexed hexahedral mesh.

`lcc` is cleared first. Each input vertex gets one vertex attribute, created
in input order (so vertex `i` of `mesh` is the `i`-th element of
`lcc.vertex_attributes()`, isolated vertices included), and each hexahedron
becomes one 3-cell made by `make_hexahedron()` with the same geometry,
vertex for vertex (MEDIT/VTK order `m0..m7` maps to the arguments
`m0, m1, m2, m3, m7, m4, m5, m6`), in input order.

Two hexahedra sharing a face (same 4 vertex indices) are 3-sewn along it.
Faces are matched by vertex index, never by coordinates: unlike
`sew3_same_facets()`, a tangled mesh with coincident or crossing vertices is
sewn as its connectivity says. Faces of one hexahedron only stay 3-free (the
boundary).

The build fails, leaving `lcc` empty, when a hexahedron refers to a vertex
that does not exist, when 3 or more hexahedra share a face (non-manifold),
or when two hexahedra sharing a face do not induce opposite orientations on
it (a hexahedron numbered inside out: a combinatorial map is orientable).
Vertices where the mesh is not manifold (two blocks of hexahedra touching at
a vertex or an edge only) keep one shared attribute although they form
several 0-cells of the map: the positions stay shared, which is what the
optimisation needs, but `lcc.is_valid()` then reports the attribute as
shared between cells.

\tparam Point a point type of a CGAL kernel (converted if it differs from `LCC::Point`)
\tparam LCC `Linear_cell_complex_for_combinatorial_map<3,3,...>`

\param mesh the input mesh
\param lcc the output linear cell complex
\param error_message if not null, receives a one-line reason on failure

\returns `true` on success

\sa `indexed_hex_mesh_from_linear_cell_complex()`
*/
template <class Point, class LCC>
bool build_linear_cell_complex(const Indexed_hex_mesh<Point>& mesh, LCC& lcc,
                               std::string* error_message = nullptr)
{
  typedef typename LCC::Vertex_attribute_handle Vertex_handle;
  typedef typename LCC::Point LCC_point;
  static_assert(LCC::dimension == 3 && LCC::ambient_dimension == 3,
                "build_linear_cell_complex() needs a 3D linear cell complex in 3D");
  namespace HMO = Hexahedral_mesh_optimization::internal;

  lcc.clear();
  const typename LCC::Traits traits;
  std::vector<Vertex_handle> vertices;
  vertices.reserve(mesh.points.size());
  for(const Point& p : mesh.points)
    vertices.push_back(lcc.create_vertex_attribute(HMO::convert_point<LCC_point>(p, traits)));

  std::string message;
  std::vector<HMO::Lcc_face_record<LCC> > faces;
  bool ok = HMO::make_lcc_hexahedra(mesh.hexahedra, vertices, lcc, faces, message);
  if(ok)
  {
    // the faces with the same vertex set are consecutive: sew each pair
    std::sort(faces.begin(), faces.end());
    for(std::size_t i = 0; i < faces.size() && ok;)
    {
      std::size_t j = i + 1;
      while(j < faces.size() && faces[j].key == faces[i].key)
        ++j;
      ok = HMO::sew_lcc_faces(faces, i, j, lcc, message);
      i = j;
    }
  }
  if(!ok)
  {
    lcc.clear();
    if(error_message)
      *error_message = message;
  }
  return ok;
}

/*!
\ingroup PkgHexahedralMeshOptimizationRef

\brief Copies a 3D linear cell complex whose 3-cells are all hexahedra into an
indexed hexahedral mesh, in one pass over its darts.

`mesh` is cleared first. Vertex `i` of `mesh` is the `i`-th element of
`lcc.vertex_attributes()`, and the hexahedra follow the order of the 3-cells
(`lcc.one_dart_per_cell<3>()`), each in MEDIT/VTK order with the orientation
of the 3-cell. For a complex made by `build_linear_cell_complex()` this gives
back the original points and hexahedra exactly (the optional MEDIT entities
such as boundary quadrilaterals and references are not stored in the
complex and stay empty).

\tparam LCC `Linear_cell_complex_for_combinatorial_map<3,3,...>`
\tparam Point a point type of a CGAL kernel (converted if it differs from `LCC::Point`)

\param lcc the input linear cell complex
\param mesh the output mesh
\param error_message if not null, receives a one-line reason on failure

\returns `true` on success, `false` (with `mesh` empty) when a 3-cell is not a
combinatorial hexahedron or a dart has no vertex attribute

\sa `build_linear_cell_complex()`
*/
template <class LCC, class Point>
bool indexed_hex_mesh_from_linear_cell_complex(const LCC& lcc, Indexed_hex_mesh<Point>& mesh,
                                               std::string* error_message = nullptr)
{
  namespace HMO = Hexahedral_mesh_optimization::internal;
  mesh.clear();
  const typename Kernel_traits<Point>::Kernel traits;
  mesh.points.reserve(lcc.vertex_attributes().size());
  for(auto it = lcc.vertex_attributes().begin(), end = lcc.vertex_attributes().end(); it != end; ++it)
    mesh.points.push_back(HMO::convert_point<Point>(lcc.point_of_vertex_attribute(it), traits));
  if(!HMO::lcc_hexahedra(lcc, mesh.hexahedra, error_message))
  {
    mesh.clear();
    return false;
  }
  return true;
}

namespace Hexahedral_mesh_optimization {
namespace internal {

/// A 3D linear cell complex based on a combinatorial map, read through its
/// vertex attributes (vertex i = i-th attribute) and its 3-cells.
template <class Traits_, class Items_, class Alloc_,
          template <unsigned int, class, class, class, class> class CMap, class Storage_>
struct Hex_mesh_adapter<Linear_cell_complex_for_combinatorial_map<3, 3, Traits_, Items_, Alloc_, CMap, Storage_> >
{
  typedef Linear_cell_complex_for_combinatorial_map<3, 3, Traits_, Items_, Alloc_, CMap, Storage_> LCC;
  typedef typename LCC::Point Point;

  /// throws `std::invalid_argument` if a 3-cell is not a hexahedron
  template <class GeomTraits>
  static Hex_mesh_arrays extract(const LCC& lcc, const GeomTraits& gt)
  {
    return lcc_to_arrays(lcc, gt);
  }

  template <class GeomTraits>
  static void write_back(const Hex_mesh_arrays& a, LCC& lcc, const GeomTraits& gt)
  {
    std::size_t i = 0;
    for(auto it = lcc.vertex_attributes().begin(), end = lcc.vertex_attributes().end();
        it != end && i < a.points.size(); ++it, ++i)
      lcc.point_of_vertex_attribute(it) = to_point(a.points[i], gt);
  }
};

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_LINEAR_CELL_COMPLEX_HEX_MESH_H
