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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_LCC_HEX_MESH_IO_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_LCC_HEX_MESH_IO_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Reading and writing a hex mesh stored in a 3D linear cell complex, through
// an `Indexed_hex_mesh` (the formats are those of `IO/hex_mesh_io.h`).

#include <CGAL/Hexahedral_mesh_optimization/IO/hex_mesh_io.h>
#include <CGAL/Hexahedral_mesh_optimization/Linear_cell_complex_hex_mesh.h>

#include <CGAL/Linear_cell_complex_for_combinatorial_map.h>

#include <string>
#include <vector>

namespace CGAL {
namespace IO {

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief Reads a hexahedral mesh file (the formats of `read_hex_mesh()` for
`Indexed_hex_mesh`) into a 3D linear cell complex, built by
`build_linear_cell_complex()`: one vertex attribute per file vertex in file
order, one 3-cell per hexahedron in file order, 3-sewn by vertex index.

`lcc` is cleared first, and left empty on failure.

\tparam LCC `Linear_cell_complex_for_combinatorial_map<3,3,...>`

\param fname the file name
\param lcc the output linear cell complex
\param err if not null, receives the reason of a failure; a mesh that reads
  but cannot become a linear cell complex (3 hexahedra on a face,
  inconsistent orientation) is reported with line 0
\param warnings if not null, receives the reader's warnings

\returns `true` on success
*/
template <class Traits_, class Items_, class Alloc_,
          template <unsigned int, class, class, class, class> class CMap, class Storage_>
bool read_hex_mesh(const std::string& fname,
                   Linear_cell_complex_for_combinatorial_map<3, 3, Traits_, Items_, Alloc_, CMap, Storage_>& lcc,
                   Hex_mesh_io_error* err = nullptr,
                   std::vector<std::string>* warnings = nullptr)
{
  typedef typename Linear_cell_complex_for_combinatorial_map<3, 3, Traits_, Items_, Alloc_, CMap, Storage_>::Point Point;
  lcc.clear();
  Indexed_hex_mesh<Point> mesh;
  if(!read_hex_mesh(fname, mesh, err, warnings))
    return false;
  std::string message;
  if(!build_linear_cell_complex(mesh, lcc, &message))
  {
    if(err)
    {
      err->file = fname;
      err->line = 0;
      err->message = message;
    }
    return false;
  }
  return true;
}

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief Writes a 3D linear cell complex whose 3-cells are hexahedra to a file
(the formats of `write_hex_mesh()` for `Indexed_hex_mesh`), through
`indexed_hex_mesh_from_linear_cell_complex()`: vertex `i` is the `i`-th vertex
attribute and the hexahedra follow the 3-cells, which is also the order of
the values of `fields`.

\tparam LCC `Linear_cell_complex_for_combinatorial_map<3,3,...>`

\param fname the file name
\param lcc the linear cell complex
\param fields scalar fields written along (VTK and VTU only)
\param err if not null, receives the reason of a failure (a 3-cell that is
  not a hexahedron is reported with line 0)

\returns `true` on success
*/
template <class Traits_, class Items_, class Alloc_,
          template <unsigned int, class, class, class, class> class CMap, class Storage_>
bool write_hex_mesh(const std::string& fname,
                    const Linear_cell_complex_for_combinatorial_map<3, 3, Traits_, Items_, Alloc_, CMap, Storage_>& lcc,
                    const Hex_mesh_fields& fields = Hex_mesh_fields(),
                    Hex_mesh_io_error* err = nullptr)
{
  typedef typename Linear_cell_complex_for_combinatorial_map<3, 3, Traits_, Items_, Alloc_, CMap, Storage_>::Point Point;
  Indexed_hex_mesh<Point> mesh;
  std::string message;
  if(!indexed_hex_mesh_from_linear_cell_complex(lcc, mesh, &message))
  {
    if(err)
    {
      err->file = fname;
      err->line = 0;
      err->message = message;
    }
    return false;
  }
  return write_hex_mesh(fname, mesh, fields, err);
}

} // namespace IO
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_LCC_HEX_MESH_IO_H
