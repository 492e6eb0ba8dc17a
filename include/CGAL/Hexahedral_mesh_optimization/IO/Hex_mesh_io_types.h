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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_HEX_MESH_IO_TYPES_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_HEX_MESH_IO_TYPES_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The public types of the hex mesh I/O functions, in a header of their own
// so that the internal readers and writers can use them; users include
// <CGAL/Hexahedral_mesh_optimization/IO/hex_mesh_io.h>, which includes it.

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace IO {

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief Describes why reading or writing a hex mesh failed.

`line` is the 1-based line of the file where the problem lies, or 0 when no
line applies (the file cannot be opened, the problem concerns the whole mesh,
or the position is in binary data: the message then gives "byte N").
*/
struct Hex_mesh_io_error
{
  /// the file being read or written
  std::string file;
  /// 1-based line number, 0 if not applicable
  std::size_t line = 0;
  /// what went wrong, e.g. "Hexahedra record 17 (line 3203): vertex index 3181
  /// out of range (mesh has 3180 vertices)"
  std::string message;

  /// the error on a single line: "file:line: message", or "file: message"
  /// when `line` is 0
  std::string what() const
  {
    std::string s = file;
    if(line != 0)
    {
      s += ':';
      s += std::to_string(line);
    }
    if(!s.empty())
      s += ": ";
    s += message;
    return s;
  }
};

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief Named scalar fields written along with a hex mesh to VTK and VTU files,
for instance `{"scaled_jacobian", per-hexahedron values}`, so that ParaView
can colour the mesh by them.

Each cell field holds one value per hexahedron, each point field one value per
vertex, in the order of the mesh arrays.
*/
struct Hex_mesh_fields
{
  /// one value per hexahedron each
  std::vector<std::pair<std::string, std::vector<double> > > cell_scalars;
  /// one value per vertex each
  std::vector<std::pair<std::string, std::vector<double> > > point_scalars;

  bool empty() const { return cell_scalars.empty() && point_scalars.empty(); }
};

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief The version of the gmsh `.msh` files that `write_MSH()` writes.
*/
enum class Gmsh_version
{
  v2_2, ///< the legacy format 2.2, still read by most solvers' converters
  v4_1  ///< the current format 4.1 (default)
};

} // namespace IO
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_HEX_MESH_IO_TYPES_H
