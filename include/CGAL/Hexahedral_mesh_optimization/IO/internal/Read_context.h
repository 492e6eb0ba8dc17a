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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_READ_CONTEXT_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_READ_CONTEXT_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// What every reader shares: reporting an error or a warning, remembering
// where each record of the file starts, and the final validation that turns
// a defect of the parsed mesh into an error naming the record of the file.

#include <CGAL/Hexahedral_mesh_optimization/IO/Hex_mesh_io_types.h>
#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/Hexahedral_mesh_optimization/validate_hex_mesh.h>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {
namespace io {

/// Where the records of one section of a file start: line numbers in text,
/// byte offsets in binary data.
struct Record_positions
{
  std::vector<std::size_t> at;
  bool bytes = false;

  void reset(bool binary, std::size_t expected)
  {
    at.clear();
    bytes = binary;
    at.reserve(expected);
  }

  /// the line of record `i`, 0 if unknown or binary
  std::size_t line(std::size_t i) const { return (bytes || i >= at.size()) ? 0 : at[i]; }

  /// " (line 12)", " (byte 1234)" or ""
  std::string where(std::size_t i) const
  {
    if(i >= at.size())
      return std::string();
    return (bytes ? " (byte " : " (line ") + std::to_string(at[i]) + ")";
  }
};

/// The file being read, where errors and warnings go.
class Read_context
{
public:
  Read_context(const std::string& fname, CGAL::IO::Hex_mesh_io_error* err,
               std::vector<std::string>* warnings)
    : fname_(fname), err_(err), warnings_(warnings)
  {}

  /// records the error; always returns false so that readers can write
  /// `return ctx.fail(...)`
  bool fail(std::size_t line, const std::string& message) const
  {
    if(err_ != nullptr)
    {
      err_->file = fname_;
      err_->line = line;
      err_->message = message;
    }
    return false;
  }

  void warn(const std::string& message) const
  {
    if(warnings_ != nullptr)
      warnings_->push_back(message);
  }

  const std::string& file_name() const { return fname_; }

private:
  std::string fname_;
  CGAL::IO::Hex_mesh_io_error* err_;
  std::vector<std::string>* warnings_;
};

/// Validates the parsed mesh; on success moves it into `out`. On failure the
/// error names the record: `describe(section, record, line)` returns e.g.
/// "Hexahedra record 12 (line 3201)" and sets `line`. `index_base` is the
/// file's first vertex index (1 for MEDIT, 0 for VTK), `record_base` the
/// number the file's first record gets in messages.
template <class Point, class Describe>
bool finish_read(Indexed_hex_mesh<Point>& parsed, Indexed_hex_mesh<Point>& out,
                 const Read_context& ctx, std::size_t index_base, std::size_t record_base,
                 const Describe& describe)
{
  Hex_mesh_defect d;
  if(!validate_hex_mesh(parsed, d))
  {
    if(d.kind == Hex_mesh_defect::NO_HEXAHEDRA)
      return ctx.fail(0, "the file contains no hexahedra");
    if(d.kind == Hex_mesh_defect::REFERENCE_COUNT)
      return ctx.fail(0, d.message(index_base, record_base));
    std::size_t line = 0;
    const std::string where = describe(d.section, d.record, line);
    return ctx.fail(line, where + ": " + d.message(index_base, record_base));
  }
  std::swap(out, parsed);
  return true;
}

/// `a * b` in `product`, false on overflow (absurd counts in a corrupt header)
inline bool checked_product(std::size_t a, std::size_t b, std::size_t& product)
{
  if(a != 0 && b > static_cast<std::size_t>(-1) / a)
    return false;
  product = a * b;
  return true;
}

/// how many records can be reserved for a section that announces `count`
/// records of at least `min_bytes` each: never more than the rest of the file
/// can hold, so that a corrupt count cannot exhaust memory
inline std::size_t reservable(std::size_t count, std::size_t remaining_bytes, std::size_t min_bytes)
{
  const std::size_t fit = remaining_bytes / (min_bytes == 0 ? 1 : min_bytes) + 1;
  return count < fit ? count : fit;
}

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_READ_CONTEXT_H
