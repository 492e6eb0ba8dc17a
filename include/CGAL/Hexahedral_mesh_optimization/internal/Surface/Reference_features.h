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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_REFERENCE_FEATURES_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_REFERENCE_FEATURES_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The feature curves and corners of a reference surface (issue 14, item 1):
// what the mesh boundary must follow, found on the reference itself rather
// than on the mesh (whose vertices need not lie on the creases at all).
//
// - Sharp edges: `Polygon_mesh_processing::detect_sharp_edges` on the
//   reference as a `Surface_mesh`: an edge is sharp when the angle between
//   the normals of its two triangles exceeds 180° − θ (θ the dihedral
//   angle, `feature_angle`), and every border edge is. A soup that is not a
//   polygon mesh is oriented first (`orient_polygon_soup`, which duplicates
//   non-manifold vertices); one that still is not has no features here.
// - Curves: the sharp edges form polylines, split at the vertices with a
//   sharp degree other than 2 and where a curve turns by more than
//   `corner_turn` (a crease that bends sharply is two creases meeting at a
//   corner). Closed loops without such a vertex stay closed.
// - Clear features: the reference has features only when at least half of
//   its sharp edges at θ are still sharp at θ − `clear_margin`: a CAD
//   part's creases lie far below any threshold, so lowering it loses few of
//   them, while the edges of a faceted organic surface spread over all
//   angles, and the creases found there would pull the boundary onto facets. Without features, the caller keeps its
//   classification of the boundary by dihedral angles.
// - Fragments: a curve shorter than `min_length` that dangles (one end of
//   sharp degree 1) or is a closed loop is dropped, until stable: a scanned
//   surface's noise gives many short sharp edges, a CAD part's creases are
//   long. Short curves between two junctions are kept (a narrow chamfer).
// - Corners: the ends of the curves that remain.

#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <set>
#include <utility>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

/// A feature curve of the reference: a polyline. An open curve starts and
/// ends at corners (`first_corner`, `last_corner`, indices into
/// `Reference_features::corners`); a closed one does not repeat its first
/// point and has no corner.
struct Reference_feature_curve
{
  static constexpr std::size_t npos = std::size_t(-1);
  std::vector<Vec3> points;
  bool closed = false;
  std::size_t first_corner = npos, last_corner = npos;
  /// the patches on its two sides (the same twice along a border or a crease inside a patch)
  std::array<std::size_t, 2> patches = {{npos, npos}};
  /// the mean angle, in degrees, between the normals of its two sides
  /// (180° − the dihedral angle; 0 along a border)
  double normal_turn = 0.;
  /// its points as a polyline: a closed curve with its first point repeated at the end
  std::vector<Vec3> polyline() const
  {
    std::vector<Vec3> p = points;
    if(closed && !p.empty()) p.push_back(p.front());
    return p;
  }
};

struct Reference_features
{
  std::vector<Vec3> corners;
  /// for each corner, the patches around it (sorted)
  std::vector<std::vector<std::size_t>> corner_patches;
  std::vector<Reference_feature_curve> curves;
  /// the patch of each non-degenerate triangle of the soup (in soup order):
  /// the parts of the surface the creases bound
  std::vector<std::size_t> triangle_patch;
  /// the reference's edges sharp at θ, and at θ − the clear margin
  std::size_t sharp_edges = 0, clearly_sharp_edges = 0;
  /// false: too few of its sharp edges are clearly sharp, no curve kept
  bool clear = true;
  /// false: the soup is not a polygon mesh, even oriented; no feature
  bool polygon_mesh = true;
  bool empty() const { return curves.empty(); }
};

