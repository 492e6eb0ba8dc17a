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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_VALIDATE_HEX_MESH_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_VALIDATE_HEX_MESH_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/face_groups.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/scaled_jacobian.h>
#include <CGAL/Kernel_traits.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace CGAL {

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief The first defect `validate_hex_mesh()` finds in an `Indexed_hex_mesh`,
with enough detail for a reader to name the record of the file it came from.

Record numbers (`record`, `other_records`) are 0-based positions in the array
named by `section`. Vertex indices are those of the mesh (0-based);
`message()` can show them in the 1-based convention of MEDIT files.
*/
struct Hex_mesh_defect
{
  /// what is wrong
  enum Kind {
    NO_HEXAHEDRA,            ///< the mesh has no hexahedron
    NON_FINITE_COORDINATE,   ///< a coordinate is NaN or infinite
    REFERENCE_COUNT,         ///< a reference array is neither empty nor as long as its array
    INDEX_OUT_OF_RANGE,      ///< an index does not name an existing vertex (or edge, for ridges)
    REPEATED_VERTEX,         ///< a hexahedron uses the same vertex twice
    NON_MANIFOLD_FACE        ///< a quadrilateral face is shared by more than two hexahedra
  };

  /// the arrays of `Indexed_hex_mesh`, named as the MEDIT sections
  enum Section { VERTICES, HEXAHEDRA, QUADRILATERALS, TRIANGLES, EDGES, CORNERS, RIDGES };

  /// what is wrong
  Kind kind = NO_HEXAHEDRA;
  /// the array holding the offending element
  Section section = HEXAHEDRA;
  /// the offending element of `section` (0-based); 0 for `NO_HEXAHEDRA` and `REFERENCE_COUNT`
  std::size_t record = 0;
  /// `INDEX_OUT_OF_RANGE`, `REPEATED_VERTEX`: the index;
  /// `NON_FINITE_COORDINATE`: the axis (0, 1, 2); `REFERENCE_COUNT`: the number of references
  std::size_t value = 0;
  /// `INDEX_OUT_OF_RANGE`: the number of valid indices; `REFERENCE_COUNT`: the number of elements
  std::size_t bound = 0;
  /// `REPEATED_VERTEX`: the two positions (0-7) in the hexahedron
  std::array<std::size_t, 2> positions = {{0, 0}};
  /// `NON_FINITE_COORDINATE`: the value found
  double coordinate = 0.;
  /// `NON_MANIFOLD_FACE`: the face (sorted vertex indices) and the two
  /// hexahedra already sharing it (`record` is the third)
  std::array<std::size_t, 4> face = {{0, 0, 0, 0}};
  /// `NON_MANIFOLD_FACE`: the two hexahedra already sharing `face`
  std::array<std::size_t, 2> other_records = {{0, 0}};

  /// the MEDIT name of a section: "Vertices", "Hexahedra", ...
  static const char* section_name(Section s)
  {
    static const char* names[] = {"Vertices", "Hexahedra", "Quadrilaterals", "Triangles",
                                  "Edges", "Corners", "Ridges"};
    return names[s];
  }

  /// what is wrong, without saying where, e.g. "vertex 5 repeated (positions 1
  /// and 6)"; vertex indices are shown plus `index_base` (1 for MEDIT), other
  /// records plus `record_base`
  std::string message(std::size_t index_base = 0, std::size_t record_base = 0) const
  {
    std::ostringstream s;
    s.precision(std::numeric_limits<double>::max_digits10);
    switch(kind)
    {
    case NO_HEXAHEDRA:
      s << "the mesh has no hexahedra";
      break;
    case NON_FINITE_COORDINATE:
      s << "coordinate " << "xyz"[value % 3] << " is " << coordinate << " (not finite)";
      break;
    case REFERENCE_COUNT:
      s << value << " references for " << bound << " " << section_name(section)
        << " (expected none or one per element)";
      break;
    case INDEX_OUT_OF_RANGE:
    {
      const bool ridge = (section == RIDGES);
      s << (ridge ? "edge" : "vertex") << " index " << shown(value, index_base)
        << " out of range (mesh has " << bound << (ridge ? " edges)" : " vertices)");
      break;
    }
    case REPEATED_VERTEX:
      s << "vertex " << shown(value, index_base) << " repeated (positions " << positions[0] + 1
        << " and " << positions[1] + 1 << " of 8)";
      break;
    case NON_MANIFOLD_FACE:
      s << "non-manifold face (" << shown(face[0], index_base) << " " << shown(face[1], index_base)
        << " " << shown(face[2], index_base) << " " << shown(face[3], index_base)
        << ") shared by more than two hexahedra (also by records "
        << other_records[0] + record_base << " and " << other_records[1] + record_base << ")";
      break;
    }
    return s.str();
  }

