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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_WRITE_MSH_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_WRITE_MSH_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Writer of gmsh .msh files, version 2.2 or 4.1, ASCII or binary (byte order
// of this machine, data size 8). The hexahedra keep their order; each
// distinct reference becomes a volume entity whose physical tag is the
// reference (none for references <= 0), and the cell fields become
// $ElementData, which gmsh shows as views.

#include <CGAL/Hexahedral_mesh_optimization/IO/Hex_mesh_io_types.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Id_map.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/write_file.h>
#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Kernel_traits.h>

#include <algorithm>
#include <climits>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {
namespace io {

/// a name for a quoted gmsh string: double quotes and line breaks replaced
inline std::string msh_quoted(const std::string& name)
{
  std::string q = "\"";
  for(char c : name)
    q += (c == '"' || c == '\n' || c == '\r') ? '_' : c;
  return q + "\"";
}


/// the reference of hexahedron `h`, 0 when the mesh has none
template <class Point>
int msh_reference(const Indexed_hex_mesh<Point>& mesh, std::size_t h)
{
  return mesh.hexahedron_references.empty() ? 0 : mesh.hexahedron_references[h];
}

/// what the sections of a gmsh file refer to: the node and element tags and
/// the volume entity of each reference
struct Msh_numbering
{
  std::vector<long long> node_tags;
  std::vector<long long> hex_tags;
  std::map<int, int> entity_of;  // reference -> entity tag, from 1
};

/// the tags of the mesh (1..n when its ids do not fit the 32-bit ints of
/// binary 2.2 and of every $ElementData) and one volume entity per distinct
/// reference, numbered from 1 in increasing order of the references
template <class Point>
Msh_numbering msh_numbering(const Indexed_hex_mesh<Point>& mesh)
{
  Msh_numbering numbering;
  numbering.node_tags = ids_for_writing(mesh.point_ids, mesh.points.size());
  numbering.hex_tags = ids_for_writing(mesh.hexahedron_ids, mesh.hexahedra.size());
  const auto fits_int = [](const std::vector<long long>& tags) {
    return std::all_of(tags.begin(), tags.end(), [](long long t) { return t <= INT_MAX; });
  };
  if(!fits_int(numbering.node_tags))
    numbering.node_tags = ids_for_writing(std::vector<long long>(), mesh.points.size());
  if(!fits_int(numbering.hex_tags))
    numbering.hex_tags = ids_for_writing(std::vector<long long>(), mesh.hexahedra.size());
  for(std::size_t h = 0; h < mesh.hexahedra.size(); ++h)
    numbering.entity_of.emplace(msh_reference(mesh, h), 0);
  int next_entity = 0;
  for(auto& e : numbering.entity_of)
    e.second = ++next_entity;
  return numbering;
}

/// writes the values of a gmsh section: as text, each followed by its
/// separator, or in binary (sizes as uint64, ints as int32, reals as double)
struct Msh_value_writer
{
  Output_buffer& out;
  bool binary;

  void size_value(std::size_t v, char after) const
  {
    if(binary)
      out.native(std::uint64_t(v));
    else
      out << v << after;
  }
  void int_value(long long v, char after) const
  {
    if(binary)
      out.native(std::int32_t(v));
    else
      out << v << after;
  }
  void real_value(double v, char after) const
  {
    if(binary)
      out.native(v);
    else
      out << v << after;
  }
  /// binary data ends with a line break before the closing keyword
  void newline_after_binary() const
  {
    if(binary)
      out << '\n';
  }
};

/// $MeshFormat, and $PhysicalNames for the named positive references
template <class Point>
void write_msh_header(Output_buffer& out, const Indexed_hex_mesh<Point>& mesh, const Msh_numbering& numbering,
                      bool v4, bool binary)
{
  out << "$MeshFormat\n" << (v4 ? "4.1 " : "2.2 ") << (binary ? "1 8\n" : "0 8\n");
  if(binary)
  {
    out.native(std::int32_t(1));
    out << '\n';
  }
  out << "$EndMeshFormat\n";

  std::vector<std::pair<int, std::string> > names;
  for(const auto& n : mesh.hexahedron_reference_names)
    if(n.first > 0 && numbering.entity_of.count(n.first))
      names.push_back(n);
  if(!names.empty())
  {
    out << "$PhysicalNames\n" << names.size() << '\n';
    for(const auto& n : names)
      out << "3 " << n.first << ' ' << msh_quoted(n.second) << '\n';
    out << "$EndPhysicalNames\n";
  }
}

/// the bounding box (min x, y, z, max x, y, z) of the hexahedra of each reference
template <class Point>
std::map<int, std::array<double, 6> > msh_entity_boxes(const Indexed_hex_mesh<Point>& mesh)
{
  const typename Kernel_traits<Point>::Kernel gt;
  std::map<int, std::array<double, 6> > boxes;
  for(std::size_t h = 0; h < mesh.hexahedra.size(); ++h)
  {
    auto it = boxes.find(msh_reference(mesh, h));
    if(it == boxes.end())
    {
      const double inf = std::numeric_limits<double>::infinity();
      it = boxes.emplace(msh_reference(mesh, h), std::array<double, 6>{{inf, inf, inf, -inf, -inf, -inf}}).first;
    }
    for(std::size_t v : mesh.hexahedra[h])
    {
      const Vec3 p = to_vec3(mesh.points[v], gt);
      for(int a = 0; a < 3; ++a)
      {
        it->second[a] = (std::min)(it->second[a], p[a]);
        it->second[a + 3] = (std::max)(it->second[a + 3], p[a]);
      }
    }
  }
  return boxes;
}

/// 4.1 $Entities: no points, curves or surfaces, one volume per reference
/// with its bounding box and, for a positive reference, its physical tag
template <class Point>
void write_msh4_entities(const Msh_value_writer& w, const Indexed_hex_mesh<Point>& mesh, const Msh_numbering& numbering)
{
  std::map<int, std::array<double, 6> > boxes = msh_entity_boxes(mesh);
  w.out << "$Entities\n";
  w.size_value(0, ' ');
  w.size_value(0, ' ');
  w.size_value(0, ' ');
  w.size_value(numbering.entity_of.size(), '\n');
  for(const auto& e : numbering.entity_of)
  {
    w.int_value(e.second, ' ');
    for(double c : boxes[e.first])
      w.real_value(c, ' ');
    w.size_value(e.first > 0 ? 1 : 0, ' ');
    if(e.first > 0)
      w.int_value(e.first, ' ');
    w.size_value(0, '\n');
  }
  w.newline_after_binary();
  w.out << "$EndEntities\n";
}

/// the smallest and largest tag, (0, 0) when there are none
inline std::pair<long long, long long> msh_tag_range(const std::vector<long long>& tags)
{
  return tags.empty() ? std::make_pair(0LL, 0LL)
                      : std::make_pair(*std::min_element(tags.begin(), tags.end()),
                                       *std::max_element(tags.begin(), tags.end()));
}

/// 4.1 $Nodes: every node in one block, on the first volume
template <class Point>
void write_msh4_nodes(const Msh_value_writer& w, const Indexed_hex_mesh<Point>& mesh, const Msh_numbering& numbering)
{
  const typename Kernel_traits<Point>::Kernel gt;
  const auto node_range = msh_tag_range(numbering.node_tags);
  w.out << "$Nodes\n";
  w.size_value(1, ' ');
  w.size_value(mesh.points.size(), ' ');
  w.size_value(std::size_t(node_range.first), ' ');
  w.size_value(std::size_t(node_range.second), '\n');
  w.int_value(3, ' ');
  w.int_value(1, ' ');
  w.int_value(0, ' ');
  w.size_value(mesh.points.size(), '\n');
  for(long long t : numbering.node_tags)
    w.size_value(std::size_t(t), '\n');
  for(const Point& q : mesh.points)
  {
    const Vec3 p = to_vec3(q, gt);
    w.real_value(p[0], ' ');
    w.real_value(p[1], ' ');
    w.real_value(p[2], '\n');
  }
  w.newline_after_binary();
  w.out << "$EndNodes\n";
}

/// 4.1 $Elements: a block per run of hexahedra of the same reference, so
/// that the order of the hexahedra is kept
template <class Point>
void write_msh4_elements(const Msh_value_writer& w, const Indexed_hex_mesh<Point>& mesh, const Msh_numbering& numbering)
{
  std::vector<std::pair<std::size_t, std::size_t> > runs;
  for(std::size_t h = 0; h < mesh.hexahedra.size(); ++h)
    if(runs.empty() || msh_reference(mesh, h) != msh_reference(mesh, runs.back().first))
      runs.push_back({h, h + 1});
    else
      runs.back().second = h + 1;
  const auto hex_range = msh_tag_range(numbering.hex_tags);
  w.out << "$Elements\n";
  w.size_value(runs.size(), ' ');
  w.size_value(mesh.hexahedra.size(), ' ');
  w.size_value(std::size_t(hex_range.first), ' ');
  w.size_value(std::size_t(hex_range.second), '\n');
  for(const auto& run : runs)
  {
    w.int_value(3, ' ');
    w.int_value(numbering.entity_of.at(msh_reference(mesh, run.first)), ' ');
    w.int_value(5, ' ');
    w.size_value(run.second - run.first, '\n');
    for(std::size_t h = run.first; h < run.second; ++h)
    {
      w.size_value(std::size_t(numbering.hex_tags[h]), ' ');
      for(int k = 0; k < 8; ++k)
        w.size_value(std::size_t(numbering.node_tags[mesh.hexahedra[h][k]]), k == 7 ? '\n' : ' ');
    }
  }
  w.newline_after_binary();
  w.out << "$EndElements\n";
}

/// 2.2 $Nodes: tag and coordinates of each node
template <class Point>
void write_msh2_nodes(const Msh_value_writer& w, const Indexed_hex_mesh<Point>& mesh, const Msh_numbering& numbering)
{
  const typename Kernel_traits<Point>::Kernel gt;
  w.out << "$Nodes\n" << mesh.points.size() << '\n';
  for(std::size_t i = 0; i < mesh.points.size(); ++i)
  {
    const Vec3 p = to_vec3(mesh.points[i], gt);
    w.int_value(numbering.node_tags[i], ' ');
    w.real_value(p[0], ' ');
    w.real_value(p[1], ' ');
    w.real_value(p[2], '\n');
  }
  w.newline_after_binary();
  w.out << "$EndNodes\n";
}

/// 2.2 $Elements: each hexahedron (type 5) with two tags, its physical tag
/// (0 for references <= 0) and its entity; binary files have one header
/// for all of them
template <class Point>
void write_msh2_elements(const Msh_value_writer& w, const Indexed_hex_mesh<Point>& mesh, const Msh_numbering& numbering)
{
  w.out << "$Elements\n" << mesh.hexahedra.size() << '\n';
  if(w.binary)
  {
    w.out.native(std::int32_t(5));
    w.out.native(std::int32_t(mesh.hexahedra.size()));
    w.out.native(std::int32_t(2));
  }
  for(std::size_t h = 0; h < mesh.hexahedra.size(); ++h)
  {
    const int reference = msh_reference(mesh, h);
    w.int_value(numbering.hex_tags[h], ' ');
    if(!w.binary)
      w.out << "5 2 ";
    w.int_value(reference > 0 ? reference : 0, ' ');
    w.int_value(numbering.entity_of.at(reference), ' ');
    for(int k = 0; k < 8; ++k)
      w.int_value(numbering.node_tags[mesh.hexahedra[h][k]], k == 7 ? '\n' : ' ');
  }
  w.newline_after_binary();
  w.out << "$EndElements\n";
}

/// one $ElementData per cell field, a view gmsh colours the mesh by
template <class Point>
void write_msh_element_data(const Msh_value_writer& w, const Indexed_hex_mesh<Point>& mesh,
                            const CGAL::IO::Hex_mesh_fields& fields, const Msh_numbering& numbering)
{
  for(const auto& f : fields.cell_scalars)
  {
    w.out << "$ElementData\n1\n" << msh_quoted(f.first) << "\n1\n0\n3\n0\n1\n" << mesh.hexahedra.size() << '\n';
    for(std::size_t h = 0; h < mesh.hexahedra.size(); ++h)
    {
      w.int_value(numbering.hex_tags[h], ' ');
      w.real_value(f.second[h], '\n');
    }
    w.newline_after_binary();
    w.out << "$EndElementData\n";
  }
}

template <class Point>
bool write_MSH_file(const std::string& fname, const Indexed_hex_mesh<Point>& mesh,
                    const CGAL::IO::Hex_mesh_fields& fields, CGAL::IO::Hex_mesh_io_error* err,
                    CGAL::IO::Gmsh_version version, bool binary)
{
  if(!check_before_writing(fname, mesh, fields, err))
    return false;
  const bool v4 = version == CGAL::IO::Gmsh_version::v4_1;
  const Msh_numbering numbering = msh_numbering(mesh);
  return write_atomically(fname, err, [&](Output_buffer& out, std::string&) {
    const Msh_value_writer w{out, binary};
    write_msh_header(out, mesh, numbering, v4, binary);
    if(v4)
    {
      write_msh4_entities(w, mesh, numbering);
      write_msh4_nodes(w, mesh, numbering);
      write_msh4_elements(w, mesh, numbering);
    }
    else
    {
      write_msh2_nodes(w, mesh, numbering);
      write_msh2_elements(w, mesh, numbering);
    }
    write_msh_element_data(w, mesh, fields, numbering);
    return true;
  });
}

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_WRITE_MSH_H
