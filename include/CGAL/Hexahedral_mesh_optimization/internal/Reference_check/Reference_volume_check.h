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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_REFERENCE_CHECK_REFERENCE_VOLUME_CHECK_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_REFERENCE_CHECK_REFERENCE_VOLUME_CHECK_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// How a hex mesh fills the volume bounded by a reference surface
// (`CGAL::check_hex_mesh_against_reference()`).
//
// Choices:
// - Reference volume: TetGen tetrahedralises the reference as a piecewise
//   linear complex (switches "pzQ": PLC, zero-based indices, quiet; no
//   quality refinement, which would only cost time), and the volume is the
//   sum of its tetrahedra. TetGen also validates the reference: it stops on
//   intersecting facets, tiny features or nearly coincident facets. Built
//   with TETLIBRARY it then throws an int; but TetGen 1.5.0 (Debian's
//   libtet1.5) frees its mesh before throwing, and its tetrahedralize()
//   keeps that mesh on its stack, whose destructor frees it again during
//   the unwinding: the process crashes before any catch. So TetGen runs
//   here in process through a driver of its own (tetrahedralize_plc()):
//   the same steps as tetrahedralize() for "pzQ" (without the mesh
//   optimisation, which moves no boundary and so does not change the
//   volume), on a mesh whose destructor is not run after TetGen threw, as
//   TetGen has freed it then (all its throws from inside the mesh pass the
//   mesh to terminatetetgen(); only a failed malloc of its memory pools
//   does not, and then the mesh is leaked rather than freed twice). The
//   int becomes the error message of the result. On that failure path
//   TetGen also leaks the temporary arrays of the step that failed
//   (bounded by the size of the reference) and may print a line on the
//   standard output. TetGen keeps global state (the tolerances of its
//   predicates, set by exactinit() from the bounding box), so calls are
//   serialised by a mutex: the check can be called from several threads.
//   No process is created: a program that wants TetGen isolated runs the
//   check in a process of its own. Before TetGen, the reference must be
//   non-empty, closed
//   (no border edge: TetGen would tetrahedralise a leaking surface without
//   complaint and remove everything or nothing) and free of
//   self-intersections (PMP::self_intersections: a clearer message than
//   TetGen's code 3, and a precondition of the point location). The
//   divergence-theorem volume of the triangles is reported next to TetGen's
//   as a cross-check (they differ only by the rounding of TetGen's Steiner
//   points on the facets).
// - Hex volume: the exact signed volume of the trilinear hexahedron,
//   ∫ det J over the unit cube, by 2×2×2 Gauss quadrature. det J has degree
//   at most 2 in each parametric variable (each column of J is independent
//   of its own variable and bilinear in the two others), so the rule is
//   exact. This is the volume bounded by the bilinear faces, and equals the
//   24-tetrahedron decomposition with face and cell centroids; the 5- or
//   6-tetrahedron splits differ on non-planar faces. Inverted parts count
//   negatively, as they do in a finite-element integral. The triangulated
//   boundary used for the self-intersection test bounds a slightly different
//   volume when boundary quads are not planar.
// - Point location: CGAL::Side_of_triangle_mesh on the reference (ray
//   parity with exact predicates, a new random ray when a ray hits an edge),
//   sharing its AABB tree with the distance queries, rather than locating
//   the points in TetGen's tetrahedra: the two differ only for vertices
//   lying on the surface, which a Steiner point of TetGen, rounded off its
//   facet, can leave marginally outside the tetrahedra, whereas
//   Side_of_triangle_mesh answers for the surface as given. It is also
//   faster than a bucket grid over the tetrahedra, and the AABB tree is
//   needed for the distances anyway. Boundary vertices projected onto the
//   surface lie on it only up to rounding and fall on either side: only the
//   vertices farther than the tolerance count against the mesh.
// - Self-intersections of the hex boundary: the boundary quads cut along
//   (q0, q2), as in the surface error, and
//   PMP::self_intersections. Two triangles sharing an edge or a vertex are
//   reported only if they also meet elsewhere (coplanar overlap), so the two
//   halves of a non-planar quad do not count; a degenerate triangle (three
//   collinear vertices, e.g. a collapsed quad) is reported by CGAL as a pair
//   (f, f) and counted apart. A non-manifold boundary (two hexes touching
//   along an edge only) has its shared vertices duplicated by the surface
//   construction and then counts as self-intersecting, which it is
//   geometrically.

