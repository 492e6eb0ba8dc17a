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

#ifndef CGAL_HEX_MESH_QUALITY_H
#define CGAL_HEX_MESH_QUALITY_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

#include <CGAL/Hexahedral_mesh_optimization/Hex_mesh_quality.h>
#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/Hexahedral_mesh_optimization/Optimization_result.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/checked_parameters.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/exact_validity.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/quality_statistics.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/scaled_jacobian.h>

#include <CGAL/Kernel_traits.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <array>
#include <vector>

namespace CGAL {

namespace Hexahedral_mesh_optimization {
namespace internal {

/// the 8 corners of a hexahedron as doubles, read through the traits of `np`
template <class PointRange, class NamedParameters>
std::array<Vec3, 8> corner_positions(const PointRange& corners, const NamedParameters& np)
{
  typedef typename std::decay<decltype(corners[0])>::type Point;
  typedef typename Kernel_traits<Point>::Kernel Default_traits;
  const auto gt = parameters::choose_parameter(parameters::get_parameter(np, CGAL::internal_np::geom_traits),
                                               Default_traits());
  std::array<Vec3, 8> p;
  for(int i = 0; i < 8; ++i)
    p[i] = to_vec3(corners[i], gt);
  return p;
}

/// the flat arrays of `mesh`, its points read through the `vertex_point_map`
/// of `np` and converted by its `geom_traits` (defaults: the mesh's points,
/// the kernel of their type)
template <class HexMesh, class NamedParameters>
Hex_mesh_arrays extract_with_traits(const HexMesh& mesh, const NamedParameters& np)
{
  return Hex_mesh_parameters<HexMesh, NamedParameters>::extract(mesh, np);
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization

/*!
\ingroup PkgHexahedralMeshOptimizationQuality

\brief Verdict scaled Jacobian of a hexahedron: the minimum, over the 8
corners and the element centre, of the determinant of the three unit edge
vectors (at the centre: the three unit principal axes).

The value is 1 for a cube and lies in [-1, 1]; it is negative for an inverted
element. A frame with a zero-length vector counts as 0 (Verdict returns
+DBL_MAX there, which would rank a collapsed element as perfect), and so does
a frame whose shortest vector is under 10<sup>-6</sup> of its longest (the
vector is then rounding noise).

\tparam PointRange a random access range of 8 points, MEDIT/VTK order
  (vertices 0-3 form the bottom face, vertex `i+4` lies above vertex `i`)

\param corners the 8 vertices of the hexahedron
\param np an optional sequence of named parameters among the ones listed below

\cgalNamedParamsBegin
  \cgalParamNBegin{geom_traits}
    \cgalParamDescription{an instance of a geometric traits class}
    \cgalParamType{a model of `HexMeshOptimizationTraits`}
    \cgalParamDefault{the kernel of the point type}
  \cgalParamNEnd
\cgalNamedParamsEnd
*/
template <class PointRange, class CGAL_NP_TEMPLATE_PARAMETERS>
double hex_scaled_jacobian(const PointRange& corners,
                           const CGAL_NP_CLASS& np = parameters::default_values())
{
  return Hexahedral_mesh_optimization::internal::scaled_jacobian(
    Hexahedral_mesh_optimization::internal::corner_positions(corners, np));
}

/*!
\ingroup PkgHexahedralMeshOptimizationQuality

\brief The 8-corner variant of `hex_scaled_jacobian()`: the minimum over the
corners only, without the centre sample (it can differ from the 9-point
value on strongly twisted elements).

Same parameters as `hex_scaled_jacobian()`.
*/
template <class PointRange, class CGAL_NP_TEMPLATE_PARAMETERS>
double hex_corner_scaled_jacobian(const PointRange& corners,
                                  const CGAL_NP_CLASS& np = parameters::default_values())
{
  return Hexahedral_mesh_optimization::internal::corner_scaled_jacobian(
    Hexahedral_mesh_optimization::internal::corner_positions(corners, np));
}

/*!
\ingroup PkgHexahedralMeshOptimizationQuality

\brief The Verdict scaled Jacobian of every hexahedron of a mesh, in the
order of its hexahedra (for an LCC: the order of its 3-cells).

\tparam HexMesh a model of `HexMesh`

\param mesh the mesh
\param np an optional sequence of named parameters among the ones listed below

\cgalNamedParamsBegin
  \cgalParamNBegin{geom_traits}
    \cgalParamDescription{an instance of a geometric traits class}
    \cgalParamType{a model of `HexMeshOptimizationTraits`}
    \cgalParamDefault{the kernel of the mesh's point type}
  \cgalParamNEnd
  \cgalParamNBegin{vertex_point_map}
    \cgalParamDescription{a property map associating points to the vertices of `mesh`}
    \cgalParamType{a model of `ReadablePropertyMap` whose key type is the vertex descriptor of `HexMesh` and whose value type is the `Point_3` of `geom_traits`}
    \cgalParamDefault{the points of the mesh}
  \cgalParamNEnd
\cgalNamedParamsEnd
*/
template <class HexMesh, class CGAL_NP_TEMPLATE_PARAMETERS>
std::vector<double> hex_mesh_scaled_jacobians(const HexMesh& mesh,
                                              const CGAL_NP_CLASS& np = parameters::default_values())
{
  namespace HMO = Hexahedral_mesh_optimization::internal;
  return HMO::scaled_jacobians(HMO::extract_with_traits(mesh, np));
}

/*!
\ingroup PkgHexahedralMeshOptimizationQuality

\brief Quality summary of a hexahedral mesh: number of hexahedra and
vertices, number of inverted elements (scaled Jacobian < 0), MSJ (minimum
scaled Jacobian), ASJ (mean) and a histogram of the scaled Jacobian.

\tparam HexMesh a model of `HexMesh`

\param mesh the mesh
\param np an optional sequence of named parameters among the ones listed below

\cgalNamedParamsBegin
  \cgalParamNBegin{geom_traits}
    \cgalParamDescription{an instance of a geometric traits class}
    \cgalParamType{a model of `HexMeshOptimizationTraits`}
    \cgalParamDefault{the kernel of the mesh's point type}
  \cgalParamNEnd
  \cgalParamNBegin{vertex_point_map}
    \cgalParamDescription{a property map associating points to the vertices of `mesh`}
    \cgalParamType{a model of `ReadablePropertyMap` whose key type is the vertex descriptor of `HexMesh` and whose value type is the `Point_3` of `geom_traits`}
    \cgalParamDefault{the points of the mesh}
  \cgalParamNEnd
\cgalNamedParamsEnd
*/
template <class HexMesh, class CGAL_NP_TEMPLATE_PARAMETERS>
Hex_mesh_quality hex_mesh_quality(const HexMesh& mesh,
                                  const CGAL_NP_CLASS& np = parameters::default_values())
{
  namespace HMO = Hexahedral_mesh_optimization::internal;
  return HMO::quality_statistics(HMO::extract_with_traits(mesh, np));
}

/*!
\ingroup PkgHexahedralMeshOptimizationQuality

\brief The exact validity certificate of a hexahedral mesh: which
hexahedra have a positive Jacobian determinant at their 8 corners and at
their centre, decided with exact arithmetic on their coordinates (see
`Hexahedral_mesh_optimization::Validity_certificate`). Where
`hex_mesh_quality()` counts the elements whose rounded scaled Jacobian is
negative, this says for certain that none is inverted or flat.

The coordinates are taken as doubles (`geom_traits`' `Compute_x_3` and
so on, converted with `to_double()`): the certificate is exact for kernels
with double coordinates, such as `Exact_predicates_inexact_constructions_kernel`.

\tparam HexMesh a model of `HexMesh`

\param mesh the mesh
\param np an optional sequence of named parameters among the ones listed below

\cgalNamedParamsBegin
  \cgalParamNBegin{geom_traits}
    \cgalParamDescription{an instance of a geometric traits class}
    \cgalParamType{a model of `HexMeshOptimizationTraits`}
    \cgalParamDefault{the kernel of the mesh's point type}
  \cgalParamNEnd
  \cgalParamNBegin{vertex_point_map}
    \cgalParamDescription{a property map associating points to the vertices of `mesh`}
    \cgalParamType{a model of `ReadablePropertyMap` whose key type is the vertex descriptor of `HexMesh` and whose value type is the `Point_3` of `geom_traits`}
    \cgalParamDefault{the points of the mesh}
  \cgalParamNEnd
\cgalNamedParamsEnd
*/
template <class HexMesh, class CGAL_NP_TEMPLATE_PARAMETERS>
Hexahedral_mesh_optimization::Validity_certificate
hex_mesh_validity_certificate(const HexMesh& mesh, const CGAL_NP_CLASS& np = parameters::default_values())
{
  namespace HMO = Hexahedral_mesh_optimization::internal;
  const HMO::Hex_mesh_arrays arrays = HMO::extract_with_traits(mesh, np);
  Hexahedral_mesh_optimization::Validity_certificate c;
  c.hexes = arrays.hexes.size();
  c.not_certified = HMO::uncertified_hexes(arrays);
  return c;
}

} // namespace CGAL

#endif // CGAL_HEX_MESH_QUALITY_H
