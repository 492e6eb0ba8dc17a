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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_WRITE_MEDIT_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_WRITE_MEDIT_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Writer of ASCII MEDIT (.mesh) files, with the optional boundary sections
// and references of the mesh. Indices are written 1-based.

#include <CGAL/Hexahedral_mesh_optimization/IO/internal/write_file.h>
#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Kernel_traits.h>

#include <array>
#include <string>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {
namespace io {

/// one record per line: the 1-based indices, then the reference (0 if none)
template <std::size_t N>
void write_medit_elements(Output_buffer& out, const char* keyword,
                          const std::vector<std::array<std::size_t, N> >& elements,
                          const std::vector<int>& references)
{
  if(elements.empty())
    return;
  out << "\n" << keyword << "\n" << elements.size() << '\n';
  for(std::size_t i = 0; i < elements.size(); ++i)
  {
    for(std::size_t v : elements[i])
      out << v + 1 << ' ';
    out << (references.empty() ? 0 : references[i]) << '\n';
  }
}

inline void write_medit_indices(Output_buffer& out, const char* keyword, const std::vector<std::size_t>& indices)
{
  if(indices.empty())
    return;
  out << "\n" << keyword << "\n" << indices.size() << '\n';
  for(std::size_t v : indices)
    out << v + 1 << '\n';
}

template <class Point>
bool write_MEDIT_file(const std::string& fname, const Indexed_hex_mesh<Point>& mesh,
                      CGAL::IO::Hex_mesh_io_error* err)
{
  if(!check_before_writing(fname, mesh, CGAL::IO::Hex_mesh_fields(), err))
    return false;
  return write_atomically(fname, err, [&mesh](Output_buffer& out, std::string&) {
    const typename Kernel_traits<Point>::Kernel gt;
    // version 2: coordinates in double precision
    out << "MeshVersionFormatted 2\nDimension 3\n\nVertices\n" << mesh.points.size() << '\n';
    for(std::size_t i = 0; i < mesh.points.size(); ++i)
    {
      const Vec3 p = to_vec3(mesh.points[i], gt);
      out << p[0] << ' ' << p[1] << ' ' << p[2] << ' '
          << (mesh.point_references.empty() ? 0 : mesh.point_references[i]) << '\n';
    }
    write_medit_elements(out, "Edges", mesh.edges, mesh.edge_references);
    write_medit_elements(out, "Triangles", mesh.triangles, mesh.triangle_references);
    write_medit_elements(out, "Quadrilaterals", mesh.quadrilaterals, mesh.quadrilateral_references);
    write_medit_elements(out, "Hexahedra", mesh.hexahedra, mesh.hexahedron_references);
    write_medit_indices(out, "Corners", mesh.corners);
    write_medit_indices(out, "Ridges", mesh.ridges);
    out << "\nEnd\n";
    return true;
  });
}

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_WRITE_MEDIT_H
