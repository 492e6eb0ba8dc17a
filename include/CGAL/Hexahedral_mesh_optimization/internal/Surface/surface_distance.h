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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_SURFACE_DISTANCE_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_SURFACE_DISTANCE_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The surface error of the paper's tables: the symmetric Hausdorff distance
// between the boundary of a hex mesh and a reference surface, relative to a
// bounding-box diagonal.
//
// Choices:
// - Distance: CGAL::Polygon_mesh_processing::bounded_error_Hausdorff_distance
//   in both directions, with an error bound of 1e-4 × the reference's
//   bounding-box diagonal: the exact Hausdorff distance up to that bound
//   (metro, which the paper used, samples and so slightly underestimates),
//   and faster than sampling densely enough to reach that bound.
// - Quads are cut along their (q0, q2) diagonal (`Quad_split::diagonal_02`),
//   a fixed rule, not the shorter diagonal: two meshes with the same
//   connectivity (an optimiser's input and output) are then triangulated
//   alike, and a warped quad whose geometry did not change contributes no
//   error. With a per-mesh shorter-diagonal rule a single warped quad
//   triangulated differently in the two meshes can dominate the error.
// - Normalisation: the reference's bounding-box diagonal. Metro instead
//   divides by the diagonal of the union of both boxes enlarged by 2 % of its
//   diagonal on every side (vcglib metro.cpp: bbox.Offset(bbox.Diag()*0.02));
//   `metro_diagonal` gives that value, for comparison with published tables
//   (about 7 % larger for a box of equal sides).

#include <CGAL/Hexahedral_mesh_optimization/Hex_mesh_surface_distance.h>
#include <CGAL/Hexahedral_mesh_optimization/Optimization_result.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_boundary.h>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Polygon_mesh_processing/distance.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Bbox_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <future>
#include <limits>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

typedef CGAL::Surface_mesh<CGAL::Exact_predicates_inexact_constructions_kernel::Point_3> Triangle_surface;

/// the distances between two surfaces: the public `CGAL::Hex_mesh_surface_distance`
typedef CGAL::Hex_mesh_surface_distance Surface_distance;

inline CGAL::Bbox_3 bbox_of(const Triangle_surface& s)
{
  CGAL::Bbox_3 b;
  for(auto v : s.vertices())
    b += s.point(v).bbox();
  return b;
}

inline double diagonal(const CGAL::Bbox_3& b)
{
  if(b.xmin() > b.xmax())
    return 0.;
  return std::sqrt(CGAL::square(b.xmax() - b.xmin()) + CGAL::square(b.ymax() - b.ymin()) +
                   CGAL::square(b.zmax() - b.zmin()));
}

/// Adds triangle abc to `s` as a face of its own (the sub-surfaces below need
/// no connectivity: the distance to a surface is the distance to its faces).
inline void add_separate_triangle(Triangle_surface& s, const Vec3& a, const Vec3& b, const Vec3& c)
{
  typedef Triangle_surface::Point Point;
  s.add_face(s.add_vertex(Point(a[0], a[1], a[2])), s.add_vertex(Point(b[0], b[1], b[2])),
             s.add_vertex(Point(c[0], c[1], c[2])));
}

