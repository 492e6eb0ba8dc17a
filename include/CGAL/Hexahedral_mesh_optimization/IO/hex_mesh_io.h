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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_HEX_MESH_IO_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_HEX_MESH_IO_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Reading and writing `Indexed_hex_mesh` in the MEDIT (.mesh), legacy VTK
// (.vtk), VTK XML (.vtu), gmsh (.msh), Abaqus (.inp) and Exodus II (.exo,
// .e; when the build has the Exodus library) formats. Every reader validates the mesh it
// parsed (validate_hex_mesh.h) and names the offending record of the file;
// every writer refuses an invalid mesh and replaces its target atomically.

#include <CGAL/Hexahedral_mesh_optimization/IO/Hex_mesh_io_types.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Read_context.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/read_INP.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/read_MEDIT.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/read_MSH.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/read_VTK.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/read_VTU.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/write_INP.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/write_MEDIT.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/write_MSH.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/write_VTK.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/write_VTU.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/write_file.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Exodus_io.h>
#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>

#include <climits>
#include <exception>
#include <map>
#include <new>
#include <set>
#include <string>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {
namespace io {

/// runs a reader, turning an exception (out of memory) into an error
template <class Read>
bool guarded_read(const std::string& fname, CGAL::IO::Hex_mesh_io_error* err,
                  std::vector<std::string>* warnings, const Read& read)
{
  const Read_context ctx(fname, err, warnings);
  try
  {
    return read(ctx);
  }
  catch(const std::bad_alloc&)
  {
    return ctx.fail(0, "out of memory");
  }
  catch(const std::exception& e)
  {
    return ctx.fail(0, std::string("cannot read: ") + e.what());
  }
}

enum class Hex_mesh_format { medit, vtk, vtu, msh, inp, exodus, unknown };

/// the format named by the extension of `fname` (case-insensitive); on
/// failure `why` explains
inline Hex_mesh_format hex_mesh_format(const std::string& fname, std::string& why)
{
  const std::size_t slash = fname.find_last_of("/\\");
  const std::size_t dot = fname.find_last_of('.');
  if(dot == std::string::npos || (slash != std::string::npos && dot < slash))
  {
    why = "no file extension: expected .mesh, .vtk, .vtu, .msh, .inp, .exo or .e";
    return Hex_mesh_format::unknown;
  }
  const std::string ext = to_lower(fname.substr(dot));
  if(ext == ".mesh")
    return Hex_mesh_format::medit;
  if(ext == ".vtk")
    return Hex_mesh_format::vtk;
  if(ext == ".vtu")
    return Hex_mesh_format::vtu;
  if(ext == ".msh")
    return Hex_mesh_format::msh;
  if(ext == ".inp")
    return Hex_mesh_format::inp;
  if(ext == ".exo" || ext == ".e")
    return Hex_mesh_format::exodus;
  if(ext == ".meshb")
    why = "binary MEDIT files (.meshb) are not supported: convert to ASCII .mesh";
  else
    why = "unknown file extension '" + fname.substr(dot) + "': expected .mesh, .vtk, .vtu, .msh, .inp, .exo or .e";
  return Hex_mesh_format::unknown;
}

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization

namespace IO {

/// \name Reading
/// @{

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief Reads an ASCII MEDIT file (`.mesh`) holding a hexahedral mesh.

Read: `MeshVersionFormatted`, `Dimension` (must be 3), `Vertices`,
`Hexahedra`, and the optional `Quadrilaterals`, `Triangles`, `Edges`,
`Corners`, `Ridges` with their references, up to `End`. Indices are 1-based
in the file and 0-based in `mesh`. Lines starting with `#` are comments.
Sections of no use here whose layout is known (`Normals`,
`RequiredVertices`, ...) are skipped with a warning; a non-empty section of
other volume cells (`Tetrahedra`, `Prisms`, `Pyramids`) or an unknown keyword
is an error. The parsed mesh must pass `validate_hex_mesh()`.

\tparam Point a model of `Kernel::Point_3`; points are built from doubles by
        the kernel of `Kernel_traits<Point>`
\param fname the file to read
\param mesh receives the mesh; left unchanged on failure
\param err if not null, receives the reason of a failure, with the line of the
       file, e.g. "Hexahedra record 12 (line 3201): vertex 5 repeated (positions 1 and 6 of 8)"
\param warnings if not null, receives a message per tolerated oddity
\return `true` on success
*/
template <class Point>
bool read_MEDIT(const std::string& fname, Indexed_hex_mesh<Point>& mesh,
                Hex_mesh_io_error* err = nullptr, std::vector<std::string>* warnings = nullptr)
{
  namespace io = Hexahedral_mesh_optimization::internal::io;
  return io::guarded_read(fname, err, warnings, [&](const io::Read_context& ctx) {
    return io::read_MEDIT_file(fname, mesh, ctx);
  });
}

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief Reads a legacy VTK file (`.vtk`), ASCII or BINARY, holding an
unstructured grid of hexahedra.

The cells are read from `CELLS` (classic layout, or the `OFFSETS` /
`CONNECTIVITY` layout of format 5.1) and `CELL_TYPES`; binary data is
big-endian, as the format specifies. Attribute data (`CELL_DATA`,
`POINT_DATA`, `FIELD`) is skipped. Cells must be hexahedra (VTK type 12);
voxels (type 11) are reordered into hexahedra, and 8-node cells labelled as
tetrahedra (type 10), a quirk of some published meshes, are read as
hexahedra; both come with a warning. Any other cell is an error naming it.
The parsed mesh must pass `validate_hex_mesh()`.

Parameters and result as for `read_MEDIT()`; cells and points are numbered
from 0 in messages, as in ParaView.
*/
template <class Point>
bool read_VTK(const std::string& fname, Indexed_hex_mesh<Point>& mesh,
              Hex_mesh_io_error* err = nullptr, std::vector<std::string>* warnings = nullptr)
{
  namespace io = Hexahedral_mesh_optimization::internal::io;
  return io::guarded_read(fname, err, warnings, [&](const io::Read_context& ctx) {
    return io::read_VTK_file(fname, mesh, ctx);
  });
}

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief Reads a VTK XML unstructured grid (`.vtu`) of hexahedra whose points
and cells are stored as text (`format="ascii"`), as `write_VTU()` writes them.

Binary, appended or compressed arrays are refused with a message saying so.
`PointData` and `CellData` are ignored. Cell types are handled as by
`read_VTK()`. Parameters and result as for `read_MEDIT()`.
*/
template <class Point>
bool read_VTU(const std::string& fname, Indexed_hex_mesh<Point>& mesh,
              Hex_mesh_io_error* err = nullptr, std::vector<std::string>* warnings = nullptr)
{
  namespace io = Hexahedral_mesh_optimization::internal::io;
  return io::guarded_read(fname, err, warnings, [&](const io::Read_context& ctx) {
    return io::read_VTU_file(fname, mesh, ctx);
  });
}

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief Reads a gmsh file (`.msh`), version 2.2 or 4.1, ASCII or binary.

Hexahedra (element type 5, whose node order is the package's) are read with
their element tags in `mesh.hexahedron_ids` and their physical tag (2.2: the
first tag of the element; 4.1: the first physical tag of its volume entity
in `$Entities`; 0 if none) in `mesh.hexahedron_references`; the names of
`$PhysicalNames` of dimension 3 go to `mesh.hexahedron_reference_names`.
Node tags are kept in `mesh.point_ids`. Points, lines, triangles and
quadrangles are skipped with one warning per element type; other volume
elements (tetrahedra, prisms, pyramids, high-order hexahedra) are an error.
Other sections (`$NodeData`, `$ElementData`, `$Periodic`, ...) are skipped
with a warning. A binary file must have been written on a machine of the
same byte order (its endianness marker is checked) with data size 8
(`sizeof(size_t)` and `sizeof(double)`), as gmsh writes them on every
64-bit machine; other files are refused with a message saying so. Other
versions (4.0, 3, 1) are refused: `gmsh -format msh41` converts.

Parameters and result as for `read_MEDIT()`; elements and nodes are named by
their tags in messages, with the line (ASCII) or byte (binary).
*/
template <class Point>
bool read_MSH(const std::string& fname, Indexed_hex_mesh<Point>& mesh,
              Hex_mesh_io_error* err = nullptr, std::vector<std::string>* warnings = nullptr)
{
  namespace io = Hexahedral_mesh_optimization::internal::io;
  return io::guarded_read(fname, err, warnings, [&](const io::Read_context& ctx) {
    return io::read_MSH_file(fname, mesh, ctx);
  });
}

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief Reads an Abaqus input file (`.inp`) holding hexahedra.

Read (keywords case-insensitive, `**` comments): `*NODE` (3 coordinates;
`NSET=` puts the nodes in that set), `*ELEMENT` of an 8-node hexahedral
type (`TYPE=C3D8`, `C3D8R`, `C3D8I`, `C3D8H`, `C3D8RH`, ...; records may continue on the next lines; `ELSET=` puts the
elements in that set), `*NSET` and `*ELSET` (ids or names of sets already
defined, or `GENERATE` ranges `first, last[, step]`) and element-based
`*SURFACE` (lines `element or element set, S1..S6`, into `mesh.side_sets`
with the faces renumbered as in `Named_side_set`). Elements of other types
are skipped with one warning per type, and so are the members of sets that
name them; other keywords (`*HEADING`, `*MATERIAL`, `*STEP`, ...) are skipped
with one warning per keyword. Node and element ids are any positive integers,
kept in `mesh.point_ids` and `mesh.hexahedron_ids`; the sets go to
`mesh.vertex_sets` and `mesh.hexahedron_sets`, the element type to
`mesh.abaqus_element_type`. Parameters and result as for `read_MEDIT()`.
*/
template <class Point>
bool read_INP(const std::string& fname, Indexed_hex_mesh<Point>& mesh,
              Hex_mesh_io_error* err = nullptr, std::vector<std::string>* warnings = nullptr)
{
  namespace io = Hexahedral_mesh_optimization::internal::io;
  return io::guarded_read(fname, err, warnings, [&](const io::Read_context& ctx) {
    return io::read_INP_file(fname, mesh, ctx);
  });
}

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief Reads an Exodus II file (`.exo`, `.e`) whose element blocks are
hexahedra (`HEX`, `HEX8`, `HEXAHEDRON`).

The block id of each hexahedron goes to `mesh.hexahedron_references` and
the block names to `mesh.hexahedron_reference_names`; the node sets go to
`mesh.vertex_sets`, the side sets to `mesh.side_sets` (Exodus face
numbering, see `Named_side_set`), the node and element number maps to
`mesh.point_ids` and `mesh.hexahedron_ids`. Blocks of surface, line and
point elements (`QUAD`, `SHELL`, `TRI`, `BAR`, `BEAM`, `TRUSS`, `SPHERE`,
...) are skipped with a warning each, and so are the sides of their
elements in side sets; blocks of other volume elements (`TETRA`, `WEDGE`,
`HEX20`, ...) are an error. Needs a build with the Exodus II
library (`CGAL_HMO_HAVE_EXODUS`); without it the function fails with a
message saying so. Parameters and result as for `read_MEDIT()`.
*/
template <class Point>
bool read_EXODUS(const std::string& fname, Indexed_hex_mesh<Point>& mesh,
                 Hex_mesh_io_error* err = nullptr, std::vector<std::string>* warnings = nullptr)
{
  namespace io = Hexahedral_mesh_optimization::internal::io;
  return io::guarded_read(fname, err, warnings, [&](const io::Read_context& ctx) {
    return io::read_EXODUS_file(fname, mesh, ctx);
  });
}

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief Reads a hexahedral mesh, choosing the reader by the extension of
`fname` (case-insensitive): `.mesh` (`read_MEDIT()`), `.vtk` (`read_VTK()`),
`.vtu` (`read_VTU()`), `.msh` (`read_MSH()`), `.inp` (`read_INP()`), `.exo`
or `.e` (`read_EXODUS()`). Any other extension is an error.

Parameters and result as for `read_MEDIT()`.
*/
template <class Point>
bool read_hex_mesh(const std::string& fname, Indexed_hex_mesh<Point>& mesh,
                   Hex_mesh_io_error* err = nullptr, std::vector<std::string>* warnings = nullptr)
{
  namespace io = Hexahedral_mesh_optimization::internal::io;
  std::string why;
  switch(io::hex_mesh_format(fname, why))
  {
  case io::Hex_mesh_format::medit: return read_MEDIT(fname, mesh, err, warnings);
  case io::Hex_mesh_format::vtk: return read_VTK(fname, mesh, err, warnings);
  case io::Hex_mesh_format::vtu: return read_VTU(fname, mesh, err, warnings);
  case io::Hex_mesh_format::msh: return read_MSH(fname, mesh, err, warnings);
  case io::Hex_mesh_format::inp: return read_INP(fname, mesh, err, warnings);
  case io::Hex_mesh_format::exodus: return read_EXODUS(fname, mesh, err, warnings);
  default: return io::write_failure(fname, err, why);
  }
}

/// @}

/// \name Writing
/// All writers refuse a mesh that fails `validate_hex_mesh()` and fields of
/// the wrong size. They write to a temporary file in the directory of
/// `fname` and rename it to `fname` only when everything was written: on
/// failure no file is left behind and an existing `fname` is untouched.
/// Coordinates are written in the shortest decimal form that reads back to
/// the same double, so that a round trip is exact.
/// @{

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief Writes `mesh` as an ASCII MEDIT file (`.mesh`), with its optional
sections (quadrilaterals, triangles, edges, corners, ridges) and references
(0 where the mesh has none).

\param fname the file to write
\param mesh the mesh
\param err if not null, receives the reason of a failure
\return `true` on success
*/
template <class Point>
bool write_MEDIT(const std::string& fname, const Indexed_hex_mesh<Point>& mesh,
                 Hex_mesh_io_error* err = nullptr)
{
  namespace io = Hexahedral_mesh_optimization::internal::io;
  return io::guarded_write(fname, err, [&]() { return io::write_MEDIT_file(fname, mesh, err); });
}

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief Writes `mesh` as a legacy VTK unstructured grid (`.vtk`) of hexahedra
(cell type 12), with `fields` as `CELL_DATA` and `POINT_DATA` scalars.

Only the points and hexahedra of the mesh are written: the optional MEDIT
sections have no place in this format.

\param fname the file to write
\param mesh the mesh
\param fields scalar fields, one value per hexahedron or per vertex
\param err if not null, receives the reason of a failure
\param binary `true` for the BINARY variant (big-endian doubles and 32-bit
       integers), `false` for ASCII
\return `true` on success
*/
template <class Point>
bool write_VTK(const std::string& fname, const Indexed_hex_mesh<Point>& mesh,
               const Hex_mesh_fields& fields = Hex_mesh_fields(), Hex_mesh_io_error* err = nullptr,
               bool binary = false)
{
  namespace io = Hexahedral_mesh_optimization::internal::io;
  return io::guarded_write(fname, err, [&]() { return io::write_VTK_file(fname, mesh, fields, err, binary); });
}

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief Writes `mesh` as a VTK XML unstructured grid (`.vtu`, ascii data
arrays) of hexahedra, with `fields` as `CellData` and `PointData`; the first
field of each kind is the active scalar, so that ParaView colours the mesh by
it (for instance by the per-hexahedron scaled Jacobian).

Only the points and hexahedra of the mesh are written. Parameters and result
as for `write_VTK()`.
*/
template <class Point>
bool write_VTU(const std::string& fname, const Indexed_hex_mesh<Point>& mesh,
               const Hex_mesh_fields& fields = Hex_mesh_fields(), Hex_mesh_io_error* err = nullptr)
{
  namespace io = Hexahedral_mesh_optimization::internal::io;
  return io::guarded_write(fname, err, [&]() { return io::write_VTU_file(fname, mesh, fields, err); });
}

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief Writes `mesh` as a gmsh file (`.msh`) of hexahedra (element type 5),
with `fields.cell_scalars` as `$ElementData` views (gmsh colours the mesh by
them; point fields are not written).

Each distinct value of `mesh.hexahedron_references` becomes a volume entity
whose physical tag is that value (none for values <= 0, which read back as
0), named after `mesh.hexahedron_reference_names`; the hexahedra keep their
order. Node and element tags are `mesh.point_ids` and `mesh.hexahedron_ids`
when these are present, unique and positive (and, where the format stores
them as 32-bit integers, small enough), 1..n otherwise. Binary files are
written in the byte order of this machine with data size 8.

\param fname the file to write
\param mesh the mesh
\param fields per-hexahedron scalar fields
\param err if not null, receives the reason of a failure
\param version `Gmsh_version::v4_1` (default) or `Gmsh_version::v2_2`
\param binary `true` for the binary variant, `false` (default) for ASCII
\return `true` on success
*/
template <class Point>
bool write_MSH(const std::string& fname, const Indexed_hex_mesh<Point>& mesh,
               const Hex_mesh_fields& fields = Hex_mesh_fields(), Hex_mesh_io_error* err = nullptr,
               Gmsh_version version = Gmsh_version::v4_1, bool binary = false)
{
  namespace io = Hexahedral_mesh_optimization::internal::io;
  return io::guarded_write(fname, err, [&]() { return io::write_MSH_file(fname, mesh, fields, err, version, binary); });
}

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief Writes `mesh` as an Abaqus input file (`.inp`): `*NODE`, one
`*ELEMENT` block of type `mesh.abaqus_element_type` (`C3D8` when empty), then
`mesh.vertex_sets` as `*NSET`, `mesh.hexahedron_sets` as `*ELSET` and
`mesh.side_sets` as element-based `*SURFACE` (one `id, Sn` line a side).
`mesh.hexahedron_references` are not written (the format has no per-element
integer); put such groups in `mesh.hexahedron_sets` to keep them. Ids are `mesh.point_ids` and `mesh.hexahedron_ids` when present, unique and
positive, 1..n otherwise. Parameters and result as for `write_MEDIT()`.
*/
template <class Point>
bool write_INP(const std::string& fname, const Indexed_hex_mesh<Point>& mesh, Hex_mesh_io_error* err = nullptr)
{
  namespace io = Hexahedral_mesh_optimization::internal::io;
  return io::guarded_write(fname, err, [&]() { return io::write_INP_file(fname, mesh, err); });
}

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief Writes `mesh` as an Exodus II file (`.exo`, `.e`): one `HEX8`
element block per distinct value of `mesh.hexahedron_references`, named
after `mesh.hexahedron_reference_names`. Block ids must be positive: a
positive reference is its own block id, and the others (0, which MEDIT
writers often leave on every element, and negative values) take, in the
order 0, -1, -2, ..., the smallest positive ids no positive reference uses;
so 0 becomes block 1 unless 1 is a reference too, and a mesh without
references is one block 1. These read back as the block ids;
`check_hex_mesh_output()` reports the remapped references, but for 0 -> 1,
as warnings. Then the node sets
`mesh.vertex_sets`, the side sets `mesh.side_sets`, and the id maps
`mesh.point_ids` and `mesh.hexahedron_ids` when usable. The hexahedra are
written block by block: a mesh whose references are not sorted reads back
in another order. Needs a build with the Exodus II library; without it the
function fails with a message saying so. Parameters and result as for
`write_MEDIT()`.
*/
template <class Point>
bool write_EXODUS(const std::string& fname, const Indexed_hex_mesh<Point>& mesh, Hex_mesh_io_error* err = nullptr)
{
  namespace io = Hexahedral_mesh_optimization::internal::io;
  return io::guarded_write(fname, err, [&]() { return io::write_EXODUS_file(fname, mesh, err); });
}

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief A file format and variant that `write_hex_mesh_as()` writes, whatever
the extension of the file name.
*/
enum class Hex_mesh_file_format
{
  medit,        ///< ASCII MEDIT `.mesh` (`write_MEDIT()`)
  vtk,          ///< legacy VTK, ASCII (`write_VTK()`)
  vtk_binary,   ///< legacy VTK, BINARY
  vtu,          ///< VTK XML unstructured grid (`write_VTU()`)
  msh41,        ///< gmsh 4.1, ASCII (`write_MSH()`)
  msh41_binary, ///< gmsh 4.1, binary
  msh22,        ///< gmsh 2.2, ASCII
  msh22_binary, ///< gmsh 2.2, binary
  inp,          ///< Abaqus input file (`write_INP()`)
  exodus        ///< Exodus II (`write_EXODUS()`)
};

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief The format named `name`: `mesh`, `vtk`, `vtk-binary`, `vtu`, `msh`
(= `msh41`), `msh41`, `msh41-binary`, `msh22`, `msh22-binary`, `inp`, `exo`
(case-insensitive).

\param name the name
\param format receives the format named
\param error if not null and `name` names no format, receives "unknown
       format '<name>' (expected mesh, vtk, ... or exo)"
\return `false` when `name` names none of them
*/
inline bool parse_hex_mesh_file_format(const std::string& name, Hex_mesh_file_format& format,
                                       std::string* error = nullptr)
{
  namespace io = Hexahedral_mesh_optimization::internal::io;
  static const std::pair<const char*, Hex_mesh_file_format> names[] = {
    {"mesh", Hex_mesh_file_format::medit},       {"vtk", Hex_mesh_file_format::vtk},
    {"vtk-binary", Hex_mesh_file_format::vtk_binary}, {"vtu", Hex_mesh_file_format::vtu},
    {"msh", Hex_mesh_file_format::msh41},        {"msh41", Hex_mesh_file_format::msh41},
    {"msh41-binary", Hex_mesh_file_format::msh41_binary}, {"msh22", Hex_mesh_file_format::msh22},
    {"msh22-binary", Hex_mesh_file_format::msh22_binary}, {"inp", Hex_mesh_file_format::inp},
    {"exo", Hex_mesh_file_format::exodus}};
  const std::string lower = io::to_lower(name);
  for(const auto& n : names)
    if(lower == n.first)
    {
      format = n.second;
      return true;
    }
  if(error != nullptr)
  {
    // the names of the table, in its order: "mesh, vtk, ... or exo"
    const std::size_t count = sizeof(names) / sizeof(names[0]);
    *error = "unknown format '" + name + "' (expected ";
    for(std::size_t i = 0; i < count; ++i)
      *error += std::string(i == 0 ? "" : i + 1 == count ? " or " : ", ") + names[i].first;
    *error += ")";
  }
  return false;
}

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief Writes `mesh` to `fname` in `format`, whatever the extension of
`fname` (for a file name without one, or an ambiguous one such as `.msh` or
`.vtk`, whose variants this chooses). `fields` are written where the format
has a place for them (VTK, VTU, gmsh) and ignored otherwise.

Parameters and result as for `write_VTK()`.
*/
template <class Point>
bool write_hex_mesh_as(Hex_mesh_file_format format, const std::string& fname, const Indexed_hex_mesh<Point>& mesh,
                       const Hex_mesh_fields& fields = Hex_mesh_fields(), Hex_mesh_io_error* err = nullptr)
{
  switch(format)
  {
  case Hex_mesh_file_format::medit: return write_MEDIT(fname, mesh, err);
  case Hex_mesh_file_format::vtk: return write_VTK(fname, mesh, fields, err, false);
  case Hex_mesh_file_format::vtk_binary: return write_VTK(fname, mesh, fields, err, true);
  case Hex_mesh_file_format::vtu: return write_VTU(fname, mesh, fields, err);
  case Hex_mesh_file_format::msh41: return write_MSH(fname, mesh, fields, err, Gmsh_version::v4_1, false);
  case Hex_mesh_file_format::msh41_binary: return write_MSH(fname, mesh, fields, err, Gmsh_version::v4_1, true);
  case Hex_mesh_file_format::msh22: return write_MSH(fname, mesh, fields, err, Gmsh_version::v2_2, false);
  case Hex_mesh_file_format::msh22_binary: return write_MSH(fname, mesh, fields, err, Gmsh_version::v2_2, true);
  case Hex_mesh_file_format::inp: return write_INP(fname, mesh, err);
  case Hex_mesh_file_format::exodus: return write_EXODUS(fname, mesh, err);
  }
  return false;
}

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief The format that `write_hex_mesh()` chooses for `fname`, by its
extension (case-insensitive): `.mesh` (`medit`), `.vtk` (`vtk`, ASCII),
`.vtu` (`vtu`), `.msh` (`msh41`, ASCII), `.inp` (`inp`), `.exo` or `.e`
(`exodus`).

\param fname the file name
\param format receives the format
\param error if not null and the extension names no format, receives why,
       e.g. "unknown file extension '.txt': expected .mesh, .vtk, .vtu, .msh, .inp, .exo or .e"
\return `false` for any other extension
*/
inline bool hex_mesh_file_format_from_extension(const std::string& fname, Hex_mesh_file_format& format,
                                                std::string* error = nullptr)
{
  namespace io = Hexahedral_mesh_optimization::internal::io;
  std::string why;
  switch(io::hex_mesh_format(fname, why))
  {
  case io::Hex_mesh_format::medit: format = Hex_mesh_file_format::medit; return true;
  case io::Hex_mesh_format::vtk: format = Hex_mesh_file_format::vtk; return true;
  case io::Hex_mesh_format::vtu: format = Hex_mesh_file_format::vtu; return true;
  case io::Hex_mesh_format::msh: format = Hex_mesh_file_format::msh41; return true;
  case io::Hex_mesh_format::inp: format = Hex_mesh_file_format::inp; return true;
  case io::Hex_mesh_format::exodus: format = Hex_mesh_file_format::exodus; return true;
  default: break;
  }
  if(error != nullptr)
    *error = why;
  return false;
}

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief Writes `mesh`, choosing the format by the extension of `fname`
(case-insensitive): `.mesh` (`write_MEDIT()`; MEDIT has no place for
`fields`, which are then ignored), `.vtk` (`write_VTK()`, ASCII), `.vtu`
(`write_VTU()`), `.msh` (`write_MSH()`, version 4.1 ASCII), `.inp`
(`write_INP()`, fields ignored), `.exo` or `.e` (`write_EXODUS()`, fields
ignored); see `hex_mesh_file_format_from_extension()`. Any other extension
is an error and nothing is written.

Parameters and result as for `write_VTK()`.
*/
template <class Point>
bool write_hex_mesh(const std::string& fname, const Indexed_hex_mesh<Point>& mesh,
                    const Hex_mesh_fields& fields = Hex_mesh_fields(), Hex_mesh_io_error* err = nullptr)
{
  namespace io = Hexahedral_mesh_optimization::internal::io;
  Hex_mesh_file_format format;
  std::string why;
  if(!hex_mesh_file_format_from_extension(fname, format, &why))
    return io::write_failure(fname, err, why);
  return write_hex_mesh_as(format, fname, mesh, fields, err);
}

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief Checks, before the work that produces a mesh, that it can be written
to `fname` in `format`, so that a bad output is found out before the work
rather than after it: the build can write the format (Exodus II needs its
library), the folder of `fname` exists, `fname` is not a folder, and a file
can be created there (the temporary file the writers write is created and
removed at once; on Linux it has no name, so nothing appears in the folder).
Nothing is written. A write can still fail later (a full disk, a folder
removed meanwhile).

\param format the format the mesh will be written in
\param fname the file it will be written to
\param err if not null, receives the reason of a failure, e.g.
       "out/mesh.vtk: its folder 'out' does not exist"
\return `true` when the checks pass
*/
inline bool check_hex_mesh_output(Hex_mesh_file_format format, const std::string& fname,
                                  Hex_mesh_io_error* err = nullptr)
{
  namespace io = Hexahedral_mesh_optimization::internal::io;
#ifndef CGAL_HMO_HAVE_EXODUS
  if(format == Hex_mesh_file_format::exodus)
    return io::write_failure(fname, err, io::no_exodus_support());
#else
  (void)format;
#endif
  std::string why;
  if(!io::probe_output_file(fname, why))
    return io::write_failure(fname, err, why);
  return true;
}

namespace internal_groups {

inline const char* format_label(Hex_mesh_file_format format)
{
  switch(format)
  {
  case Hex_mesh_file_format::medit: return "MEDIT (.mesh)";
  case Hex_mesh_file_format::vtk:
  case Hex_mesh_file_format::vtk_binary: return "legacy VTK (.vtk)";
  case Hex_mesh_file_format::vtu: return "VTK XML (.vtu)";
  case Hex_mesh_file_format::inp: return "Abaqus (.inp)";
  case Hex_mesh_file_format::exodus: return "Exodus II";
  default: return "gmsh (.msh)";
  }
}

inline bool is_msh(Hex_mesh_file_format f)
{
  return f == Hex_mesh_file_format::msh41 || f == Hex_mesh_file_format::msh41_binary ||
         f == Hex_mesh_file_format::msh22 || f == Hex_mesh_file_format::msh22_binary;
}

/// "a, b, c" (at most 5, then "...")
template <class Range, class Name>
std::string listed(const Range& r, const Name& name)
{
  std::string s;
  std::size_t n = 0;
  for(const auto& x : r)
  {
    if(n == 5)
      return s + ", ...";
    s += (n++ == 0 ? "" : ", ") + name(x);
  }
  return s;
}

/// ids other than 1..n (empty ids are 1..n)
inline bool numbered_otherwise(const std::vector<long long>& ids)
{
  for(std::size_t i = 0; i < ids.size(); ++i)
    if(ids[i] != static_cast<long long>(i + 1))
      return true;
  return false;
}

/// the ids `format` writes for `kept` (see the writers): empty when it has no ids
inline std::vector<long long> written_ids(Hex_mesh_file_format format, const std::vector<long long>& kept, std::size_t n)
{
  namespace io = Hexahedral_mesh_optimization::internal::io;
  if(format == Hex_mesh_file_format::medit || format == Hex_mesh_file_format::vtk ||
     format == Hex_mesh_file_format::vtk_binary || format == Hex_mesh_file_format::vtu)
    return std::vector<long long>();
  std::vector<long long> ids = io::ids_for_writing(kept, n);
  if(format != Hex_mesh_file_format::inp)  // gmsh and Exodus: 32-bit ids
    for(long long i : ids)
      if(i > INT_MAX)
        return io::ids_for_writing(std::vector<long long>(), n);
  return ids;
}

} // namespace internal_groups

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief What of the groups of `mesh` a file of `format` cannot hold: one
message for each kind of group (hexahedron references, their names, named
node, element and side sets, the MEDIT boundary sections and vertex
references, node and element ids other than 1..n) that `format` does not
write or writes otherwise, e.g. "3 named node sets (BOTTOM, corner, top)
are not written: Abaqus (.inp) keeps them, MEDIT (.mesh) has none". Nothing
is refused: the writers write what the format holds. The table of the
manual's Input and Output section says what each format holds.

\param format the format the mesh will be written in
\param mesh the mesh (only its groups and ids are looked at)
\return the messages, empty when the file holds every group of `mesh`
*/
template <class Point>
std::vector<std::string> hex_mesh_groups_not_written(Hex_mesh_file_format format, const Indexed_hex_mesh<Point>& mesh)
{
  namespace g = internal_groups;
  namespace io = Hexahedral_mesh_optimization::internal::io;
  std::vector<std::string> w;
  const std::string label = g::format_label(format);
  const bool medit = format == Hex_mesh_file_format::medit, msh = g::is_msh(format),
             inp = format == Hex_mesh_file_format::inp, exodus = format == Hex_mesh_file_format::exodus;
  const auto number = [](int i) { return std::to_string(i); };
  const auto set_name = [](const auto& s) { return s.name; };

  // the hexahedron references and their names
  std::set<int> references(mesh.hexahedron_references.begin(), mesh.hexahedron_references.end());
  const bool any_reference = !references.empty() && !(references.size() == 1 && *references.begin() == 0);
  std::set<int> unnamed_written; // references whose name is written
  if(exodus)
  {
    const std::map<int, int> block_of = io::exodus_block_ids(mesh.hexahedron_references, &w);
    for(std::size_t h = 1; h < mesh.hexahedron_references.size(); ++h)
      if(block_of.at(mesh.hexahedron_references[h]) < block_of.at(mesh.hexahedron_references[h - 1]))
      {
        w.push_back("the hexahedra are written block by block (Exodus II element blocks): their references are "
                    "not in increasing order, so they read back in another order");
        break;
      }
  }
  else if(msh)
  {
    std::set<int> negative;
    for(int r : references)
      if(r < 0)
        negative.insert(r);
    if(!negative.empty())
      w.push_back("hexahedron references " + g::listed(negative, number) + " are not written: gmsh physical tags "
                  "are positive, these hexahedra read back with reference 0 (use positive references to keep them)");
  }
  else if(!medit && any_reference)
    w.push_back(std::to_string(references.size()) + " hexahedron references (" + g::listed(references, number) +
                ") are not written: " + label + " has no per-element group" +
                (inp ? " (put them in mesh.hexahedron_sets to write them as *ELSET)" : "") +
                "; Exodus II, gmsh and MEDIT keep them");
  std::set<int> names_lost;
  for(const auto& n : mesh.hexahedron_reference_names)
    if(references.count(n.first) != 0 && !(exodus || (msh && n.first > 0)))
      names_lost.insert(n.first);
  if(!names_lost.empty())
    w.push_back("the names of hexahedron references " + g::listed(names_lost, number) + " are not written: " +
                (msh ? std::string("gmsh names physical tags, which are positive")
                     : label + " has no names of groups (Exodus II and gmsh keep them)"));

  // the named sets
  const auto sets_lost = [&](std::size_t count, const std::string& what, const std::string& names,
                             const char* kept_by) {
    if(count != 0)
      w.push_back(std::to_string(count) + " " + what + " (" + names + ") " + (count == 1 ? "is" : "are") +
                  " not written: " + label + " has none (" + kept_by + " keep" + (std::string(kept_by).find(" and ") ==
                  std::string::npos ? "s" : "") + " them)");
  };
  if(!inp && !exodus)
    sets_lost(mesh.vertex_sets.size(), "named node sets", g::listed(mesh.vertex_sets, set_name), "Abaqus and Exodus II");
  if(!inp)
    sets_lost(mesh.hexahedron_sets.size(), "named element sets", g::listed(mesh.hexahedron_sets, set_name), "Abaqus");
  if(!inp && !exodus)
    sets_lost(mesh.side_sets.size(), "named side sets", g::listed(mesh.side_sets, set_name), "Abaqus and Exodus II");

  // the MEDIT sections
  if(!medit)
  {
    std::vector<std::string> sections;
    const auto section = [&](std::size_t n, const char* name) {
      if(n != 0)
        sections.push_back(std::string(name) + " (" + std::to_string(n) + ")");
    };
    bool vertex_references = false;
    for(int r : mesh.point_references)
      vertex_references = vertex_references || r != 0;
    section(vertex_references ? mesh.point_references.size() : 0, "vertex references");
    section(mesh.quadrilaterals.size(), "Quadrilaterals");
    section(mesh.triangles.size(), "Triangles");
    section(mesh.edges.size(), "Edges");
    section(mesh.corners.size(), "Corners");
    section(mesh.ridges.size(), "Ridges");
    if(!sections.empty())
      w.push_back("the MEDIT " + g::listed(sections, [](const std::string& x) { return x; }) + " are not written: " +
                  label + " holds the points and hexahedra only of them");
  }

  // the ids
  const std::pair<const std::vector<long long>*, std::size_t> ids[] = {{&mesh.point_ids, mesh.points.size()},
                                                                       {&mesh.hexahedron_ids, mesh.hexahedra.size()}};
  for(int k = 0; k < 2; ++k)
  {
    const std::vector<long long>& kept = *ids[k].first;
    if(!g::numbered_otherwise(kept))
      continue;
    const std::vector<long long> written = g::written_ids(format, kept, ids[k].second);
    if(written == kept)
      continue;
    w.push_back(std::string(k == 0 ? "the node ids" : "the element ids") + " are not kept: " +
                (written.empty() ? label + " has no ids, the file numbers them from 1"
                                 : label + " needs them unique, positive" + (inp ? "" : " and below 2^31") +
                                   ", they are written as 1.." + std::to_string(ids[k].second)));
  }
  return w;
}

/*!
\ingroup PkgHexahedralMeshOptimizationIO

\brief The checks of `check_hex_mesh_output(format, fname, err)`, and what
of the groups of `mesh` the file will not hold, as warnings
(`hex_mesh_groups_not_written()`): a format that cannot hold a group gets a
warning here, before the work, and the writer writes what it can. Only the
connectivity and the groups of `mesh` are looked at, which the optimisation
never changes: call this on the mesh read, before optimising it.

\param format the format the mesh will be written in
\param fname the file it will be written to
\param mesh the mesh (its groups and ids)
\param err if not null, receives the reason of a failure
\param warnings if not null, receives one message per kind of group written otherwise than it is
\return `true` when the checks pass
*/
template <class Point>
bool check_hex_mesh_output(Hex_mesh_file_format format, const std::string& fname, const Indexed_hex_mesh<Point>& mesh,
                           Hex_mesh_io_error* err = nullptr, std::vector<std::string>* warnings = nullptr)
{
  if(!check_hex_mesh_output(format, fname, err))
    return false;
  if(warnings != nullptr)
  {
    const std::vector<std::string> w = hex_mesh_groups_not_written(format, mesh);
    warnings->insert(warnings->end(), w.begin(), w.end());
  }
  return true;
}

/// @}

} // namespace IO
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_HEX_MESH_IO_H
