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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_READ_VTK_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_READ_VTK_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Reader of legacy VTK (.vtk) unstructured grids, ASCII or BINARY.
//
// The dataset part is read: POINTS, CELLS (classic "n i0 .. in-1" records,
// or the OFFSETS/CONNECTIVITY arrays of format 5.1) and CELL_TYPES. The
// attribute data (CELL_DATA, POINT_DATA: SCALARS, VECTORS, FIELD...) and
// METADATA blocks are stepped over. Text values may span lines in any way.

#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Read_context.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Text_scanner.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Vtk_array_reader.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/load_file.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/vtk_cells.h>
#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Kernel_traits.h>

#include <cstddef>
#include <string>
#include <string_view>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {
namespace io {

template <class Point>
class Vtk_legacy_reader
{
  typedef Indexed_hex_mesh<Point> Mesh;
  typedef typename Kernel_traits<Point>::Kernel Kernel;
  typedef Hex_mesh_defect D;

public:
  Vtk_legacy_reader(Text_scanner& sc, const Read_context& ctx) : sc_(sc), ctx_(ctx) {}

  bool read(Mesh& out)
  {
    if(!read_header())
      return false;
    Token t;
    while(sc_.next(t))
    {
      const std::string_view k = t.text;
      bool ok = true;
      if(iequals(k, "DATASET"))
        ok = read_dataset(t);
      else if(!dataset_seen_)
        return ctx_.fail(t.line, "expected 'DATASET UNSTRUCTURED_GRID', found " + quote_token(k) + at(t));
      else if(iequals(k, "POINTS"))
        ok = read_points(t);
      else if(iequals(k, "CELLS"))
        ok = read_cells(t);
      else if(iequals(k, "CELL_TYPES"))
        ok = read_cell_types(t);
      else if(iequals(k, "CELL_DATA") || iequals(k, "POINT_DATA"))
      {
        ok = read_size(t, attribute_count_);
        attribute_section_ = std::string(k);
      }
      else if(iequals(k, "FIELD"))
        ok = skip_field(t);
      else if(iequals(k, "METADATA"))
        skip_metadata();
      else if(is_attribute_keyword(k))
        ok = skip_attribute(t);
      else
        return ctx_.fail(t.line, "unknown keyword " + quote_token(k) + at(t));
      if(!ok)
        return false;
    }

    if(!dataset_seen_)
      return ctx_.fail(0, "no DATASET line");
    if(points_line_ == 0)
      return ctx_.fail(0, "no POINTS section");
    if(cells_line_ == 0)
      return ctx_.fail(0, "no CELLS section");
    if(types_line_ == 0)
      return ctx_.fail(0, "no CELL_TYPES section");
    if(cells_.types.size() != cells_.size())
      return ctx_.fail(types_line_, "CELL_TYPES has " + std::to_string(cells_.types.size()) + " entries for " +
                                      std::to_string(cells_.size()) + " cells (line " +
                                      std::to_string(types_line_) + ")");
    if(!vtk_cells_to_hexahedra(cells_, mesh_.hexahedra, ctx_))
      return false;
    return finish_read(mesh_, out, ctx_, 0, 0,
                       [this](D::Section s, std::size_t record, std::size_t& line) {
                         if(s == D::VERTICES)
                         {
                           line = point_positions_.line(record);
                           return "point " + std::to_string(record) + point_positions_.where(record);
                         }
                         line = cells_.records.line(record);
                         return cells_.describe(record);
                       });
  }

private:
  static std::string at(const Token& t) { return " (line " + std::to_string(t.line) + ")"; }

  static bool is_attribute_keyword(std::string_view k)
  {
    static const char* keywords[] = {"SCALARS", "COLOR_SCALARS", "LOOKUP_TABLE", "VECTORS", "NORMALS",
                                     "TENSORS", "TENSORS6", "TEXTURE_COORDINATES", "GLOBAL_IDS",
                                     "PEDIGREE_IDS"};
    for(const char* w : keywords)
      if(iequals(k, w))
        return true;
    return false;
  }