namespace surface_distance_detail {

typedef CGAL::Simple_cartesian<double> Soup_kernel;
typedef Soup_kernel::Point_3 Soup_point;
typedef Soup_kernel::Triangle_3 Soup_triangle;
typedef CGAL::AABB_tree<CGAL::AABB_traits<
  Soup_kernel, CGAL::AABB_triangle_primitive<Soup_kernel, std::vector<Soup_triangle>::const_iterator> > >
  Soup_tree;

inline std::vector<Soup_triangle> triangles_of(const Triangle_surface& s)
{
  std::vector<Soup_triangle> t;
  t.reserve(s.number_of_faces());
  for(auto f : s.faces())
  {
    Soup_point p[3];
    int i = 0;
    for(auto v : CGAL::vertices_around_face(s.halfedge(f), s))
    {
      const auto& q = s.point(v);
      if(i < 3) p[i] = Soup_point(q.x(), q.y(), q.z());
      ++i;
    }
    t.push_back(Soup_triangle(p[0], p[1], p[2]));
  }
  return t;
}

/// For each face of `s` (in face order, as `triangles_of`), the face across
/// each of its edges: entry k is across the edge from its vertex k to its
/// vertex k + 1 (vertices in `triangles_of`'s order); `none` on a border.
inline std::vector<std::array<std::size_t, 3> > face_neighbours(const Triangle_surface& s)
{
  const std::size_t none = (std::numeric_limits<std::size_t>::max)();
  std::vector<std::array<std::size_t, 3> > n(s.number_of_faces(), {none, none, none});
  std::size_t i = 0;
  for(auto f : s.faces())
  {
    // triangles_of lists target(h0), target(h1), target(h2), h0 = halfedge(f):
    // the edge from vertex k to k + 1 is h_{k+1}
    Triangle_surface::Halfedge_index h[3];
    h[0] = s.halfedge(f);
    h[1] = s.next(h[0]);
    h[2] = s.next(h[1]);
    for(int k = 0; k < 3; ++k)
    {
      const auto g = s.face(s.opposite(h[(k + 1) % 3]));
      if(g != Triangle_surface::null_face()) n[i][k] = std::size_t(g);
    }
    ++i;
  }
  return n;
}

/// An upper bound of the squared distance from triangle `t` to the surface
/// made of `triangles`, through `r` (the index of one of them): t is cut by
/// the plane through one edge of r that bisects the angle between r and its
/// neighbour across that edge, and each side is bounded by its own triangle
/// (the distance to one triangle is convex, so it is at most its largest value
/// at the corners of a convex piece). The single-triangle bound, max over the
/// corners of t of their distance to r, is loose by up to an edge length
/// where t straddles an edge of the reference (a boundary quad whose
/// corners slid across the reference's triangles); this one is close to the
/// distance there. t crossing two or more edges' planes: the single-triangle
/// bound. `across` (if given) receives the other triangle the bound used
/// (`r` itself for the single-triangle bound).
inline double straddle_bound(const Soup_triangle& t, std::size_t r, const std::vector<Soup_triangle>& triangles,
                             const std::vector<std::array<std::size_t, 3> >& neighbours,
                             std::size_t* across = nullptr)
{
  if(across) *across = r;
  typedef Soup_kernel::Vector_3 V;
  const Soup_triangle& R = triangles[r];
  double single = 0.;
  for(int k = 0; k < 3; ++k) single = (std::max)(single, CGAL::squared_distance(t.vertex(k), R));
  if(neighbours.empty()) return single;
  const V nr = CGAL::cross_product(R.vertex(1) - R.vertex(0), R.vertex(2) - R.vertex(0));
  const double lr = std::sqrt(nr.squared_length());
  if(!(lr > 0.)) return single;
  int crossed = -1;
  double side[3] = {0., 0., 0.};
  for(int k = 0; k < 3; ++k)
  {
    const std::size_t o = neighbours[r][k];
    if(o == (std::numeric_limits<std::size_t>::max)()) continue;
    const Soup_triangle& O = triangles[o];
    V no = CGAL::cross_product(O.vertex(1) - O.vertex(0), O.vertex(2) - O.vertex(0));
    const double lo = std::sqrt(no.squared_length());
    if(!(lo > 0.)) continue;
    no = no / lo;
    if(no * nr < 0.) no = -no;
    const Soup_point& a = R.vertex(k);
    V m = CGAL::cross_product(R.vertex((k + 1) % 3) - a, nr / lr + no);
    if(m * (R.vertex((k + 2) % 3) - a) > 0.) m = -m; // r on the negative side
    double s[3];
    bool beyond = false;
    for(int j = 0; j < 3; ++j) { s[j] = m * (t.vertex(j) - a); beyond = beyond || s[j] > 0.; }
    if(!beyond) continue;
    if(crossed >= 0) return single; // near a corner of r
    for(int j = 0; j < 3; ++j) side[j] = s[j];
    crossed = k;
  }
  if(crossed < 0) return single;
  const Soup_triangle& O = triangles[neighbours[r][crossed]];
  double u = 0.;
  for(int j = 0; j < 3; ++j)
  {
    const Soup_point& p = t.vertex(j);
    u = (std::max)(u, CGAL::squared_distance(p, side[j] > 0. ? O : R));
    const int i = (j + 1) % 3;
    if((side[j] > 0.) != (side[i] > 0.))
    {
      // where the edge (j, i) crosses the plane: on both pieces
      const double w = side[j] / (side[j] - side[i]);
      const Soup_point x = p + w * (t.vertex(i) - p);
      u = (std::max)(u, (std::max)(CGAL::squared_distance(x, R), CGAL::squared_distance(x, O)));
    }
  }
  if(across && u < single) *across = neighbours[r][crossed];
  return (std::min)(u, single);
}

} // namespace surface_distance_detail

/// A bound of the distance from every point of a triangle to a surface,
/// through a few triangles of that surface: the distance to those alone is
/// at most `bound` everywhere on the triangle. When the triangle was cut
/// into pieces (`one_sided_distance_above`), the bound is the largest of
/// theirs if that is lower, through the triangles of them all if there are
/// at most `max_witnesses`, else the triangle's own bound. `surface_bound`
/// (at most `bound`) is the lower of the two in any case: a bound of the
/// distance to the whole surface.
struct Distance_witness
{
  static const std::size_t max_witnesses = 4;
  double bound = 0.;
  double surface_bound = 0.;
  std::array<std::size_t, max_witnesses> through = {{0, 0, 0, 0}};
  std::size_t count = 0;

