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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_WRITE_FILE_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_WRITE_FILE_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The steps every writer shares: refuse an invalid mesh or inconsistent
// fields, then produce the file atomically (see Atomic_output_file).

#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Atomic_output_file.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/Hex_mesh_io_types.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Output_buffer.h>
#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/Hexahedral_mesh_optimization/validate_hex_mesh.h>

#include <exception>
#include <new>
#include <string>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {
namespace io {

inline bool write_failure(const std::string& fname, CGAL::IO::Hex_mesh_io_error* err, const std::string& message)
{
  if(err != nullptr)
  {
    err->file = fname;
    err->line = 0;
    err->message = message;
  }
  return false;
}

/// runs a writer, turning an exception (out of memory) into an error
template <class Write>
bool guarded_write(const std::string& fname, CGAL::IO::Hex_mesh_io_error* err, const Write& write)
{
  try
  {
    return write();
  }
  catch(const std::bad_alloc&)
  {
    return write_failure(fname, err, "out of memory");
  }
  catch(const std::exception& e)
  {
    return write_failure(fname, err, std::string("cannot write: ") + e.what());
  }
}

/// the mesh and the fields must be consistent before anything is written
template <class Point>
bool check_before_writing(const std::string& fname, const Indexed_hex_mesh<Point>& mesh,
                          const CGAL::IO::Hex_mesh_fields& fields, CGAL::IO::Hex_mesh_io_error* err)
{
  Hex_mesh_defect d;
  if(!validate_hex_mesh(mesh, d))
    return write_failure(fname, err, "refusing to write an invalid mesh: " + d.what());
  // the sets of the simulation formats must index existing elements
  for(int hex_set = 0; hex_set < 2; ++hex_set)
  {
    const std::size_t bound = hex_set ? mesh.hexahedra.size() : mesh.points.size();
    for(const Named_index_set& s : hex_set ? mesh.hexahedron_sets : mesh.vertex_sets)
      for(std::size_t i : s.indices)
        if(i >= bound)
          return write_failure(fname, err, std::string(hex_set ? "hexahedron" : "vertex") + " set '" + s.name +
                                             "': index " + std::to_string(i) + " out of range (mesh has " +
                                             std::to_string(bound) + (hex_set ? " hexahedra)" : " vertices)"));
  }
  for(const Named_side_set& s : mesh.side_sets)
    for(const auto& side : s.sides)
      if(side.first >= mesh.hexahedra.size() || side.second < 0 || side.second > 5)
        return write_failure(fname, err, "side set '" + s.name + "': side (" + std::to_string(side.first) + ", " +
                                           std::to_string(side.second) + ") out of range");
  if(!mesh.point_ids.empty() && mesh.point_ids.size() != mesh.points.size())
    return write_failure(fname, err, std::to_string(mesh.point_ids.size()) + " point ids for " +
                                       std::to_string(mesh.points.size()) + " vertices");
  if(!mesh.hexahedron_ids.empty() && mesh.hexahedron_ids.size() != mesh.hexahedra.size())
    return write_failure(fname, err, std::to_string(mesh.hexahedron_ids.size()) + " hexahedron ids for " +
                                       std::to_string(mesh.hexahedra.size()) + " hexahedra");
  for(int point_field = 0; point_field < 2; ++point_field)
  {
    const auto& list = point_field ? fields.point_scalars : fields.cell_scalars;
    const std::size_t expected = point_field ? mesh.points.size() : mesh.hexahedra.size();
    const char* kind = point_field ? "point" : "cell";
    for(const auto& f : list)
    {
      if(f.first.empty())
        return write_failure(fname, err, std::string(kind) + " field with an empty name");
      if(f.second.size() != expected)
        return write_failure(fname, err, std::string(kind) + " field '" + f.first + "' has " +
                                           std::to_string(f.second.size()) + " values for " +
                                           std::to_string(expected) +
                                           (point_field ? " vertices" : " hexahedra"));
    }
  }
  return true;
}

/// runs `body(Output_buffer&, std::string& message)` (false with `message`
/// set on failure) into a temporary file, renamed to `fname` only on success;
/// an exception leaves no file either
template <class Body>
bool write_atomically(const std::string& fname, CGAL::IO::Hex_mesh_io_error* err, const Body& body)
{
  Atomic_output_file file;  // its destructor removes the temporary unless committed
  std::string why;
  if(!file.open(fname, why))
    return write_failure(fname, err, why);
  Output_buffer out(file);
  std::string message;
  if(!body(out, message))
    return write_failure(fname, err, message);
  out.flush();
  if(!file.commit(why))
    return write_failure(fname, err, why);
  return true;
}

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_WRITE_FILE_H