  // ------------------------------------------------------------ header
  bool read_header()
  {
    std::string_view l;
    sc_.next_line(l);
    const std::string_view magic = "# vtk DataFile Version";
    if(l.size() < magic.size() || !iequals(l.substr(0, magic.size()), magic))
      return ctx_.fail(1, "not a legacy VTK file: line 1 must start with '# vtk DataFile Version', found " +
                            quote_token(l));
    if(!sc_.next_line(l))
      return ctx_.fail(1, "truncated header: the title line (line 2) is missing");
    if(!sc_.next_line(l))
      return ctx_.fail(2, "truncated header: line 3 (ASCII or BINARY) is missing");
    while(!l.empty() && is_blank(l.back()))
      l.remove_suffix(1);
    while(!l.empty() && is_blank(l.front()))
      l.remove_prefix(1);
    if(iequals(l, "BINARY"))
      binary_ = true;
    else if(!iequals(l, "ASCII"))
      return ctx_.fail(3, "line 3 must be ASCII or BINARY, found " + quote_token(l));
    return true;
  }

  bool read_dataset(const Token& keyword)
  {
    Token t;
    if(!sc_.next(t))
      return ctx_.fail(keyword.line, "DATASET: type missing (file ends)");
    if(!iequals(t.text, "UNSTRUCTURED_GRID"))
      return ctx_.fail(t.line, "DATASET " + std::string(t.text) + at(t) +
                                 " is not supported: only UNSTRUCTURED_GRID holds hexahedra");
    dataset_seen_ = true;
    return true;
  }

  /// a non-negative count following `keyword` on its line
  bool read_size(const Token& keyword, std::size_t& n)
  {
    Token t;
    long long v = 0;
    if(!sc_.next_on_line(t))
      return ctx_.fail(keyword.line, std::string(keyword.text) + ": count missing" + at(keyword));
    if(parse_integer(t.text, v) != Number_status::ok || v < 0)
      return ctx_.fail(t.line, std::string(keyword.text) + ": expected a count, found " + quote_token(t.text) + at(t));
    n = static_cast<std::size_t>(v);
    return true;
  }

  bool absurd(const Token& keyword)
  {
    return ctx_.fail(keyword.line, std::string(keyword.text) + at(keyword) + ": absurd number of values");
  }

  bool read_word(const Token& keyword, Token& t, const char* what)
  {
    if(sc_.next_on_line(t))
      return true;
    return ctx_.fail(keyword.line, std::string(keyword.text) + ": " + what + " missing" + at(keyword));
  }

  bool first_time(std::size_t& seen_line, const Token& keyword)
  {
    if(seen_line == 0)
    {
      seen_line = keyword.line;
      return true;
    }
    return ctx_.fail(keyword.line, "second " + std::string(keyword.text) + " section" + at(keyword) +
                                     "; the first one is at line " + std::to_string(seen_line));
  }

  // ------------------------------------------------------------ dataset
  bool read_points(const Token& keyword)
  {
    std::size_t n = 0;
    Token type_token;
    if(!first_time(points_line_, keyword) || !read_size(keyword, n) ||
       !read_word(keyword, type_token, "data type"))
      return false;
    const Vtk_data_type type = vtk_data_type(type_token.text);
    if(binary_ && (type.bit || !type.known()))
      return ctx_.fail(type_token.line, "POINTS: unsupported data type " + quote_token(type_token.text) + at(type_token));
    std::size_t count = 0;
    if(!checked_product(3, n, count))
      return absurd(keyword);
    Vtk_array_reader values(sc_, ctx_, binary_);
    if(!values.begin("POINTS", type, count, n, "points", type_token))
      return false;
    const std::size_t r = reservable(n, sc_.remaining() + (binary_ ? n * 3 * type.bytes : 0), 6);
    mesh_.points.reserve(r);
    point_positions_.reset(binary_, r);
    const Kernel gt;
    for(std::size_t i = 0; i < n; ++i)
    {
      values.set_records_done(i);
      Vec3 p;
      for(std::size_t a = 0; a < 3; ++a)
      {
        if(!values.next_real(p[a]))
          return false;
        if(a == 0)
          point_positions_.at.push_back(values.last_position());
      }
      mesh_.points.push_back(to_point(p, gt));
    }
    return true;
  }

