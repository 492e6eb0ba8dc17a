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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INDEXED_HEX_MESH_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INDEXED_HEX_MESH_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

#include <array>
#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {

/*!
\ingroup PkgHexahedralMeshOptimizationRef

\brief A named set of indices (vertices or hexahedra of an `Indexed_hex_mesh`),
as the node sets and element sets of simulation formats (Abaqus `*NSET` and
`*ELSET`, Exodus II node sets).
*/
struct Named_index_set
{
  /// the name of the set in the file (Exodus node sets without a name get "nodeset_<id>")
  std::string name;
  /// 0-based indices into `points` or `hexahedra`
  std::vector<std::size_t> indices;
};

/*!
\ingroup PkgHexahedralMeshOptimizationRef

\brief A named set of hexahedron faces (an Exodus II side set, an Abaqus
element-based surface): each side is a hexahedron index and a local face
number 0..5.

The faces are numbered as in Exodus II (side `i+1` there), against the
vertex order of `Indexed_hex_mesh` (0-3 bottom, `i+4` above `i`): face 0 =
(0,1,5,4), 1 = (1,2,6,5), 2 = (2,3,7,6), 3 = (0,4,7,3), 4 = (0,3,2,1)
(bottom), 5 = (4,5,6,7) (top); the Abaqus faces of C3D8 are S3, S4, S5, S6,
S1, S2 in this order.
*/
struct Named_side_set
{
  /// the name of the set (Exodus side sets without a name get "sideset_<id>")
  std::string name;
  /// (0-based hexahedron index, local face 0..5)
  std::vector<std::pair<std::size_t, int> > sides;
};

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

  /// the integer reference of each vertex
  std::vector<int> point_references;
  /// the reference (group) of each hexahedron: see also the simulation formats below
  std::vector<int> hexahedron_references;
  /// boundary quadrilaterals, 4 indices into `points` each
  std::vector<Quadrilateral> quadrilaterals;
  /// the reference of each quadrilateral
  std::vector<int> quadrilateral_references;
  /// boundary triangles, 3 indices into `points` each
  std::vector<Triangle> triangles;
  /// the reference of each triangle
  std::vector<int> triangle_references;
  /// edges, 2 indices into `points` each
  std::vector<Edge> edges;
  /// the reference of each edge
  std::vector<int> edge_references;
  /// indices into `points`
  std::vector<std::size_t> corners;
  /// indices into `edges`
  std::vector<std::size_t> ridges;
  /// @}

  /// \name Optional data carried by simulation formats
  /// `hexahedron_references` above holds the group of each hexahedron: the
  /// MEDIT reference, the gmsh physical tag, the Exodus II element block id
  /// (0: none). The sets below survive a read and write in the formats that
  /// have them (Abaqus `.inp`, Exodus II) and are ignored by the others
  /// (gmsh keeps the references and their names only).
  /// @{

  /// names of hexahedron references (gmsh physical names, Exodus block names)
  std::map<int, std::string> hexahedron_reference_names;
  /// named vertex sets (Abaqus `*NSET`, Exodus node sets)
  std::vector<Named_index_set> vertex_sets;
  /// named hexahedron sets (Abaqus `*ELSET`)
  std::vector<Named_index_set> hexahedron_sets;
  /// named side sets (Exodus side sets, Abaqus element-based `*SURFACE`)
  std::vector<Named_side_set> side_sets;
  /// the ids of the vertices and hexahedra in the file read (gmsh node and
  /// element tags, Abaqus and Exodus ids), positive; empty, or as long as
  /// `points` / `hexahedra`. Writers of these formats reuse them when they
  /// are present, unique and positive, and number from 1 otherwise.
  std::vector<long long> point_ids;
  /// the ids of the hexahedra in the file read (see `point_ids`)
  std::vector<long long> hexahedron_ids;
  /// the Abaqus element type of the hexahedra (`C3D8`, `C3D8R`, `C3D8I`,
  /// `C3D8H`, ...); empty: `C3D8`
  std::string abaqus_element_type;
  /// @}

  /// the number of vertices
  std::size_t number_of_vertices() const { return points.size(); }
  /// the number of hexahedra
  std::size_t number_of_hexahedra() const { return hexahedra.size(); }

  /// empties the mesh, optional data included
  void clear()
  {
    *this = Indexed_hex_mesh();
  }
};

} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INDEXED_HEX_MESH_H