  /// where and what, for a mesh in memory, e.g. "hexahedra[11]: vertex 5 repeated (positions 1 and 6 of 8)"
  std::string what() const
  {
    if(kind == NO_HEXAHEDRA)
      return message();
    std::string where = section_name(section);
    where[0] = static_cast<char>(where[0] - 'A' + 'a');
    if(kind != REFERENCE_COUNT)
      where += "[" + std::to_string(record) + "]";
    return where + ": " + message();
  }

private:
  // an index as the file showed it; a negative file index, stored wrapped
  // around, comes out negative again
  static long long shown(std::size_t v, std::size_t base)
  {
    return static_cast<long long>(v) + static_cast<long long>(base);
  }
};

namespace Hexahedral_mesh_optimization {
namespace internal {

template <class Element, class Ref>
bool check_reference_count(const std::vector<Element>& elements, const std::vector<Ref>& refs,
                           Hex_mesh_defect::Section section, Hex_mesh_defect& d)
{
  if(refs.empty() || refs.size() == elements.size())
    return true;
  d.kind = Hex_mesh_defect::REFERENCE_COUNT;
  d.section = section;
  d.value = refs.size();
  d.bound = elements.size();
  return false;
}

template <std::size_t N>
bool check_index_range(const std::vector<std::array<std::size_t, N> >& elements, std::size_t bound,
                       Hex_mesh_defect::Section section, Hex_mesh_defect& d)
{
  for(std::size_t i = 0; i < elements.size(); ++i)
    for(std::size_t v : elements[i])
      if(v >= bound)
      {
        d.kind = Hex_mesh_defect::INDEX_OUT_OF_RANGE;
        d.section = section;
        d.record = i;
        d.value = v;
        d.bound = bound;
        return false;
      }
  return true;
}

inline bool check_index_range(const std::vector<std::size_t>& elements, std::size_t bound,
                              Hex_mesh_defect::Section section, Hex_mesh_defect& d)
{
  for(std::size_t i = 0; i < elements.size(); ++i)
    if(elements[i] >= bound)
    {
      d.kind = Hex_mesh_defect::INDEX_OUT_OF_RANGE;
      d.section = section;
      d.record = i;
      d.value = elements[i];
      d.bound = bound;
      return false;
    }
  return true;
}

/// every quadrilateral face in at most two hexahedra
template <class Hexahedra>
bool check_manifold_faces(const Hexahedra& hexes, Hex_mesh_defect& d)
{
  // the first hexahedron, in index order, whose face two others already
  // have: over the groups of equal faces (face_groups.h), the smallest
  // third face id
  std::size_t vertices = 0;
  for(const auto& h : hexes)
    for(std::size_t v : h) vertices = (std::max)(vertices, std::size_t(v) + 1);
  const std::size_t none = (std::numeric_limits<std::size_t>::max)();
  std::size_t third = none;
  for_each_face_group(hexes, vertices, [&](const std::array<std::size_t, 4>& key, const std::size_t* ids,
                                           std::size_t count) {
    if(count < 3 || ids[2] >= third) return;
    third = ids[2];
    d.face = key;
    d.other_records = {{ids[0] / 6, ids[1] / 6}};
  });
  if(third != none)
  {
    d.kind = Hex_mesh_defect::NON_MANIFOLD_FACE;
    d.section = Hex_mesh_defect::HEXAHEDRA;
    d.record = third / 6;
    return false;
  }
  return true;
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief Checks that `mesh` is a hex mesh the package can work on, and reports
the first defect found.

The checks, in this order:
- there is at least one hexahedron;
- every coordinate is finite (no NaN, no infinity);
- every reference array is empty or as long as the array it refers to;
- every hexahedron index names a vertex, and no hexahedron uses a vertex twice;
- the indices of the optional arrays are in range (quadrilaterals, triangles,
  edges and corners into `points`, ridges into `edges`);
- every quadrilateral face is shared by at most two hexahedra (the volume is
  a manifold).

The cost is linear in the size of the mesh (the faces are bucketed by their
smallest vertex).

\tparam Point a model of `Kernel::Point_3`
\param mesh the mesh to check
\param defect receives the first defect found; unchanged when the mesh is valid
\return `true` if `mesh` has no defect
*/
template <class Point>
bool validate_hex_mesh(const Indexed_hex_mesh<Point>& mesh, Hex_mesh_defect& defect)
{
  namespace HMO = Hexahedral_mesh_optimization::internal;
  typedef Hex_mesh_defect D;
  D d;
  if(mesh.hexahedra.empty())
  {
    defect = d;
    return false;
  }

  const typename Kernel_traits<Point>::Kernel gt;
  for(std::size_t i = 0; i < mesh.points.size(); ++i)
  {
    const HMO::Vec3 p = HMO::to_vec3(mesh.points[i], gt);
    for(std::size_t a = 0; a < 3; ++a)
      if(!std::isfinite(p[a]))
      {
        d.kind = D::NON_FINITE_COORDINATE;
        d.section = D::VERTICES;
        d.record = i;
        d.value = a;
        d.coordinate = p[a];
        defect = d;
        return false;
      }
  }

  const bool references_ok =
    HMO::check_reference_count(mesh.points, mesh.point_references, D::VERTICES, d) &&
    HMO::check_reference_count(mesh.hexahedra, mesh.hexahedron_references, D::HEXAHEDRA, d) &&
    HMO::check_reference_count(mesh.quadrilaterals, mesh.quadrilateral_references, D::QUADRILATERALS, d) &&
    HMO::check_reference_count(mesh.triangles, mesh.triangle_references, D::TRIANGLES, d) &&
    HMO::check_reference_count(mesh.edges, mesh.edge_references, D::EDGES, d);
  if(!references_ok)
  {
    defect = d;
    return false;
  }

  const std::size_t nv = mesh.points.size();
  for(std::size_t h = 0; h < mesh.hexahedra.size(); ++h)
  {
    const typename Indexed_hex_mesh<Point>::Hexahedron& hex = mesh.hexahedra[h];
    for(std::size_t i = 0; i < 8; ++i)
    {
      if(hex[i] >= nv)
      {
        d.kind = D::INDEX_OUT_OF_RANGE;
        d.section = D::HEXAHEDRA;
        d.record = h;
        d.value = hex[i];
        d.bound = nv;
        defect = d;
        return false;
      }
      for(std::size_t j = 0; j < i; ++j)
        if(hex[j] == hex[i])
        {
          d.kind = D::REPEATED_VERTEX;
          d.section = D::HEXAHEDRA;
          d.record = h;
          d.value = hex[i];
          d.positions = {{j, i}};
          defect = d;
          return false;
        }
    }
  }

  const bool ranges_ok =
    HMO::check_index_range(mesh.quadrilaterals, nv, D::QUADRILATERALS, d) &&
    HMO::check_index_range(mesh.triangles, nv, D::TRIANGLES, d) &&
    HMO::check_index_range(mesh.edges, nv, D::EDGES, d) &&
    HMO::check_index_range(mesh.corners, nv, D::CORNERS, d) &&
    HMO::check_index_range(mesh.ridges, mesh.edges.size(), D::RIDGES, d);
  if(!ranges_ok || !HMO::check_manifold_faces(mesh.hexahedra, d))
  {
    defect = d;
    return false;
  }
  return true;
}

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief Checks that `mesh` is a valid hex mesh (see the overload taking a
`Hex_mesh_defect`), and describes the first defect found.

\param mesh the mesh to check
\param problem if not null and the mesh is invalid, receives a one-line
       description such as "hexahedra[11]: vertex 5 repeated (positions 1 and 6 of 8)"
\return `true` if `mesh` has no defect
*/
template <class Point>
bool validate_hex_mesh(const Indexed_hex_mesh<Point>& mesh, std::string* problem = nullptr)
{
  Hex_mesh_defect d;
  if(validate_hex_mesh(mesh, d))
    return true;
  if(problem != nullptr)
    *problem = d.what();
  return false;
}

} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_VALIDATE_HEX_MESH_H
