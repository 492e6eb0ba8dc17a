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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_READ_MSH_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_READ_MSH_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Reader of gmsh .msh files, versions 2.2 and 4.1, ASCII and binary. The
// hexahedra (element type 5) are kept with their physical tag as reference;
// other surface, line and point elements are skipped with one warning per
// type; other volume elements are an error. Binary files must have the byte
// order of this machine (the endianness marker says) and data-size 8.

#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Id_map.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Read_context.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Text_scanner.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/load_file.h>
#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Kernel_traits.h>

#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {
namespace io {

/// nodes of a gmsh element type (0: unknown type), its dimension and name
inline int msh_element_nodes(long long type, int& dimension, const char*& name)
{
  struct Type { int nodes; int dimension; const char* name; };
  static const Type table[] = {
    {0, 0, "?"}, {2, 1, "2-node line"}, {3, 2, "3-node triangle"}, {4, 2, "4-node quadrangle"},
    {4, 3, "4-node tetrahedron"}, {8, 3, "8-node hexahedron"}, {6, 3, "6-node prism"},
    {5, 3, "5-node pyramid"}, {3, 1, "3-node line"}, {6, 2, "6-node triangle"},
    {9, 2, "9-node quadrangle"}, {10, 3, "10-node tetrahedron"}, {27, 3, "27-node hexahedron"},
    {18, 3, "18-node prism"}, {14, 3, "14-node pyramid"}, {1, 0, "point"}, {8, 2, "8-node quadrangle"},
    {20, 3, "20-node hexahedron"}, {15, 3, "15-node prism"}, {13, 3, "13-node pyramid"},
    {9, 2, "9-node triangle"}, {10, 2, "10-node triangle"}, {12, 2, "12-node triangle"},
    {15, 2, "15-node triangle"}, {15, 2, "15-node triangle"}, {21, 2, "21-node triangle"},
    {4, 1, "4-node line"}, {5, 1, "5-node line"}, {6, 1, "6-node line"}, {20, 3, "20-node tetrahedron"},
    {35, 3, "35-node tetrahedron"}, {56, 3, "56-node tetrahedron"}
  };
  if(type >= 1 && type <= 31)
  {
    dimension = table[type].dimension;
    name = table[type].name;
    return table[type].nodes;
  }
  dimension = 3;
  if(type == 92) { name = "64-node hexahedron"; return 64; }
  if(type == 93) { name = "125-node hexahedron"; return 125; }
  name = "?";
  return 0;
}

template <class Point>
class Msh_reader
{
  typedef Indexed_hex_mesh<Point> Mesh;
  typedef typename Kernel_traits<Point>::Kernel Kernel;
  typedef Hex_mesh_defect D;

public:
  Msh_reader(Text_scanner& sc, const Read_context& ctx) : sc_(sc), ctx_(ctx) {}

