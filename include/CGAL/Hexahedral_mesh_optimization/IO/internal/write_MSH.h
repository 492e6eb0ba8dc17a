// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Package: Hexahedral_mesh_optimization

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_WRITE_MSH_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_WRITE_MSH_H

// Writer of gmsh .msh files, version 2.2 or 4.1, ASCII or binary (byte order
// of this machine, data size 8). The hexahedra keep their order; each
// distinct reference becomes a volume entity whose physical tag is the
// reference (none for references <= 0), and the cell fields become
// $ElementData, which gmsh shows as views.

#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Hex_mesh_io_types.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Id_map.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/write_file.h>
#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Hex_mesh_arrays.h>
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

template <class Point>
bool write_MSH_file(const std::string& fname, const Indexed_hex_mesh<Point>& mesh,
                    const CGAL::IO::Hex_mesh_fields& fields, CGAL::IO::Hex_mesh_io_error* err,
                    CGAL::IO::Gmsh_version version, bool binary)
{
  if(!check_before_writing(fname, mesh, fields, err))
    return false;
  const bool v4 = version == CGAL::IO::Gmsh_version::v4_1;
  std::vector<long long> node_tags = ids_for_writing(mesh.point_ids, mesh.points.size());
  std::vector<long long> hex_tags = ids_for_writing(mesh.hexahedron_ids, mesh.hexahedra.size());
  // binary 2.2 and every $ElementData store tags as 32-bit ints
  const auto fits_int = [](const std::vector<long long>& tags) {
    return std::all_of(tags.begin(), tags.end(), [](long long t) { return t <= INT_MAX; });
  };
  if(!fits_int(node_tags))
    node_tags = ids_for_writing(std::vector<long long>(), mesh.points.size());
  if(!fits_int(hex_tags))
    hex_tags = ids_for_writing(std::vector<long long>(), mesh.hexahedra.size());

  // one volume entity per distinct reference, numbered from 1
  const auto reference = [&mesh](std::size_t h) {
    return mesh.hexahedron_references.empty() ? 0 : mesh.hexahedron_references[h];
  };
  std::map<int, int> entity_of;
  for(std::size_t h = 0; h < mesh.hexahedra.size(); ++h)
    entity_of.emplace(reference(h), 0);
  int next_entity = 0;
  for(auto& e : entity_of)
    e.second = ++next_entity;

  return write_atomically(fname, err, [&](Output_buffer& out, std::string&) {
    const typename Kernel_traits<Point>::Kernel gt;
    const auto newline_after_binary = [&]() {
      if(binary)
        out << '\n';
    };
    out << "$MeshFormat\n" << (v4 ? "4.1 " : "2.2 ") << (binary ? "1 8\n" : "0 8\n");
    if(binary)
    {
      out.native(std::int32_t(1));
      out << '\n';
    }
    out << "$EndMeshFormat\n";

    std::vector<std::pair<int, std::string> > names;
    for(const auto& n : mesh.hexahedron_reference_names)
      if(n.first > 0 && entity_of.count(n.first))
        names.push_back(n);
    if(!names.empty())
    {
      out << "$PhysicalNames\n" << names.size() << '\n';
      for(const auto& n : names)
        out << "3 " << n.first << ' ' << msh_quoted(n.second) << '\n';
      out << "$EndPhysicalNames\n";
    }

    const auto size_value = [&](std::size_t v, char after) {
      if(binary)
        out.native(std::uint64_t(v));
      else
        out << v << after;
    };
    const auto int_value = [&](long long v, char after) {
      if(binary)
        out.native(std::int32_t(v));
      else
        out << v << after;
    };
    const auto real_value = [&](double v, char after) {
      if(binary)
        out.native(v);
      else
        out << v << after;
    };

    if(v4)
    {
      // bounding boxes of the entities
      std::map<int, std::array<double, 6> > boxes;
      for(std::size_t h = 0; h < mesh.hexahedra.size(); ++h)
      {
        auto it = boxes.find(reference(h));
        if(it == boxes.end())
        {
          const double inf = std::numeric_limits<double>::infinity();
          it = boxes.emplace(reference(h), std::array<double, 6>{{inf, inf, inf, -inf, -inf, -inf}}).first;
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
      out << "$Entities\n";
      size_value(0, ' ');
      size_value(0, ' ');
      size_value(0, ' ');
      size_value(entity_of.size(), '\n');
      for(const auto& e : entity_of)
      {
        int_value(e.second, ' ');
        for(double c : boxes[e.first])
          real_value(c, ' ');
        size_value(e.first > 0 ? 1 : 0, ' ');
        if(e.first > 0)
          int_value(e.first, ' ');
        size_value(0, '\n');
      }
      newline_after_binary();
      out << "$EndEntities\n";

      const auto minmax = [](const std::vector<long long>& t) {
        return t.empty() ? std::make_pair(0LL, 0LL)
                         : std::make_pair(*std::min_element(t.begin(), t.end()), *std::max_element(t.begin(), t.end()));
      };
      // every node in one block, on the first volume
      const auto node_range = minmax(node_tags);
      out << "$Nodes\n";
      size_value(1, ' ');
      size_value(mesh.points.size(), ' ');
      size_value(std::size_t(node_range.first), ' ');
      size_value(std::size_t(node_range.second), '\n');
      int_value(3, ' ');
      int_value(1, ' ');
      int_value(0, ' ');
      size_value(mesh.points.size(), '\n');
      for(long long t : node_tags)
        size_value(std::size_t(t), '\n');
      for(const Point& q : mesh.points)
      {
        const Vec3 p = to_vec3(q, gt);
        real_value(p[0], ' ');
        real_value(p[1], ' ');
        real_value(p[2], '\n');
      }
      newline_after_binary();
      out << "$EndNodes\n";

      // a block per run of hexahedra of the same reference: the order is kept
      std::vector<std::pair<std::size_t, std::size_t> > runs;
      for(std::size_t h = 0; h < mesh.hexahedra.size(); ++h)
        if(runs.empty() || reference(h) != reference(runs.back().first))
          runs.push_back({h, h + 1});
        else
          runs.back().second = h + 1;
      const auto hex_range = minmax(hex_tags);
      out << "$Elements\n";
      size_value(runs.size(), ' ');
      size_value(mesh.hexahedra.size(), ' ');
      size_value(std::size_t(hex_range.first), ' ');
      size_value(std::size_t(hex_range.second), '\n');
      for(const auto& run : runs)
      {
        int_value(3, ' ');
        int_value(entity_of[reference(run.first)], ' ');
        int_value(5, ' ');
        size_value(run.second - run.first, '\n');
        for(std::size_t h = run.first; h < run.second; ++h)
        {
          size_value(std::size_t(hex_tags[h]), ' ');
          for(int k = 0; k < 8; ++k)
            size_value(std::size_t(node_tags[mesh.hexahedra[h][k]]), k == 7 ? '\n' : ' ');
        }
      }
      newline_after_binary();
      out << "$EndElements\n";
    }
    else
    {
      out << "$Nodes\n" << mesh.points.size() << '\n';
      for(std::size_t i = 0; i < mesh.points.size(); ++i)
      {
        const Vec3 p = to_vec3(mesh.points[i], gt);
        int_value(node_tags[i], ' ');
        real_value(p[0], ' ');
        real_value(p[1], ' ');
        real_value(p[2], '\n');
      }
      newline_after_binary();
      out << "$EndNodes\n$Elements\n" << mesh.hexahedra.size() << '\n';
      if(binary)
      {
        out.native(std::int32_t(5));
        out.native(std::int32_t(mesh.hexahedra.size()));
        out.native(std::int32_t(2));
      }
      for(std::size_t h = 0; h < mesh.hexahedra.size(); ++h)
      {
        int_value(hex_tags[h], ' ');
        if(!binary)
          out << "5 2 ";
        int_value(reference(h) > 0 ? reference(h) : 0, ' ');
        int_value(entity_of[reference(h)], ' ');
        for(int k = 0; k < 8; ++k)
          int_value(node_tags[mesh.hexahedra[h][k]], k == 7 ? '\n' : ' ');
      }
      newline_after_binary();
      out << "$EndElements\n";
    }

    // the cell fields, as views gmsh colours the mesh by
    for(const auto& f : fields.cell_scalars)
    {
      out << "$ElementData\n1\n" << msh_quoted(f.first) << "\n1\n0\n3\n0\n1\n" << mesh.hexahedra.size() << '\n';
      for(std::size_t h = 0; h < mesh.hexahedra.size(); ++h)
      {
        int_value(hex_tags[h], ' ');
        real_value(f.second[h], '\n');
      }
      newline_after_binary();
      out << "$EndElementData\n";
    }
    return true;
  });
}

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_WRITE_MSH_H
