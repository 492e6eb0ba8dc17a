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
#include <CGAL/Linear_cell_complex_for_generalized_map.h>

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
/// of `d` is a combinatorial hexahedron: six quadrilaterals glued as
/// `make_hexahedron()` glues them. Written with the moves CGAL offers on
/// both kinds of map (`next`, `previous`, `opposite<2>`: beta1, beta0 and
/// beta2 of a combinatorial map, alpha01, alpha10 and alpha02 of a
/// generalized map), so that it walks both. Marks the darts of the volume
/// with `mark`, both orientations of a generalized map (a dart already
/// marked means the volume is not a hexahedron). Returns false when it is
/// not one.
template <class LCC, class Dart>
bool lcc_hexahedron_faces_checked(const LCC& lcc, Dart d, std::array<Dart, 6>& f,
                                  typename LCC::size_type mark)
{
  auto nx = [&lcc](Dart x) { return lcc.next(x); };
  auto pv = [&lcc](Dart x) { return lcc.previous(x); };
  auto op2 = [&lcc](Dart x) { return lcc.template opposite<2>(x); };
  auto free2 = [&lcc](Dart x) { return !lcc.template is_opposite_exist<2>(x); };
  auto is_quad = [&](Dart x) {
    return lcc.is_next_exist(x) && lcc.is_next_exist(nx(x)) && lcc.is_next_exist(nx(nx(x))) &&
           lcc.is_next_exist(nx(nx(nx(x)))) && nx(nx(nx(nx(x)))) == x && lcc.is_previous_exist(x);
  };
  if(!is_quad(d))
    return false;
  // F2, F4, F5, F6 through the opposite links of F1, then F3
  if(free2(d) || free2(nx(d)) || free2(nx(nx(d))) || free2(pv(d)))
    return false;
  f[0] = d;
  f[1] = op2(nx(nx(d)));
  f[3] = nx(nx(op2(d)));
  f[4] = op2(pv(d));
  f[5] = nx(op2(nx(d)));
  for(int i : {1, 3, 4, 5})
    if(!is_quad(f[i]))
      return false;
  if(free2(nx(nx(f[1]))))
    return false;
  f[2] = op2(nx(nx(f[1])));
  if(!is_quad(f[2]))
    return false;
  // the remaining links of make_combinatorial_hexahedron
  if(op2(f[2]) != nx(nx(f[1])) ||
     op2(nx(f[2])) != nx(f[5]) ||
     op2(nx(nx(f[2]))) != f[3] ||
     op2(pv(f[2])) != nx(nx(f[4])) ||
     op2(f[5]) != nx(f[3]) ||
     op2(nx(nx(f[5]))) != nx(f[1]) ||
     op2(pv(f[4])) != pv(f[3]) ||
     op2(nx(f[4])) != pv(f[1]))
    return false;
  // 24 distinct darts (48 in a generalized map)
  for(int i = 0; i < 6; ++i)
  {
    Dart x = f[i];
    for(int k = 0; k < 4; ++k, x = nx(x))
    {
      if(lcc.is_marked(x, mark))
        return false;
      lcc.mark(x, mark);
      const Dart y = lcc.other_orientation(x);
      if(y != x)
      {
        if(lcc.is_marked(y, mark))
          return false;
        lcc.mark(y, mark);
      }
    }
  }
  return true;
}

/// whether `LCC` is based on a generalized map (specialised below)
template <class LCC>
struct Is_generalized_map_lcc : std::false_type {};

template <class Traits_, class Items_, class Alloc_,
          template <unsigned int, class, class, class, class> class GMap, class Storage_>
struct Is_generalized_map_lcc<Linear_cell_complex_for_generalized_map<3, 3, Traits_, Items_, Alloc_, GMap, Storage_> >
  : std::true_type {};

