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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_READ_VTU_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_READ_VTU_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Reader of VTK XML unstructured grids (.vtu) whose Points and Cells arrays
// are stored as text (format="ascii"), as write_VTU() writes them. Binary,
// appended and compressed encodings are refused with a message saying so.
// PointData and CellData are ignored, whatever their encoding.

#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Read_context.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Text_scanner.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Xml_scanner.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/load_file.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/vtk_cells.h>
#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Kernel_traits.h>

#include <cstddef>
#include <string>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {
namespace io {

/// a DataArray of interest: its attributes and where its text lies
struct Vtu_data_array
{
  std::string label;           // for messages: "Points DataArray", "DataArray 'offsets'"
  bool found = false;
  bool closed = false;
  std::string format = "ascii";
  std::string components;      // NumberOfComponents, "" if absent
  std::size_t line = 0;        // line of the start tag
  const char* text_begin = nullptr;
  const char* text_end = nullptr;
  std::size_t text_line = 0;   // line where the text starts

  void open(const Xml_tag& tag)
  {
    found = true;
    line = tag.line;
    if(const std::string* f = tag.attribute("format"))
      format = *f;
    if(const std::string* c = tag.attribute("NumberOfComponents"))
      components = *c;
    text_begin = text_end = tag.end;
    text_line = tag.end_line;
    closed = tag.self_closing;
  }

  std::string where() const { return label + " (line " + std::to_string(line) + ")"; }
};

template <class Point>
class Vtu_reader
{
  typedef Indexed_hex_mesh<Point> Mesh;
  typedef typename Kernel_traits<Point>::Kernel Kernel;
  typedef Hex_mesh_defect D;

public:
  Vtu_reader(const std::string& content, const Read_context& ctx) : content_(content), ctx_(ctx)
  {
    points_.label = "Points DataArray";
    connectivity_.label = "DataArray 'connectivity'";
    offsets_.label = "DataArray 'offsets'";
    types_.label = "DataArray 'types'";
  }

