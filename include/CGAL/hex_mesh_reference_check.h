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

#ifndef CGAL_HEX_MESH_REFERENCE_CHECK_H
#define CGAL_HEX_MESH_REFERENCE_CHECK_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/Hexahedral_mesh_optimization/Reference_volume_report.h>
#include <CGAL/Hexahedral_mesh_optimization/parameters.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/checked_parameters.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Reference_check/Reference_volume_check.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/surface_distance.h>
#include <CGAL/hex_mesh_surface_error.h>

#include <CGAL/Kernel_traits.h>
#include <CGAL/Linear_cell_complex_fwd.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <type_traits>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

/// whether `T` is one of the hexahedral mesh types of the package (its
/// boundary is then the reference surface)
template <class HexMesh, class NamedParameters>
Hex_mesh_arrays hex_mesh_arrays_of(const HexMesh& mesh, const NamedParameters& np)
{
  return Hex_mesh_parameters<HexMesh, NamedParameters>::extract(mesh, np);
}

// the reference surface: the boundary of a hex mesh ...
template <class HexMesh, class NamedParameters>
void reference_triangle_surface(const HexMesh& reference, const NamedParameters& np,
                                Triangle_surface& out, std::true_type /* is a hex mesh */)
{
  boundary_surface(hex_mesh_arrays_of(reference, np), out);
}

// ... or a face graph
template <class TriangleMesh, class NamedParameters>
void reference_triangle_surface(const TriangleMesh& reference, const NamedParameters& np,
                                Triangle_surface& out, std::false_type /* is a hex mesh */)
{
  face_graph_to_triangle_surface(reference, np, out);
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization

/*!
\ingroup PkgHexahedralMeshOptimizationRef

\brief checks a hexahedral mesh against the volume bounded by a reference
surface, which TetGen tetrahedralises.

The function reports (see `Hexahedral_mesh_optimization::Reference_volume_report`):
- the volume bounded by the reference: the sum of the volumes of the
  tetrahedra of TetGen's tetrahedralisation of the reference as a piecewise
  linear complex (switches `-pzQ`), next to the volume given by the
  divergence theorem on its triangles;
- the volume of the hexahedral mesh: the sum of the exact signed volumes of
  its trilinear hexahedra (the integral of the Jacobian determinant, computed
  by a 2×2×2 Gauss rule, which is exact for it; it equals the decomposition
  into 24 tetrahedra through the face and cell centroids), and the relative
  difference between the two volumes;
- whether the boundary of the hexahedral mesh self-intersects: its
  quadrilaterals are cut into two triangles along their diagonal from their
  first vertex, and `CGAL::Polygon_mesh_processing::self_intersections()` is
  run on them; the two triangles of a quadrilateral, or any two triangles
  sharing an edge or a vertex, count only if they also meet elsewhere;
  degenerate triangles are counted apart;
- the vertices of the hexahedral mesh outside the volume, found with
  `CGAL::Side_of_triangle_mesh` on the reference, and their distance to it
  (an AABB tree query); only those farther than `outside_tolerance` times
  the reference's bounding-box diagonal count against the mesh, since
  boundary vertices lying on the surface fall on either side by rounding.

A reference that bounds no volume (no triangle, a border edge, intersecting
or degenerate triangles) or on which TetGen fails is reported in the
`error` field of the result, with a message; the function does not throw on
it. The package must have been configured with TetGen
(`CGAL_HMO_HAVE_TETGEN`, defined by its CMake target when TetGen is found);
otherwise every call reports that TetGen is unavailable.

\tparam HexMesh a model of `HexMesh`
\tparam Reference a model of `FaceListGraph` (faces of degree larger than 3
  are cut into fans), or one of the two hexahedral mesh types above, whose
  boundary (cut along the diagonals from the first vertex of each quadrilateral)
  is then the reference surface, for example the input of an optimisation

\param mesh the hexahedral mesh to check
\param reference the reference surface, for example read by `IO::read_reference_surface()`
\param np1 an optional sequence of named parameters for `mesh`, among the ones listed below
\param np2 an optional sequence of named parameters for `reference`: `vertex_point_map` and
  `geom_traits` as in `CGAL::Polygon_mesh_processing` for a face graph, `geom_traits` for a
  hexahedral mesh

\cgalNamedParamsBegin
  \cgalParamNBegin{volume_tolerance}
    \cgalParamDescription{largest accepted relative volume difference}
    \cgalParamType{`double`}
    \cgalParamDefault{0.01}
  \cgalParamNEnd
  \cgalParamNBegin{outside_tolerance}
    \cgalParamDescription{distance to the reference, as a fraction of its bounding-box diagonal,
      beyond which a vertex outside the reference volume fails the check}
    \cgalParamType{`double`}
    \cgalParamDefault{0.01}
  \cgalParamNEnd
  \cgalParamNBegin{geom_traits}
    \cgalParamDescription{an instance of a geometric traits class}
    \cgalParamType{a model of `HexMeshOptimizationTraits`}
    \cgalParamDefault{the kernel of the mesh's point type}
  \cgalParamNEnd
\cgalNamedParamsEnd

\returns the report; its `passed()` is true when the reference is valid, the
  volumes agree within `volume_tolerance`, no vertex is outside beyond
  `outside_tolerance` and the boundary neither self-intersects nor has
  degenerate triangles

\cgalHeading{Example}
\code
CGAL::Surface_mesh<K::Point_3> surface;
CGAL::IO::read_reference_surface("bunny_reference.obj", surface);
const auto report = CGAL::check_hex_mesh_against_reference(mesh, surface,
    CGAL::parameters::volume_tolerance(0.02));
std::cout << report << std::endl; // report.passed(), report.relative_volume_difference, ...
\endcode
*/
template <class HexMesh, class Reference,
          class NamedParameters1 = parameters::Default_named_parameters,
          class NamedParameters2 = parameters::Default_named_parameters>
Hexahedral_mesh_optimization::Reference_volume_report
check_hex_mesh_against_reference(const HexMesh& mesh,
                                 const Reference& reference,
                                 const NamedParameters1& np1 = parameters::default_values(),
                                 const NamedParameters2& np2 = parameters::default_values())
{
  namespace HMO = Hexahedral_mesh_optimization::internal;
  using parameters::choose_parameter;
  using parameters::get_parameter;
  const double volume_tolerance =
    choose_parameter(get_parameter(np1, hex_mesh_internal_np::volume_tolerance), 0.01);
  const double outside_tolerance =
    choose_parameter(get_parameter(np1, hex_mesh_internal_np::outside_tolerance), 0.01);

  HMO::Triangle_surface surface;
  HMO::reference_triangle_surface(reference, np2, surface,
                                  std::integral_constant<bool, HMO::Is_hex_mesh<Reference>::value>());
  return HMO::check_reference_volume(HMO::hex_mesh_arrays_of(mesh, np1), surface,
                                     volume_tolerance, outside_tolerance);
}

} // namespace CGAL

#endif // CGAL_HEX_MESH_REFERENCE_CHECK_H
