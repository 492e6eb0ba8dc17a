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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_WRITE_INP_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_WRITE_INP_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Writer of Abaqus input files (.inp): *NODE, one *ELEMENT block of 8-node
// hexahedra, the vertex sets as *NSET, the hexahedron sets as *ELSET and the
// side sets as element-based *SURFACE.

#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Id_map.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/read_INP.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/write_file.h>
#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Kernel_traits.h>

#include <string>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {
namespace io {

/// a set name Abaqus accepts: no commas, blanks or '=' (replaced by '_'),
/// "SET_<n>" when empty
inline std::string inp_set_name(const std::string& name, std::size_t n)
{
  if(name.empty())
    return "SET_" + std::to_string(n);
  std::string r = name;
  for(char& c : r)
    if(c == ',' || c == '=' || c == '*' || is_blank(c))
      c = '_';
  return r;
}

inline void write_inp_set(Output_buffer& out, const char* keyword, const std::string& name,
                          const std::vector<std::size_t>& indices, const std::vector<long long>& ids)
{
  out << "*" << keyword << ", " << keyword << "=" << name << '\n';
  for(std::size_t i = 0; i < indices.size(); ++i)
    out << ids[indices[i]] << ((i % 16 == 15 || i + 1 == indices.size()) ? "\n" : ", ");
}

template <class Point>
bool write_INP_file(const std::string& fname, const Indexed_hex_mesh<Point>& mesh, CGAL::IO::Hex_mesh_io_error* err)
{
  if(!check_before_writing(fname, mesh, CGAL::IO::Hex_mesh_fields(), err))
    return false;
  const std::string type = mesh.abaqus_element_type.empty() ? std::string("C3D8") : mesh.abaqus_element_type;
  if(!is_abaqus_hex_type(type))
    return write_failure(fname, err, "Abaqus element type '" + type + "' is not an 8-node hexahedron (C3D8, C3D8R, C3D8I)");
  const std::vector<long long> node_ids = ids_for_writing(mesh.point_ids, mesh.points.size());
  const std::vector<long long> hex_ids = ids_for_writing(mesh.hexahedron_ids, mesh.hexahedra.size());
  return write_atomically(fname, err, [&](Output_buffer& out, std::string&) {
    const typename Kernel_traits<Point>::Kernel gt;
    out << "*HEADING\nhexahedral mesh written by CGAL Hexahedral_mesh_optimization\n*NODE\n";
    for(std::size_t i = 0; i < mesh.points.size(); ++i)
    {
      const Vec3 p = to_vec3(mesh.points[i], gt);
      out << node_ids[i] << ", " << p[0] << ", " << p[1] << ", " << p[2] << '\n';
    }
    out << "*ELEMENT, TYPE=" << type << '\n';
    for(std::size_t h = 0; h < mesh.hexahedra.size(); ++h)
    {
      out << hex_ids[h];
      for(std::size_t v : mesh.hexahedra[h])
        out << ", " << node_ids[v];
      out << '\n';
    }
    std::size_t n = 0;
    for(const Named_index_set& s : mesh.vertex_sets)
      if(!s.indices.empty())
        write_inp_set(out, "NSET", inp_set_name(s.name, ++n), s.indices, node_ids);
    for(const Named_index_set& s : mesh.hexahedron_sets)
      if(!s.indices.empty())
        write_inp_set(out, "ELSET", inp_set_name(s.name, ++n), s.indices, hex_ids);
    // side sets as element-based surfaces; local faces (Exodus numbering) as
    // the Abaqus faces of C3D8: 0 -> S3, 1 -> S4, 2 -> S5, 3 -> S6, 4 -> S1, 5 -> S2
    static const char* const abaqus_face[6] = {"S3", "S4", "S5", "S6", "S1", "S2"};
    for(const Named_side_set& s : mesh.side_sets)
      if(!s.sides.empty())
      {
        out << "*SURFACE, NAME=" << inp_set_name(s.name, ++n) << ", TYPE=ELEMENT\n";
        for(const auto& side : s.sides)
          out << hex_ids[side.first] << ", " << abaqus_face[side.second] << '\n';
      }
    return true;
  });
}

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_WRITE_INP_H