  bool read(Mesh& out)
  {
    if(!scan_xml() || !check_arrays())
      return false;

    std::size_t coordinate_count = 0;
    if(!checked_product(3, number_of_points_, coordinate_count))
      return ctx_.fail(0, "<Piece>: absurd NumberOfPoints");
    std::vector<double> coordinates;
    std::vector<long long> offsets;
    std::vector<std::size_t> point_lines, connectivity_lines, offset_lines;
    if(!parse(points_, coordinate_count, 3, "points", coordinates, &point_lines) ||
       !parse(connectivity_, std::size_t(-1), 1, "values", cells_.connectivity, &connectivity_lines) ||
       !parse(offsets_, number_of_cells_, 1, "cells", offsets, &offset_lines) ||
       !parse(types_, number_of_cells_, 1, "cells", cells_.types, nullptr))
      return false;

    const Kernel gt;
    mesh_.points.reserve(number_of_points_);
    point_positions_.reset(false, number_of_points_);
    for(std::size_t i = 0; i < number_of_points_; ++i)
    {
      mesh_.points.push_back(to_point(Vec3{{coordinates[3 * i], coordinates[3 * i + 1], coordinates[3 * i + 2]}}, gt));
      point_positions_.at.push_back(point_lines[3 * i]);
    }

    // VTU offsets are the ends of the cells
    cells_.offsets.reserve(number_of_cells_ + 1);
    cells_.offsets.push_back(0);
    cells_.records.reset(false, number_of_cells_);
    for(std::size_t i = 0; i < number_of_cells_; ++i)
    {
      const long long begin = cells_.offsets.back(), end = offsets[i];
      if(end < begin || end > static_cast<long long>(cells_.connectivity.size()))
        return ctx_.fail(offset_lines[i], offsets_.where() + ": offset " + std::to_string(end) + " of cell " +
                                            std::to_string(i) + " (line " + std::to_string(offset_lines[i]) +
                                            ") is inconsistent with the " +
                                            std::to_string(cells_.connectivity.size()) + " connectivity values");
      cells_.offsets.push_back(end);
      cells_.records.at.push_back(end > begin ? connectivity_lines[static_cast<std::size_t>(begin)] : offset_lines[i]);
    }
    if(cells_.offsets.back() != static_cast<long long>(cells_.connectivity.size()))
      return ctx_.fail(offsets_.line, offsets_.where() + ": the cells use " + std::to_string(cells_.offsets.back()) +
                                        " of the " + std::to_string(cells_.connectivity.size()) +
                                        " connectivity values");

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
  bool scan_xml()
  {
    Xml_scanner xml(content_.data(), content_.data() + content_.size());
    std::vector<std::string> open_elements;
    Vtu_data_array* open_array = nullptr;
    std::size_t pieces = 0;
    bool appended_data = false;
    Xml_tag tag;
    while(xml.next(tag))
    {
      const std::string name(tag.name);
      if(open_array != nullptr && !open_array->closed)
      {
        // the text ends at the first tag: the end tag, or a child such as
        // the <InformationKey> elements VTK writes after the values
        open_array->text_end = tag.begin;
        open_array->closed = true;
      }
      if(tag.closing)
      {
        if(open_elements.empty() || open_elements.back() != name)
          return ctx_.fail(tag.line, "malformed XML: </" + name + "> at line " + std::to_string(tag.line) +
                                       (open_elements.empty() ? std::string(" closes nothing")
                                                              : " where </" + open_elements.back() + "> is expected"));
        open_elements.pop_back();
        if(open_array != nullptr && name == "DataArray")
          open_array = nullptr;
        continue;
      }
      if(open_elements.empty())
      {
        if(!open_root(tag, name))
          return false;
      }
      else if(name == "AppendedData")
      {
        appended_data = true;  // raw bytes follow: no more markup to read
        break;
      }
      else if(name == "Piece")
      {
        if(++pieces > 1)
          return ctx_.fail(tag.line, "more than one <Piece> (line " + std::to_string(tag.line) +
                                       "): multi-piece .vtu files are not supported");
        if(!piece_size(tag, "NumberOfPoints", number_of_points_) ||
           !piece_size(tag, "NumberOfCells", number_of_cells_))
          return false;
      }
      else if(name == "DataArray")
      {
        if(!open_data_array(tag, open_elements.back(), open_array))
          return false;
      }
      if(!tag.self_closing)
        open_elements.push_back(name);
    }
    if(!xml.error().empty())
      return ctx_.fail(xml.error_line(), xml.error());
    if(!root_seen_)
      return ctx_.fail(0, "not a VTK XML file: no <VTKFile> element");
    if(pieces == 0)
      return ctx_.fail(0, "no <Piece> element");
    if(!appended_data && !open_elements.empty())
      return ctx_.fail(xml.line(), "truncated XML: <" + open_elements.back() + "> is not closed at the end of the file");
    return true;
  }

  // the root element: <VTKFile type="UnstructuredGrid">, uncompressed
  bool open_root(const Xml_tag& tag, const std::string& name)
  {
    if(name != "VTKFile")
      return ctx_.fail(tag.line, "not a VTK XML file: the root element is <" + name + ">, not <VTKFile>");
    const std::string* type = tag.attribute("type");
    if(type == nullptr || *type != "UnstructuredGrid")
      return ctx_.fail(tag.line, "VTK XML file of type '" + (type ? *type : std::string()) +
                                   "': only UnstructuredGrid (.vtu) is supported");
    const std::string* compressor = tag.attribute("compressor");
    if(compressor != nullptr && !compressor->empty())
      return ctx_.fail(tag.line, "compressed data (compressor=\"" + *compressor +
                                   "\") is not supported: save the .vtu with ascii data");
    root_seen_ = true;
    return true;
  }

  // a <DataArray> in `parent`: the points, or one of the three arrays of the
  // cells (the others are skipped); `open_array` receives it when its text
  // follows
  bool open_data_array(const Xml_tag& tag, const std::string& parent, Vtu_data_array*& open_array)
  {
    const std::string* array_name = tag.attribute("Name");
    Vtu_data_array* a = nullptr;
    if(parent == "Points" && !points_.found)
      a = &points_;
    else if(parent == "Cells" && array_name != nullptr)
    {
      if(*array_name == "connectivity") a = &connectivity_;
      else if(*array_name == "offsets") a = &offsets_;
      else if(*array_name == "types") a = &types_;
    }
    if(a == nullptr)
      return true;
    if(a->found)
      return ctx_.fail(tag.line, "second " + a->label + " at line " + std::to_string(tag.line));
    a->open(tag);
    if(!tag.self_closing)
      open_array = a;
    return true;
  }

  bool piece_size(const Xml_tag& tag, const char* key, std::size_t& n)
  {
    const std::string* v = tag.attribute(key);
    long long w = 0;
    if(v == nullptr || parse_integer(*v, w) != Number_status::ok || w < 0)
      return ctx_.fail(tag.line, std::string("<Piece> (line ") + std::to_string(tag.line) + "): " + key +
                                   (v ? " is " + quote_token(*v) : std::string(" is missing")));
    n = static_cast<std::size_t>(w);
    return true;
  }

  bool check_arrays()
  {
    for(const Vtu_data_array* a : {&points_, &connectivity_, &offsets_, &types_})
    {
      if(!a->found)
        return ctx_.fail(0, "no " + a->label + (a == &points_ ? " in <Points>" : " in <Cells>"));
      if(a->format != "ascii")
        return ctx_.fail(a->line, a->where() + " has format=\"" + a->format +
                                    "\": only format=\"ascii\" is supported (in ParaView, save with "
                                    "Data Mode 'Ascii')");
      if(!a->closed)
        return ctx_.fail(a->line, a->where() + " is not closed: truncated file?");
    }
    if(points_.components != "3")
      return ctx_.fail(points_.line, points_.where() + ": NumberOfComponents must be 3, not '" +
                                       points_.components + "'");
    return true;
  }

  /// the numbers of array `a`: exactly `expected` of them unless `expected`
  /// is -1; `per_record` numbers make one of the `record_word` in messages
  template <class Number>
  bool parse(const Vtu_data_array& a, std::size_t expected, std::size_t per_record, const char* record_word,
             std::vector<Number>& out, std::vector<std::size_t>* lines)
  {
    Text_scanner sc(a.text_begin, a.text_end, a.text_line);
    const bool any = (expected == std::size_t(-1));
    if(!any)
    {
      out.reserve(reservable(expected, static_cast<std::size_t>(a.text_end - a.text_begin), 2));
      if(lines != nullptr)
        lines->reserve(out.capacity());
    }
    Token t;
    while(any || out.size() < expected)
    {
      if(!sc.next(t))
      {
        if(any)
          break;
        return ctx_.fail(a.line, a.where() + ": expected " + std::to_string(expected / per_record) + " " +
                                   record_word + ", the array ends after " +
                                   std::to_string(out.size() / per_record));
      }
      Number v = 0;
      const Number_status st = parse_number(t.text, v);
      if(st != Number_status::ok)
        return ctx_.fail(t.line, (st == Number_status::out_of_range ? "number " : "non-numeric token ") +
                                   quote_token(t.text) + " in " + a.label + " (line " + std::to_string(t.line) + ")");
      out.push_back(v);
      if(lines != nullptr)
        lines->push_back(t.line);
    }
    if(!any && sc.next(t))
      return ctx_.fail(t.line, a.where() + ": more than the " + std::to_string(expected) +
                                 " values announced by <Piece> (line " + std::to_string(t.line) + ")");
    return true;
  }

  static Number_status parse_number(std::string_view s, double& v) { return parse_real(s, v); }
  static Number_status parse_number(std::string_view s, long long& v) { return parse_integer(s, v); }

  const std::string& content_;
  const Read_context& ctx_;
  bool root_seen_ = false;
  std::size_t number_of_points_ = 0, number_of_cells_ = 0;
  Vtu_data_array points_, connectivity_, offsets_, types_;
  Mesh mesh_;
  Record_positions point_positions_;
  Vtk_cells cells_;
};

/// reads the .vtu file `fname` into `out` (unchanged on failure)
template <class Point>
bool read_VTU_file(const std::string& fname, Indexed_hex_mesh<Point>& out, const Read_context& ctx)
{
  std::string content, why;
  if(!load_file(fname, content, why))
    return ctx.fail(0, why);
  if(Text_scanner(content.data(), content.data() + content.size()).at_end())
    return ctx.fail(0, content.empty() ? "empty file" : "empty file (only blanks)");
  Vtu_reader<Point> reader(content, ctx);
  return reader.read(out);
}

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_READ_VTU_H