  bool read(Mesh& out)
  {
    Token t;
    while(sc_.next(t))
    {
      if(t.text.empty() || t.text[0] != '$')
        return ctx_.fail(t.line, "expected a section ($Name), found " + quote_token(t.text) + at(t.line));
      section_ = std::string(t.text.substr(1));
      section_line_ = t.line;
      bool ok = true;
      if(section_ == "MeshFormat")
        ok = read_format();
      else if(version_ == 0)
        return ctx_.fail(t.line, "the file does not start with $MeshFormat (found " + quote_token(t.text) +
                                   at(t.line) + "): not a gmsh file?");
      else if(section_ == "PhysicalNames")
        ok = read_physical_names();
      else if(section_ == "Entities" && version_ == 4)
        ok = read_entities();
      else if(section_ == "Nodes")
        ok = nodes_read_ ? fail_here("second $Nodes section") : (version_ == 2 ? read_nodes_2() : read_nodes_4());
      else if(section_ == "Elements")
        ok = elements_read_ ? fail_here("second $Elements section")
                            : (version_ == 2 ? read_elements_2() : read_elements_4());
      else
      {
        ok = skip_section();
        continue;
      }
      if(!ok || !end_section())
        return false;
    }
    if(version_ == 0)
      return ctx_.fail(0, "no $MeshFormat section: not a gmsh file");
    if(!nodes_read_)
      return ctx_.fail(0, "no $Nodes section");
    if(!elements_read_)
      return ctx_.fail(0, "no $Elements section");

    for(const auto& s : skipped_)
      ctx_.warn("skipped " + std::to_string(s.second.count) + " elements of type " + std::to_string(s.first) +
                " (" + s.second.name + "), the first " + s.second.where);
    for(const auto& s : skipped_sections_)
      ctx_.warn("skipped section $" + s.first + " (line " + std::to_string(s.second) + ")");
    if(version_ == 4)
    {
      // the reference of a hexahedron is the physical tag of its volume entity
      for(std::size_t h = 0; h < hex_entities_.size(); ++h)
      {
        const auto it = volume_physicals_.find(hex_entities_[h]);
        mesh_.hexahedron_references[h] = it == volume_physicals_.end() ? 0 : it->second;
      }
      if(several_physicals_)
        ctx_.warn("volume entities with several physical tags: each hexahedron keeps the first one");
    }
    for(auto it = mesh_.hexahedron_reference_names.begin(); it != mesh_.hexahedron_reference_names.end();)
      it = it->first == 0 ? mesh_.hexahedron_reference_names.erase(it) : ++it;

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
  static std::string at(std::size_t line) { return " (line " + std::to_string(line) + ")"; }

  bool fail_here(const std::string& what) const
  {
    return ctx_.fail(section_line_, "$" + section_ + at(section_line_) + ": " + what);
  }

  // ------------------------------------------------------------ ASCII
  bool token(Token& t)
  {
    if(sc_.next(t))
      return true;
    return ctx_.fail(sc_.line(), "$" + section_ + ": file ends before $End" + section_);
  }

  bool integer(long long& v, const char* what, long long min = 0)
  {
    Token t;
    if(!token(t))
      return false;
    const Number_status st = parse_integer(t.text, v);
    if(st != Number_status::ok || v < min)
      return ctx_.fail(t.line, "$" + section_ + ": expected " + what + ", found " + quote_token(t.text) + at(t.line));
    last_line_ = t.line;
    return true;
  }

  bool real(double& v, const char* what)
  {
    Token t;
    if(!token(t))
      return false;
    const Number_status st = parse_real(t.text, v);
    if(st != Number_status::ok)
      return ctx_.fail(t.line, "$" + section_ + ": expected " + what + ", found " + quote_token(t.text) + at(t.line));
    return true;
  }

  // ------------------------------------------------------------ binary
  std::string byte_at() const { return " (byte " + std::to_string(sc_.offset()) + ")"; }

  bool raw(std::size_t n, const char*& p, const char* what)
  {
    if(sc_.remaining() < n)
      return ctx_.fail(0, "$" + section_ + ": file ends in the binary data (" + what + ")" + byte_at());
    p = sc_.take(n);
    return true;
  }

  template <class T>
  bool bin(T& v, const char* what)
  {
    const char* p = nullptr;
    if(!raw(sizeof(T), p, what))
      return false;
    std::memcpy(&v, p, sizeof(T));
    return true;
  }

  /// a count or tag: ASCII token or binary size_t (4.1) / int (2.2)
  bool value(long long& v, const char* what, bool binary_size_t, long long min = 0)
  {
    if(!binary_)
      return integer(v, what, min);
    const std::size_t pos = sc_.offset();
    if(binary_size_t)
    {
      std::uint64_t u = 0;
      if(!bin(u, what))
        return false;
      if(u > static_cast<std::uint64_t>(1) << 62)
        return ctx_.fail(0, "$" + section_ + ": " + what + " " + std::to_string(u) + " out of range (byte " +
                              std::to_string(pos) + ")");
      v = static_cast<long long>(u);
    }
    else
    {
      std::int32_t i = 0;
      if(!bin(i, what))
        return false;
      v = i;
    }
    if(v < min)
      return ctx_.fail(0, "$" + section_ + ": " + what + " " + std::to_string(v) + " out of range (byte " +
                            std::to_string(pos) + ")");
    return true;
  }

  bool coordinate(double& v)
  {
    return binary_ ? bin(v, "a coordinate") : real(v, "a coordinate");
  }

  // ------------------------------------------------------------ sections
  bool end_section()
  {
    Token t;
    if(!sc_.next(t))
      return ctx_.fail(sc_.line(), "$" + section_ + ": file ends before $End" + section_);
    if(t.text != "$End" + section_)
    {
      if(binary_ && t.text.size() > 0 && t.text[0] != '$')
        return ctx_.fail(0, "$" + section_ + ": expected $End" + section_ + " after the binary data" +
                              byte_at() + ": wrong counts, or a file written with another data size?");
      return ctx_.fail(t.line, "$" + section_ + ": expected $End" + section_ + ", found " +
                                 quote_token(t.text) + at(t.line) + ": more records than announced?");
    }
    return true;
  }

  bool skip_section()
  {
    const std::string end = "$End" + section_;
    // search the bytes, which may be binary, for the end marker at the start of a line
    for(;;)
    {
      std::string_view l;
      if(!sc_.next_line(l))
        return ctx_.fail(section_line_, "$" + section_ + at(section_line_) + ": no " + end);
      while(!l.empty() && is_blank(l.front()))
        l.remove_prefix(1);
      while(!l.empty() && is_blank(l.back()))
        l.remove_suffix(1);
      if(l == end)
        break;
    }
    skipped_sections_.emplace(section_, section_line_);
    return true;
  }

  bool read_format()
  {
    if(version_ != 0)
      return fail_here("second $MeshFormat section");
    Token t;
    if(!token(t))
      return false;
    const std::size_t line = t.line;
    if(t.text == "2.2")
      version_ = 2;
    else if(t.text == "4.1")
      version_ = 4;
    else
      return ctx_.fail(line, "$MeshFormat" + at(line) + ": version " + quote_token(t.text) +
                               " is not supported (only 2.2 and 4.1; gmsh -save_all -format msh41 converts)");
    long long file_type = 0, data_size = 0;
    if(!integer(file_type, "the file type (0 ASCII, 1 binary)") || !integer(data_size, "the data size"))
      return false;
    if(file_type > 1)
      return ctx_.fail(line, "$MeshFormat" + at(line) + ": file type " + std::to_string(file_type) +
                               " (expected 0 for ASCII or 1 for binary)");
    if(data_size != 8)
      return ctx_.fail(line, "$MeshFormat" + at(line) + ": data size " + std::to_string(data_size) +
                               " is not supported (only 8: 64-bit size_t and double)");
    binary_ = file_type == 1;
    if(binary_)
    {
      if(!sc_.finish_line())
        return ctx_.fail(line, "$MeshFormat" + at(line) + ": the binary endianness marker must follow on its own line");
      std::int32_t one = 0;
      if(!bin(one, "the endianness marker"))
        return false;
      if(one != 1)
      {
        std::uint32_t u;
        std::memcpy(&u, &one, 4);
        const bool swapped = u == 0x01000000u;
        return ctx_.fail(line + 1, swapped ? std::string("$MeshFormat: binary file of the other byte order "
                                                         "(endianness marker 1 byte-swapped): not supported")
                                           : "$MeshFormat: bad binary endianness marker (expected the integer 1)");
      }
    }
    return true;
  }

  bool read_physical_names()
  {
    long long n = 0;
    if(!integer(n, "the number of physical names"))
      return false;
    if(!sc_.finish_line())
      return fail_here("the number of names must end its line");
    for(long long i = 0; i < n; ++i)
    {
      std::string_view l;
      const std::size_t line = sc_.line();
      if(!sc_.next_line(l))
        return ctx_.fail(line, "$PhysicalNames: file ends after " + std::to_string(i) + " of " + std::to_string(n) + " names");
      Text_scanner fields(l.data(), l.data() + l.size(), line);
      Token d, tag;
      long long dim = 0;
      int tag_value = 0;
      if(!fields.next(d) || !fields.next(tag) || parse_integer(d.text, dim) != Number_status::ok ||
         parse_int(tag.text, tag_value) != Number_status::ok)
        return ctx_.fail(line, "$PhysicalNames" + at(line) + ": expected 'dimension tag \"name\"', found " + quote_token(l));
      const std::size_t open = l.find('"');
      const std::size_t close = l.rfind('"');
      if(open == std::string_view::npos || close == open)
        return ctx_.fail(line, "$PhysicalNames" + at(line) + ": the name must be in double quotes");
      if(dim == 3)
        mesh_.hexahedron_reference_names[tag_value] = std::string(l.substr(open + 1, close - open - 1));
    }
    return true;
  }

  /// 4.1 $Entities: the physical tags of the volumes
  bool read_entities()
  {
    if(binary_ && !sc_.finish_line())
      return fail_here("binary data must start on the line after $Entities");
    long long counts[4];
    for(long long& c : counts)
      if(!value(c, "an entity count", true))
        return false;
    for(int dim = 0; dim < 4; ++dim)
      for(long long e = 0; e < counts[dim]; ++e)
      {
        long long tag = 0;
        if(binary_)
        {
          std::int32_t i = 0;
          if(!bin(i, "an entity tag"))
            return false;
          tag = i;
        }
        else if(!integer(tag, "an entity tag", LLONG_MIN))
          return false;
        double box = 0.;
        for(int k = 0; k < (dim == 0 ? 3 : 6); ++k)
          if(!coordinate(box))
            return false;
        long long physicals = 0;
        if(!value(physicals, "a number of physical tags", true))
          return false;
        for(long long p = 0; p < physicals; ++p)
        {
          long long phys = 0;
          if(!value(phys, "a physical tag", false, LLONG_MIN))
            return false;
          if(dim == 3 && p == 0)
            volume_physicals_[static_cast<int>(tag)] = static_cast<int>(phys);
          if(dim == 3 && p == 1)
            several_physicals_ = true;
        }
        if(dim > 0)
        {
          long long bounding = 0;
          if(!value(bounding, "a number of bounding entities", true))
            return false;
          for(long long b = 0; b < bounding; ++b)
          {
            long long bt = 0;
            if(!value(bt, "a bounding entity tag", false, LLONG_MIN))
              return false;
          }
        }
      }
    return true;
  }

  bool add_node(long long tag, const Vec3& p, std::size_t where)
  {
    if(tag <= 0)
      return ctx_.fail(binary_ ? 0 : where, "$Nodes: node tag " + std::to_string(tag) + " is not positive" +
                                               (binary_ ? " (byte " : " (line ") + std::to_string(where) + ")");
    if(!node_ids_.insert(tag, mesh_.points.size()))
      return ctx_.fail(binary_ ? 0 : where, "$Nodes: node tag " + std::to_string(tag) + " defined twice" +
                                               (binary_ ? " (byte " : " (line ") + std::to_string(where) + ")");
    mesh_.points.push_back(to_point(p, gt_));
    mesh_.point_ids.push_back(tag);
    node_positions_.at.push_back(where);
    return true;
  }

  bool read_nodes_2()
  {
    nodes_read_ = true;
    long long n = 0;
    if(!integer(n, "the number of nodes"))
      return false;
    const std::size_t r = reservable(static_cast<std::size_t>(n), sc_.remaining(), binary_ ? 28 : 8);
    mesh_.points.reserve(r);
    node_positions_.reset(binary_, r);
    if(binary_ && !sc_.finish_line())
      return fail_here("the number of nodes must end its line");
    for(long long i = 0; i < n; ++i)
    {
      long long tag = 0;
      Vec3 p;
      const std::size_t where = binary_ ? sc_.offset() : 0;
      if(!value(tag, "a node tag", false, LLONG_MIN))
        return false;
      for(double& c : p)
        if(!coordinate(c))
          return false;
      if(!add_node(tag, p, binary_ ? where : last_line_))
        return false;
    }
    return true;
  }

  bool read_nodes_4()
  {
    nodes_read_ = true;
    if(binary_ && !sc_.finish_line())
      return fail_here("binary data must start on the line after $Nodes");
    long long blocks = 0, n = 0, min_tag = 0, max_tag = 0;
    if(!value(blocks, "the number of entity blocks", true) || !value(n, "the number of nodes", true) ||
       !value(min_tag, "the minimum node tag", true) || !value(max_tag, "the maximum node tag", true))
      return false;
    const std::size_t r = reservable(static_cast<std::size_t>(n), sc_.remaining(), binary_ ? 32 : 8);
    mesh_.points.reserve(r);
    node_positions_.reset(binary_, r);
    for(long long b = 0; b < blocks; ++b)
    {
      long long dim = 0, entity = 0, parametric = 0, count = 0;
      if(!value(dim, "an entity dimension", false) || !value(entity, "an entity tag", false, LLONG_MIN) ||
         !value(parametric, "the parametric flag", false) || !value(count, "a number of nodes", true))
        return false;
      if(dim > 3 || parametric > 1)
        return fail_here("bad node block header (entity dimension " + std::to_string(dim) + ", parametric " +
                         std::to_string(parametric) + ")");
      const std::size_t extra = parametric == 1 ? static_cast<std::size_t>(dim) : 0;
      tags_.clear();
      std::vector<std::size_t> where;
      for(long long i = 0; i < count; ++i)
      {
        long long tag = 0;
        where.push_back(binary_ ? sc_.offset() : 0);
        if(!value(tag, "a node tag", true, LLONG_MIN))
          return false;
        if(!binary_)
          where.back() = last_line_;
        tags_.push_back(tag);
      }
      for(long long i = 0; i < count; ++i)
      {
        Vec3 p;
        for(double& c : p)
          if(!coordinate(c))
            return false;
        for(std::size_t k = 0; k < extra; ++k)
        {
          double u = 0.;
          if(!coordinate(u))
            return false;
        }
        if(!add_node(tags_[static_cast<std::size_t>(i)], p, where[static_cast<std::size_t>(i)]))
          return false;
      }
    }
    if(static_cast<long long>(mesh_.points.size()) != n)
      return fail_here("announces " + std::to_string(n) + " nodes, its blocks hold " + std::to_string(mesh_.points.size()));
    return true;
  }

  /// an element of `type` with tag `tag` and `nodes` node tags; `reference`
  /// (2.2) or `entity` (4.1) its group
  bool add_element(long long type, long long tag, const std::vector<long long>& nodes, int reference, int entity,
                   std::size_t where)
  {
    const std::string place = (binary_ ? " (byte " : " (line ") + std::to_string(where) + ")";
    if(type != 5)
    {
      int dim = 0;
      const char* name = nullptr;
      msh_element_nodes(type, dim, name);
      if(dim == 3)
        return ctx_.fail(binary_ ? 0 : where, "$Elements: element " + std::to_string(tag) + place + " is a " + name +
                                                 " (type " + std::to_string(type) + "): only hexahedra (type 5) are supported");
      Skipped& s = skipped_[static_cast<int>(type)];
      if(s.count++ == 0)
      {
        s.name = name;
        s.where = "element " + std::to_string(tag) + place;
      }
      return true;
    }
    if(tag <= 0 || !element_ids_.insert(tag, element_ids_.size()))
      return ctx_.fail(binary_ ? 0 : where, "$Elements: element tag " + std::to_string(tag) + place +
                                               (tag <= 0 ? " is not positive" : " used twice"));
    typename Mesh::Hexahedron h;
    for(std::size_t k = 0; k < 8; ++k)
    {
      const std::size_t v = node_ids_.find(nodes[k]);
      if(v == Id_map::none)
        return ctx_.fail(binary_ ? 0 : where, "$Elements: element " + std::to_string(tag) + place + ": node tag " +
                                                 std::to_string(nodes[k]) + " is not in $Nodes");
      h[k] = v;
    }
    mesh_.hexahedra.push_back(h);
    mesh_.hexahedron_ids.push_back(tag);
    mesh_.hexahedron_references.push_back(reference);
    if(version_ == 4)
      hex_entities_.push_back(entity);
    hex_positions_.at.push_back(where);
    return true;
  }

  bool element_type(long long type, std::size_t& nodes, std::size_t where)
  {
    int dim = 0;
    const char* name = nullptr;
    nodes = static_cast<std::size_t>(msh_element_nodes(type, dim, name));
    if(nodes == 0)
      return ctx_.fail(binary_ ? 0 : where, "$Elements: unknown element type " + std::to_string(type) +
                                               (binary_ ? " (byte " : " (line ") + std::to_string(where) + ")");
    return true;
  }

  bool read_elements_2()
  {
    elements_read_ = true;
    hex_positions_.reset(binary_, 0);
    long long n = 0;
    if(!integer(n, "the number of elements"))
      return false;
    if(binary_ && !sc_.finish_line())
      return fail_here("the number of elements must end its line");
    std::vector<long long> nodes;
    long long done = 0;
    while(done < n)
    {
      // ASCII: one element per line; binary: blocks of elements of one type
      long long type = 0, count = 1, ntags = 0, tag = 0;
      std::size_t where = sc_.offset();
      if(binary_)
      {
        if(!value(type, "an element type", false) || !value(count, "a number of elements", false, 1) ||
           !value(ntags, "a number of tags", false))
          return false;
        if(count > n - done)
          return ctx_.fail(0, "$Elements: a block of " + std::to_string(count) + " elements beyond the " +
                                std::to_string(n) + " announced (byte " + std::to_string(where) + ")");
      }
      std::size_t nn = 0;
      for(long long i = 0; i < count; ++i)
      {
        where = binary_ ? sc_.offset() : 0;
        if(!value(tag, "an element tag", false, LLONG_MIN))
          return false;
        if(!binary_)
        {
          where = last_line_;
          if(!integer(type, "an element type") || !integer(ntags, "a number of tags"))
            return false;
        }
        if(!element_type(type, nn, where))
          return false;
        int reference = 0;
        for(long long k = 0; k < ntags; ++k)
        {
          long long v = 0;
          if(!value(v, "a tag", false, LLONG_MIN))
            return false;
          if(k == 0)
            reference = static_cast<int>(v);
        }
        nodes.assign(nn, 0);
        for(long long& v : nodes)
          if(!value(v, "a node tag", false, LLONG_MIN))
            return false;
        if(!add_element(type, tag, nodes, reference, 0, where))
          return false;
      }
      done += count;
    }
    return true;
  }

  bool read_elements_4()
  {
    elements_read_ = true;
    hex_positions_.reset(binary_, 0);
    if(binary_ && !sc_.finish_line())
      return fail_here("binary data must start on the line after $Elements");
    long long blocks = 0, n = 0, min_tag = 0, max_tag = 0;
    if(!value(blocks, "the number of entity blocks", true) || !value(n, "the number of elements", true) ||
       !value(min_tag, "the minimum element tag", true) || !value(max_tag, "the maximum element tag", true))
      return false;
    std::vector<long long> nodes;
    long long total = 0;
    for(long long b = 0; b < blocks; ++b)
    {
      long long dim = 0, entity = 0, type = 0, count = 0;
      const std::size_t header = binary_ ? sc_.offset() : sc_.line();
      if(!value(dim, "an entity dimension", false) || !value(entity, "an entity tag", false, LLONG_MIN) ||
         !value(type, "an element type", false) || !value(count, "a number of elements", true))
        return false;
      std::size_t nn = 0;
      if(!element_type(type, nn, binary_ ? header : last_line_))
        return false;
      for(long long i = 0; i < count; ++i)
      {
        long long tag = 0;
        std::size_t where = binary_ ? sc_.offset() : 0;
        if(!value(tag, "an element tag", true, LLONG_MIN))
          return false;
        if(!binary_)
          where = last_line_;
        nodes.assign(nn, 0);
        for(long long& v : nodes)
          if(!value(v, "a node tag", true, LLONG_MIN))
            return false;
        if(!add_element(type, tag, nodes, 0, static_cast<int>(entity), where))
          return false;
      }
      total += count;
    }
    if(total != n)
      return fail_here("announces " + std::to_string(n) + " elements, its blocks hold " + std::to_string(total));
    return true;
  }

  struct Skipped
  {
    std::size_t count = 0;
    std::string name, where;
  };

  Text_scanner& sc_;
  const Read_context& ctx_;
  const Kernel gt_ = Kernel();
  Mesh mesh_;
  int version_ = 0;
  bool binary_ = false;
  bool nodes_read_ = false, elements_read_ = false, several_physicals_ = false;
  std::string section_;
  std::size_t section_line_ = 0, last_line_ = 0;
  Id_map node_ids_, element_ids_;
  Record_positions node_positions_, hex_positions_;
  std::vector<long long> tags_;
  std::vector<int> hex_entities_;
  std::map<int, int> volume_physicals_;
  std::map<int, Skipped> skipped_;
  std::map<std::string, std::size_t> skipped_sections_;
};

/// reads the gmsh file `fname` into `out` (unchanged on failure)
template <class Point>
bool read_MSH_file(const std::string& fname, Indexed_hex_mesh<Point>& out, const Read_context& ctx)
{
  std::string content, why;
  if(!load_file(fname, content, why))
    return ctx.fail(0, why);
  Text_scanner sc(content.data(), content.data() + content.size(), 1);
  if(sc.at_end())
    return ctx.fail(0, "empty file");
  Msh_reader<Point> reader(sc, ctx);
  return reader.read(out);
}

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_READ_MSH_H