#include <CGAL/Hexahedral_mesh_optimization/Reference_volume_report.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_boundary.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/surface_distance.h>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <boost/function_output_iterator.hpp>

#ifdef CGAL_HMO_HAVE_TETGEN
#ifndef TETLIBRARY
#define TETLIBRARY
#endif
#include <tetgen.h>
#endif

#include <array>
#include <chrono>
#include <cmath>
#include <ctime>
#include <exception>
#include <limits>
#include <mutex>
#include <new>
#include <string>
#include <utility>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

/// Exact signed volume of the trilinear hexahedron with corners `c` (MEDIT
/// order): ∫ det J over the unit cube by 2×2×2 Gauss quadrature.
inline double trilinear_hex_volume(const std::array<Vec3, 8>& c)
{
  // parametric corners (r, s, t) of the MEDIT order
  static const int rst[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const double g[2] = {0.5 - 0.5 / std::sqrt(3.), 0.5 + 0.5 / std::sqrt(3.)};
  double v = 0.;
  for(int a = 0; a < 2; ++a)
    for(int b = 0; b < 2; ++b)
      for(int d = 0; d < 2; ++d)
      {
        const double x[3] = {g[a], g[b], g[d]};
        Vec3 J[3] = {{0., 0., 0.}, {0., 0., 0.}, {0., 0., 0.}};
        for(int i = 0; i < 8; ++i)
        {
          // N_i = Π_k (rst_k ? x_k : 1 - x_k); dN_i/dx_k replaces factor k by ±1
          double f[3], df[3];
          for(int k = 0; k < 3; ++k)
          {
            f[k] = rst[i][k] ? x[k] : 1. - x[k];
            df[k] = rst[i][k] ? 1. : -1.;
          }
          J[0] = J[0] + (df[0] * f[1] * f[2]) * c[i];
          J[1] = J[1] + (f[0] * df[1] * f[2]) * c[i];
          J[2] = J[2] + (f[0] * f[1] * df[2]) * c[i];
        }
        v += dot(J[0], cross(J[1], J[2]));
      }
  return v / 8.;
}

/// Signed volume bounded by a closed triangle soup (divergence theorem;
/// positive for outward-oriented triangles). Points are taken relative to
/// their centroid to limit cancellation.
inline double closed_surface_volume(const std::vector<Vec3>& points, const std::vector<Tri>& triangles)
{
  if(points.empty())
    return 0.;
  Vec3 o{0., 0., 0.};
  for(const Vec3& p : points)
    o = o + p;
  o = (1. / double(points.size())) * o;
  double v = 0.;
  for(const Tri& t : triangles)
    v += dot(points[t[0]] - o, cross(points[t[1]] - o, points[t[2]] - o));
  return v / 6.;
}

inline double tetrahedron_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
{
  return dot(b - a, cross(c - a, d - a)) / 6.;
}

/// What TetGen made of a closed surface.
struct Surface_tetrahedralization
{
  bool ok = false;
  std::string error;
  std::size_t number_of_tetrahedra = 0;
  double volume = 0.; ///< sum of the (absolute) volumes of the tetrahedra
  double seconds = 0.;
  /// the tetrahedra themselves, only when asked for
  std::vector<Vec3> points;
  std::vector<std::array<std::size_t, 4>> tetrahedra;
};

inline bool tetgen_available()
{
#ifdef CGAL_HMO_HAVE_TETGEN
  return true;
#else
  return false;
#endif
}

inline std::string tetgen_error_message(int code)
{
  switch(code)
  {
  case 1: return "TetGen ran out of memory";
  case 2: return "TetGen met an internal error";
  case 3: return "TetGen found a self-intersection of the reference surface";
  case 4: return "TetGen found a very small input feature (nearly touching parts of the reference surface)";
  case 5: return "TetGen found two very close facets of the reference surface";
  case 10: return "TetGen rejected the reference surface as invalid input";
  default: return "TetGen failed with code " + std::to_string(code);
  }
}

namespace tetgen_detail {

#ifdef CGAL_HMO_HAVE_TETGEN
/// TetGen's input: the points, and the triangles as one-polygon facets
inline void fill_tetgen_input(const std::vector<Vec3>& points, const std::vector<Tri>& triangles, tetgenio& in)
{
  in.firstnumber = 0;
  in.numberofpoints = int(points.size());
  in.pointlist = new REAL[3 * points.size()];
  for(std::size_t i = 0; i < points.size(); ++i)
    for(int k = 0; k < 3; ++k)
      in.pointlist[3 * i + k] = points[i][k];
  in.numberoffacets = int(triangles.size());
  in.facetlist = new tetgenio::facet[triangles.size()];
  for(std::size_t f = 0; f < triangles.size(); ++f)
  {
    tetgenio::facet& fa = in.facetlist[f];
    tetgenio::init(&fa);
    fa.numberofpolygons = 1;
    fa.polygonlist = new tetgenio::polygon[1];
    tetgenio::init(&fa.polygonlist[0]);
    fa.polygonlist[0].numberofvertices = 3;
    fa.polygonlist[0].vertexlist = new int[3];
    for(int k = 0; k < 3; ++k)
      fa.polygonlist[0].vertexlist[k] = int(triangles[f][k]);
  }
}

/// the volume of TetGen's tetrahedra and, with `keep_tetrahedra`, the
/// tetrahedra themselves
inline void read_tetgen_output(const tetgenio& out, bool keep_tetrahedra, Surface_tetrahedralization& r)
{
  if(out.numberoftetrahedra <= 0 || out.numberofcorners < 4)
  {
    r.error = "TetGen produced no tetrahedron (the reference surface bounds no volume)";
  }
  else
  {
    const int nc = out.numberofcorners;
    const REAL* P = out.pointlist;
    auto pt = [&](int i) { return Vec3{P[3 * i], P[3 * i + 1], P[3 * i + 2]}; };
    r.number_of_tetrahedra = std::size_t(out.numberoftetrahedra);
    for(int t = 0; t < out.numberoftetrahedra; ++t)
    {
      const int* T = out.tetrahedronlist + nc * t;
      r.volume += std::abs(tetrahedron_volume(pt(T[0]), pt(T[1]), pt(T[2]), pt(T[3])));
    }
    if(keep_tetrahedra)
    {
      r.points.reserve(std::size_t(out.numberofpoints));
      for(int i = 0; i < out.numberofpoints; ++i)
        r.points.push_back(pt(i));
      r.tetrahedra.reserve(r.number_of_tetrahedra);
      for(int t = 0; t < out.numberoftetrahedra; ++t)
      {
        const int* T = out.tetrahedronlist + nc * t;
        r.tetrahedra.push_back({std::size_t(T[0]), std::size_t(T[1]), std::size_t(T[2]), std::size_t(T[3])});
      }
    }
    r.ok = true;
  }
}

/// TetGen's tetrahedralize() for the switches "pzQ" (TetGen 1.5.0's own
/// sequence of steps, without the mesh optimisation), on a mesh that is
/// not destroyed a second time when TetGen throws (see the file comment).
inline void tetrahedralize_plc(tetgenio& in, tetgenio& out)
{
  tetgenbehavior b;
  char switches[] = "pzQ";
  if(!b.parse_commandline(switches))
    throw 10;
  // the mesh's storage, released in any case; the mesh's destructor runs
  // only if TetGen did not throw an int (it has freed the mesh then)
  struct Storage
  {
    void* p = ::operator new(sizeof(tetgenmesh));
    ~Storage() { ::operator delete(p); }
  } storage;
  tetgenmesh* m = new(storage.p) tetgenmesh();
  try
  {
    m->b = &b;
    m->in = &in;
    m->initializepools();
    m->transfernodes();
    exactinit(b.verbose, b.noexact, b.nostaticfilter, m->xmax - m->xmin, m->ymax - m->ymin, m->zmax - m->zmin);
    std::clock_t step_time = 0;
    m->incrementaldelaunay(step_time);
    m->meshsurface();
    m->constraineddelaunay(step_time);
    m->carveholes();
    if(m->dupverts > 0 || m->unuverts > 0)
      m->jettisonnodes();
    out.firstnumber = in.firstnumber;
    out.mesh_dim = 3;
    m->outnodes(&out);
    if(m->tetrahedrons->items > 0)
      m->outelements(&out);
  }
  catch(int)
  {
    throw; // TetGen freed the mesh before throwing: no destructor
  }
  catch(...)
  {
    m->~tetgenmesh(); // bad_alloc of a `new` inside TetGen: the mesh is intact
    throw;
  }
  m->~tetgenmesh();
}

/// the one lock of TetGen's global state (see the file comment)
inline std::mutex& tetgen_mutex()
{
  static std::mutex m;
  return m;
}
#endif

/// TetGen in this process, its failures turned into `error`.
inline Surface_tetrahedralization run_tetgen_in_process(const std::vector<Vec3>& points,
                                                        const std::vector<Tri>& triangles,
                                                        bool keep_tetrahedra)
{
  Surface_tetrahedralization r;
#ifndef CGAL_HMO_HAVE_TETGEN
  CGAL_USE(points);
  CGAL_USE(triangles);
  CGAL_USE(keep_tetrahedra);
  r.error = "TetGen is not available (the package was configured without it)";
#else
  try
  {
    tetgenio in, out;
    fill_tetgen_input(points, triangles, in);
    {
      std::lock_guard<std::mutex> lock(tetgen_mutex());
      tetrahedralize_plc(in, out);
    }
    read_tetgen_output(out, keep_tetrahedra, r);
  }
  catch(int code)
  {
    r.error = tetgen_error_message(code);
  }
  catch(const std::bad_alloc&)
  {
    r.error = tetgen_error_message(1);
  }
  catch(const std::exception& e)
  {
    r.error = std::string("TetGen failed: ") + e.what();
  }
  catch(...)
  {
    r.error = "TetGen failed";
  }
#endif
  return r;
}

} // namespace tetgen_detail

/// Tetrahedralises the volume bounded by a closed triangle soup with TetGen
/// ("pzQ"), in this process. Never throws, never crashes on the failures
/// TetGen reports: a failure is reported in `error`.
inline Surface_tetrahedralization tetrahedralize_closed_surface(const std::vector<Vec3>& points,
                                                                const std::vector<Tri>& triangles,
                                                                bool keep_tetrahedra = false)
{
  const auto start = std::chrono::steady_clock::now();
  Surface_tetrahedralization r;
  if(triangles.empty())
    r.error = "the reference surface has no triangle";
  else
    r = tetgen_detail::run_tetgen_in_process(points, triangles, keep_tetrahedra);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

/// Counts the pairs of intersecting faces of a triangle surface, and apart
/// the degenerate faces (reported by CGAL as pairs (f, f)).
inline void count_self_intersections(const Triangle_surface& s, std::size_t& pairs, std::size_t& degenerate)
{
  typedef boost::graph_traits<Triangle_surface>::face_descriptor face_descriptor;
  pairs = degenerate = 0;
  if(s.number_of_faces() == 0)
    return;
  CGAL::Polygon_mesh_processing::self_intersections<CGAL::Sequential_tag>(
    faces(s), s,
    boost::make_function_output_iterator([&](const std::pair<face_descriptor, face_descriptor>& p) {
      if(p.first == p.second)
        ++degenerate;
      else
        ++pairs;
    }));
}

inline std::size_t number_of_border_edges(const Triangle_surface& s)
{
  std::size_t n = 0;
  for(auto h : halfedges(s))
    if(is_border(h, s))
      ++n;
  return n;
}

/// The soup of a triangle surface (vertex i = i-th vertex).
inline void surface_to_soup(const Triangle_surface& s, std::vector<Vec3>& points, std::vector<Tri>& triangles)
{
  points.clear();
  triangles.clear();
  std::vector<std::size_t> index(s.number_of_vertices() + s.number_of_removed_vertices(), 0);
  for(auto v : s.vertices())
  {
    index[std::size_t(v)] = points.size();
    const auto& p = s.point(v);
    points.push_back({p.x(), p.y(), p.z()});
  }
  for(auto f : s.faces())
  {
    Tri t;
    int k = 0;
    for(auto v : vertices_around_face(s.halfedge(f), s))
      if(k < 3)
        t[k++] = index[std::size_t(v)];
    triangles.push_back(t);
  }
}

/// the hex mesh alone: volume, hexes of non-positive volume, and its boundary
/// (triangles, self-intersections, degenerate triangles)
inline void measure_hex_mesh(const Hex_mesh_arrays& mesh, Reference_volume_report& r)
{
  r.hexahedra = mesh.number_of_hexes();
  r.vertices = mesh.number_of_vertices();
  for(std::size_t h = 0; h < mesh.number_of_hexes(); ++h)
  {
    const double v = trilinear_hex_volume(mesh.corners(h));
    r.hex_mesh_volume += v;
    if(!(v > 0.))
      ++r.nonpositive_volume_hexahedra;
  }
  Triangle_surface boundary;
  boundary_surface(mesh, boundary);
  r.boundary_triangles = boundary.number_of_faces();
  count_self_intersections(boundary, r.boundary_self_intersections, r.degenerate_boundary_triangles);
}

/// whether the reference bounds a volume (triangles, closed, no
/// self-intersection); otherwise `r.error` says why
inline bool reference_bounds_a_volume(const Triangle_surface& reference, Reference_volume_report& r)
{
  r.reference_triangles = reference.number_of_faces();
  r.reference_diagonal = diagonal(bbox_of(reference));
  if(r.reference_triangles == 0)
  {
    r.error = "the reference surface has no triangle";
    return false;
  }
  if(!CGAL::is_triangle_mesh(reference))
  {
    r.error = "the reference surface is not a triangle mesh";
    return false;
  }
  r.reference_border_edges = number_of_border_edges(reference);
  if(r.reference_border_edges > 0)
  {
    r.error = "the reference surface is not closed (" + std::to_string(r.reference_border_edges) +
              " border edges): it bounds no volume";
    return false;
  }
  std::size_t degenerate = 0;
  count_self_intersections(reference, r.reference_self_intersections, degenerate);
  r.reference_self_intersections += degenerate;
  if(r.reference_self_intersections > 0)
  {
    r.error = "the reference surface self-intersects (" + std::to_string(r.reference_self_intersections) +
              " pairs of intersecting or degenerate triangles)";
    return false;
  }
  return true;
}

/// the mesh vertices outside the reference volume, how many beyond
/// `outside_tolerance` × its diagonal, and the farthest
inline void count_vertices_outside(const Hex_mesh_arrays& mesh, const Triangle_surface& reference,
                                   double outside_tolerance, Reference_volume_report& r)
{
  typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
  typedef CGAL::Side_of_triangle_mesh<Triangle_surface, K> Side;
  typename Side::AABB_tree tree(faces(reference).first, faces(reference).second, reference);
  tree.accelerate_distance_queries();
  const Side side(tree);
  const double tolerance = outside_tolerance * r.reference_diagonal;
  for(std::size_t v = 0; v < mesh.number_of_vertices(); ++v)
  {
    const K::Point_3 p(mesh.points[v][0], mesh.points[v][1], mesh.points[v][2]);
    if(side(p) != CGAL::ON_UNBOUNDED_SIDE)
      continue;
    ++r.vertices_outside;
    const double d = std::sqrt(CGAL::to_double(tree.squared_distance(p)));
    if(d > tolerance)
      ++r.vertices_outside_beyond_tolerance;
    if(r.farthest_outside_vertex == Reference_volume_report::npos || d > r.max_outside_distance)
    {
      r.max_outside_distance = d;
      r.farthest_outside_vertex = v;
    }
  }
  r.outside_checked = true;
}

/// The check itself, on flat arrays and a triangle surface.
inline Reference_volume_report check_reference_volume(const Hex_mesh_arrays& mesh,
                                                      const Triangle_surface& reference,
                                                      double volume_tolerance,
                                                      double outside_tolerance)
{
  const auto start = std::chrono::steady_clock::now();
  Reference_volume_report r;
  r.volume_tolerance = volume_tolerance;
  r.outside_tolerance = outside_tolerance;
  auto finish = [&]() {
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return r;
  };
  measure_hex_mesh(mesh, r);
  if(!reference_bounds_a_volume(reference, r))
    return finish();

  // the reference volume by TetGen
  std::vector<Vec3> soup_points;
  std::vector<Tri> soup_triangles;
  surface_to_soup(reference, soup_points, soup_triangles);
  r.reference_surface_volume = std::abs(closed_surface_volume(soup_points, soup_triangles));
  const Surface_tetrahedralization tets = tetrahedralize_closed_surface(soup_points, soup_triangles);
  r.tetgen_seconds = tets.seconds;
  if(!tets.ok)
  {
    r.error = tets.error;
    return finish();
  }
  r.reference_tetrahedra = tets.number_of_tetrahedra;
  r.reference_volume = tets.volume;
  if(r.reference_volume > 0.)
    r.relative_volume_difference = std::abs(r.hex_mesh_volume - r.reference_volume) / r.reference_volume;

  count_vertices_outside(mesh, reference, outside_tolerance, r);
  return finish();
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_REFERENCE_CHECK_REFERENCE_VOLUME_CHECK_H
