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

#include <CGAL/Named_function_parameters.h>

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

/// the `time_limit` named parameter: seconds, or infinity (no limit)
template <class NamedParameters>
double time_limit_parameter(const NamedParameters& np)
{
  return checked_parameter("time_limit",
                           parameters::choose_parameter(parameters::get_parameter(np, hex_mesh_internal_np::time_limit),
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

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_CHECKED_PARAMETERS_H
