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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_WRITE_VTK_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_WRITE_VTK_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Writer of legacy VTK (.vtk) unstructured grids, ASCII or BINARY (big-endian
// doubles and 32-bit integers, as the format requires), with the scalar
// fields as CELL_DATA and POINT_DATA.

#include <CGAL/Hexahedral_mesh_optimization/IO/internal/write_file.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/vtk_cells.h>
#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Kernel_traits.h>

#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {
namespace io {

/// legacy VTK names are single tokens: blanks and '%' are written as %XX,
/// which VTK's reader decodes
inline std::string vtk_legacy_name(const std::string& name)
{
  static const char hex[] = "0123456789ABCDEF";
  std::string r;
  for(char c : name)
  {
    const unsigned char u = static_cast<unsigned char>(c);
    if(u <= ' ' || u == '%' || u >= 127)
    {
      r += '%';
      r += hex[u >> 4];
      r += hex[u & 15];
    }
    else
      r += c;
  }
  return r;
}

inline void write_vtk_scalars(Output_buffer& out, bool binary, const char* section, std::size_t n,
                              const std::vector<std::pair<std::string, std::vector<double> > >& fields)
{
  if(fields.empty())
    return;
  out << section << ' ' << n << '\n';
  for(const auto& f : fields)
  {
    out << "SCALARS " << vtk_legacy_name(f.first) << " double 1\nLOOKUP_TABLE default\n";
    for(double v : f.second)
    {
      if(binary)
        out.big_endian_double(v);
      else
        out << v << '\n';
    }
    if(binary)
      out << '\n';
  }
}

template <class Point>
bool write_VTK_file(const std::string& fname, const Indexed_hex_mesh<Point>& mesh,
                    const CGAL::IO::Hex_mesh_fields& fields, CGAL::IO::Hex_mesh_io_error* err, bool binary)
{
  if(!check_before_writing(fname, mesh, fields, err))
    return false;
  const std::size_t int32_max = static_cast<std::size_t>((std::numeric_limits<std::int32_t>::max)());
  if(binary && (mesh.points.size() > int32_max || 9 * mesh.hexahedra.size() > int32_max))
    return write_failure(fname, err, "mesh too large for the 32-bit integers of binary legacy VTK");

  return write_atomically(fname, err, [&](Output_buffer& out, std::string&) {
    const typename Kernel_traits<Point>::Kernel gt;
    const std::size_t nv = mesh.points.size(), nh = mesh.hexahedra.size();
    out << "# vtk DataFile Version 3.0\nHexahedral mesh\n" << (binary ? "BINARY" : "ASCII")
        << "\nDATASET UNSTRUCTURED_GRID\nPOINTS " << nv << " double\n";
    for(const Point& point : mesh.points)
    {
      const Vec3 p = to_vec3(point, gt);
      if(binary)
        for(double c : p)
          out.big_endian_double(c);
      else
        out << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
    }
    if(binary)
      out << '\n';

    out << "CELLS " << nh << ' ' << 9 * nh << '\n';
    for(const auto& h : mesh.hexahedra)
    {
      if(binary)
      {
        out.big_endian_int32(8);
        for(std::size_t v : h)
          out.big_endian_int32(static_cast<std::int32_t>(v));
      }
      else
      {
        out << '8';
        for(std::size_t v : h)
          out << ' ' << v;
        out << '\n';
      }
    }
    if(binary)
      out << '\n';

    out << "CELL_TYPES " << nh << '\n';
    for(std::size_t i = 0; i < nh; ++i)
    {
      if(binary)
        out.big_endian_int32(VTK_HEXAHEDRON_TYPE);
      else
        out << "12\n";
    }
    if(binary)
      out << '\n';

    write_vtk_scalars(out, binary, "CELL_DATA", nh, fields.cell_scalars);
    write_vtk_scalars(out, binary, "POINT_DATA", nv, fields.point_scalars);
    return true;
  });
}

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_WRITE_VTK_H