  bool read_cells(const Token& keyword)
  {
    std::size_t n = 0, size = 0;
    if(!first_time(cells_line_, keyword) || !read_size(keyword, n) || !read_size(keyword, size))
      return false;
    Token next;
    if(sc_.peek(next) && iequals(next.text, "OFFSETS"))
      return read_offsets_and_connectivity(n, size);

    // classic layout: each record is "k i0 ... ik-1", `size` numbers in all
    Vtk_array_reader values(sc_, ctx_, binary_);
    if(!values.begin("CELLS", vtk_int32_type(), size, n, "cells", keyword))
      return false;
    const std::size_t r = reservable(n, sc_.remaining() + (binary_ ? size * 4 : 0), 18);
    cells_.offsets.reserve(r + 1);
    cells_.connectivity.reserve(8 * r);
    cells_.records.reset(binary_, r);
    cells_.offsets.push_back(0);
    std::size_t used = 0;
    for(std::size_t i = 0; i < n; ++i)
    {
      values.set_records_done(i);
      if(used >= size)
        return ctx_.fail(keyword.line, "CELLS: the header (line " + std::to_string(keyword.line) + ") announces " +
                                         std::to_string(n) + " cells in " + std::to_string(size) +
                                         " numbers, but the numbers are used up after " + std::to_string(i) +
                                         " cells");
      long long k = 0;
      if(!values.next_integer(k))
        return false;
      cells_.records.at.push_back(values.last_position());
      if(k < 0 || static_cast<std::size_t>(k) > size - used - 1)
        return ctx_.fail(cells_.records.line(i),
                         "CELLS: " + cells_.describe(i) + " has " + std::to_string(k) +
                           " nodes, more than the " + std::to_string(size) +
                           " numbers announced by the CELLS header (line " + std::to_string(keyword.line) +
                           ") can hold");
      for(long long j = 0; j < k; ++j)
      {
        long long v = 0;
        if(!values.next_integer(v))
          return false;
        cells_.connectivity.push_back(v);
      }
      used += 1 + static_cast<std::size_t>(k);
      cells_.offsets.push_back(static_cast<long long>(cells_.connectivity.size()));
    }
    if(used != size)
      return ctx_.fail(keyword.line, "CELLS: the header (line " + std::to_string(keyword.line) + ") announces " +
                                       std::to_string(size) + " numbers but the " + std::to_string(n) +
                                       " cells hold " + std::to_string(used));
    return true;
  }

  /// reads the array announced by the keyword `name` that must come next
  bool read_named_array(const char* name, std::size_t count, std::vector<long long>& out,
                        std::vector<std::size_t>* positions)
  {
    Token keyword, type_token;
    if(!sc_.next(keyword) || !iequals(keyword.text, name))
      return ctx_.fail(sc_.line(), std::string("CELLS: expected ") + name + " at line " + std::to_string(sc_.line()));
    if(!read_word(keyword, type_token, "data type"))
      return false;
    const Vtk_data_type type = vtk_data_type(type_token.text);
    if(binary_ && (type.bit || !type.known()))
      return ctx_.fail(type_token.line, std::string(name) + ": unsupported data type " + quote_token(type_token.text) +
                                          at(type_token));
    Vtk_array_reader values(sc_, ctx_, binary_);
    if(!values.begin(name, type, count, count, "values", type_token))
      return false;
    out.reserve(reservable(count, sc_.remaining() + (binary_ ? count * type.bytes : 0), 2));
    for(std::size_t i = 0; i < count; ++i)
    {
      values.set_records_done(i);
      long long v = 0;
      if(!values.next_integer(v))
        return false;
      out.push_back(v);
      if(positions != nullptr)
        positions->push_back(values.last_position());
    }
    return true;
  }

