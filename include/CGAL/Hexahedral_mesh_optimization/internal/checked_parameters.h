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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_CHECKED_PARAMETERS_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_CHECKED_PARAMETERS_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The numeric named parameters read by more than one public function, each
// with its default and its range in one place: a value out of range, NaN
// included, is an `std::invalid_argument` naming the parameter, raised
// before anything moves.

#include <CGAL/Hexahedral_mesh_optimization/parameters.h>

#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>

#include <CGAL/Kernel_traits.h>
#include <CGAL/Named_function_parameters.h>

#include <boost/property_map/property_map.hpp>

#include <limits>
#include <sstream>
#include <stdexcept>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

/// `value` of the named parameter `name` when it lies in [min, max] (in
/// (min, max] with `min_excluded`); `std::invalid_argument` saying so
/// otherwise, NaN included
inline double checked_parameter(const char* name, double value, double min, double max, bool min_excluded = false)
{
  if(value >= min && value <= max && !(min_excluded && value == min)) return value;
  std::ostringstream message;
  message << name << " must be in " << (min_excluded ? "(" : "[") << min << ", " << max << "], got " << value;
  throw std::invalid_argument(message.str());
}

/// the time limit, CGAL's `maximum_running_time` named parameter (the tag
/// CGAL 5.6's Mesh_3 reads for its `time_limit` too; see parameters.h):
/// seconds, or infinity (no limit)
template <class NamedParameters>
double time_limit_parameter(const NamedParameters& np)
{
  return checked_parameter("maximum_running_time",
                           parameters::choose_parameter(parameters::get_parameter(np, CGAL::internal_np::maximum_running_time),
                                                        std::numeric_limits<double>::infinity()),
                           0., std::numeric_limits<double>::infinity());
}

/// the `surface_tolerance` named parameter, in [0, 1] (default 0.005)
template <class NamedParameters>
double surface_tolerance_parameter(const NamedParameters& np)
{
  return checked_parameter(
    "surface_tolerance",
    parameters::choose_parameter(parameters::get_parameter(np, hex_mesh_internal_np::surface_tolerance), 0.005), 0., 1.);
}

/// the `local_surface_tolerance` named parameter, at least 0; negative
/// (the default) when not given or given negative (none)
template <class NamedParameters>
double local_surface_tolerance_parameter(const NamedParameters& np)
{
  const double t =
    parameters::choose_parameter(parameters::get_parameter(np, hex_mesh_internal_np::local_surface_tolerance), -1.);
  return t < 0. ? -1. : checked_parameter("local_surface_tolerance", t, 0., std::numeric_limits<double>::infinity());
}

/// CGAL's named parameters of a model of `HexMesh`: `vertex_point_map`
/// (default: the mesh's own points), `geom_traits` (default: the kernel of
/// the map's point type) and `vertex_is_constrained_map` (default: none)
template <class HexMesh, class NamedParameters>
struct Hex_mesh_parameters
{
  typedef Hex_mesh_adapter<HexMesh> Adapter;
  typedef typename CGAL::internal_np::Lookup_named_param_def<
    CGAL::internal_np::vertex_point_t, NamedParameters, typename Adapter::Default_vertex_point_map>::type Vertex_point_map;
  typedef typename boost::property_traits<Vertex_point_map>::value_type Point;
  typedef typename CGAL::internal_np::Lookup_named_param_def<
    CGAL::internal_np::geom_traits_t, NamedParameters, typename Kernel_traits<Point>::Kernel>::type Geom_traits;

  static Vertex_point_map vertex_point_map(const HexMesh& mesh, const NamedParameters& np)
  {
    return parameters::choose_parameter(parameters::get_parameter(np, CGAL::internal_np::vertex_point),
                                        Adapter::vertex_point_map(mesh));
  }
  static Geom_traits geom_traits(const NamedParameters& np)
  {
    return parameters::choose_parameter<Geom_traits>(parameters::get_parameter(np, CGAL::internal_np::geom_traits));
  }
  /// the flat arrays of `mesh`, through the point map and the traits of `np`
  static Hex_mesh_arrays extract(const HexMesh& mesh, const NamedParameters& np)
  {
    Hex_mesh_arrays a = extract_hex_mesh(mesh, vertex_point_map(mesh, np), geom_traits(np));
    a.constrained = constrained_mask(mesh, np);
    return a;
  }
  /// vertex i constrained (`vertex_is_constrained_map`): 1; empty when no
  /// vertex is
  static std::vector<unsigned char> constrained_mask(const HexMesh& mesh, const NamedParameters& np)
  {
    return constrained_mask(mesh, parameters::get_parameter(np, CGAL::internal_np::vertex_is_constrained));
  }
  /// writes back the vertices that moved (see `write_back_moved()`)
  static void write_back(const Hex_mesh_arrays& a, const std::vector<Vec3>& before, HexMesh& mesh,
                         const NamedParameters& np)
  {
    write_back_moved(a, before, mesh, vertex_point_map(mesh, np), geom_traits(np));
  }

private:
  static std::vector<unsigned char> constrained_mask(const HexMesh&, CGAL::internal_np::Param_not_found)
  {
    return std::vector<unsigned char>();
  }
  template <class VertexIsConstrainedMap>
  static std::vector<unsigned char> constrained_mask(const HexMesh& mesh, const VertexIsConstrainedMap& vcm)
  {
    const auto vertices = Adapter::vertices(mesh);
    std::vector<unsigned char> mask(vertices.size(), 0);
    bool any = false;
    for(std::size_t i = 0; i < vertices.size(); ++i)
      if(get(vcm, vertices[i])) { mask[i] = 1; any = true; }
    if(!any) mask.clear();
    return mask;
  }
};

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_CHECKED_PARAMETERS_H