namespace reference_features_detail {

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Surface_mesh<K::Point_3> Mesh;
typedef Mesh::Vertex_index Vertex;
typedef Mesh::Halfedge_index Halfedge;
typedef Mesh::Edge_index Edge;
typedef Mesh::Face_index Face;

/// the soup as a Surface_mesh (degenerate triangles left out); false when
/// it cannot be one
inline bool to_surface_mesh(const std::vector<Vec3>& points, const std::vector<Tri>& tris, Mesh& out)
{
  std::vector<K::Point_3> p;
  p.reserve(points.size());
  for(const Vec3& x : points) p.emplace_back(x[0], x[1], x[2]);
  std::vector<std::array<std::size_t, 3>> f;
  f.reserve(tris.size());
  for(const Tri& t : tris)
    if(squared_norm(cross(points[t[1]] - points[t[0]], points[t[2]] - points[t[0]])) > 0.)
      f.push_back({std::size_t(t[0]), std::size_t(t[1]), std::size_t(t[2])});
  if(f.empty()) return false;
  namespace PMP = CGAL::Polygon_mesh_processing;
  if(!PMP::is_polygon_soup_a_polygon_mesh(f))
  {
    PMP::orient_polygon_soup(p, f);
    if(!PMP::is_polygon_soup_a_polygon_mesh(f)) return false;
  }
  PMP::polygon_soup_to_polygon_mesh(p, f, out);
  return true;
}

inline Vec3 point_of(const Mesh& m, Vertex v)
{
  const K::Point_3& p = m.point(v);
  return {p.x(), p.y(), p.z()};
}

/// the sharp edges as a per-edge flag
inline std::vector<unsigned char> sharp_edges(Mesh& m, double feature_angle)
{
  auto is_feature = m.add_property_map<Edge, bool>("e:hmo_is_feature", false).first;
  CGAL::Polygon_mesh_processing::detect_sharp_edges(m, 180. - feature_angle, is_feature);
  std::vector<unsigned char> sharp(m.number_of_edges(), 0);
  for(Edge e : m.edges()) sharp[std::size_t(e)] = is_feature[e] ? 1 : 0;
  m.remove_property_map(is_feature);
  return sharp;
}

/// the curves of the sharp edges, split at `is_end` vertices; a chain with
/// no end on it is a closed curve. Each curve as its vertices and edges.
struct Chain
{
  std::vector<Vertex> vertices; // closed: the first is not repeated
  std::vector<Edge> edges;
  bool closed = false;
};

inline std::vector<Chain> chains(const Mesh& m, const std::vector<unsigned char>& sharp,
                                 const std::vector<unsigned char>& is_end)
{
  std::vector<Chain> out;
  std::vector<unsigned char> used(m.number_of_edges(), 0);
  auto next_sharp = [&](Vertex v) {
    for(Halfedge h : CGAL::halfedges_around_target(m.halfedge(v), m))
    {
      const Edge e = m.edge(h);
      if(sharp[std::size_t(e)] && !used[std::size_t(e)]) return h; // h points to v
    }
    return Halfedge();
  };
  auto walk = [&](Vertex start, Halfedge into_start) {
    Chain c;
    c.vertices.push_back(start);
    Halfedge h = m.opposite(into_start); // from start outward
    for(;;)
    {
      used[std::size_t(m.edge(h))] = 1;
      c.edges.push_back(m.edge(h));
      const Vertex t = m.target(h);
      if(t == start) { c.closed = true; break; }
      c.vertices.push_back(t);
      if(is_end[std::size_t(t)]) break;
      const Halfedge n = next_sharp(t);
      if(n == Halfedge()) break; // cannot happen: sharp degree 2
      h = m.opposite(n);
    }
    out.push_back(c);
  };
  for(Vertex v : m.vertices()) // the open curves, from their ends
    if(is_end[std::size_t(v)])
      for(Halfedge h = next_sharp(v); h != Halfedge(); h = next_sharp(v))
        walk(v, h);
  for(Vertex v : m.vertices()) // the closed loops
    for(Halfedge h = next_sharp(v); h != Halfedge(); h = next_sharp(v))
      walk(v, h);
  return out;
}

/// the patch of every face: the components of the faces, the sharp edges cutting them
inline std::vector<std::size_t> patches(Mesh& m, const std::vector<unsigned char>& sharp)
{
  auto constrained = m.add_property_map<Edge, bool>("e:hmo_constrained", false).first;
  for(Edge e : m.edges()) constrained[e] = sharp[std::size_t(e)] != 0;
  auto component = m.add_property_map<Mesh::Face_index, std::size_t>("f:hmo_patch", 0).first;
  CGAL::Polygon_mesh_processing::connected_components(
    m, component, CGAL::parameters::edge_is_constrained_map(constrained));
  std::vector<std::size_t> out(m.number_of_faces(), 0);
  for(Mesh::Face_index f : m.faces()) out[std::size_t(f)] = component[f];
  m.remove_property_map(constrained);
  m.remove_property_map(component);
  return out;
}

inline double length_of(const Mesh& m, const Chain& c)
{
  double l = 0.;
  for(Edge e : c.edges)
    l += norm(point_of(m, m.target(m.halfedge(e))) - point_of(m, m.source(m.halfedge(e))));
  return l;
}

/// the mean angle, in degrees, between the normals of the two faces of the
/// chain's edges (border edges left out; 0 when all are)
inline double mean_normal_turn(const Mesh& m, const Chain& c)
{
  double sum = 0.;
  std::size_t n = 0;
  for(Edge e : c.edges)
  {
    const Halfedge h = m.halfedge(e);
    if(m.is_border(h) || m.is_border(m.opposite(h))) continue;
    const K::Vector_3 a = CGAL::Polygon_mesh_processing::compute_face_normal(m.face(h), m);
    const K::Vector_3 b = CGAL::Polygon_mesh_processing::compute_face_normal(m.face(m.opposite(h)), m);
    sum += std::acos((std::max)(-1., (std::min)(1., a * b))) * 180. / CGAL_PI;
    ++n;
  }
  return n > 0 ? sum / double(n) : 0.;
}

/// sharp degree per vertex
inline std::vector<std::size_t> degrees(const Mesh& m, const std::vector<unsigned char>& sharp)
{
  std::vector<std::size_t> d(m.number_of_vertices(), 0);
  for(Edge e : m.edges())
    if(sharp[std::size_t(e)])
    {
      ++d[std::size_t(m.source(m.halfedge(e)))];
      ++d[std::size_t(m.target(m.halfedge(e)))];
    }
  return d;
}

/// the vertices of sharp degree 2 where the crease turns by more than
/// `corner_turn` degrees
inline void mark_turns(const Mesh& m, const std::vector<unsigned char>& sharp,
                       const std::vector<std::size_t>& degree, double corner_turn,
                       std::vector<unsigned char>& is_end)
{
  const double least_cosine = std::cos(corner_turn * CGAL_PI / 180.);
  for(Vertex v : m.vertices())
  {
    if(degree[std::size_t(v)] != 2) continue;
    Vec3 ends[2];
    int k = 0;
    for(Halfedge h : CGAL::halfedges_around_target(m.halfedge(v), m))
      if(sharp[std::size_t(m.edge(h))] && k < 2) ends[k++] = point_of(m, m.source(h));
    const Vec3 p = point_of(m, v);
    const Vec3 in = p - ends[0], out = ends[1] - p;
    const double l = norm(in) * norm(out);
    if(l > 0. && dot(in, out) / l < least_cosine) is_end[std::size_t(v)] = 1;
  }
}

} // namespace reference_features_detail