  /// adds triangle `t` to those it goes through; false if there is no room
  bool add(std::size_t t)
  {
    for(std::size_t i = 0; i < count; ++i)
      if(through[i] == t) return true;
    if(count == max_witnesses) return false;
    through[count++] = t;
    return true;
  }
};

namespace surface_distance_detail {

/// One triangle of `one_sided_distance_above` that its own bound could not
/// leave out: cut into 4 at its edge midpoints, down to `depth` levels, each
/// part bounded again (`bound_of`, which also gives the part's realised
/// squared distance, raising `lower2`); a part whose bound is within
/// `cull2()` is left out, and the parts still uncertain at the last level
/// go to `rest` for CGAL. `pieces2` receives the largest bound of the parts
/// not cut further and `through` the triangles of the other surface those
/// bounds go through; returns false if there were more of them than
/// `Distance_witness::max_witnesses`. `parts` is scratch (the parts still
/// to look at, with their levels), kept by the caller from one triangle to
/// the next.
template <class BoundOf, class Cull2>
bool subdivide_and_bound(const Soup_triangle& triangle, int depth, const BoundOf& bound_of, const Cull2& cull2,
                         double& lower2, double& pieces2, Distance_witness& through, Triangle_surface& rest,
                         std::vector<std::pair<Soup_triangle, int> >& parts)
{
  bool room = true;
  parts.assign(1, {triangle, 0});
  while(!parts.empty())
  {
    const Soup_triangle t = parts.back().first;
    const int level = parts.back().second;
    parts.pop_back();
    if(level > 0)
    {
      double r2 = 0.;
      std::size_t closest = 0, across = 0;
      const double u = bound_of(t, r2, closest, across);
      lower2 = (std::max)(lower2, r2);
      if(u <= cull2() || level == depth)
      {
        pieces2 = (std::max)(pieces2, u);
        room = room && through.add(closest) && through.add(across);
      }
      if(u <= cull2()) continue;
    }
    if(level < depth)
    {
      const Soup_point a = t.vertex(0), b = t.vertex(1), c = t.vertex(2);
      const Soup_point ab = CGAL::midpoint(a, b), bc = CGAL::midpoint(b, c), ca = CGAL::midpoint(c, a);
      parts.push_back({Soup_triangle(a, ab, ca), level + 1});
      parts.push_back({Soup_triangle(ab, b, bc), level + 1});
      parts.push_back({Soup_triangle(ca, bc, c), level + 1});
      parts.push_back({Soup_triangle(ab, bc, ca), level + 1});
      continue;
    }
    Vec3 p[3];
    for(int k = 0; k < 3; ++k) p[k] = Vec3{t.vertex(k).x(), t.vertex(k).y(), t.vertex(k).z()};
    add_separate_triangle(rest, p[0], p[1], p[2]);
  }
  return room;
}

} // namespace surface_distance_detail