  /// VTK 5.1 layout: "CELLS n_offsets n_connectivity", then the two arrays
  bool read_offsets_and_connectivity(std::size_t n_offsets, std::size_t n_connectivity)
  {
    cells_.records.reset(binary_, 0);
    if(!read_named_array("OFFSETS", n_offsets, cells_.offsets, &cells_.records.at) ||
       !read_named_array("CONNECTIVITY", n_connectivity, cells_.connectivity, nullptr))
      return false;
    if(cells_.offsets.empty())
      cells_.offsets.push_back(0);
    if(!cells_.records.at.empty())
      cells_.records.at.pop_back();  // the last offset closes the last cell
    for(std::size_t i = 0; i < cells_.offsets.size(); ++i)
    {
      const long long o = cells_.offsets[i];
      const bool ok = (i == 0) ? (o == 0)
                               : (o >= cells_.offsets[i - 1] && o <= static_cast<long long>(n_connectivity));
      if(!ok)
        return ctx_.fail(cells_.records.line(i), "OFFSETS: offset " + std::to_string(o) + " of " +
                                                   cells_.describe(i) + " is inconsistent");
    }
    if(cells_.offsets.back() != static_cast<long long>(n_connectivity))
      return ctx_.fail(cells_line_, "OFFSETS: the last offset is " + std::to_string(cells_.offsets.back()) +
                                      " but CONNECTIVITY has " + std::to_string(n_connectivity) + " values");
    return true;
  }

  bool read_cell_types(const Token& keyword)
  {
    std::size_t n = 0;
    if(!first_time(types_line_, keyword) || !read_size(keyword, n))
      return false;
    Vtk_array_reader values(sc_, ctx_, binary_);
    if(!values.begin("CELL_TYPES", vtk_int32_type(), n, n, "cell types", keyword))
      return false;
    cells_.types.reserve(reservable(n, sc_.remaining() + (binary_ ? 4 * n : 0), 2));
    for(std::size_t i = 0; i < n; ++i)
    {
      values.set_records_done(i);
      long long type = 0;
      if(!values.next_integer(type))
        return false;
      cells_.types.push_back(type);
    }
    return true;
  }

  // ------------------------------------------------------------ attributes
  bool skip_values(const std::string& what, const Vtk_data_type& type, std::size_t count,
                   const Token& last_header_token)
  {
    Vtk_array_reader values(sc_, ctx_, binary_);
    return values.begin(what, type, count, count, "values", last_header_token) && values.skip_all();
  }

  /// SCALARS, VECTORS, ... inside CELL_DATA or POINT_DATA
  bool skip_attribute(const Token& keyword)
  {
    const std::string k = std::string(keyword.text);
    if(attribute_section_.empty() && !iequals(k, "LOOKUP_TABLE"))
      return ctx_.fail(keyword.line, k + at(keyword) + " outside of a CELL_DATA or POINT_DATA section");
    const std::string what = attribute_section_ + " " + k;
    const std::size_t n = attribute_count_;
    Token name, type_token, extra;
    if(!read_word(keyword, name, "name"))
      return false;
    if(iequals(k, "LOOKUP_TABLE") || iequals(k, "COLOR_SCALARS"))
    {
      // "LOOKUP_TABLE name size": size RGBA entries; "COLOR_SCALARS name m": m per element;
      // binary as unsigned char, text as floats in [0, 1]
      std::size_t m = 0;
      if(!read_size(keyword, m))
        return false;
      std::size_t count = 0;
      if(!checked_product(iequals(k, "LOOKUP_TABLE") ? 4 : n, m, count))
        return absurd(keyword);
      return skip_values(what, vtk_data_type("unsigned_char"), count, keyword);
    }
    std::size_t components = 1;
    if(iequals(k, "TEXTURE_COORDINATES") && !read_size(keyword, components))
      return false;
    if(!read_word(keyword, type_token, "data type"))
      return false;
    const Vtk_data_type type = vtk_data_type(type_token.text);
    Token last = type_token;
    if(iequals(k, "SCALARS"))
    {
      if(sc_.next_on_line(extra))
      {
        long long c = 0;
        if(parse_integer(extra.text, c) != Number_status::ok || c < 1)
          return ctx_.fail(extra.line, what + ": expected a number of components, found " + quote_token(extra.text) +
                                         at(extra));
        components = static_cast<std::size_t>(c);
        last = extra;
      }
      Token lookup;
      if(sc_.peek(lookup) && iequals(lookup.text, "LOOKUP_TABLE"))
      {
        sc_.next(lookup);
        if(!read_word(lookup, last, "table name"))
          return false;
      }
    }
    else if(iequals(k, "VECTORS") || iequals(k, "NORMALS"))
      components = 3;
    else if(iequals(k, "TENSORS"))
      components = 9;
    else if(iequals(k, "TENSORS6"))
      components = 6;
    std::size_t count = 0;
    if(!checked_product(n, components, count))
      return absurd(keyword);
    return skip_values(what, type, count, last);
  }

