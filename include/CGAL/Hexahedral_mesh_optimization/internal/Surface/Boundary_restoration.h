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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_BOUNDARY_RESTORATION_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_BOUNDARY_RESTORATION_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Stage "surface restoration": moves boundary vertices back toward a home
// position on the reference, one vertex at a time, wherever the quality
// allows it.
//
// Why: the surface error is a Hausdorff distance, so it is set by the few
// places where untangling (the edge-angle optimiser relaxes α and β until
// the last element is free; the barrier stage lets vertices slide along the
// surface) or a quality stage moved the boundary furthest. Projecting a
// vertex onto the reference does not undo a slide along a curved or creased
// surface; moving it home does. The home of a vertex is its input position
// when the reference is the input's own boundary (the vertex was on it) and
// its projection onto the reference otherwise.
//
// A move, from x toward home h, tries x + s (h − x) for s = 1, 1/2, 1/4, 1/8
// and is kept only if
//   - neither direction of the surface deviation around the vertex
//     (Surface_guard) grows, and
//   - no hex around the vertex falls below min(floor, its minimum before),
//     `floor` being the MSJ the mesh has: the MSJ never drops; nor below 0
//     when none is inverted, and no more become inverted when one is
//     (`element_floor`, `Worst_element_smoothing::keeps_floor`).
// Vertices are visited furthest from home first; the interior vertices around
// the ones that could not move are then given a max-min move
// (Worst_element_smoothing) so that the next sweep may move them further.
// The sweeps stop when neither kind of move changed anything, after
// `max_sweeps` or at the run's time limit (a hard stop).

#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_topology.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Surface_guard.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/Time_limit.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Smoothing/Worst_element_smoothing.h>

#include <algorithm>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

struct Boundary_restoration_settings
{
  /// vertices whose surface deviation is at most this are left alone (mesh units)
  double threshold = 0.;
  /// vertices at most this far from home are home (mesh units): after an
  /// untangling that kept the boundary fixed, all of them are, up to
  /// rounding, and visiting them would cost a sweep over the whole boundary
  double home_distance = 0.;
  /// no hex may fall below min(floor, its minimum before the move) (see `element_floor`)
  double floor = 0.;
  int max_sweeps = 8;
  /// the run's hard stop (null: none), read between vertices
  const Time_limit* time_limit = nullptr;
};

struct Boundary_restoration_report
{
  double distance_before = 0., distance_after = 0.; ///< largest distance of a boundary vertex to its home (mesh units)
  std::size_t moves = 0;
  int sweeps = 0;
};

/// Moves the boundary vertices of `points` toward `home` (see the top).
inline Boundary_restoration_report restore_boundary(const Hex_mesh_topology& topo, const Surface_guard& guard,
                                                     const std::vector<std::size_t>& boundary_vertices,
                                                     const std::vector<Vec3>& home, std::vector<Vec3>& points,
                                                     const Boundary_restoration_settings& s)
{
  const Worst_element_smoothing probe(topo, nullptr, nullptr);
  Boundary_restoration_report rep;
  auto largest_distance = [&] {
    double w = 0.;
    for(std::size_t v : boundary_vertices) w = (std::max)(w, norm(home[v] - points[v]));
    return w;
  };
  rep.distance_before = rep.distance_after = largest_distance();
  // vertices to visit: all at first, then those next to a vertex that moved
  std::vector<char> active(topo.number_of_vertices(), 1);
  auto activate_around = [&](std::size_t v, std::vector<char>& next) {
    for(auto c = topo.vertex_corners_begin(v); c != topo.vertex_corners_end(v); ++c)
      for(std::size_t u : topo.hexes()[c->hex]) next[u] = 1;
  };
  for(int sweep = 0; sweep < s.max_sweeps; ++sweep)
  {
    if(time_limit_reached(s.time_limit)) break;
    // furthest from home first (the deviation would cost a guard query each)
    std::vector<std::pair<double, std::size_t> > order;
    for(std::size_t v : boundary_vertices)
    {
      const double d = squared_norm(home[v] - points[v]);
      if(active[v] && d > s.home_distance * s.home_distance && !topo.is_constrained(v)) order.push_back({-d, v});
    }
    if(order.empty()) break;
    std::sort(order.begin(), order.end());
    ++rep.sweeps;
    std::vector<char> next(topo.number_of_vertices(), 0);
    std::size_t moved = 0;
    std::vector<std::size_t> stuck;
    for(const auto& o : order)
    {
      if(time_limit_reached(s.time_limit)) break;
      const std::size_t v = o.second;
      const Vec3 x = points[v];
      const Surface_deviation dev = guard.local_deviations(points, v, x);
      if(dev.max() <= s.threshold) continue;
      const double now = probe.local_minimum(points, v, x);
      bool done = false;
      for(double step = 1.; step >= 0.125 && !done; step *= 0.5)
      {
        const Vec3 y = x + step * (home[v] - x);
        if(!probe.keeps_floor(points, v, y, s.floor, now)) continue;
        if(!guard.allows(points, v, y, dev)) continue;
        points[v] = y;
        done = true;
      }
      if(done) { ++moved; activate_around(v, next); }
      else stuck.push_back(v);
    }
    rep.moves += moved;
    // give the interior around the stuck vertices room: a max-min move of
    // each interior neighbour (the boundary stays where it is)
    std::size_t interior_moved = 0;
    if(!stuck.empty())
    {
      std::vector<char> seen(topo.number_of_vertices(), 0);
      std::vector<std::size_t> ring;
      for(std::size_t v : stuck)
        for(auto c = topo.vertex_corners_begin(v); c != topo.vertex_corners_end(v); ++c)
          for(std::size_t u : topo.hexes()[c->hex])
            if(!seen[u] && !topo.is_boundary_vertex(u)) { seen[u] = 1; ring.push_back(u); }
      Worst_element_smoothing smoother(topo, nullptr, nullptr);
      const std::vector<Vec3> before = points;
      smoother.raise_vertices(points, ring);
      for(std::size_t u : ring)
        if(squared_norm(points[u] - before[u]) > 0.) { ++interior_moved; activate_around(u, next); }
    }
    active.swap(next);
    // the sweeps go on while the interior moves too: what it gains is what
    // the next sweep needs to move a stuck vertex (when every boundary
    // vertex is stuck after the pull-back, stopping as soon as none moved
    // would end after one sweep and leave the MSJ stages a poor start)
    if(moved == 0 && interior_moved == 0) break;
  }
  rep.distance_after = largest_distance();
  return rep;
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_BOUNDARY_RESTORATION_H