/// max(`lower`, the one-sided Hausdorff distance from the triangles `from`
/// to the surface `to`), to `error_bound`, for a caller that only needs the
/// distance where it exceeds `lower` (a value it knows, or 0).
///
/// Before CGAL's bounded-error computation, every triangle that cannot
/// realise more than that is left out: the distance to one triangle R of
/// `to` is convex, so a triangle T is within max over its corners of
/// d(corner, R) of `to` everywhere; R is the triangle of `to` closest to
/// T's centroid. The distances of the centroids themselves raise `lower`
/// first (they are realised). A triangle this bound cannot leave out is cut
/// into 4 (at its edge midpoints) and each part tried again, down to
/// `subdivision_depth` levels; only the parts left then go to CGAL. The
/// single-triangle bound is loose where T spans several triangles of `to`
/// (a boundary quad that slid across the reference's triangles: the corners
/// lie on other triangles than R, up to an edge length from it). Where T
/// crosses one edge of R, `straddle_bound` bounds each side by its own
/// triangle, which is close to the distance; parts near a corner of R are
/// left to the subdivision (RESULTS.md of the benchmark has what both
/// bounds save). `tree` holds `to_triangles`, the triangles of `to` in face
/// order (`triangles_of`), distance queries accelerated; `to_neighbours` their
/// `face_neighbours` (`Reference_distance_index` keeps all three for a
/// whole run). `witnesses` (if given) receives the bound of each triangle
/// of `from` and the triangles of `to` (indices in `to_triangles`) it went
/// through.
inline double one_sided_distance_above(const std::vector<surface_distance_detail::Soup_triangle>& from,
                                       const surface_distance_detail::Soup_tree& tree,
                                       const std::vector<surface_distance_detail::Soup_triangle>& to_triangles,
                                       const std::vector<std::array<std::size_t, 3> >& to_neighbours,
                                       const Triangle_surface& to, double lower, double error_bound,
                                       int subdivision_depth = 4, std::vector<Distance_witness>* witnesses = nullptr)
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  using namespace surface_distance_detail;
  if(witnesses) witnesses->assign(from.size(), Distance_witness());
  if(from.empty()) return lower;
  if(to.number_of_faces() == 0) return std::numeric_limits<double>::infinity();
  // the centroid's squared distance to `to` (realised), and the bound of the
  // triangle's squared distance through the triangle of `to` closest to it
  // (and the one across, in `across`)
  auto bound_of = [&](const Soup_triangle& t, double& realised2, std::size_t& closest, std::size_t& across) {
    const Soup_point c = CGAL::centroid(t);
    const auto hit = tree.closest_point_and_primitive(c);
    realised2 = CGAL::squared_distance(c, hit.first);
    closest = std::size_t(hit.second - to_triangles.begin());
    return straddle_bound(t, closest, to_triangles, to_neighbours, &across);
  };
  std::vector<double> upper(from.size());
  double lower2 = lower * lower;
  for(std::size_t i = 0; i < from.size(); ++i)
  {
    double r2 = 0.;
    std::size_t closest = 0, across = 0;
    upper[i] = bound_of(from[i], r2, closest, across);
    lower2 = (std::max)(lower2, r2);
    if(witnesses)
    {
      Distance_witness& w = (*witnesses)[i];
      w.bound = w.surface_bound = std::sqrt(upper[i]);
      w.add(closest);
      w.add(across);
    }
  }
  // within `error_bound` of the realised distance: cannot change the answer
  // beyond the precision asked for
  auto cull2 = [&lower2, error_bound] {
    const double c = std::sqrt(lower2) + error_bound;
    return c * c;
  };
  Triangle_surface rest;
  std::vector<std::pair<Soup_triangle, int> > parts; // scratch of `subdivide_and_bound`
  for(std::size_t i = 0; i < from.size(); ++i)
  {
    if(upper[i] <= cull2()) continue;
    double pieces2 = 0.;
    Distance_witness through_pieces;
    const bool room = surface_distance_detail::subdivide_and_bound(from[i], subdivision_depth, bound_of, cull2, lower2,
                                                                   pieces2, through_pieces, rest, parts);
    // (the pieces' bounds, through other triangles, may be the looser)
    if(witnesses && subdivision_depth > 0 && pieces2 < upper[i])
    {
      if(room)
      {
        through_pieces.bound = std::sqrt(pieces2);
        (*witnesses)[i] = through_pieces;
      }
      (*witnesses)[i].surface_bound = std::sqrt(pieces2);
    }
  }
  const double realised = std::sqrt(lower2);
  if(rest.number_of_faces() == 0) return realised;
  return (std::max)(realised, PMP::bounded_error_Hausdorff_distance<CGAL::Sequential_tag>(rest, to, error_bound));
}

/// The same, building the tree of `to` for this one call.
inline double one_sided_distance_above(const std::vector<surface_distance_detail::Soup_triangle>& from,
                                       const Triangle_surface& to, double lower, double error_bound,
                                       int subdivision_depth = 4, std::vector<Distance_witness>* witnesses = nullptr)
{
  using namespace surface_distance_detail;
  if(from.empty()) return lower;
  if(to.number_of_faces() == 0) return std::numeric_limits<double>::infinity();
  const std::vector<Soup_triangle> to_triangles = triangles_of(to);
  Soup_tree tree(to_triangles.begin(), to_triangles.end());
  tree.accelerate_distance_queries();
  return one_sided_distance_above(from, tree, to_triangles, face_neighbours(to), to, lower, error_bound,
                                  subdivision_depth, witnesses);
}

/// A reference surface set up once for the repeated checks of a run
/// (`surface_error_after_change`): its triangles, their AABB tree with
/// accelerated distance queries and its diagonal. Not copyable: the tree
/// refers into the triangles.
class Reference_distance_index
{
public:
  explicit Reference_distance_index(const Triangle_surface& reference)
    : m_surface(reference), m_triangles(surface_distance_detail::triangles_of(reference)),
      m_neighbours(surface_distance_detail::face_neighbours(reference)),
      m_tree(m_triangles.begin(), m_triangles.end()), m_diagonal(internal::diagonal(bbox_of(reference)))
  {
    m_tree.accelerate_distance_queries();
  }
  Reference_distance_index(const Reference_distance_index&) = delete;
  Reference_distance_index& operator=(const Reference_distance_index&) = delete;

