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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_VTK_CELLS_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_VTK_CELLS_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The cells of a VTK unstructured grid (legacy or XML) and their conversion
// to hexahedra, shared by the .vtk and .vtu readers.
//
// Accepted: type 12 (hexahedron) with 8 nodes; type 11 (voxel), reordered to
// the hexahedron order; and, with a warning, 8-node cells labelled type 10
// (tetrahedron), a quirk of real files (HexaLab's hex_torus.vtk). Any other
// cell is refused, naming the cell and its type.

#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Read_context.h>

#include <array>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {
namespace io {

/// VTK cell type codes (vtkCellType.h) the reader distinguishes
enum Vtk_cell_type {
  VTK_TETRA_TYPE = 10,
  VTK_VOXEL_TYPE = 11,
  VTK_HEXAHEDRON_TYPE = 12
};

inline std::string vtk_cell_type_name(long long type)
{
  switch(type)
  {
  case 1: return "vertex";
  case 2: return "poly-vertex";
  case 3: return "line";
  case 4: return "poly-line";
  case 5: return "triangle";
  case 6: return "triangle strip";
  case 7: return "polygon";
  case 8: return "pixel";
  case 9: return "quad";
  case 10: return "tetrahedron";
  case 11: return "voxel";
  case 12: return "hexahedron";
  case 13: return "wedge";
  case 14: return "pyramid";
  case 15: return "pentagonal prism";
  case 16: return "hexagonal prism";
  case 24: return "quadratic tetrahedron";
  case 25: return "quadratic hexahedron";
  case 29: return "triquadratic hexahedron";
  case 42: return "polyhedron";
  case 72: return "Lagrange hexahedron";
  default: return "unknown type";
  }
}

/// the cells as read: cell i has the nodes connectivity[offsets[i] .. offsets[i+1])
struct Vtk_cells
{
  std::vector<long long> offsets;  // number of cells + 1, starting at 0
  std::vector<long long> connectivity;
  std::vector<long long> types;
  Record_positions records;        // where each cell record starts in the file

  std::size_t size() const { return offsets.empty() ? 0 : offsets.size() - 1; }

  /// "cell 17 (line 9003)": VTK cells are numbered from 0, as in ParaView
  std::string describe(std::size_t i) const { return "cell " + std::to_string(i) + records.where(i); }
};

/// fills `hexes`; fails on the first cell that is not a hexahedron
template <class Hexahedron>
bool vtk_cells_to_hexahedra(const Vtk_cells& cells, std::vector<Hexahedron>& hexes, const Read_context& ctx)
{
  const std::size_t n = cells.size();
  hexes.clear();
  hexes.reserve(n);
  std::size_t tetra_labelled = 0, voxels = 0;
  for(std::size_t i = 0; i < n; ++i)
  {
    const long long type = cells.types[i];
    const long long begin = cells.offsets[i];
    const long long nodes = cells.offsets[i + 1] - begin;
    const bool eight = (nodes == 8);
    if(!eight || (type != VTK_HEXAHEDRON_TYPE && type != VTK_TETRA_TYPE && type != VTK_VOXEL_TYPE))
      return ctx.fail(cells.records.line(i),
                      cells.describe(i) + " has VTK cell type " + std::to_string(type) + " (" +
                        vtk_cell_type_name(type) + ") with " + std::to_string(nodes) +
                        " nodes: only hexahedra (type 12, 8 nodes) are supported");
    Hexahedron h;
    for(std::size_t j = 0; j < 8; ++j)
      // a negative index wraps around; the validation reports it as out of range
      h[j] = static_cast<std::size_t>(cells.connectivity[static_cast<std::size_t>(begin) + j]);
    if(type == VTK_VOXEL_TYPE)
    {
      std::swap(h[2], h[3]);
      std::swap(h[6], h[7]);
      ++voxels;
    }
    else if(type == VTK_TETRA_TYPE)
      ++tetra_labelled;
    hexes.push_back(h);
  }
  if(tetra_labelled > 0)
    ctx.warn(std::to_string(tetra_labelled) +
             " cells have 8 nodes but VTK cell type 10 (tetrahedron); read as hexahedra (type 12)");
  if(voxels > 0)
    ctx.warn(std::to_string(voxels) + " cells are VTK voxels (type 11); reordered as hexahedra (type 12)");
  return true;
}

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_VTK_CELLS_H