/// Walks every 3-cell of `lcc` once, in the order of its first dart in
/// `lcc.darts()` (for a combinatorial map, the order of
/// `lcc.one_dart_per_cell<3>()`), calls `fun(faces, dart)` with the six face
/// darts (F1..F6) of each. A generalized map has two orientations: the walk
/// starts from the darts of one class (`skip`: the darts of the other).
/// Returns false, with a message, when a 3-cell is not a hexahedron.
template <class LCC, class Skip, class Function>
bool for_each_lcc_hexahedron(const LCC& lcc, Skip skip, Function fun, std::string* message)
{
  typedef typename LCC::Dart_const_handle Dart;
  const typename LCC::size_type mark = lcc.get_new_mark();
  bool ok = true;
  std::size_t h = 0;
  std::array<Dart, 6> faces;
  for(auto it = lcc.darts().begin(), end = lcc.darts().end(); it != end; ++it)
  {
    Dart d = it;
    if(lcc.is_marked(d, mark) || skip(d))
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
    fun(faces, d);
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

/// Of a generalized map: the darts at an odd number of alpha moves from the
/// first dart of their connected component (marked with `odd`), and the
/// component of each dart, numbered in the order of `lcc.darts()`.
template <class LCC>
std::unordered_map<typename LCC::Dart_const_handle, std::size_t>
gmap_orientation_classes(const LCC& lcc, typename LCC::size_type odd)
{
  typedef typename LCC::Dart_const_handle Dart;
  std::unordered_map<Dart, std::size_t> component;
  component.reserve(lcc.number_of_darts());
  std::size_t c = 0;
  std::vector<Dart> stack;
  for(auto it = lcc.darts().begin(), end = lcc.darts().end(); it != end; ++it)
  {
    if(component.count(it)) continue;
    component.emplace(it, c);
    stack.push_back(it);
    while(!stack.empty())
    {
      const Dart x = stack.back();
      stack.pop_back();
      const bool x_odd = lcc.is_marked(x, odd);
      const Dart next[4] = {lcc.template alpha<0>(x), lcc.template alpha<1>(x), lcc.template alpha<2>(x),
                            lcc.template alpha<3>(x)};
      for(const Dart y : next)
      {
        if(y == x || component.count(y)) continue; // free, or seen
        component.emplace(y, c);
        if(!x_odd) lcc.mark(y, odd);
        stack.push_back(y);
      }
    }
    ++c;
  }
  return component;
}

/// The hexahedra of `lcc` as MEDIT/VTK-ordered vertex indices (vertex i is
/// the i-th vertex attribute), in 3-cell order. In a generalized map, the
/// orientation of each connected component is the one of its two under
/// which the sum of the corner Jacobian determinants of its hexahedra is
/// not negative (a combinatorial map has its orientation in its darts).
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
  auto walk = [&](const std::array<Dart, 6>& f) {
    // m0 = p0, m1 = p1, m2 = p2, m3 = p3, m4 = p5, m5 = p6, m6 = p7, m7 = p4
    hexes.push_back({vertex(f[0]), vertex(lcc.previous(f[0])), vertex(lcc.previous(f[1])),
                     vertex(lcc.previous(f[4])), vertex(lcc.next(f[0])),
                     vertex(lcc.next(lcc.next(f[0]))), vertex(lcc.next(lcc.next(f[1]))),
                     vertex(lcc.next(f[5]))});
  };
  bool ok = true;
  if constexpr(!Is_generalized_map_lcc<LCC>::value)
    ok = for_each_lcc_hexahedron(lcc, [](Dart) { return false; },
                                 [&](const std::array<Dart, 6>& f, Dart) { walk(f); }, message);
  else
  {
    const typename LCC::size_type odd = lcc.get_new_mark();
    const auto component = gmap_orientation_classes(lcc, odd);
    std::vector<std::size_t> hex_component;
    ok = for_each_lcc_hexahedron(lcc, [&](Dart d) { return lcc.is_marked(d, odd); },
                                 [&](const std::array<Dart, 6>& f, Dart d) {
                                   walk(f);
                                   hex_component.push_back(component.at(d));
                                 }, message);
    lcc.unmark_all(odd);
    lcc.free_mark(odd);
    if(ok && !missing)
    {
      // the orientation of each component: the sign of its total corner determinant
      typedef typename Kernel_traits<typename LCC::Point>::Kernel Kernel;
      std::vector<Vec3> points;
      for(auto it = lcc.vertex_attributes().begin(), end = lcc.vertex_attributes().end(); it != end; ++it)
        points.push_back(to_vec3(lcc.point_of_vertex_attribute(it), Kernel()));
      std::vector<double> sum;
      static const int corner_edges[8][3] = {{1, 3, 4}, {2, 0, 5}, {3, 1, 6}, {0, 2, 7},
                                             {7, 5, 0}, {4, 6, 1}, {5, 7, 2}, {6, 4, 3}};
      for(std::size_t h = 0; h < hexes.size(); ++h)
      {
        if(hex_component[h] >= sum.size()) sum.resize(hex_component[h] + 1, 0.);
        for(int c = 0; c < 8; ++c)
        {
          const Vec3& o = points[hexes[h][c]];
          sum[hex_component[h]] += dot(cross(points[hexes[h][corner_edges[c][0]]] - o,
                                             points[hexes[h][corner_edges[c][1]]] - o),
                                       points[hexes[h][corner_edges[c][2]]] - o);
        }
      }
      for(std::size_t h = 0; h < hexes.size(); ++h)
        if(sum[hex_component[h]] < 0.)
        {
          std::swap(hexes[h][1], hexes[h][3]);
          std::swap(hexes[h][5], hexes[h][7]);
        }
    }
  }
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

/// the points of a linear cell complex, by vertex attribute
template <class LCC>
struct Lcc_point_map
{
  typedef typename LCC::Vertex_attribute_const_handle key_type;
  typedef typename LCC::Point value_type;
  typedef const value_type& reference;
  typedef boost::read_write_property_map_tag category;
  friend reference get(const Lcc_point_map&, key_type v) { return v->point(); }
  /// (the complex is not const when it is written: its attributes are not)
  friend void put(const Lcc_point_map&, key_type v, const value_type& p) { const_cast<value_type&>(v->point()) = p; }
};

/// A 3D linear cell complex, based on a combinatorial or a generalized map,
/// read through its vertex attributes (vertex i = i-th attribute, the key
/// of its vertex property maps is `Vertex_attribute_const_handle`) and its
/// 3-cells.
template <class LCC>
struct Lcc_hex_mesh_adapter
{
  typedef typename LCC::Point Point;
  typedef typename LCC::Vertex_attribute_const_handle vertex_descriptor;
  typedef Lcc_point_map<LCC> Default_vertex_point_map;

  static std::vector<vertex_descriptor> vertices(const LCC& lcc)
  {
    std::vector<vertex_descriptor> v;
    v.reserve(lcc.vertex_attributes().size());
    for(auto it = lcc.vertex_attributes().begin(), end = lcc.vertex_attributes().end(); it != end; ++it)
      v.push_back(it);
    return v;
  }
  /// throws `std::invalid_argument` if a 3-cell is not a hexahedron
  static void hexahedra(const LCC& lcc, std::vector<Hex>& hexes)
  {
    std::string message;
    if(!lcc_hexahedra(lcc, hexes, &message))
      throw std::invalid_argument(message);
  }
  static Default_vertex_point_map vertex_point_map(const LCC&) { return Default_vertex_point_map(); }
};

template <class Traits_, class Items_, class Alloc_,
          template <unsigned int, class, class, class, class> class CMap, class Storage_>
struct Is_hex_mesh<Linear_cell_complex_for_combinatorial_map<3, 3, Traits_, Items_, Alloc_, CMap, Storage_> >
  : std::true_type {};

template <class Traits_, class Items_, class Alloc_,
          template <unsigned int, class, class, class, class> class GMap, class Storage_>
struct Is_hex_mesh<Linear_cell_complex_for_generalized_map<3, 3, Traits_, Items_, Alloc_, GMap, Storage_> >
  : std::true_type {};

template <class Traits_, class Items_, class Alloc_,
          template <unsigned int, class, class, class, class> class CMap, class Storage_>
struct Hex_mesh_adapter<Linear_cell_complex_for_combinatorial_map<3, 3, Traits_, Items_, Alloc_, CMap, Storage_> >
  : Lcc_hex_mesh_adapter<Linear_cell_complex_for_combinatorial_map<3, 3, Traits_, Items_, Alloc_, CMap, Storage_> >
{};

template <class Traits_, class Items_, class Alloc_,
          template <unsigned int, class, class, class, class> class GMap, class Storage_>
struct Hex_mesh_adapter<Linear_cell_complex_for_generalized_map<3, 3, Traits_, Items_, Alloc_, GMap, Storage_> >
  : Lcc_hex_mesh_adapter<Linear_cell_complex_for_generalized_map<3, 3, Traits_, Items_, Alloc_, GMap, Storage_> >
{};

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_LINEAR_CELL_COMPLEX_HEX_MESH_H