  const Triangle_surface& surface() const { return m_surface; }
  const std::vector<surface_distance_detail::Soup_triangle>& triangles() const { return m_triangles; }
  /// the faces across the edges of each triangle (`face_neighbours`)
  const std::vector<std::array<std::size_t, 3> >& neighbours() const { return m_neighbours; }
  const surface_distance_detail::Soup_tree& tree() const { return m_tree; }
  double diagonal() const { return m_diagonal; }

private:
  const Triangle_surface& m_surface;
  std::vector<surface_distance_detail::Soup_triangle> m_triangles;
  std::vector<std::array<std::size_t, 3> > m_neighbours;
  surface_distance_detail::Soup_tree m_tree;
  double m_diagonal;
};

/// Distances between two triangle surfaces; `relative_error_bound` × the
/// reference diagonal bounds the error of each one-sided distance. Returns
/// infinite distances when exactly one surface is empty.
inline Surface_distance surface_distance(const Triangle_surface& mesh,
                                         const Triangle_surface& reference,
                                         double relative_error_bound = 1e-4)
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  Surface_distance d;
  const CGAL::Bbox_3 rb = bbox_of(reference), mb = bbox_of(mesh);
  d.reference_diagonal = diagonal(rb);
  CGAL::Bbox_3 u = rb + mb;
  const double o = 0.02 * diagonal(u);
  u = CGAL::Bbox_3(u.xmin() - o, u.ymin() - o, u.zmin() - o, u.xmax() + o, u.ymax() + o, u.zmax() + o);
  d.metro_diagonal = diagonal(u);

  const bool me = mesh.number_of_faces() == 0, re = reference.number_of_faces() == 0;
  if(me || re)
  {
    const double inf = (me && re) ? 0. : std::numeric_limits<double>::infinity();
    d.mesh_to_reference = d.reference_to_mesh = inf;
    return d;
  }
  const double bound = relative_error_bound * (std::max)(d.reference_diagonal, diagonal(mb));
  // the two directions at once (CGAL's Parallel_tag needs METIS as well);
  // each only reads both surfaces
  auto other = std::async(std::launch::async, [&] {
    return one_sided_distance_above(surface_distance_detail::triangles_of(reference), mesh, 0., bound);
  });
  d.mesh_to_reference = one_sided_distance_above(surface_distance_detail::triangles_of(mesh), reference, 0., bound);
  d.reference_to_mesh = other.get();
  return d;
}

/// the boundary of a hex mesh (arrays) as a triangle surface, quads cut along (q0, q2)
inline void boundary_surface(const Hex_mesh_arrays& m, Triangle_surface& out)
{
  const Hex_mesh_boundary b = extract_boundary(m);
  boundary_to_surface_mesh(b, m.points, out, Quad_split::diagonal_02);
}

/// surface distances between the boundary of `mesh` and a triangle surface
inline Surface_distance surface_distance(const Hex_mesh_arrays& mesh,
                                         const Triangle_surface& reference,
                                         double relative_error_bound = 1e-4)
{
  Triangle_surface s;
  boundary_surface(mesh, s);
  return surface_distance(s, reference, relative_error_bound);
}

/// surface distances between the boundaries of two hex meshes
inline Surface_distance surface_distance(const Hex_mesh_arrays& mesh,
                                         const Hex_mesh_arrays& reference,
                                         double relative_error_bound = 1e-4)
{
  Triangle_surface s, r;
  boundary_surface(mesh, s);
  boundary_surface(reference, r);
  return surface_distance(s, r, relative_error_bound);
}

