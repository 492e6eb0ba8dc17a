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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_UNTANGLING_LOCAL_REGION_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_UNTANGLING_LOCAL_REGION_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Local regions (Section 3.2 of the paper): the union of the k-ring
// neighbourhoods (k = 2 by default) of the bad elements, split into connected
// clusters. A hex is in the 1-ring of another when they share a vertex.
// Vertices of region hexes that are also used by hexes outside the region are
// the region's fixed boundary; the other vertices are free (mesh boundary
// vertices among them are held by the boundary energy, not fixed).
// Where bad elements are dense the optimiser asks for more rings
// (`rings` grows with the number of failed rounds, see Untangler.h).

#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_topology.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/parallel_for_each_index.h>

#include <algorithm>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

struct Local_region
{
  std::vector<std::size_t> hexes;         ///< hexes of the region
  std::vector<std::size_t> free_vertices; ///< vertices the solver moves
  std::size_t bad_hexes = 0;              ///< number of seed elements in it
};

/// Regions around `bad` (hex indices), each grown by `rings` rings.
inline std::vector<Local_region> extract_local_regions(const Hex_mesh_topology& topo,
                                                       const std::vector<std::size_t>& bad,
                                                       int rings)
{
  const std::size_t nh = topo.number_of_hexes(), nv = topo.number_of_vertices();
  const auto& hexes = topo.hexes();
  std::vector<char> in_region(nh, 0), is_bad(nh, 0);
  std::vector<std::size_t> front(bad.begin(), bad.end());
  for(std::size_t h : bad) { in_region[h] = 1; is_bad[h] = 1; }
  std::vector<char> vertex_seen(nv, 0);
  for(int r = 0; r < rings && !front.empty(); ++r)
  {
    std::vector<std::size_t> next;
    for(std::size_t h : front)
      for(std::size_t v : hexes[h])
      {
        if(vertex_seen[v]) continue;
        vertex_seen[v] = 1;
        for(auto c = topo.vertex_corners_begin(v); c != topo.vertex_corners_end(v); ++c)
          if(!in_region[c->hex]) { in_region[c->hex] = 1; next.push_back(c->hex); }
      }
    front.swap(next);
  }

  // a vertex is free when every hex around it is in the region and the
  // user did not constrain it
  std::vector<char> free_vertex(nv, 0);
  for(std::size_t v = 0; v < nv; ++v)
  {
    bool all = topo.vertex_corners_begin(v) != topo.vertex_corners_end(v) && !topo.is_constrained(v);
    for(auto c = topo.vertex_corners_begin(v); c != topo.vertex_corners_end(v) && all; ++c)
      all = in_region[c->hex] != 0;
    free_vertex[v] = all ? 1 : 0;
  }

  // clusters: region hexes connected through free vertices
  std::fill(vertex_seen.begin(), vertex_seen.end(), 0);
  std::vector<long> label(nh, -1);
  std::vector<Local_region> regions;
  for(std::size_t seed = 0; seed < nh; ++seed)
  {
    if(!in_region[seed] || label[seed] >= 0) continue;
    Local_region reg;
    const long id = static_cast<long>(regions.size());
    std::vector<std::size_t> stack{seed};
    label[seed] = id;
    while(!stack.empty())
    {
      const std::size_t h = stack.back(); stack.pop_back();
      reg.hexes.push_back(h);
      if(is_bad[h]) ++reg.bad_hexes;
      for(std::size_t v : hexes[h])
      {
        if(!free_vertex[v]) continue;
        for(auto c = topo.vertex_corners_begin(v); c != topo.vertex_corners_end(v); ++c)
          if(label[c->hex] < 0) { label[c->hex] = id; stack.push_back(c->hex); }
      }
    }
    // its free vertices, each once (`vertex_seen` marks them, then is
    // cleared for the next cluster), in increasing order
    std::vector<std::size_t> verts;
    for(std::size_t h : reg.hexes)
      for(std::size_t v : hexes[h])
        if(free_vertex[v] && !vertex_seen[v]) { vertex_seen[v] = 1; verts.push_back(v); }
    for(std::size_t v : verts) vertex_seen[v] = 0;
    std::sort(verts.begin(), verts.end());
    reg.free_vertices = std::move(verts);
    std::sort(reg.hexes.begin(), reg.hexes.end());
    if(!reg.free_vertices.empty())
      regions.push_back(std::move(reg));
  }
  return regions;
}

/// f(region) for every region of `regions` (from `extract_local_regions`),
/// on TBB's threads when the package is linked with TBB. The regions are
/// independent: a free vertex has every hex around it in its own region, so
/// no region moves a vertex another region reads, and the result is the same
/// on any number of threads and in any order. f must only write the free
/// vertices of its region (and what it owns).
template <class F>
void for_each_region(const std::vector<Local_region>& regions, F f)
{
  parallel_for_each_index(regions.size(), [&](std::size_t i) { f(regions[i]); });
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_UNTANGLING_LOCAL_REGION_H
