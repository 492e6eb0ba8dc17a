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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_READ_MEDIT_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_READ_MEDIT_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Reader of ASCII MEDIT (.mesh) hex meshes. The file is loaded at once and
// parsed token by token with std::from_chars; every record remembers its
// line so that the final validation can name it.

#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Read_context.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Text_scanner.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/load_file.h>
#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Kernel_traits.h>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {
namespace io {

/// a section that the reader knows how to step over: its number of tokens per record
struct Medit_section_layout
{
  const char* keyword;
  std::size_t tokens;
};

/// volume cells other than hexahedra: a mesh with such records is refused
inline const Medit_section_layout* medit_non_hex_cells(std::string_view keyword)
{
  static const Medit_section_layout table[] = {
    {"Tetrahedra", 5}, {"Prisms", 7}, {"Pyramids", 6}, {"TetrahedraP2", 11}, {"HexahedraQ2", 28}
  };
  for(const Medit_section_layout& s : table)
    if(iequals(keyword, s.keyword))
      return &s;
  return nullptr;
}

/// sections of no use here, skipped with a warning (layouts of libMeshb)
inline const Medit_section_layout* medit_skippable(std::string_view keyword)
{
  static const Medit_section_layout table[] = {
    {"RequiredVertices", 1}, {"RequiredEdges", 1}, {"RequiredTriangles", 1},
    {"RequiredQuadrilaterals", 1}, {"Normals", 3}, {"Tangents", 3},
    {"NormalAtVertices", 2}, {"NormalAtTriangleVertices", 3},
    {"NormalAtQuadrilateralVertices", 3}, {"TangentAtVertices", 2},
    {"TangentAtEdgeVertices", 3}, {"EdgesP2", 4}, {"TrianglesP2", 7}, {"QuadrilateralsQ2", 10}
  };
  for(const Medit_section_layout& s : table)
    if(iequals(keyword, s.keyword))
      return &s;
  return nullptr;
}

template <class Point>
class Medit_reader
{
  typedef Indexed_hex_mesh<Point> Mesh;
  typedef typename Kernel_traits<Point>::Kernel Kernel;
  typedef Hex_mesh_defect D;

public:
  Medit_reader(Text_scanner& sc, const Read_context& ctx) : sc_(sc), ctx_(ctx) {}

  bool read(Mesh& out)
  {
    Token t;
    while(sc_.next(t))
    {
      const std::string_view k = t.text;
      bool ok = true;
      if(iequals(k, "End"))
        break;
      else if(iequals(k, "MeshVersionFormatted"))
      {
        long long version = 0;
        ok = read_header_integer(t, version);
      }
      else if(iequals(k, "Dimension"))
      {
        long long dimension = 0;
        ok = read_header_integer(t, dimension);
        if(ok && dimension != 3)
          return ctx_.fail(t.line, "Dimension " + std::to_string(dimension) +
                                     ": only 3-dimensional meshes are supported");
      }
      else if(iequals(k, "Vertices"))
        ok = read_vertices(t);
      else if(iequals(k, "Hexahedra"))
        ok = read_elements(t, D::HEXAHEDRA, mesh_.hexahedra, mesh_.hexahedron_references);
      else if(iequals(k, "Quadrilaterals"))
        ok = read_elements(t, D::QUADRILATERALS, mesh_.quadrilaterals, mesh_.quadrilateral_references);
      else if(iequals(k, "Triangles"))
        ok = read_elements(t, D::TRIANGLES, mesh_.triangles, mesh_.triangle_references);
      else if(iequals(k, "Edges"))
        ok = read_elements(t, D::EDGES, mesh_.edges, mesh_.edge_references);
      else if(iequals(k, "Corners"))
        ok = read_indices(t, D::CORNERS, mesh_.corners);
      else if(iequals(k, "Ridges"))
        ok = read_indices(t, D::RIDGES, mesh_.ridges);
      else if(const Medit_section_layout* cells = medit_non_hex_cells(k))
        ok = refuse_cells(t, *cells);
      else if(const Medit_section_layout* skip = medit_skippable(k))
        ok = skip_section(t, *skip);
      else
        return unexpected(t);
      if(!ok)
        return false;
    }

    if(section_line_[D::VERTICES] == 0)
      return ctx_.fail(0, "no Vertices section");
    if(section_line_[D::HEXAHEDRA] == 0)
      return ctx_.fail(0, "no Hexahedra section");

    return finish_read(mesh_, out, ctx_, 1, 1,
                       [this](D::Section s, std::size_t record, std::size_t& line) {
                         line = positions_[s].line(record);
                         return std::string(D::section_name(s)) + " record " +
                                std::to_string(record + 1) + positions_[s].where(record);
                       });
  }

private:
  // ------------------------------------------------------------ tokens
  bool read_header_integer(const Token& keyword, long long& v)
  {
    Token t;
    if(!sc_.next(t))
      return ctx_.fail(keyword.line, std::string(keyword.text) + ": value missing (file ends)");
    if(parse_integer(t.text, v) != Number_status::ok)
      return ctx_.fail(t.line, std::string(keyword.text) + ": expected an integer, found " +
                                 quote_token(t.text) + " (line " + std::to_string(t.line) + ")");
    return true;
  }