  /// "FIELD name m", then m arrays "name components tuples type" + values
  bool skip_field(const Token& keyword)
  {
    Token name;
    std::size_t arrays = 0;
    if(!read_word(keyword, name, "name") || !read_size(keyword, arrays))
      return false;
    for(std::size_t a = 0; a < arrays; ++a)
    {
      Token array_name, type_token;
      if(!sc_.next(array_name))
        return ctx_.fail(sc_.line(), "FIELD " + std::string(name.text) + ": expected " + std::to_string(arrays) +
                                       " arrays, file ends after " + std::to_string(a));
      if(iequals(array_name.text, "NULL_ARRAY"))
        continue;
      std::size_t components = 0, tuples = 0;
      if(!read_size(array_name, components) || !read_size(array_name, tuples) ||
         !read_word(array_name, type_token, "data type"))
        return false;
      const std::string what = "FIELD array " + std::string(array_name.text);
      std::size_t count = 0;
      if(!checked_product(components, tuples, count))
        return absurd(array_name);
      if(!skip_values(what, vtk_data_type(type_token.text), count, type_token))
        return false;
      Token metadata;
      if(sc_.peek(metadata) && iequals(metadata.text, "METADATA"))
      {
        sc_.next(metadata);
        skip_metadata();
      }
    }
    return true;
  }

  /// METADATA blocks (format 5.1) end with an empty line
  void skip_metadata()
  {
    std::string_view l;
    sc_.next_line(l);  // the rest of the METADATA line
    while(sc_.next_line(l))
    {
      while(!l.empty() && is_blank(l.back()))
        l.remove_suffix(1);
      if(l.empty())
        break;
    }
  }

  Text_scanner& sc_;
  const Read_context& ctx_;
  bool binary_ = false;
  bool dataset_seen_ = false;
  std::size_t points_line_ = 0, cells_line_ = 0, types_line_ = 0;
  std::string attribute_section_;
  std::size_t attribute_count_ = 0;
  Mesh mesh_;
  Record_positions point_positions_;
  Vtk_cells cells_;
};

/// reads the legacy VTK file `fname` into `out` (unchanged on failure)
template <class Point>
bool read_VTK_file(const std::string& fname, Indexed_hex_mesh<Point>& out, const Read_context& ctx)
{
  std::string content, why;
  if(!load_file(fname, content, why))
    return ctx.fail(0, why);
  Text_scanner sc(content.data(), content.data() + content.size());
  if(Text_scanner(sc).at_end())
    return ctx.fail(0, content.empty() ? "empty file" : "empty file (only blanks)");
  Vtk_legacy_reader<Point> reader(sc, ctx);
  return reader.read(out);
}

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_READ_VTK_H
