// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Package: Hexahedral_mesh_optimization

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_EXODUS_IO_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_EXODUS_IO_H

// Exodus II (.exo, .e) reading and writing. Exodus files are netCDF files:
// they are read and written through the Exodus II C library (Debian
// libexodusii-dev), found by CMake, which then defines CGAL_HMO_HAVE_EXODUS.
// Without it both functions fail with a message saying so.

#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Read_context.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/write_file.h>
#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>

#include <string>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {
namespace io {

#ifndef CGAL_HMO_HAVE_EXODUS

inline const char* no_exodus_support()
{
  return "this build has no Exodus II support (the Exodus II library, Debian libexodusii-dev, was not found "
         "when it was configured): convert the mesh to .msh, .inp, .mesh or .vtu";
}

template <class Point>
bool read_EXODUS_file(const std::string&, Indexed_hex_mesh<Point>&, const Read_context& ctx)
{
  return ctx.fail(0, no_exodus_support());
}

template <class Point>
bool write_EXODUS_file(const std::string& fname, const Indexed_hex_mesh<Point>&, CGAL::IO::Hex_mesh_io_error* err)
{
  return write_failure(fname, err, no_exodus_support());
}

#endif // CGAL_HMO_HAVE_EXODUS

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_EXODUS_IO_H
