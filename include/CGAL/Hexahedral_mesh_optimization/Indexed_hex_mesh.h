// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Package: Hexahedral_mesh_optimization

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INDEXED_HEX_MESH_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INDEXED_HEX_MESH_H

#include <array>
#include <cstddef>
#include <vector>

namespace CGAL {

/*!
\ingroup PkgHexahedralMeshOptimizationRef

\brief A plain indexed all-hexahedral mesh: an array of points and an array of
hexahedra, each given by 8 indices into the point array.

The vertex order of a hexahedron is the MEDIT/VTK order: vertices 0-3 form the
bottom face, and vertex `i+4` lies above vertex `i`. With this order a
well-shaped hexahedron has a positive Jacobian at every corner.

Besides the volume, a MEDIT file may carry boundary entities (quadrilaterals,
triangles, edges, corners and ridges) and integer references. They are kept so
that a mesh read and written again loses nothing; the optimisation functions
never change the connectivity, so these entities stay valid.

\tparam Point_3 a model of `Kernel::Point_3`
*/
template <class Point_3>
struct Indexed_hex_mesh
{
  typedef Point_3 Point;
  typedef std::array<std::size_t, 8> Hexahedron;
  typedef std::array<std::size_t, 4> Quadrilateral;
  typedef std::array<std::size_t, 3> Triangle;
  typedef std::array<std::size_t, 2> Edge;

  /// the vertex positions
  std::vector<Point> points;
  /// the hexahedra, 8 indices into `points` each (MEDIT/VTK order)
  std::vector<Hexahedron> hexahedra;

  /// \name Optional data carried by MEDIT files
  /// Empty when the file had none; a reference array is either empty or as
  /// long as the array it refers to.
  /// @{
  std::vector<int> point_references;
  std::vector<int> hexahedron_references;
  std::vector<Quadrilateral> quadrilaterals;
  std::vector<int> quadrilateral_references;
  std::vector<Triangle> triangles;
  std::vector<int> triangle_references;
  std::vector<Edge> edges;
  std::vector<int> edge_references;
  /// indices into `points`
  std::vector<std::size_t> corners;
  /// indices into `edges`
  std::vector<std::size_t> ridges;
  /// @}

  std::size_t number_of_vertices() const { return points.size(); }
  std::size_t number_of_hexahedra() const { return hexahedra.size(); }

  void clear()
  {
    *this = Indexed_hex_mesh();
  }
};

} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INDEXED_HEX_MESH_H