  /// the number of records after a section keyword (same line or next)
  bool read_count(const Token& keyword, std::size_t& n)
  {
    Token t;
    if(!sc_.next(t))
      return ctx_.fail(keyword.line, std::string(keyword.text) + ": record count missing (file ends)");
    long long v = 0;
    if(parse_integer(t.text, v) != Number_status::ok || v < 0)
      return ctx_.fail(t.line, std::string(keyword.text) + ": expected a record count, found " +
                                 quote_token(t.text) + " (line " + std::to_string(t.line) + ")");
    n = static_cast<std::size_t>(v);
    return true;
  }

  /// notes the section, refusing a second one with the same keyword
  bool begin_section(const Token& keyword, D::Section s)
  {
    if(section_line_[s] != 0)
      return ctx_.fail(keyword.line, "second " + std::string(D::section_name(s)) + " section (line " +
                                       std::to_string(keyword.line) + "; the first one is at line " +
                                       std::to_string(section_line_[s]) + ")");
    section_line_[s] = keyword.line;
    return true;
  }

  /// token `field` of record `i` of a section of `n` records
  bool next_field(const std::string_view section, std::size_t n, std::size_t i, std::size_t field, Token& t)
  {
    if(sc_.next(t))
      return true;
    return ctx_.fail(sc_.line(), std::string(section) + ": expected " + std::to_string(n) +
                                   " records, file ends after " + std::to_string(i) +
                                   (field > 0 ? " and a partial record" : ""));
  }

  bool bad_number(const std::string_view section, std::size_t n, std::size_t i, std::size_t field,
                  const Token& t, Number_status st, const char* expected)
  {
    const std::string at = " (line " + std::to_string(t.line) + ")";
    if(st == Number_status::out_of_range)
      return ctx_.fail(t.line, "number " + quote_token(t.text) + " out of range in " + std::string(section) +
                                 " record " + std::to_string(i + 1) + at);
    if(field == 0 && starts_with_letter(t.text))
      return ctx_.fail(t.line, std::string(section) + ": expected " + std::to_string(n) +
                                 " records, found only " + std::to_string(i) + " before " +
                                 quote_token(t.text) + at);
    return ctx_.fail(t.line, "non-numeric token " + quote_token(t.text) + " in " + std::string(section) +
                               " record " + std::to_string(i + 1) + at + ": expected " + expected);
  }

  bool index_field(const std::string_view section, std::size_t n, std::size_t i, std::size_t field,
                   Token& t, std::size_t& index)
  {
    if(!next_field(section, n, i, field, t))
      return false;
    long long v = 0;
    const Number_status st = parse_integer(t.text, v);
    if(st != Number_status::ok)
      return bad_number(section, n, i, field, t, st, "an integer index");
    // 1-based in the file; 0 and negative values wrap around and are
    // reported as out of range by the validation, with their file value
    index = static_cast<std::size_t>(v - 1);
    return true;
  }

  bool reference_field(const std::string_view section, std::size_t n, std::size_t i, std::size_t field,
                       int& ref)
  {
    Token t;
    if(!next_field(section, n, i, field, t))
      return false;
    const Number_status st = parse_int(t.text, ref);
    return st == Number_status::ok || bad_number(section, n, i, field, t, st, "an integer reference");
  }

  // ------------------------------------------------------------ sections
  bool read_vertices(const Token& keyword)
  {
    std::size_t n = 0;
    if(!begin_section(keyword, D::VERTICES) || !read_count(keyword, n))
      return false;
    const std::string_view section = "Vertices";
    const std::size_t r = reservable(n, sc_.remaining(), 8);
    mesh_.points.reserve(r);
    mesh_.point_references.reserve(r);
    positions_[D::VERTICES].reset(false, r);
    const Kernel gt;
    Token t;
    for(std::size_t i = 0; i < n; ++i)
    {
      Vec3 p;
      for(std::size_t a = 0; a < 3; ++a)
      {
        if(!next_field(section, n, i, a, t))
          return false;
        if(a == 0)
          positions_[D::VERTICES].at.push_back(t.line);
        const Number_status st = parse_real(t.text, p[a]);
        if(st != Number_status::ok)
          return bad_number(section, n, i, a, t, st, "a coordinate");
      }
      int ref = 0;
      if(!reference_field(section, n, i, 3, ref))
        return false;
      mesh_.points.push_back(to_point(p, gt));
      mesh_.point_references.push_back(ref);
    }
    return true;
  }