/// Bounds of distances between triangles and a moving hex mesh boundary,
/// kept from one surface check to the next (`surface_error_after_change`).
/// Entry e holds a bound of the distance from every point of one triangle
/// (a boundary quad's, or a fixed reference triangle) to the other side,
/// through at most `max_quads` boundary quads, its witnesses, and where
/// their corners were then. When those corners have each moved by at most d
/// since, the bound + d still holds: every point of a quad's triangles is
/// the same convex combination of its corners as before, so it moved by at
/// most d too. A check then leaves out whatever is certainly below the
/// error it already knows, without a closest-point query: in a turn of the
/// quality stages most of the boundary moves a little and stays well within
/// the error, so most of it is left out.
class Moving_distance_bounds
{
public:
  /// `n` entries, all unknown (unless there were `n` already)
  void resize(std::size_t n)
  {
    if(m_entries.size() != n) m_entries.assign(n, Entry());
  }
  /// whether entry `e` is certainly below `value`; `corner(q, k)` is where
  /// corner k of boundary quad q is now
  template <class Corner>
  bool below(std::size_t e, const Corner& corner, double value) const
  {
    const Entry& x = m_entries[e];
    if(!(x.bound < value)) return false;
    double moved2 = 0.;
    for(std::size_t w = 0; w < x.quads; ++w)
      for(int k = 0; k < 4; ++k) moved2 = (std::max)(moved2, squared_norm(corner(x.quad[w], k) - x.corners[4 * w + k]));
    // the relative margin covers the rounding of the bound
    return (x.bound + std::sqrt(moved2)) * (1. + 1e-9) < value;
  }
  /// entry `e` is within `bound`, through the `n` quads `quads` (at most
  /// `max_quads`), their corners now at `corner`
  template <class Corner>
  void set(std::size_t e, double bound, const std::size_t* quads, std::size_t n, const Corner& corner)
  {
    CGAL_precondition(n <= max_quads);
    Entry& x = m_entries[e];
    x.bound = bound;
    x.quads = n;
    for(std::size_t w = 0; w < n; ++w)
    {
      x.quad[w] = quads[w];
      for(int k = 0; k < 4; ++k) x.corners[4 * w + k] = corner(quads[w], k);
    }
  }
  static const std::size_t max_quads = Distance_witness::max_witnesses;

private:
  struct Entry
  {
    double bound = std::numeric_limits<double>::infinity();
    std::size_t quads = 0;
    std::array<std::size_t, max_quads> quad;
    std::array<Vec3, 4 * max_quads> corners;
  };
  std::vector<Entry> m_entries;
};

/// What `surface_error_after_change` keeps from one call to the next, for
/// one boundary and one reference: the bounds of each boundary quad's
/// distance to the reference (the quad its own witness) and of each
/// reference triangle's distance to the boundary.
struct Surface_error_bounds
{
  Moving_distance_bounds boundary_to_reference;
  Moving_distance_bounds reference_to_boundary;
};

namespace surface_distance_detail {

/// the boundary quads with a corner that moved from `before` to `after`
inline std::vector<std::size_t> moved_quads(const Hex_mesh_boundary& b, const std::vector<Vec3>& before,
                                            const std::vector<Vec3>& after)
{
  std::vector<std::size_t> moved;
  for(std::size_t q = 0; q < b.quads.size(); ++q)
    for(std::size_t v : b.quads[q])
      if(before[v] != after[v]) { moved.push_back(q); break; }
  return moved;
}

/// per reference triangle: whether it meets the box around one of the
/// `moved` quads as they were (`before`), grown by `error_before`
template <class Map>
std::vector<char> reference_triangles_near(const Hex_mesh_boundary& b, const std::vector<Vec3>& before,
                                           const std::vector<std::size_t>& moved,
                                           const Reference_distance_index& reference, double error_before,
                                           const Map& to_reference_frame)
{
  std::vector<char> near(reference.triangles().size(), 0);
  std::vector<std::vector<Soup_triangle>::const_iterator> hits;
  for(std::size_t q : moved)
  {
    CGAL::Bbox_3 box;
    for(int i = 0; i < 4; ++i)
    {
      const Vec3 o = to_reference_frame(before[b.quads[q][i]]);
      box += CGAL::Bbox_3(o[0], o[1], o[2], o[0], o[1], o[2]);
    }
    box = CGAL::Bbox_3(box.xmin() - error_before, box.ymin() - error_before, box.zmin() - error_before,
                       box.xmax() + error_before, box.ymax() + error_before, box.zmax() + error_before);
    hits.clear();
    reference.tree().all_intersected_primitives(box, std::back_inserter(hits));
    for(auto it : hits) near[std::size_t(it - reference.triangles().begin())] = 1;
  }
  return near;
}

/// the bounds of the measured quads for the next call: each to the whole
/// reference (which does not move), through the quad itself
template <class Corner>
void keep_quad_bounds(const std::vector<std::size_t>& measured_quads, const std::vector<Distance_witness>& to_reference,
                      const Corner& corner, Surface_error_bounds& bounds)
{
  for(std::size_t k = 0; k < measured_quads.size(); ++k)
  {
    const std::size_t q = measured_quads[k];
    const double w = (std::max)(to_reference[2 * k].surface_bound, to_reference[2 * k + 1].surface_bound);
    bounds.boundary_to_reference.set(q, w, &q, 1, corner);
  }
}

/// the bounds of the measured reference triangles for the next call: each
/// through the quads of the boundary triangles it went through
template <class Corner>
void keep_reference_bounds(const std::vector<std::size_t>& measured_reference,
                           const std::vector<Distance_witness>& to_boundary, const Corner& corner,
                           Surface_error_bounds& bounds)
{
  for(std::size_t k = 0; k < measured_reference.size(); ++k)
  {
    const Distance_witness& w = to_boundary[k];
    std::size_t quads[Distance_witness::max_witnesses];
    std::size_t n = 0;
    for(std::size_t i = 0; i < w.count; ++i)
      if(std::find(quads, quads + n, w.through[i] / 2) == quads + n) quads[n++] = w.through[i] / 2;
    bounds.reference_to_boundary.set(measured_reference[k], w.bound, quads, n, corner);
  }
}

} // namespace surface_distance_detail

