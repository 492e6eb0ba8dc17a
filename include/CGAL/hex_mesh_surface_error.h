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

#ifndef CGAL_HEX_MESH_SURFACE_ERROR_H
#define CGAL_HEX_MESH_SURFACE_ERROR_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

#include <CGAL/Hexahedral_mesh_optimization/Hex_mesh_surface_distance.h>
#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/checked_parameters.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_boundary.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/reference_fit.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/surface_distance.h>
#include <CGAL/Hexahedral_mesh_optimization/parameters.h>

#include <CGAL/Hexahedral_mesh_optimization/IO/internal/read_OFF_soup.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Kernel_traits.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

namespace CGAL {

namespace Hexahedral_mesh_optimization {
namespace internal {

template <class Point, class NamedParameters>
Hex_mesh_arrays hex_mesh_to_arrays(const Indexed_hex_mesh<Point>& mesh, const NamedParameters& np)
{
  typedef typename CGAL::Kernel_traits<Point>::Kernel Default_GT;
  const auto gt = parameters::choose_parameter<Default_GT>(
    parameters::get_parameter(np, internal_np::geom_traits));
  return make_hex_mesh_arrays(mesh, gt);
}

template <class TriangleMesh, class NamedParameters>
void face_graph_to_triangle_surface(const TriangleMesh& tm, const NamedParameters& np,
                                    Triangle_surface& out)
{
  typedef typename GetGeomTraits<TriangleMesh, NamedParameters>::type GT;
  const GT gt = parameters::choose_parameter<GT>(parameters::get_parameter(np, internal_np::geom_traits));
  const auto vpm = parameters::choose_parameter(parameters::get_parameter(np, internal_np::vertex_point),
                                                get_const_property_map(CGAL::vertex_point, tm));
  std::vector<Vec3> points;
  std::vector<Tri> triangles;
  face_graph_to_triangle_soup(tm, vpm, gt, points, triangles);
  soup_to_surface_mesh(points, triangles, out);
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization

/*!
\ingroup PkgHexahedralMeshOptimizationRef

\brief computes the distances between the boundary of the hexahedral mesh
`mesh` and the triangle mesh `reference`.

The boundary of `mesh` is made of the faces of exactly one hexahedron; each
boundary quadrilateral is cut into two triangles along its diagonal from its
first vertex, so that two meshes with the same connectivity are triangulated
alike. Each one-sided Hausdorff distance is computed with
`CGAL::Polygon_mesh_processing::bounded_error_Hausdorff_distance()` with an
error bound of \f$10^{-4}\f$ times the larger bounding-box diagonal.

\tparam Point_3 the point type of the hexahedral mesh
\tparam TriangleMesh a model of `FaceListGraph`; faces of degree larger than 3
        are cut into fans
\tparam NamedParameters1 a sequence of \ref bgl_namedparameters "Named Parameters"
\tparam NamedParameters2 a sequence of \ref bgl_namedparameters "Named Parameters"

\param mesh the hexahedral mesh
\param reference the reference surface
\param np1 optional named parameters for `mesh`: `geom_traits` (a model of
       `Kernel` whose `Point_3` is `Point_3`; default
       `Kernel_traits<Point_3>::%Kernel`)
\param np2 optional named parameters for `reference`: `vertex_point_map`
       and `geom_traits`, as in `CGAL::Polygon_mesh_processing`

\returns the one-sided and symmetric distances and the normalising diagonals;
         distances are infinite when exactly one of the two surfaces is empty
*/
template <class Point_3, class TriangleMesh,
          class NamedParameters1 = parameters::Default_named_parameters,
          class NamedParameters2 = parameters::Default_named_parameters>
Hex_mesh_surface_distance
hex_mesh_surface_distance(const Indexed_hex_mesh<Point_3>& mesh,
                          const TriangleMesh& reference,
                          const NamedParameters1& np1 = parameters::default_values(),
                          const NamedParameters2& np2 = parameters::default_values())
{
  namespace HMO = Hexahedral_mesh_optimization::internal;
  HMO::Triangle_surface ref;
  HMO::face_graph_to_triangle_surface(reference, np2, ref);
  return HMO::surface_distance(HMO::hex_mesh_to_arrays(mesh, np1), ref);
}

/*!
\ingroup PkgHexahedralMeshOptimizationRef

\brief tells whether the triangle mesh `reference` fits the boundary of the
hexahedral mesh `mesh` as its reference surface: the test that
`untangle_hex_mesh()`, `improve_hex_mesh_quality()` and `optimize_hex_mesh()`
make before they move anything (see `Hexahedral_mesh_optimization::Reference_fit`
for the verdicts and what is measured).

\tparam Point_3 the point type of the hexahedral mesh
\tparam TriangleMesh a model of `FaceListGraph`; faces of degree larger than 3
        are cut into fans

\param mesh the hexahedral mesh
\param reference the reference surface
\param np1 optional named parameters for `mesh`:
\cgalNamedParamsBegin
  \cgalParamNBegin{surface_tolerance}
    \cgalParamDescription{distance, relative to the reference's bounding-box diagonal, beyond which a vertex makes the reference `distant`; in [0, 1] (`std::invalid_argument` otherwise)}
    \cgalParamType{`double`}
    \cgalParamDefault{0.005}
  \cgalParamNEnd
  \cgalParamNBegin{geom_traits}
    \cgalParamDescription{an instance of a geometric traits class}
    \cgalParamType{a model of `Kernel` whose `Point_3` is `Point_3`}
    \cgalParamDefault{`Kernel_traits<Point_3>::%Kernel`}
  \cgalParamNEnd
\cgalNamedParamsEnd
\param np2 optional named parameters for `reference`: `vertex_point_map`
       and `geom_traits`, as in `CGAL::Polygon_mesh_processing`

\returns the verdict, the measures it rests on and, unless the reference
  fits, a message saying what does not match or how far the boundary starts
*/
template <class Point_3, class TriangleMesh,
          class NamedParameters1 = parameters::Default_named_parameters,
          class NamedParameters2 = parameters::Default_named_parameters>
Hexahedral_mesh_optimization::Reference_fit
hex_mesh_reference_fit(const Indexed_hex_mesh<Point_3>& mesh,
                       const TriangleMesh& reference,
                       const NamedParameters1& np1 = parameters::default_values(),
                       const NamedParameters2& np2 = parameters::default_values())
{
  namespace HMO = Hexahedral_mesh_optimization::internal;
  typedef typename GetGeomTraits<TriangleMesh, NamedParameters2>::type GT;
  const GT gt = parameters::choose_parameter<GT>(parameters::get_parameter(np2, internal_np::geom_traits));
  const auto vpm = parameters::choose_parameter(parameters::get_parameter(np2, internal_np::vertex_point),
                                                get_const_property_map(CGAL::vertex_point, reference));
  std::vector<HMO::Vec3> points;
  std::vector<HMO::Tri> triangles;
  HMO::face_graph_to_triangle_soup(reference, vpm, gt, points, triangles);
  const double tolerance = HMO::surface_tolerance_parameter(np1);
  return HMO::measure_reference_fit(HMO::hex_mesh_to_arrays(mesh, np1), points, triangles, tolerance);
}

/*!
\ingroup PkgHexahedralMeshOptimizationRef

\brief computes the distances between the boundaries of two hexahedral meshes,
`reference`'s boundary being the reference surface (both are triangulated as
in the overload above).

\param mesh the hexahedral mesh
\param reference the hexahedral mesh whose boundary is the reference surface
\param np optional named parameters for both meshes: `geom_traits`
*/
template <class Point_3, class Point_3_2,
          class NamedParameters = parameters::Default_named_parameters>
Hex_mesh_surface_distance
hex_mesh_surface_distance(const Indexed_hex_mesh<Point_3>& mesh,
                          const Indexed_hex_mesh<Point_3_2>& reference,
                          const NamedParameters& np = parameters::default_values())
{
  namespace HMO = Hexahedral_mesh_optimization::internal;
  return HMO::surface_distance(HMO::hex_mesh_to_arrays(mesh, np), HMO::hex_mesh_to_arrays(reference, np));
}

/*!
\ingroup PkgHexahedralMeshOptimizationRef

\brief returns the surface error of `mesh` with respect to the triangle mesh
`reference`: the symmetric Hausdorff distance between the boundary of `mesh`
and `reference`, divided by the bounding-box diagonal of `reference`.

The paper's tables use metro, which divides by the diagonal of the union of
both bounding boxes enlarged by 2 % of its diagonal on every side (about 7 %
larger on compact shapes); `hex_mesh_surface_distance()` returns that
diagonal too, for comparisons.

See `hex_mesh_surface_distance()` for the parameters.
*/
template <class Point_3, class TriangleMesh,
          class NamedParameters1 = parameters::Default_named_parameters,
          class NamedParameters2 = parameters::Default_named_parameters>
double hex_mesh_surface_error(const Indexed_hex_mesh<Point_3>& mesh,
                              const TriangleMesh& reference,
                              const NamedParameters1& np1 = parameters::default_values(),
                              const NamedParameters2& np2 = parameters::default_values())
{
  return hex_mesh_surface_distance(mesh, reference, np1, np2).relative();
}

/*!
\ingroup PkgHexahedralMeshOptimizationRef

\brief returns the surface error of `mesh` with respect to the boundary of the
hexahedral mesh `reference` (typically the input of an optimisation): the
symmetric Hausdorff distance between the two boundaries, divided by the
bounding-box diagonal of `reference`'s boundary.

\param mesh the hexahedral mesh
\param reference the hexahedral mesh whose boundary is the reference surface
\param np optional named parameters for both meshes: `geom_traits`
*/
template <class Point_3, class Point_3_2,
          class NamedParameters = parameters::Default_named_parameters>
double hex_mesh_surface_error(const Indexed_hex_mesh<Point_3>& mesh,
                              const Indexed_hex_mesh<Point_3_2>& reference,
                              const NamedParameters& np = parameters::default_values())
{
  return hex_mesh_surface_distance(mesh, reference, np).relative();
}

namespace IO {

/*!
\ingroup PkgHexahedralMeshOptimizationRef

\brief builds a reference surface `mesh` from a polygon soup, with the
checks and repairs of `read_reference_surface()`.

The soup is checked first: every face has at least 3 vertices, every vertex
index is in range and every coordinate is finite (otherwise the error names
the face or vertex). Faces are then cut into triangles: a quadrilateral along
its shorter diagonal, a larger face into a fan from its first vertex. A soup
that is not a clean 2-manifold (an STL triangle soup, duplicated or
non-manifold vertices, a vertex repeated in a face, inconsistent
orientations) is repaired and oriented
(`Polygon_mesh_processing::repair_polygon_soup()` and
`orient_polygon_soup()`) before the mesh is built.

\tparam PolygonMesh a model of `MutableFaceGraph` with an internal point
        property map, for example `CGAL::Surface_mesh<Point_3>`
\tparam Point the point type of `mesh`

\param points the vertices of the soup (modified by the repairs)
\param polygons the faces, indices into `points` numbered from 0 (modified:
       triangulated and repaired)
\param mesh the output mesh, cleared first
\param source what the soup is called in messages, e.g. "reference surface 'ref.obj'"
\param error if not null, receives a message when the soup fails the checks

\returns `false`, with a message, when the soup fails the checks or holds no face
*/
template <class PolygonMesh, class Point>
bool polygon_soup_to_reference_surface(std::vector<Point>& points, std::vector<std::vector<std::size_t> >& polygons,
                                       PolygonMesh& mesh, const std::string& source, std::string* error = nullptr)
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  auto fail = [&](const std::string& msg) {
    if(error != nullptr)
      *error = msg;
    CGAL::clear(mesh);
    return false;
  };
  CGAL::clear(mesh);
  if(polygons.empty())
    return fail(source + " has no face");
  for(std::size_t v = 0; v < points.size(); ++v)
    if(!std::isfinite(CGAL::to_double(points[v].x())) || !std::isfinite(CGAL::to_double(points[v].y())) ||
       !std::isfinite(CGAL::to_double(points[v].z())))
      return fail(source + ": vertex " + std::to_string(v) + " has a coordinate that is not a finite number");
  for(std::size_t f = 0; f < polygons.size(); ++f)
  {
    if(polygons[f].size() < 3)
      return fail(source + ": face " + std::to_string(f) + " has " + std::to_string(polygons[f].size()) +
                  " vertices (at least 3 needed)");
    for(std::size_t v : polygons[f])
      if(v >= points.size())
        return fail(source + ": face " + std::to_string(f) + " uses vertex " + std::to_string(v) +
                    ", out of range (the surface has " + std::to_string(points.size()) +
                    " vertices, numbered from 0 here)");
  }
  // triangles: a quad is cut along its shorter diagonal, a larger face into
  // a fan from its first vertex (CGAL's triangulate_faces, a constrained
  // triangulation, bound a reference to null on a degenerate face: found
  // by fuzzing, test/Hexahedral_mesh_optimization/fuzz/regressions)
  {
    std::vector<std::vector<std::size_t> > triangles;
    triangles.reserve(polygons.size());
    for(const std::vector<std::size_t>& f : polygons)
    {
      if(f.size() == 4 && CGAL::squared_distance(points[f[1]], points[f[3]]) <
                            CGAL::squared_distance(points[f[0]], points[f[2]]))
      {
        triangles.push_back({f[0], f[1], f[3]});
        triangles.push_back({f[1], f[2], f[3]});
        continue;
      }
      for(std::size_t i = 1; i + 1 < f.size(); ++i) triangles.push_back({f[0], f[i], f[i + 1]});
    }
    polygons.swap(triangles);
  }
  // a clean 2-manifold is built as is; anything else (STL triangle soups,
  // duplicated or non-manifold vertices, repeated vertices in a face,
  // inconsistent orientation) is repaired and oriented first
  if(!PMP::is_polygon_soup_a_polygon_mesh(polygons))
  {
    PMP::repair_polygon_soup(points, polygons, parameters::verbose(false));
    PMP::orient_polygon_soup(points, polygons);
    if(polygons.empty())
      return fail(source + " has no face left once degenerate faces are removed");
    if(!PMP::is_polygon_soup_a_polygon_mesh(polygons))
      return fail("the faces of " + source + " do not form an orientable surface");
  }
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  if(faces(mesh).empty())
    return fail(source + " has no face");
  return true;
}

/*!
\ingroup PkgHexahedralMeshOptimizationRef

\brief reads a reference surface (any format `CGAL::IO::read_polygon_soup()`
reads: OBJ, OFF, STL, PLY, ...) into `mesh` and triangulates its faces when
needed.

The file is read as a polygon soup, then checked, triangulated and, when it
is not a clean 2-manifold, repaired and oriented by
`polygon_soup_to_reference_surface()`; the errors name the file and the face
or vertex. ASCII OFF files are read by the package's own reader, which names
the line of a bad token.

\tparam PolygonMesh a model of `MutableFaceGraph` with an internal point
        property map, for example `CGAL::Surface_mesh<Point_3>`

\param fname the file name
\param mesh the output mesh, cleared first
\param error if not null, receives a message when reading fails

\returns `false`, with a message, when the file cannot be opened or read,
         fails the checks above, or holds no face
*/
template <class PolygonMesh>
bool read_reference_surface(const std::string& fname, PolygonMesh& mesh, std::string* error = nullptr)
{
  typedef typename boost::property_map<PolygonMesh, vertex_point_t>::type Vertex_point_map;
  typedef typename boost::property_traits<Vertex_point_map>::value_type Point;
  auto fail = [&](const std::string& msg) {
    if(error != nullptr)
      *error = msg;
    CGAL::clear(mesh);
    return false;
  };
  CGAL::clear(mesh);
  {
    std::ifstream probe(fname);
    if(!probe)
      return fail("cannot open reference surface '" + fname + "'");
  }
  // Read as a polygon soup and check it before building anything: CGAL's
  // mesh builders trust the face indices of the file (a face index out of
  // range in an OBJ file overflowed a buffer in CGAL 5.5's builder; found by
  // fuzzing, test/Hexahedral_mesh_optimization/fuzz/regressions/obj).
  std::vector<Point> points;
  std::vector<std::vector<std::size_t> > polygons;
  const std::string extension = fname.size() >= 4 ? fname.substr(fname.size() - 4) : std::string();
  if(extension == ".off" || extension == ".OFF")
  {
    std::string why;
    if(!Hexahedral_mesh_optimization::internal::io::read_OFF_soup(fname, points, polygons, why)) return fail(why);
  }
  else if(!CGAL::IO::read_polygon_soup(fname, points, polygons, parameters::verbose(false)))
    return fail("cannot read a surface from '" + fname +
                "': unsupported extension (use OBJ, OFF, STL or PLY) or malformed file");
  return polygon_soup_to_reference_surface(points, polygons, mesh, "reference surface '" + fname + "'", error);
}

} // namespace IO
} // namespace CGAL

#endif // CGAL_HEX_MESH_SURFACE_ERROR_H
