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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_EXODUS_IO_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_EXODUS_IO_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Exodus II (.exo, .e) reading and writing. Exodus files are netCDF files:
// they are read and written through the Exodus II C library (Debian
// libexodusii-dev), found by CMake, which then defines CGAL_HMO_HAVE_EXODUS.
// Without it both functions fail with a message saying so.

#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Read_context.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/write_file.h>
#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>

#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Id_map.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/internal/Text_scanner.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Kernel_traits.h>

#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#ifdef CGAL_HMO_HAVE_EXODUS
#include <exodusII.h>
#include <netcdf.h>
#include <stdlib.h>   // mkstemp
#include <sys/stat.h> // fchmod, umask
#include <unistd.h>
#endif

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {
namespace io {

/// Exodus II element block ids must be positive; MEDIT references and gmsh
/// physical tags need not be (MEDIT writers often leave every element at
/// reference 0). The block id of each value of `references`: a positive
/// reference is its own block id; the others take, in the order 0, -1, -2,
/// ..., the smallest positive ids that no positive reference uses, so that
/// 0 becomes block 1 unless 1 is a reference too. With `warnings`, one per
/// reference written under another id, but for 0 -> 1 (the common case,
/// which reads back as a mesh whose hexahedra are all in block 1).
inline std::map<int, int> exodus_block_ids(const std::vector<int>& references,
                                           std::vector<std::string>* warnings = nullptr)
{
  std::map<int, int> block_of;
  for(int r : references)
    block_of.emplace(r, r);
  int free_id = 1;
  // the non-positive references, from 0 down (the map is in increasing order)
  for(auto it = block_of.rbegin(); it != block_of.rend(); ++it)
  {
    if(it->first > 0)
      continue;
    while(block_of.count(free_id) != 0)  // a positive reference
      ++free_id;
    it->second = free_id++;
    if(warnings != nullptr && !(it->first == 0 && it->second == 1))
      warnings->push_back("hexahedron reference " + std::to_string(it->first) + " written as Exodus II element block " +
                          std::to_string(it->second) + " (block ids must be positive)");
  }
  return block_of;
}

#ifdef CGAL_HMO_HAVE_EXODUS

/// an open Exodus file, closed at the end of the scope
struct Exodus_file
{
  int id = -1;
  ~Exodus_file()
  {
    if(id >= 0)
      ex_close(id);
  }
};

/// A classic netCDF file cut short reads as zeros past its end, without an
/// error (so libnetcdf 4.9 and libexodusii 6.02 behave): the file must
/// be at least as long as its variables. (netCDF-4 files are HDF5 files,
/// which detect truncation themselves, and may be compressed.)
inline bool netcdf_file_complete(int ncid, const std::string& fname, std::string& why)
{
  int format = 0;
  if(nc_inq_format(ncid, &format) != NC_NOERR)
    return true;
  if(format != NC_FORMAT_CLASSIC && format != NC_FORMAT_64BIT_OFFSET && format != NC_FORMAT_CDF5)
    return true;
  int variables = 0;
  if(nc_inq_nvars(ncid, &variables) != NC_NOERR)
    return true;
  unsigned long long needed = 0;
  for(int v = 0; v < variables; ++v)
  {
    nc_type type;
    int dimensions = 0;
    int ids[NC_MAX_VAR_DIMS];
    if(nc_inq_var(ncid, v, nullptr, &type, &dimensions, ids, nullptr) != NC_NOERR)
      return true;
    std::size_t type_size = 0;
    if(nc_inq_type(ncid, type, nullptr, &type_size) != NC_NOERR)
      return true;
    unsigned long long n = type_size;
    for(int d = 0; d < dimensions; ++d)
    {
      std::size_t length = 0;
      if(nc_inq_dimlen(ncid, ids[d], &length) != NC_NOERR)
        return true;
      n *= length;
    }
    needed += n;
  }
  std::FILE* file = std::fopen(fname.c_str(), "rb");
  if(file == nullptr)
    return true;
  std::fseek(file, 0, SEEK_END);
  const long size = std::ftell(file);
  std::fclose(file);
  if(size >= 0 && static_cast<unsigned long long>(size) < needed)
  {
    why = "truncated file: " + std::to_string(size) + " bytes, its variables need at least " + std::to_string(needed);
    return false;
  }
  return true;
}

/// the first word of an Exodus element type, in lower case
inline std::string exodus_type_word(const char* type)
{
  std::string t;
  for(const char* c = type; *c != '\0' && *c != ' '; ++c)
    t += to_lower_ascii(*c);
  return t;
}

/// element types of lower dimension, whose blocks are skipped with a warning
inline bool exodus_surface_type(const char* type)
{
  const std::string t = exodus_type_word(type);
  for(const char* prefix : {"quad", "shell", "tri", "bar", "beam", "truss", "sphere", "circle", "edge", "nsided"})
    if(t.compare(0, std::strlen(prefix), prefix) == 0)
      return true;
  return false;
}

inline bool exodus_hex_type(const char* type)
{
  const std::string t = exodus_type_word(type);
  return t == "hex" || t == "hex8" || t == "hexahedron";
}

/// the counts of the Exodus header (ex_get_init)
struct Exodus_parameters
{
  int dimension = 0;
  int nodes = 0;
  int elements = 0;
  int blocks = 0;
  int node_sets = 0;
  int side_sets = 0;
};

/// opens `fname` for reading into `f` and checks that it is a complete
/// Exodus (netCDF) file
inline bool open_exodus_for_reading(const std::string& fname, Exodus_file& f, const Read_context& ctx)
{
  ex_opts(0);  // no messages on stderr: the errors come back as values
  int comp_ws = 8, io_ws = 0;
  float version = 0.f;
  {
    std::FILE* probe = std::fopen(fname.c_str(), "rb");
    if(probe == nullptr)
      return ctx.fail(0, std::string("cannot open: ") + std::strerror(errno));
    std::fclose(probe);
  }
  f.id = ex_open(fname.c_str(), EX_READ, &comp_ws, &io_ws, &version);
  if(f.id < 0)
    return ctx.fail(0, "not an Exodus II (netCDF) file, or a damaged one");
  ex_set_max_name_length(f.id, 255);
  std::string why;
  if(!netcdf_file_complete(f.id, fname, why))
    return ctx.fail(0, why);
  return true;
}

/// the header: a 3-dimensional mesh and non-negative counts
inline bool read_exodus_parameters(int exo, Exodus_parameters& p, const Read_context& ctx)
{
  char title[MAX_LINE_LENGTH + 1] = {0};
  if(ex_get_init(exo, title, &p.dimension, &p.nodes, &p.elements, &p.blocks, &p.node_sets, &p.side_sets) < 0)
    return ctx.fail(0, "cannot read the Exodus header (ex_get_init)");
  if(p.dimension != 3)
    return ctx.fail(0, "dimension " + std::to_string(p.dimension) + ": only 3-dimensional meshes are supported");
  if(p.nodes < 0 || p.elements < 0 || p.blocks < 0 || p.node_sets < 0 || p.side_sets < 0)
    return ctx.fail(0, "negative counts in the Exodus header");
  return true;
}

template <class Point>
bool read_exodus_coordinates(int exo, int nodes, Indexed_hex_mesh<Point>& mesh, const Read_context& ctx)
{
  const typename Kernel_traits<Point>::Kernel gt;
  std::vector<double> x(static_cast<std::size_t>(nodes)), y(x.size()), z(x.size());
  if(nodes > 0 && ex_get_coord(exo, x.data(), y.data(), z.data()) < 0)
    return ctx.fail(0, "cannot read the coordinates (ex_get_coord)");
  for(std::size_t i = 0; i < x.size(); ++i)
    mesh.points.push_back(to_point(Vec3{{x[i], y[i], z[i]}}, gt));
  return true;
}

/// Exodus numbers the elements of all blocks in turn: element g (0-based)
/// is hexahedron `hex_of[g]`, or `exodus_no_hexahedron` when its block was skipped
const std::size_t exodus_no_hexahedron = static_cast<std::size_t>(-1);

/// the `n` hexahedra of the HEX8 block `id`, with the block id as their reference
template <class Point>
bool read_exodus_hex_block(int exo, int id, int n, int nodes, Indexed_hex_mesh<Point>& mesh,
                           std::vector<std::size_t>& hex_of, const Read_context& ctx)
{
  std::vector<int> conn(static_cast<std::size_t>(n) * 8);
  if(ex_get_conn(exo, EX_ELEM_BLOCK, id, conn.data(), nullptr, nullptr) < 0)
    return ctx.fail(0, "element block " + std::to_string(id) + ": cannot read its connectivity");
  for(std::size_t e = 0; e < static_cast<std::size_t>(n); ++e)
  {
    typename Indexed_hex_mesh<Point>::Hexahedron h;
    for(std::size_t k = 0; k < 8; ++k)
    {
      const int v = conn[8 * e + k];
      if(v < 1 || v > nodes)
        return ctx.fail(0, "element block " + std::to_string(id) + ", element " + std::to_string(e + 1) +
                             ": node " + std::to_string(v) + " out of range (1.." + std::to_string(nodes) + ")" +
                             (v == 0 ? ": truncated file?" : ""));
      h[k] = static_cast<std::size_t>(v - 1);
    }
    hex_of.push_back(mesh.hexahedra.size());
    mesh.hexahedra.push_back(h);
    mesh.hexahedron_references.push_back(id);
  }
  char name[256] = {0};
  if(ex_get_name(exo, EX_ELEM_BLOCK, id, name) >= 0 && name[0] != '\0')
    mesh.hexahedron_reference_names[id] = name;
  return true;
}

/// the element blocks: hexahedra read, blocks of lower dimension skipped
/// with a warning, anything else an error
template <class Point>
bool read_exodus_element_blocks(int exo, const Exodus_parameters& p, Indexed_hex_mesh<Point>& mesh,
                                std::vector<std::size_t>& hex_of, const Read_context& ctx)
{
  std::vector<int> ids(static_cast<std::size_t>(p.blocks));
  if(p.blocks > 0 && ex_get_ids(exo, EX_ELEM_BLOCK, ids.data()) < 0)
    return ctx.fail(0, "cannot read the element block ids");
  long long skipped = 0;
  for(int id : ids)
  {
    char type[MAX_STR_LENGTH + 1] = {0};
    int n = 0, per = 0, edges = 0, faces = 0, attributes = 0;
    if(ex_get_block(exo, EX_ELEM_BLOCK, id, type, &n, &per, &edges, &faces, &attributes) < 0)
      return ctx.fail(0, "element block " + std::to_string(id) + ": cannot read its parameters");
    if(n == 0)
      continue;
    if(exodus_surface_type(type))
    {
      ctx.warn("skipped element block " + std::to_string(id) + " (" + std::to_string(n) + " elements of type " +
               quote_token(type) + ")");
      skipped += n;
      hex_of.insert(hex_of.end(), static_cast<std::size_t>(n), exodus_no_hexahedron);
      continue;
    }
    if(!exodus_hex_type(type) || per != 8)
      return ctx.fail(0, "element block " + std::to_string(id) + ": " + std::to_string(n) + " elements of type " +
                           quote_token(type) + " with " + std::to_string(per) +
                           " nodes: only hexahedra (HEX8) are supported");
    if(!read_exodus_hex_block(exo, id, n, p.nodes, mesh, hex_of, ctx))
      return false;
  }
  if(mesh.hexahedra.size() + static_cast<std::size_t>(skipped) != static_cast<std::size_t>(p.elements))
    return ctx.fail(0, "the header announces " + std::to_string(p.elements) + " elements, the blocks hold " +
                         std::to_string(mesh.hexahedra.size() + static_cast<std::size_t>(skipped)));
  return true;
}

/// the node and element number maps (absent maps read as 1..n)
template <class Point>
bool read_exodus_id_maps(int exo, Indexed_hex_mesh<Point>& mesh, const std::vector<std::size_t>& hex_of,
                         const Read_context& ctx)
{
  for(int element_map = 0; element_map < 2; ++element_map)
  {
    std::vector<int> map(element_map ? hex_of.size() : mesh.points.size());
    if(map.empty() || ex_get_id_map(exo, element_map ? EX_ELEM_MAP : EX_NODE_MAP, map.data()) < 0)
      continue;
    for(std::size_t i = 0; i < map.size(); ++i)
      if(map[i] <= 0)
        return ctx.fail(0, std::string(element_map ? "element" : "node") + " number map, entry " +
                             std::to_string(i + 1) + ": id " + std::to_string(map[i]) + " is not positive" +
                             (map[i] == 0 ? ": truncated file?" : ""));
    if(!element_map)
      mesh.point_ids.assign(map.begin(), map.end());
    else
    {
      mesh.hexahedron_ids.assign(mesh.hexahedra.size(), 0);
      for(std::size_t g = 0; g < hex_of.size(); ++g)
        if(hex_of[g] != exodus_no_hexahedron)
          mesh.hexahedron_ids[hex_of[g]] = map[g];
    }
  }
  return true;
}

inline const char* exodus_set_label(bool side) { return side ? "side set " : "node set "; }

/// the ids of the `count` node sets or side sets
inline bool read_exodus_set_ids(int exo, bool side, int count, std::vector<int>& set_ids, const Read_context& ctx)
{
  set_ids.assign(static_cast<std::size_t>(count), 0);
  if(count > 0 && ex_get_ids(exo, side ? EX_SIDE_SET : EX_NODE_SET, set_ids.data()) < 0)
    return ctx.fail(0, std::string("cannot read the ") + exodus_set_label(side) + "ids");
  return true;
}

/// the name and the entries of node set or side set `id`: 1-based node
/// numbers up to `bound`, or 1-based element numbers up to `bound` with
/// their sides 1..6 in `sides`
inline bool read_exodus_set(int exo, bool side, int id, long long bound, std::string& set_name,
                            std::vector<int>& entries, std::vector<int>& sides, const Read_context& ctx)
{
  const ex_entity_type kind = side ? EX_SIDE_SET : EX_NODE_SET;
  const char* label = exodus_set_label(side);
  int n = 0, factors = 0;
  if(ex_get_set_param(exo, kind, id, &n, &factors) < 0 || n < 0)
    return ctx.fail(0, label + std::to_string(id) + ": cannot read its parameters");
  entries.assign(static_cast<std::size_t>(n), 0);
  sides.assign(side ? entries.size() : 0, 0);
  if(n > 0 && ex_get_set(exo, kind, id, entries.data(), side ? sides.data() : nullptr) < 0)
    return ctx.fail(0, label + std::to_string(id) + ": cannot read its entries");
  char name[256] = {0};
  set_name = (ex_get_name(exo, kind, id, name) >= 0 && name[0] != '\0')
               ? std::string(name)
               : std::string(side ? "sideset_" : "nodeset_") + std::to_string(id);
  for(std::size_t i = 0; i < entries.size(); ++i)
    if(entries[i] < 1 || entries[i] > bound || (side && (sides[i] < 1 || sides[i] > 6)))
      return ctx.fail(0, label + std::to_string(id) + ", entry " + std::to_string(i + 1) + ": " +
                           (side ? "element " : "node ") + std::to_string(entries[i]) +
                           (side ? ", side " + std::to_string(sides[i]) : std::string()) + " out of range" +
                           (entries[i] == 0 ? ": truncated file?" : ""));
  return true;
}

template <class Point>
bool read_exodus_node_sets(int exo, int count, Indexed_hex_mesh<Point>& mesh, const Read_context& ctx)
{
  std::vector<int> set_ids, entries, unused;
  if(!read_exodus_set_ids(exo, false, count, set_ids, ctx))
    return false;
  for(int id : set_ids)
  {
    Named_index_set s{std::string(), {}};
    if(!read_exodus_set(exo, false, id, static_cast<long long>(mesh.points.size()), s.name, entries, unused, ctx))
      return false;
    for(int v : entries)
      s.indices.push_back(static_cast<std::size_t>(v - 1));
    mesh.vertex_sets.push_back(s);
  }
  return true;
}

/// the side sets; the sides of elements of skipped blocks are dropped with a warning
template <class Point>
bool read_exodus_side_sets(int exo, int count, const std::vector<std::size_t>& hex_of, Indexed_hex_mesh<Point>& mesh,
                           const Read_context& ctx)
{
  std::vector<int> set_ids, elements, sides;
  if(!read_exodus_set_ids(exo, true, count, set_ids, ctx))
    return false;
  for(int id : set_ids)
  {
    Named_side_set s{std::string(), {}};
    if(!read_exodus_set(exo, true, id, static_cast<long long>(hex_of.size()), s.name, elements, sides, ctx))
      return false;
    std::size_t dropped = 0;
    for(std::size_t i = 0; i < elements.size(); ++i)
    {
      const std::size_t h = hex_of[static_cast<std::size_t>(elements[i] - 1)];
      if(h == exodus_no_hexahedron)
        ++dropped;
      else
        s.sides.push_back({h, sides[i] - 1});
    }
    if(dropped > 0)
      ctx.warn(exodus_set_label(true) + std::to_string(id) + ": " + std::to_string(dropped) +
               " sides of elements of skipped blocks dropped");
    mesh.side_sets.push_back(s);
  }
  return true;
}

template <class Point>
bool read_EXODUS_file(const std::string& fname, Indexed_hex_mesh<Point>& out, const Read_context& ctx)
{
  Exodus_file f;
  Exodus_parameters p;
  if(!open_exodus_for_reading(fname, f, ctx) || !read_exodus_parameters(f.id, p, ctx))
    return false;
  Indexed_hex_mesh<Point> mesh;
  std::vector<std::size_t> hex_of;
  if(!read_exodus_coordinates(f.id, p.nodes, mesh, ctx) || !read_exodus_element_blocks(f.id, p, mesh, hex_of, ctx) ||
     !read_exodus_id_maps(f.id, mesh, hex_of, ctx) || !read_exodus_node_sets(f.id, p.node_sets, mesh, ctx) ||
     !read_exodus_side_sets(f.id, p.side_sets, hex_of, mesh, ctx))
    return false;
  return finish_read(mesh, out, ctx, 1, 1, [](Hex_mesh_defect::Section s, std::size_t record, std::size_t& line) {
    line = 0;
    return std::string(s == Hex_mesh_defect::VERTICES ? "node " : "element ") + std::to_string(record + 1);
  });
}

/// the ids the Exodus writer writes for `kept` (`mesh.point_ids` or
/// `mesh.hexahedron_ids`): those of ids_for_writing(), but 1..n when one of
/// them does not fit the 32-bit ids of this writer
inline std::vector<long long> exodus_ids_for_writing(const std::vector<long long>& kept, std::size_t n)
{
  std::vector<long long> ids = ids_for_writing(kept, n);
  for(long long i : ids)
    if(i > INT_MAX)
      return ids_for_writing(std::vector<long long>(), n);
  return ids;
}

/// the hexahedra grouped by block (see exodus_block_ids), in the order of
/// the block ids, the reference of each block, and the position of each
/// hexahedron in the Exodus numbering that follows the blocks
struct Exodus_blocks
{
  std::map<int, std::vector<std::size_t> > hexahedra_of_block;
  std::map<int, int> reference_of_block;
  std::vector<std::size_t> new_position;
};

template <class Point>
Exodus_blocks exodus_blocks(const Indexed_hex_mesh<Point>& mesh)
{
  Exodus_blocks blocks;
  const std::map<int, int> block_of = exodus_block_ids(mesh.hexahedron_references);
  for(const auto& rb : block_of)
    blocks.reference_of_block[rb.second] = rb.first;
  for(std::size_t h = 0; h < mesh.hexahedra.size(); ++h)
    blocks.hexahedra_of_block[mesh.hexahedron_references.empty() ? 1 : block_of.at(mesh.hexahedron_references[h])]
      .push_back(h);
  blocks.new_position.resize(mesh.hexahedra.size());
  std::size_t next = 0;
  for(const auto& b : blocks.hexahedra_of_block)
    for(std::size_t h : b.second)
      blocks.new_position[h] = next++;
  return blocks;
}

/// netCDF writes the file by name: a temporary file of a unique name in the
/// folder of the target (".<name>.XXXXXX", created by mkstemp so that no
/// other file is overwritten), renamed onto the target at the end, removed
/// on failure (unless `keep` was set)
struct Exodus_temporary_file
{
  std::string name;
  bool keep = false;

  /// creates the file; false (with `errno`) when it cannot be
  bool create(const std::string& target)
  {
    const std::size_t slash = target.find_last_of('/');
    const std::string folder = slash == std::string::npos ? std::string() : target.substr(0, slash + 1);
    const std::string base = slash == std::string::npos ? target : target.substr(slash + 1);
    std::vector<char> templ;
    const std::string t = folder + "." + base + ".XXXXXX";
    templ.assign(t.begin(), t.end());
    templ.push_back('\0');
    const int fd = ::mkstemp(templ.data());
    if(fd < 0)
      return false;
    // the permissions of a new file (mkstemp's are 0600)
    const mode_t mask = ::umask(0);
    ::umask(mask);
    ::fchmod(fd, 0666 & ~mask);
    ::close(fd);
    name = templ.data();
    return true;
  }
  ~Exodus_temporary_file()
  {
    if(!keep && !name.empty())
      std::remove(name.c_str());
  }
};

// Each `write_exodus_*` section returns `failed(what)` (false) when the
// library refuses it.

template <class Point, class Failure>
bool write_exodus_parameters(int exo, const Indexed_hex_mesh<Point>& mesh, std::size_t block_count,
                             const Failure& failed)
{
  if(ex_put_init(exo, "hexahedral mesh written by CGAL Hexahedral_mesh_optimization", 3,
                 static_cast<int64_t>(mesh.points.size()), static_cast<int64_t>(mesh.hexahedra.size()),
                 static_cast<int64_t>(block_count), static_cast<int64_t>(mesh.vertex_sets.size()),
                 static_cast<int64_t>(mesh.side_sets.size())) < 0)
    return failed("the header");
  return true;
}

template <class Point, class Failure>
bool write_exodus_coordinates(int exo, const Indexed_hex_mesh<Point>& mesh, const Failure& failed)
{
  const typename Kernel_traits<Point>::Kernel gt;
  std::vector<double> x, y, z;
  for(const Point& q : mesh.points)
  {
    const Vec3 p = to_vec3(q, gt);
    x.push_back(p[0]);
    y.push_back(p[1]);
    z.push_back(p[2]);
  }
  const char* axes[] = {"x", "y", "z"};
  if(ex_put_coord(exo, x.data(), y.data(), z.data()) < 0 || ex_put_coord_names(exo, const_cast<char**>(axes)) < 0)
    return failed("the coordinates");
  return true;
}

/// one HEX8 block per reference, with its name if it has one
template <class Point, class Failure>
bool write_exodus_element_blocks(int exo, const Indexed_hex_mesh<Point>& mesh, const Exodus_blocks& blocks,
                                 const Failure& failed)
{
  for(const auto& b : blocks.hexahedra_of_block)
  {
    std::vector<int> conn;
    for(std::size_t h : b.second)
      for(std::size_t v : mesh.hexahedra[h])
        conn.push_back(static_cast<int>(v + 1));
    if(ex_put_block(exo, EX_ELEM_BLOCK, b.first, "HEX8", static_cast<int64_t>(b.second.size()), 8, 0, 0, 0) < 0 ||
       ex_put_conn(exo, EX_ELEM_BLOCK, b.first, conn.data(), nullptr, nullptr) < 0)
      return failed("an element block");
    const auto reference = blocks.reference_of_block.find(b.first);
    const auto name = mesh.hexahedron_reference_names.find(
      reference == blocks.reference_of_block.end() ? b.first : reference->second);
    if(name != mesh.hexahedron_reference_names.end() && ex_put_name(exo, EX_ELEM_BLOCK, b.first, name->second.c_str()) < 0)
      return failed("a block name");
  }
  return true;
}

/// the node and element number maps (the elements in the order of the blocks)
template <class Point, class Failure>
bool write_exodus_id_maps(int exo, const Indexed_hex_mesh<Point>& mesh, const Exodus_blocks& blocks,
                          const Failure& failed)
{
  const std::vector<long long> node_ids = exodus_ids_for_writing(mesh.point_ids, mesh.points.size());
  const std::vector<long long> hex_ids = exodus_ids_for_writing(mesh.hexahedron_ids, mesh.hexahedra.size());
  std::vector<int> map(node_ids.begin(), node_ids.end());
  if(ex_put_id_map(exo, EX_NODE_MAP, map.data()) < 0)
    return failed("the node map");
  map.assign(hex_ids.size(), 0);
  for(std::size_t h = 0; h < hex_ids.size(); ++h)
    map[blocks.new_position[h]] = static_cast<int>(hex_ids[h]);
  if(ex_put_id_map(exo, EX_ELEM_MAP, map.data()) < 0)
    return failed("the element map");
  return true;
}

/// the vertex sets as node sets, numbered from 1
template <class Point, class Failure>
bool write_exodus_node_sets(int exo, const Indexed_hex_mesh<Point>& mesh, const Failure& failed)
{
  int set_id = 0;
  for(const Named_index_set& s : mesh.vertex_sets)
  {
    ++set_id;
    std::vector<int> entries;
    for(std::size_t v : s.indices)
      entries.push_back(static_cast<int>(v + 1));
    if(ex_put_set_param(exo, EX_NODE_SET, set_id, static_cast<int64_t>(entries.size()), 0) < 0 ||
       (!entries.empty() && ex_put_set(exo, EX_NODE_SET, set_id, entries.data(), nullptr) < 0) ||
       ex_put_name(exo, EX_NODE_SET, set_id, s.name.c_str()) < 0)
      return failed("a node set");
  }
  return true;
}

/// the side sets, numbered from 1, their elements in the Exodus numbering
template <class Point, class Failure>
bool write_exodus_side_sets(int exo, const Indexed_hex_mesh<Point>& mesh, const Exodus_blocks& blocks,
                            const Failure& failed)
{
  int set_id = 0;
  for(const Named_side_set& s : mesh.side_sets)
  {
    ++set_id;
    std::vector<int> elements, sides;
    for(const auto& side : s.sides)
    {
      elements.push_back(static_cast<int>(blocks.new_position[side.first] + 1));
      sides.push_back(side.second + 1);
    }
    if(ex_put_set_param(exo, EX_SIDE_SET, set_id, static_cast<int64_t>(elements.size()), 0) < 0 ||
       (!elements.empty() && ex_put_set(exo, EX_SIDE_SET, set_id, elements.data(), sides.data()) < 0) ||
       ex_put_name(exo, EX_SIDE_SET, set_id, s.name.c_str()) < 0)
      return failed("a side set");
  }
  return true;
}

template <class Point>
bool write_EXODUS_file(const std::string& fname, const Indexed_hex_mesh<Point>& mesh, CGAL::IO::Hex_mesh_io_error* err)
{
  if(!check_before_writing(fname, mesh, CGAL::IO::Hex_mesh_fields(), err))
    return false;
  const Exodus_blocks blocks = exodus_blocks(mesh);
  Exodus_temporary_file temp;
  if(!temp.create(fname))
    return write_failure(fname, err, std::string("cannot create a temporary file in its folder: ") + std::strerror(errno));
  ex_opts(0);
  int comp_ws = 8, io_ws = 8;
  Exodus_file f;
  f.id = ex_create(temp.name.c_str(), EX_CLOBBER, &comp_ws, &io_ws);
  if(f.id < 0)
    return write_failure(fname, err, "cannot create the file (ex_create)");
  ex_set_max_name_length(f.id, 80);
  const auto failed = [&](const char* what) { return write_failure(fname, err, std::string("cannot write ") + what); };
  if(!write_exodus_parameters(f.id, mesh, blocks.hexahedra_of_block.size(), failed) ||
     !write_exodus_coordinates(f.id, mesh, failed) || !write_exodus_element_blocks(f.id, mesh, blocks, failed) ||
     !write_exodus_id_maps(f.id, mesh, blocks, failed) || !write_exodus_node_sets(f.id, mesh, failed) ||
     !write_exodus_side_sets(f.id, mesh, blocks, failed))
    return false;
  const int id = f.id;
  f.id = -1;
  if(ex_close(id) < 0)
    return failed("the file (ex_close)");
  if(std::rename(temp.name.c_str(), fname.c_str()) != 0)
    return write_failure(fname, err, std::string("cannot rename the temporary file: ") + std::strerror(errno));
  temp.keep = true;
  return true;
}

#else // CGAL_HMO_HAVE_EXODUS

inline const char* no_exodus_support()
{
  return "this build has no Exodus II support (the Exodus II library, Debian libexodusii-dev, was not found "
         "when it was configured): convert the mesh to .msh, .inp, .mesh or .vtu";
}

template <class Point>
bool read_EXODUS_file(const std::string&, Indexed_hex_mesh<Point>&, const Read_context& ctx)
{
  return ctx.fail(0, no_exodus_support());
}

template <class Point>
bool write_EXODUS_file(const std::string& fname, const Indexed_hex_mesh<Point>&, CGAL::IO::Hex_mesh_io_error* err)
{
  return write_failure(fname, err, no_exodus_support());
}

#endif // CGAL_HMO_HAVE_EXODUS

} // namespace io
} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_IO_INTERNAL_EXODUS_IO_H