/// The surface error (Hausdorff distance between the boundary cut along the
/// (0, 2) diagonals and `reference`, absolute) after the boundary vertices
/// moved from `before` to `after`, when it was at most `error_before` at
/// `before`: max(`error_before`, the two one-sided distances of the part
/// that moved). Only that part is measured:
///   - boundary -> reference: the quads with a moved corner;
///   - reference -> boundary: the reference triangles within `error_before`
///     of those quads as they were (a reference point whose closest point
///     was on a quad that did not move is no further from the boundary now
///     than `error_before`), to the whole boundary.
/// The answer is an upper bound of the error, and exact whenever the error
/// grew beyond `error_before`: what a check against a bound needs, at the
/// cost of the part that moved. `to_reference_frame` maps the points to the
/// reference's coordinates.
///
/// With `kept_bounds` (kept by the caller from one call to the next, for
/// this boundary and reference), what is certainly below `error_before` by its
/// last bound and how far its witnesses moved since is left out
/// (`Moving_distance_bounds`), since it cannot realise more:
///   - boundary -> reference: a moved quad;
///   - reference -> boundary: any reference triangle. Those bounds cover
///     the whole reference, so every triangle they do not clear is measured
///     and the search for the triangles near the moved quads is not needed.
template <class Map>
double surface_error_after_change(const Hex_mesh_boundary& b, const std::vector<Vec3>& before,
                                  const std::vector<Vec3>& after, const Reference_distance_index& reference,
                                  double error_before, const Map& to_reference_frame,
                                  double relative_error_bound = 1e-4, Surface_error_bounds* kept_bounds = nullptr)
{
  using surface_distance_detail::Soup_point;
  using surface_distance_detail::Soup_triangle;
  const std::vector<std::size_t> moved_quads = surface_distance_detail::moved_quads(b, before, after);
  if(moved_quads.empty()) return error_before;
  std::vector<Vec3> now(after.size());
  for(std::size_t v : b.vertices) now[v] = to_reference_frame(after[v]);
  auto corner = [&](std::size_t q, int k) -> const Vec3& { return now[b.quads[q][k]]; };
  Triangle_surface whole;
  // the bounds through the boundary's triangles need faces 2q and 2q + 1
  // to be quad q's (the usual case: a manifold boundary)
  const bool faces_by_quad = boundary_to_surface_mesh(b, now, whole, Quad_split::diagonal_02) &&
                             whole.number_of_faces() == 2 * b.quads.size();
  const std::vector<Soup_triangle>& reference_triangles = reference.triangles();
  // (a local object rather than a null pointer when none are kept: GCC's
  // -Warray-bounds saw the pointer dereferenced on paths that never run)
  Surface_error_bounds unused;
  Surface_error_bounds& bounds = kept_bounds ? *kept_bounds : unused;
  const bool use_quad_bounds = kept_bounds != nullptr;
  const bool use_reference_bounds = use_quad_bounds && faces_by_quad;
  if(use_quad_bounds)
  {
    bounds.boundary_to_reference.resize(b.quads.size());
    bounds.reference_to_boundary.resize(reference_triangles.size());
  }

  // boundary -> reference: the moved quads not cleared by their bounds
  auto point = [](const Vec3& p) { return Soup_point(p[0], p[1], p[2]); };
  std::vector<Soup_triangle> moved;
  std::vector<std::size_t> measured_quads;
  for(std::size_t q : moved_quads)
    if(!use_quad_bounds || !bounds.boundary_to_reference.below(q, corner, error_before))
    {
      moved.push_back(Soup_triangle(point(corner(q, 0)), point(corner(q, 1)), point(corner(q, 2))));
      moved.push_back(Soup_triangle(point(corner(q, 0)), point(corner(q, 2)), point(corner(q, 3))));
      measured_quads.push_back(q);
    }

  // reference -> boundary: the triangles not cleared by their bounds, or
  // without them, those that meet the boxes around the moved quads as they
  // were, grown by `error_before`
  const std::vector<char> near =
    use_reference_bounds
      ? std::vector<char>(reference_triangles.size(), 1)
      : surface_distance_detail::reference_triangles_near(b, before, moved_quads, reference, error_before,
                                                          to_reference_frame);
  std::vector<Soup_triangle> near_reference;
  std::vector<std::size_t> measured_reference;
  for(std::size_t t = 0; t < reference_triangles.size(); ++t)
    if(near[t] && !(use_reference_bounds && bounds.reference_to_boundary.below(t, corner, error_before)))
    {
      near_reference.push_back(reference_triangles[t]);
      measured_reference.push_back(t);
    }

  const double bound = relative_error_bound * reference.diagonal();
  std::vector<Distance_witness> to_boundary, to_reference;
  auto other = std::async(std::launch::async, [&] {
    return one_sided_distance_above(near_reference, whole, error_before, bound, 4,
                                    use_reference_bounds ? &to_boundary : nullptr);
  });
  const double mesh_to_reference =
    one_sided_distance_above(moved, reference.tree(), reference_triangles, reference.neighbours(),
                             reference.surface(), error_before, bound, 4, use_quad_bounds ? &to_reference : nullptr);
  const double reference_to_mesh = other.get();

  // what was measured gives its bounds for the next call
  if(use_quad_bounds) surface_distance_detail::keep_quad_bounds(measured_quads, to_reference, corner, bounds);
  if(use_reference_bounds)
    surface_distance_detail::keep_reference_bounds(measured_reference, to_boundary, corner, bounds);
  return (std::max)(mesh_to_reference, reference_to_mesh);
}