  template <std::size_t N>
  bool read_elements(const Token& keyword, D::Section s, std::vector<std::array<std::size_t, N> >& elements,
                     std::vector<int>& references)
  {
    std::size_t n = 0;
    if(!begin_section(keyword, s) || !read_count(keyword, n))
      return false;
    const std::string_view section = D::section_name(s);
    const std::size_t r = reservable(n, sc_.remaining(), 2 * (N + 1));
    elements.reserve(r);
    references.reserve(r);
    positions_[s].reset(false, r);
    Token t;
    for(std::size_t i = 0; i < n; ++i)
    {
      std::array<std::size_t, N> e;
      for(std::size_t j = 0; j < N; ++j)
      {
        if(!index_field(section, n, i, j, t, e[j]))
          return false;
        if(j == 0)
          positions_[s].at.push_back(t.line);
      }
      int ref = 0;
      if(!reference_field(section, n, i, N, ref))
        return false;
      elements.push_back(e);
      references.push_back(ref);
    }
    return true;
  }

  /// Corners and Ridges: one index per record, no reference
  bool read_indices(const Token& keyword, D::Section s, std::vector<std::size_t>& indices)
  {
    std::size_t n = 0;
    if(!begin_section(keyword, s) || !read_count(keyword, n))
      return false;
    const std::string_view section = D::section_name(s);
    const std::size_t r = reservable(n, sc_.remaining(), 2);
    indices.reserve(r);
    positions_[s].reset(false, r);
    Token t;
    for(std::size_t i = 0; i < n; ++i)
    {
      std::size_t v = 0;
      if(!index_field(section, n, i, 0, t, v))
        return false;
      positions_[s].at.push_back(t.line);
      indices.push_back(v);
    }
    return true;
  }

  bool refuse_cells(const Token& keyword, const Medit_section_layout& layout)
  {
    std::size_t n = 0;
    if(!read_count(keyword, n))
      return false;
    if(n > 0)
      return ctx_.fail(keyword.line, "cells that are not hexahedra (section " + std::string(layout.keyword) +
                                       ", " + std::to_string(n) + " records, line " +
                                       std::to_string(keyword.line) + ")");
    return true;
  }

  bool skip_section(const Token& keyword, const Medit_section_layout& layout)
  {
    std::size_t n = 0;
    if(!read_count(keyword, n))
      return false;
    const std::string_view section = layout.keyword;
    Token t;
    for(std::size_t i = 0; i < n; ++i)
      for(std::size_t j = 0; j < layout.tokens; ++j)
      {
        if(!next_field(section, n, i, j, t))
          return false;
        double v = 0.;
        const Number_status st = parse_real(t.text, v);
        if(st == Number_status::not_a_number)
          return bad_number(section, n, i, j, t, st, "a number");
      }
    ctx_.warn("skipped section " + std::string(layout.keyword) + " (" + std::to_string(n) +
              " records, line " + std::to_string(keyword.line) + ")");
    return true;
  }

  bool unexpected(const Token& t)
  {
    const std::string at = " (line " + std::to_string(t.line) + ")";
    if(starts_with_letter(t.text))
      return ctx_.fail(t.line, "unknown keyword " + quote_token(t.text) + at +
                                 ": cannot tell the layout of its records");
    double v = 0.;
    if(parse_real(t.text, v) != Number_status::not_a_number)
      return ctx_.fail(t.line, "unexpected number " + quote_token(t.text) + at +
                                 ": more records than a section announced?");
    return ctx_.fail(t.line, "unexpected token " + quote_token(t.text) + at);
  }

  Text_scanner& sc_;
  const Read_context& ctx_;
  Mesh mesh_;
  std::array<Record_positions, 7> positions_;
  std::array<std::size_t, 7> section_line_ = {{0, 0, 0, 0, 0, 0, 0}};
};

/// reads the ASCII MEDIT file `fname` into `out` (unchanged on failure)
template <class Point>
bool read_MEDIT_file(const std::string& fname, Indexed_hex_mesh<Point>& out, const Read_context& ctx)
{
  std::string content, why;
  if(!load_file(fname, content, why))
    return ctx.fail(0, why);
  Text_scanner sc(content.data(), content.data() + content.size(), 1, '#');
  if(sc.at_end())
    return ctx.fail(0, content.empty() ? "empty file" : "empty file (only blanks and comments)");
  Medit_reader<Point> reader(sc, ctx);
  return reader.read(out);
}

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_READ_MEDIT_H