/// The feature curves and corners of the reference surface given as a
/// triangle soup (see the top of this file). `min_length`: the shortest
/// dangling or closed curve kept; `clear_margin`: see "Clear features" at
/// the top of this file (0: not checked). `given_creases`: edges of the
/// reference (pairs of indices into `points`) the user gave as features
/// (CGAL's `edge_is_constrained_map`): they are sharp whatever their angle,
/// are never dropped as fragments, and make the reference's features clear.
inline Reference_features detect_reference_features(const std::vector<Vec3>& points,
                                                    const std::vector<Tri>& triangles,
                                                    double feature_angle,
                                                    double corner_turn,
                                                    double min_length,
                                                    double clear_margin,
                                                    const std::vector<std::array<std::size_t, 2> >& given_creases = {})
{
  using namespace reference_features_detail;
  Reference_features rf;
  Mesh m;
  rf.polygon_mesh = to_surface_mesh(points, triangles, m);
  if(!rf.polygon_mesh) return rf;
  std::vector<unsigned char> sharp = sharp_edges(m, feature_angle);
  // the given creases, found by their end points (the polygon mesh may have
  // duplicated vertices of the soup)
  std::vector<unsigned char> given(m.number_of_edges(), 0);
  if(!given_creases.empty())
  {
    std::set<std::pair<Vec3, Vec3> > ends;
    for(const auto& e : given_creases)
      if(e[0] < points.size() && e[1] < points.size())
        ends.insert(std::minmax(points[e[0]], points[e[1]]));
    auto vec3 = [&m](Vertex v) { const auto& p = m.point(v); return Vec3{p.x(), p.y(), p.z()}; };
    for(Edge e : m.edges())
      if(ends.count(std::minmax(vec3(m.source(m.halfedge(e))), vec3(m.target(m.halfedge(e))))))
        given[std::size_t(e)] = 1;
  }
  const bool any_given = std::count(given.begin(), given.end(), 1) > 0;
  for(std::size_t e = 0; e < sharp.size(); ++e) sharp[e] = sharp[e] || given[e];
  const auto count = [](const std::vector<unsigned char>& f) { return std::size_t(std::count(f.begin(), f.end(), 1)); };
  rf.sharp_edges = count(sharp);
  if(clear_margin > 0.)
  {
    // features at all only when most edges sharp at θ are sharp at θ − margin
    rf.clearly_sharp_edges = count(sharp_edges(m, feature_angle - clear_margin));
    rf.clear = 2 * rf.clearly_sharp_edges >= rf.sharp_edges;
    if(!rf.clear && !any_given) return rf;
    if(!rf.clear) // no clear creases of its own: the given ones only
    {
      sharp = given;
      rf.clear = true;
    }
  }

  std::vector<Chain> cs;
  std::vector<unsigned char> is_end;
  for(;;) // drop short dangling and closed fragments, until stable
  {
    const std::vector<std::size_t> degree = degrees(m, sharp);
    is_end.assign(m.number_of_vertices(), 0);
    for(Vertex v : m.vertices())
      is_end[std::size_t(v)] = (degree[std::size_t(v)] != 0 && degree[std::size_t(v)] != 2) ? 1 : 0;
    mark_turns(m, sharp, degree, corner_turn, is_end);
    cs = chains(m, sharp, is_end);
    bool removed = false;
    for(const Chain& c : cs)
    {
      const bool dangling = c.closed || degree[std::size_t(c.vertices.front())] == 1
                                     || degree[std::size_t(c.vertices.back())] == 1;
      if(!dangling || length_of(m, c) >= min_length) continue;
      bool has_given = false;
      for(Edge e : c.edges) has_given = has_given || given[std::size_t(e)];
      if(has_given) continue;
      for(Edge e : c.edges) sharp[std::size_t(e)] = 0;
      removed = true;
    }
    if(!removed) break;
  }

  rf.triangle_patch = patches(m, sharp);
  const std::size_t npos = Reference_feature_curve::npos;
  auto patch_of = [&](Halfedge h) { return m.is_border(h) ? npos : rf.triangle_patch[std::size_t(m.face(h))]; };
  std::vector<std::size_t> corner_of(m.number_of_vertices(), npos);
  auto corner = [&](Vertex v) {
    std::size_t& c = corner_of[std::size_t(v)];
    if(c == npos)
    {
      c = rf.corners.size();
      rf.corners.push_back(point_of(m, v));
      std::vector<std::size_t> around;
      for(Halfedge h : CGAL::halfedges_around_target(m.halfedge(v), m))
        if(patch_of(h) != npos) around.push_back(patch_of(h));
      std::sort(around.begin(), around.end());
      around.erase(std::unique(around.begin(), around.end()), around.end());
      rf.corner_patches.push_back(around);
    }
    return c;
  };
  for(const Chain& c : cs)
  {
    Reference_feature_curve curve;
    for(Vertex v : c.vertices) curve.points.push_back(point_of(m, v));
    const Halfedge h = m.halfedge(c.edges.front());
    curve.patches = {{patch_of(h), patch_of(m.opposite(h))}};
    if(curve.patches[0] == npos) curve.patches[0] = curve.patches[1];
    if(curve.patches[1] == npos) curve.patches[1] = curve.patches[0];
    curve.normal_turn = mean_normal_turn(m, c);
    curve.closed = c.closed && !is_end[std::size_t(c.vertices.front())];
    if(!curve.closed)
    {
      if(c.closed) curve.points.push_back(curve.points.front()); // a loop through one corner
      curve.first_corner = corner(c.vertices.front());
      curve.last_corner = corner(c.closed ? c.vertices.front() : c.vertices.back());
    }
    rf.curves.push_back(std::move(curve));
  }
  return rf;
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_REFERENCE_FEATURES_H
