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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_READ_INP_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_READ_INP_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Reader of Abaqus input files (.inp): *NODE, *ELEMENT of the 8-node
// hexahedral types, *NSET and *ELSET. Lines are read one by one; keywords
// are case-insensitive, "**" starts a comment line, data values are
// separated by commas and an element record may go on over several lines.

#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Id_map.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Read_context.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Text_scanner.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/load_file.h>
#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Kernel_traits.h>

#include <map>
#include <string>
#include <string_view>
#include <unordered_set>
#include <utility>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {
namespace io {

inline std::string_view trim_blanks(std::string_view s)
{
  while(!s.empty() && is_blank(s.front()))
    s.remove_prefix(1);
  while(!s.empty() && is_blank(s.back()))
    s.remove_suffix(1);
  return s;
}

/// the comma-separated fields of a line, trimmed; an empty last field
/// (a trailing comma) is dropped
inline std::vector<std::string_view> split_commas(std::string_view l)
{
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  for(;;)
  {
    const std::size_t comma = l.find(',', start);
    fields.push_back(trim_blanks(l.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
    if(comma == std::string_view::npos)
      break;
    start = comma + 1;
  }
  if(!fields.empty() && fields.back().empty())
    fields.pop_back();
  return fields;
}

/// whether an Abaqus element type (upper case) is an 8-node hexahedron:
/// C3D8 and its variants (R reduced integration, I incompatible modes, H
/// hybrid, T coupled temperature: C3D8R, C3D8RH, C3D8T, ...)
inline bool is_abaqus_hex_type(const std::string& type)
{
  if(type.compare(0, 4, "C3D8") != 0)
    return false;
  for(std::size_t i = 4; i < type.size(); ++i)
    if(type[i] != 'R' && type[i] != 'I' && type[i] != 'H' && type[i] != 'T')
      return false;
  return true;
}

template <class Point>
class Inp_reader
{
  typedef Indexed_hex_mesh<Point> Mesh;
  typedef typename Kernel_traits<Point>::Kernel Kernel;
  typedef Hex_mesh_defect D;

  enum class Mode { none, skip, node, hex, other_element, nset, elset, surface };

public:
  Inp_reader(Text_scanner& sc, const Read_context& ctx) : sc_(sc), ctx_(ctx) {}

  bool read(Mesh& out)
  {
    std::string_view l;
    for(;;)
    {
      line_ = sc_.line();
      if(!sc_.next_line(l))
        break;
      l = trim_blanks(l);
      if(l.empty() || (l.size() >= 2 && l[0] == '*' && l[1] == '*'))
        continue;
      const bool ok = l[0] == '*' ? keyword(l) : data(l);
      if(!ok)
        return false;
    }
    if(!end_block())
      return false;
    if(mesh_.points.empty())
      return ctx_.fail(0, "no *NODE data");
    if(raw_hexes_.empty())
      return ctx_.fail(0, other_elements_.empty() ? "no *ELEMENT data"
                                                  : "no hexahedra (*ELEMENT of TYPE=C3D8, C3D8R, C3D8I, C3D8H, ...)");
    // the nodes of the hexahedra, which may come before their *NODE lines
    mesh_.hexahedra.resize(raw_hexes_.size());
    for(std::size_t h = 0; h < raw_hexes_.size(); ++h)
      for(std::size_t k = 0; k < 8; ++k)
      {
        const std::size_t v = node_ids_.find(raw_hexes_[h][k]);
        if(v == Id_map::none)
          return ctx_.fail(hex_positions_.line(h), "element " + std::to_string(mesh_.hexahedron_ids[h]) +
                                                     hex_positions_.where(h) + ": node " +
                                                     std::to_string(raw_hexes_[h][k]) + " is not defined by *NODE");
        mesh_.hexahedra[h][k] = v;
      }
    for(const auto& s : skipped_types_)
      ctx_.warn("skipped " + std::to_string(s.second.first) + " elements of type " + s.first + " (first line " +
                std::to_string(s.second.second) + "): only 8-node hexahedra (C3D8, C3D8R, C3D8I, C3D8H, ...) are read");
    for(const auto& s : skipped_keywords_)
      ctx_.warn("skipped keyword *" + s.first + " (" + std::to_string(s.second.first) + " times, first line " +
                std::to_string(s.second.second) + ")");
    for(const auto& s : dropped_members_)
      ctx_.warn("*ELSET " + s.first + ": " + std::to_string(s.second) + " members that are not hexahedra dropped");

    return finish_read(mesh_, out, ctx_, 1, 1, [this](D::Section s, std::size_t record, std::size_t& line) {
      if(s == D::VERTICES)
      {
        line = node_positions_.line(record);
        return "node " + std::to_string(mesh_.point_ids[record]) + node_positions_.where(record);
      }
      line = hex_positions_.line(record);
      return "element " + std::to_string(mesh_.hexahedron_ids[record]) + hex_positions_.where(record);
    });
  }

private:
  std::string at() const { return " (line " + std::to_string(line_) + ")"; }

  bool fail(const std::string& what) const { return ctx_.fail(line_, keyword_ + at() + ": " + what); }

  /// the value of parameter `name` of the keyword line (case of the value kept)
  bool parameter(const std::vector<std::string_view>& fields, std::string_view name, std::string& value) const
  {
    for(std::size_t i = 1; i < fields.size(); ++i)
    {
      const std::size_t eq = fields[i].find('=');
      if(iequals(trim_blanks(fields[i].substr(0, eq)), name))
      {
        value = eq == std::string_view::npos ? std::string() : std::string(trim_blanks(fields[i].substr(eq + 1)));
        return true;
      }
    }
    return false;
  }

  /// the set named `name` (case-insensitive), created if needed
  std::size_t set_index(std::vector<Named_index_set>& sets, const std::string& name)
  {
    for(std::size_t i = 0; i < sets.size(); ++i)
      if(iequals(sets[i].name, name))
        return i;
    sets.push_back(Named_index_set{name, {}});
    return sets.size() - 1;
  }

  bool end_block()
  {
    if(!pending_.empty())
      return ctx_.fail(pending_line_, "*ELEMENT (line " + std::to_string(pending_line_) + "): incomplete record (" +
                                        std::to_string(pending_.size()) + " of 9 values: id and 8 nodes)");
    return true;
  }

  bool keyword(std::string_view l)
  {
    if(!end_block())
      return false;
    const std::vector<std::string_view> fields = split_commas(l.substr(1));
    const std::string name = fields.empty() ? std::string() : to_upper(fields[0]);
    keyword_ = "*" + name;
    set_ = static_cast<std::size_t>(-1);
    std::string value;
    generate_ = parameter(fields, "GENERATE", value);
    if(name == "NODE")
    {
      mode_ = Mode::node;
      if(parameter(fields, "NSET", value))
        set_ = set_index(mesh_.vertex_sets, value);
    }
    else if(name == "ELEMENT")
    {
      if(!parameter(fields, "TYPE", value))
        return fail("no TYPE= parameter");
      type_ = to_upper(value);
      mode_ = is_abaqus_hex_type(type_) ? Mode::hex : Mode::other_element;
      if(mode_ == Mode::hex)
      {
        if(mesh_.abaqus_element_type.empty())
          mesh_.abaqus_element_type = type_;
        else if(mesh_.abaqus_element_type != type_ && !mixed_types_)
        {
          mixed_types_ = true;
          ctx_.warn("hexahedra of types " + mesh_.abaqus_element_type + " and " + type_ + " (line " +
                    std::to_string(line_) + "): all are written back as " + mesh_.abaqus_element_type);
        }
        if(parameter(fields, "ELSET", value))
          set_ = set_index(mesh_.hexahedron_sets, value);
      }
      else
      {
        auto& s = skipped_types_[type_];
        if(s.second == 0)
          s.second = line_;
      }
    }
    else if(name == "NSET" || name == "ELSET")
    {
      const bool nodes = name == "NSET";
      if(!parameter(fields, nodes ? "NSET" : "ELSET", value) || value.empty())
        return fail(std::string("no ") + (nodes ? "NSET=" : "ELSET=") + " parameter");
      mode_ = nodes ? Mode::nset : Mode::elset;
      set_ = nodes ? set_index(mesh_.vertex_sets, value) : set_index(mesh_.hexahedron_sets, value);
    }
    else if(name == "SURFACE" && (!parameter(fields, "TYPE", value) || iequals(value, "ELEMENT")))
    {
      if(!parameter(fields, "NAME", value) || value.empty())
        return fail("no NAME= parameter");
      mode_ = Mode::surface;
      set_ = mesh_.side_sets.size();
      for(std::size_t i = 0; i < mesh_.side_sets.size(); ++i)
        if(iequals(mesh_.side_sets[i].name, value))
          set_ = i;
      if(set_ == mesh_.side_sets.size())
        mesh_.side_sets.push_back(Named_side_set{value, {}});
    }
    else
    {
      mode_ = Mode::skip;
      if(name == "HEADING")  // a title, of no use here
        return true;
      auto& s = skipped_keywords_[name];
      if(s.first++ == 0)
        s.second = line_;
    }
    return true;
  }

  bool id_value(std::string_view f, long long& v, const char* what)
  {
    if(parse_integer(f, v) != Number_status::ok)
      return fail(std::string("expected ") + what + ", found " + quote_token(f));
    if(v <= 0)
      return fail(std::string(what) + " " + std::to_string(v) + " is not positive");
    return true;
  }

  bool data(std::string_view l)
  {
    const std::vector<std::string_view> fields = split_commas(l);
    switch(mode_)
    {
    case Mode::none:
      return ctx_.fail(line_, "data line before any keyword" + at() + ": not an Abaqus input file?");
    case Mode::skip:
      return true;
    case Mode::other_element:
      if(l.back() != ',')  // a record ends on a line that does not end with a comma
        ++skipped_types_[type_].first;
      for(std::string_view f : fields)
      {
        long long id = 0;
        if(parse_integer(f, id) == Number_status::ok && !record_started_)
          other_elements_.insert(id);
        record_started_ = true;
      }
      record_started_ = l.back() == ',';
      return true;
    case Mode::node:
      return node(fields);
    case Mode::hex:
      return hex(fields);
    case Mode::nset:
    case Mode::elset:
      return set_members(fields, mode_ == Mode::nset);
    case Mode::surface:
      return surface_sides(fields);
    }
    return true;
  }

  bool node(const std::vector<std::string_view>& fields)
  {
    if(fields.size() != 4)
      return fail("expected 'id, x, y, z', found " + std::to_string(fields.size()) + " values");
    long long id = 0;
    if(!id_value(fields[0], id, "a node id"))
      return false;
    Vec3 p;
    for(int a = 0; a < 3; ++a)
      if(parse_real(fields[std::size_t(a) + 1], p[std::size_t(a)]) != Number_status::ok)
        return fail("expected a coordinate, found " + quote_token(fields[std::size_t(a) + 1]));
    if(!node_ids_.insert(id, mesh_.points.size()))
      return fail("node " + std::to_string(id) + " defined twice");
    if(set_ != static_cast<std::size_t>(-1))
      mesh_.vertex_sets[set_].indices.push_back(mesh_.points.size());
    mesh_.points.push_back(to_point(p, gt_));
    mesh_.point_ids.push_back(id);
    node_positions_.at.push_back(line_);
    return true;
  }

  bool hex(const std::vector<std::string_view>& fields)
  {
    if(pending_.empty())
      pending_line_ = line_;
    for(std::string_view f : fields)
    {
      long long v = 0;
      if(!id_value(f, v, pending_.empty() ? "an element id" : "a node id"))
        return false;
      pending_.push_back(v);
    }
    if(pending_.size() < 9)
      return true;  // continued on the next line
    if(pending_.size() > 9)
      return ctx_.fail(pending_line_, "*ELEMENT, TYPE=" + type_ + " (line " + std::to_string(pending_line_) +
                                        "): " + std::to_string(pending_.size()) +
                                        " values in a record (expected 9: id and 8 nodes)");
    const long long id = pending_[0];
    if(!element_ids_.insert(id, raw_hexes_.size()))
      return ctx_.fail(pending_line_, "*ELEMENT (line " + std::to_string(pending_line_) + "): element " +
                                        std::to_string(id) + " defined twice");
    if(set_ != static_cast<std::size_t>(-1))
      mesh_.hexahedron_sets[set_].indices.push_back(raw_hexes_.size());
    std::array<long long, 8> nodes;
    std::copy(pending_.begin() + 1, pending_.end(), nodes.begin());
    raw_hexes_.push_back(nodes);
    mesh_.hexahedron_ids.push_back(id);
    hex_positions_.at.push_back(pending_line_);
    pending_.clear();
    return true;
  }

  bool add_member(bool nodes, long long id)
  {
    std::vector<Named_index_set>& sets = nodes ? mesh_.vertex_sets : mesh_.hexahedron_sets;
    const std::size_t i = nodes ? node_ids_.find(id) : element_ids_.find(id);
    if(i != Id_map::none)
    {
      sets[set_].indices.push_back(i);
      return true;
    }
    if(!nodes && other_elements_.count(id))
    {
      ++dropped_members_[sets[set_].name];
      return true;
    }
    return fail(std::string(nodes ? "node " : "element ") + std::to_string(id) + " is not defined");
  }

  bool set_members(const std::vector<std::string_view>& fields, bool nodes)
  {
    if(generate_)
    {
      if(fields.size() < 2 || fields.size() > 3)
        return fail("GENERATE expects 'first, last[, step]'");
      long long first = 0, last = 0, step = 1;
      if(!id_value(fields[0], first, "an id") || !id_value(fields[1], last, "an id") ||
         (fields.size() == 3 && !id_value(fields[2], step, "a step")))
        return false;
      if(last < first || (last - first) / step > 100000000)
        return fail("bad GENERATE range " + std::to_string(first) + ", " + std::to_string(last));
      for(long long id = first; id <= last; id += step)
        if(!add_member(nodes, id))
          return false;
      return true;
    }
    std::vector<Named_index_set>& sets = nodes ? mesh_.vertex_sets : mesh_.hexahedron_sets;
    for(std::string_view f : fields)
    {
      long long id = 0;
      if(parse_integer(f, id) == Number_status::ok)
      {
        if(!add_member(nodes, id))
          return false;
        continue;
      }
      // the name of a set defined before
      std::size_t other = sets.size();
      for(std::size_t i = 0; i < sets.size(); ++i)
        if(i != set_ && iequals(sets[i].name, f))
          other = i;
      if(other == sets.size())
        return fail("expected an id or the name of a set, found " + quote_token(f));
      // a bound on repeated members, against sets that double one another
      if(sets[set_].indices.size() + sets[other].indices.size() > 8 * (mesh_.points.size() + raw_hexes_.size()) + 4096)
        return fail("set " + quote_token(sets[set_].name) + " grows beyond 8 times the mesh: sets repeated in one another?");
      const std::vector<std::size_t> members = sets[other].indices;
      sets[set_].indices.insert(sets[set_].indices.end(), members.begin(), members.end());
    }
    return true;
  }

  /// a line of an element-based *SURFACE: "element id or element set, Sn"
  bool surface_sides(const std::vector<std::string_view>& fields)
  {
    if(fields.size() != 2)
      return fail("expected 'element or element set, face (S1..S6)', found " + std::to_string(fields.size()) + " values");
    const std::string face = to_upper(fields[1]);
    if(face.size() != 2 || face[0] != 'S' || face[1] < '1' || face[1] > '6')
      return fail("face " + quote_token(fields[1]) + " of an 8-node hexahedron must be S1..S6");
    // Abaqus faces S1..S6 as local faces of Named_side_set (Exodus numbering)
    static const int local_face[6] = {4, 5, 0, 1, 2, 3};
    const int local = local_face[face[1] - '1'];
    std::vector<std::pair<std::size_t, int> >& sides = mesh_.side_sets[set_].sides;
    long long id = 0;
    if(parse_integer(fields[0], id) == Number_status::ok)
    {
      const std::size_t h = element_ids_.find(id);
      if(h == Id_map::none)
        return fail("element " + std::to_string(id) + " is not a hexahedron defined before");
      sides.push_back({h, local});
      return true;
    }
    for(const Named_index_set& set : mesh_.hexahedron_sets)
      if(iequals(set.name, fields[0]))
      {
        for(std::size_t h : set.indices)
          sides.push_back({h, local});
        return true;
      }
    return fail("expected an element id or the name of an element set, found " + quote_token(fields[0]));
  }

  static std::string to_upper(std::string_view s)
  {
    std::string r(trim_blanks(s));
    for(char& c : r)
      if(c >= 'a' && c <= 'z')
        c = static_cast<char>(c - 'a' + 'A');
    return r;
  }

  Text_scanner& sc_;
  const Read_context& ctx_;
  const Kernel gt_ = Kernel();
  Mesh mesh_;
  Mode mode_ = Mode::none;
  std::string keyword_, type_;
  std::size_t line_ = 0, pending_line_ = 0, set_ = static_cast<std::size_t>(-1);
  bool generate_ = false, mixed_types_ = false, record_started_ = false;
  std::vector<long long> pending_;
  std::vector<std::array<long long, 8> > raw_hexes_;
  Id_map node_ids_, element_ids_;
  std::unordered_set<long long> other_elements_;
  Record_positions node_positions_, hex_positions_;
  std::map<std::string, std::pair<std::size_t, std::size_t> > skipped_types_, skipped_keywords_;
  std::map<std::string, std::size_t> dropped_members_;
};

/// reads the Abaqus input file `fname` into `out` (unchanged on failure)
template <class Point>
bool read_INP_file(const std::string& fname, Indexed_hex_mesh<Point>& out, const Read_context& ctx)
{
  std::string content, why;
  if(!load_file(fname, content, why))
    return ctx.fail(0, why);
  Text_scanner sc(content.data(), content.data() + content.size(), 1);
  if(sc.at_end())
    return ctx.fail(0, "empty file");
  Text_scanner lines(content.data(), content.data() + content.size(), 1);
  Inp_reader<Point> reader(lines, ctx);
  return reader.read(out);
}

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_READ_INP_H