/// Hausdorff distance between the boundary of `mesh` and `reference`,
/// divided by the reference's bounding-box diagonal
inline double relative_surface_error(const Hex_mesh_arrays& mesh, const Triangle_surface& reference)
{
  return surface_distance(mesh, reference).relative();
}

inline double relative_surface_error(const Hex_mesh_arrays& mesh, const Hex_mesh_arrays& reference)
{
  return surface_distance(mesh, reference).relative();
}

/// the shortest edge at each vertex of `mesh` (0 at a vertex no hex uses):
/// the length scale of a boundary layer's first cell at its wall vertices
inline std::vector<double> shortest_edge_at_vertices(const Hex_mesh_arrays& mesh)
{
  std::vector<double> shortest(mesh.points.size(), std::numeric_limits<double>::infinity());
  for(const auto& h : mesh.hexes)
    for(const auto& e : hex_edges)
    {
      const std::size_t a = h[e[0]], b = h[e[1]];
      const double l = norm(mesh.points[a] - mesh.points[b]);
      shortest[a] = (std::min)(shortest[a], l);
      shortest[b] = (std::min)(shortest[b], l);
    }
  for(double& l : shortest) if(l == std::numeric_limits<double>::infinity()) l = 0.;
  return shortest;
}

/// The boundary vertices of `mesh` farther from `reference` than they are
/// allowed: `tolerance` (model units), and with `local` ≥ 0 also `local`
/// times the shortest edge at the vertex in `input` (same vertices as
/// `mesh`), never less than 1e-12 of the reference's diagonal (rounding);
/// the farthest first relative to what they are allowed, then by index.
inline std::vector<Off_surface_vertex> off_surface_vertices(const Hex_mesh_arrays& mesh, const Hex_mesh_arrays& input,
                                                            const Triangle_surface& reference, double tolerance,
                                                            double local)
{
  namespace sd = surface_distance_detail;
  std::vector<Off_surface_vertex> off;
  const std::vector<sd::Soup_triangle> triangles = sd::triangles_of(reference);
  if(triangles.empty()) return off;
  sd::Soup_tree tree(triangles.begin(), triangles.end());
  tree.accelerate_distance_queries();
  const std::vector<double> h = shortest_edge_at_vertices(input);
  const double rounding = 1e-12 * diagonal(bbox_of(reference)); // "on the reference" to rounding
  const Hex_mesh_boundary b = extract_boundary(mesh);
  for(std::size_t v : b.vertices)
  {
    const Vec3& p = mesh.points[v];
    const double d = std::sqrt(tree.squared_distance(sd::Soup_point(p[0], p[1], p[2])));
    const double allowed = (std::max)(local >= 0. ? (std::min)(tolerance, local * h[v]) : tolerance, rounding);
    if(d > allowed) off.push_back(Off_surface_vertex{v, d, allowed, h[v]});
  }
  auto ratio = [](const Off_surface_vertex& x) {
    return x.allowed > 0. ? x.distance / x.allowed : std::numeric_limits<double>::infinity();
  };
  std::sort(off.begin(), off.end(), [&](const Off_surface_vertex& x, const Off_surface_vertex& y) {
    if(ratio(x) != ratio(y)) return ratio(x) > ratio(y);
    return x.distance != y.distance ? x.distance > y.distance : x.vertex < y.vertex;
  });
  return off;
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_SURFACE_DISTANCE_H
