// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Package: Hexahedral_mesh_optimization

#ifndef CGAL_HEX_MESH_SURFACE_ERROR_H
#define CGAL_HEX_MESH_SURFACE_ERROR_H

#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Hex_mesh_arrays.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Hex_mesh_boundary.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/reference_fit.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/surface_distance.h>
#include <CGAL/Hexahedral_mesh_optimization/parameters.h>

#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Kernel_traits.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>

#include <fstream>
#include <string>
#include <vector>

namespace CGAL {

/*!
\ingroup PkgHexahedralMeshOptimizationRef

\brief Distances between the boundary of a hexahedral mesh and a reference
surface, as computed by `hex_mesh_surface_distance()`. All values are in model
units.
*/
typedef Hexahedral_mesh_optimization::internal::Surface_distance Hex_mesh_surface_distance;

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
    \cgalParamDescription{distance, relative to the reference's bounding-box diagonal, beyond which a vertex makes the reference `distant`}
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
  const double tolerance = parameters::choose_parameter(
    parameters::get_parameter(np1, CGAL::hex_mesh_internal_np::surface_tolerance), 0.005);
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

\brief reads a reference surface (any format `CGAL::IO::read_polygon_mesh()`
reads: OBJ, OFF, STL, PLY, ...) into `mesh` and triangulates its faces when
needed.

A file that is not a clean 2-manifold (an STL triangle soup, duplicated or
non-manifold vertices, inconsistent orientations) is read again through
`CGAL::Polygon_mesh_processing::IO::read_polygon_mesh()`, which repairs and
orients the polygon soup first.

\tparam PolygonMesh a model of `MutableFaceGraph` with an internal point
        property map, for example `CGAL::Surface_mesh<Point_3>`

\param fname the file name
\param mesh the output mesh, cleared first
\param error if not null, receives a message when reading fails

\returns `false`, with a message, when the file cannot be opened or read,
         holds no face, or has faces that cannot be triangulated
*/
template <class PolygonMesh>
bool read_reference_surface(const std::string& fname, PolygonMesh& mesh, std::string* error = nullptr)
{
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
  // a clean 2-manifold file is read as is; anything else (STL triangle soups,
  // duplicated or non-manifold vertices, inconsistent orientation) goes
  // through the polygon-soup repair and orientation of Polygon_mesh_processing
  bool ok = CGAL::IO::read_polygon_mesh(fname, mesh, parameters::verbose(false));
  if(!ok || faces(mesh).empty())
  {
    CGAL::clear(mesh);
    ok = CGAL::Polygon_mesh_processing::IO::read_polygon_mesh(fname, mesh, parameters::verbose(false));
  }
  if(!ok)
    return fail("cannot read a surface from '" + fname +
                "': unsupported extension (use OBJ, OFF, STL or PLY), malformed file,"
                " or faces that do not form an orientable surface");
  if(faces(mesh).empty())
    return fail("reference surface '" + fname + "' has no face");
  if(!CGAL::is_triangle_mesh(mesh))
  {
    if(!CGAL::Polygon_mesh_processing::triangulate_faces(mesh) || !CGAL::is_triangle_mesh(mesh))
      return fail("the faces of reference surface '" + fname + "' cannot be triangulated");
  }
  return true;
}

} // namespace IO
} // namespace CGAL

#endif // CGAL_HEX_MESH_SURFACE_ERROR_H
