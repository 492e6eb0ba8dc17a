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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_WRITE_VTU_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_WRITE_VTU_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Writer of VTK XML unstructured grids (.vtu) with ascii data arrays: the
// points, the hexahedra (connectivity, offsets, types = 12) and the scalar
// fields as CellData and PointData, the first of each marked as the active
// scalars so that ParaView colours the mesh by it.

#include <CGAL/Hexahedral_mesh_optimization/IO/internal/write_file.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/vtk_cells.h>
#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Kernel_traits.h>

#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {
namespace io {

/// text for an XML attribute value
inline std::string xml_escaped(const std::string& s)
{
  std::string r;
  for(char c : s)
  {
    switch(c)
    {
    case '&': r += "&amp;"; break;
    case '<': r += "&lt;"; break;
    case '>': r += "&gt;"; break;
    case '"': r += "&quot;"; break;
    case '\'': r += "&apos;"; break;
    default: r += c;
    }
  }
  return r;
}

inline void write_vtu_fields(Output_buffer& out, const char* element,
                             const std::vector<std::pair<std::string, std::vector<double> > >& fields)
{
  if(fields.empty())
    return;
  out << "      <" << element << " Scalars=\"" << xml_escaped(fields.front().first) << "\">\n";
  for(const auto& f : fields)
  {
    out << "        <DataArray type=\"Float64\" Name=\"" << xml_escaped(f.first) << "\" format=\"ascii\">\n";
    for(std::size_t i = 0; i < f.second.size(); ++i)
      out << f.second[i] << ((i % 8 == 7 || i + 1 == f.second.size()) ? '\n' : ' ');
    out << "        </DataArray>\n";
  }
  out << "      </" << element << ">\n";
}

template <class Point>
bool write_VTU_file(const std::string& fname, const Indexed_hex_mesh<Point>& mesh,
                    const CGAL::IO::Hex_mesh_fields& fields, CGAL::IO::Hex_mesh_io_error* err)
{
  if(!check_before_writing(fname, mesh, fields, err))
    return false;
  return write_atomically(fname, err, [&](Output_buffer& out, std::string&) {
    const typename Kernel_traits<Point>::Kernel gt;
    const std::size_t nh = mesh.hexahedra.size();
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "  <UnstructuredGrid>\n"
        << "    <Piece NumberOfPoints=\"" << mesh.points.size() << "\" NumberOfCells=\"" << nh << "\">\n";
    write_vtu_fields(out, "PointData", fields.point_scalars);
    write_vtu_fields(out, "CellData", fields.cell_scalars);

    out << "      <Points>\n"
        << "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for(const Point& point : mesh.points)
    {
      const Vec3 p = to_vec3(point, gt);
      out << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
    }
    out << "        </DataArray>\n      </Points>\n      <Cells>\n"
        << "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for(const auto& h : mesh.hexahedra)
    {
      for(std::size_t j = 0; j < 8; ++j)
        out << h[j] << (j == 7 ? '\n' : ' ');
    }
    out << "        </DataArray>\n"
        << "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for(std::size_t i = 0; i < nh; ++i)
      out << 8 * (i + 1) << ((i % 8 == 7 || i + 1 == nh) ? '\n' : ' ');
    out << "        </DataArray>\n"
        << "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for(std::size_t i = 0; i < nh; ++i)
      out << static_cast<int>(VTK_HEXAHEDRON_TYPE) << ((i % 16 == 15 || i + 1 == nh) ? '\n' : ' ');
    out << "        </DataArray>\n      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
    return true;
  });
}

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_WRITE_VTU_H
