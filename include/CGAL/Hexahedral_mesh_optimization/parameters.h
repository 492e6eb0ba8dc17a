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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_PARAMETERS_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_PARAMETERS_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The package's own named parameters, as CGAL users write them: free
// functions of `CGAL::parameters` that start a chain, e.g.
//
//   CGAL::untangle_hex_mesh(mesh,
//       CGAL::parameters::reference_surface(surface)
//                        .sharp_angle(160.)
//                        .number_of_iterations(40)
//                        .maximum_running_time(60.)
//                        .vertex_is_constrained_map(vcm));
//
// With a stock CGAL 5.5 a chain takes the package's parameters first and
// CGAL's after them: the member functions of `CGAL::Named_function_parameters`
// are generated from CGAL's list of parameters
// (`CGAL/STL_Extension/internal/parameters_interface.h`), which a package
// cannot extend, so `CGAL::parameters::geom_traits(k).sharp_angle(160.)` does
// not compile. The package's free functions return a class derived from
// `CGAL::Named_function_parameters` that adds the package's parameters as
// member functions: package, package, ..., then CGAL, CGAL, ... all work.
// With CGAL's list patched by
// `package_info/Hexahedral_mesh_optimization/parameters_interface.patch`
// (which defines CGAL_PARAMETERS_INTERFACE_HAS_HEX_MESH_OPTIMIZATION), the
// parameters are CGAL's own and every order works.
//
// The hard stop of a run is CGAL's own `maximum_running_time` (seconds; tag
// `CGAL::internal_np::maximum_running_time_t`, already in CGAL 5.5's list),
// not a parameter of the package: CGAL 5.5's Mesh_3 declares
// `CGAL::parameters::time_limit` as a Boost.Parameter keyword
// (CGAL/boost/parameter.h, included by CGAL/make_mesh_3.h and the other
// Mesh_3 functions), which a package function of that name would clash with
// in any translation unit that includes both. CGAL 5.6 moved Mesh_3 to named
// function parameters, and CGAL's list declares its `time_limit` as a second
// name of that same tag (`CGAL_add_extra_named_parameter_with_compatibility(
// maximum_running_time_t, maximum_running_time, time_limit)`): with those
// versions `CGAL::parameters::time_limit` is read as the time limit too.
//
// The parameters that only tune the schedule are not public: their tags stay
// in `hex_mesh_internal_np` and only the tool, the Python binding and the
// benchmark set them, through `internal::add_internal_parameter()`.

#include <CGAL/Named_function_parameters.h>

namespace CGAL {
namespace Hexahedral_mesh_optimization {

/// The optimisation method (named parameter `method`).
enum class Method
{
  /// the package's pipeline: the paper's method with the stages that measure
  /// better (barrier untangling, surface restoration, max-min smoothing and
  /// the ASJ/max-min turns); see the user manual
  package,
  /// the method of Xu & Chen (2018) alone, as published
  paper
};

/// The parameters of one published run of the paper (named parameter
/// `paper_recipe`, read with `Method::paper` only; other named parameters
/// given explicitly take precedence). The defaults are the generic recipe of
/// the authors' scripts; the per-model ones of the paper's Table 1 are in
/// the benchmark and the user manual.
struct Paper_recipe
{
  /// θ in degrees while untangling (the named parameter `sharp_angle`
  /// overrides it), and in the MSJ stages (0: the same)
  double sharp_angle = 165., msj_sharp_angle = 0.;
  /// untangling: α, β, ξ at the start (ξ falls by 0.1 to 0.2, then α, β are halved)
  double alpha = 1000., beta = 1000., xi = 0.6;
  /// untangling on the whole mesh at once (the global variant) instead of local regions
  bool global = false;
  /// untangling: rings of hexes around the inverted ones in each region (the
  /// authors' `LocalMeshOpt` grows them by 2 layers with `useSmallBlock`, by
  /// `blockSize`, 50 unless given, without)
  int untangle_rings = 2;
  /// untangling: a step may move a vertex more than 2 mean edges (their `allowBigStep`)
  bool untangle_big_step = false;
  /// the SLIM pull-back toward the input's vertices runs when α ended below this (0: never)
  double pull_back_below_alpha = 500.;
  int pull_back_iterations = 20;
  /// MSJ stages: the target, reached in steps of 0.1 up to 0.4 and of 0.05
  /// above (`msj_in_steps`) or in one stage; α, β, ξ
  double target_msj = 1.;
  bool msj_in_steps = true;
  double msj_alpha = 1000., msj_beta = 1000., msj_xi = 0.6;
};

} // namespace Hexahedral_mesh_optimization

#ifdef CGAL_PARAMETERS_INTERFACE_HAS_HEX_MESH_OPTIMIZATION
// CGAL's list knows the public parameters: their tags are CGAL's
#define CGAL_HMO_PUBLIC_PARAMETER(NAME) using CGAL::internal_np::NAME##_t; using CGAL::internal_np::NAME;
#else
#define CGAL_HMO_PUBLIC_PARAMETER(NAME) enum NAME##_t { NAME };
#endif

namespace hex_mesh_internal_np {

// public parameters (free functions of `CGAL::parameters`)
CGAL_HMO_PUBLIC_PARAMETER(reference_surface)
CGAL_HMO_PUBLIC_PARAMETER(reference_vertex_point_map)
CGAL_HMO_PUBLIC_PARAMETER(sharp_angle)
CGAL_HMO_PUBLIC_PARAMETER(reference_feature_angle)
CGAL_HMO_PUBLIC_PARAMETER(stop_flag)
CGAL_HMO_PUBLIC_PARAMETER(target_msj)
CGAL_HMO_PUBLIC_PARAMETER(surface_tolerance)
CGAL_HMO_PUBLIC_PARAMETER(local_surface_tolerance)
CGAL_HMO_PUBLIC_PARAMETER(method)
CGAL_HMO_PUBLIC_PARAMETER(paper_recipe)
CGAL_HMO_PUBLIC_PARAMETER(volume_tolerance)
CGAL_HMO_PUBLIC_PARAMETER(outside_tolerance)

// not public API: settings of the schedule, set by the tool, the Python
// binding and the benchmark through `internal::add_internal_parameter()`
/// quality stages: creases start only at edges below this dihedral angle and
/// the edges below `sharp_angle` only continue them (default 180)
enum crease_seed_angle_t { crease_seed_angle };
/// quality stages: the turns' ASJ pass reshapes the neighbourhood of the
/// elements below MSJ + this band (default 0.15)
enum turn_focus_band_t { turn_focus_band };
/// weight of the feature-line and corner constraints of Eq. 6 (default 1000)
enum alpha_t { alpha };
/// weight of the tangent-plane constraint of Eq. 6 (default 1000)
enum beta_t { beta };
/// initial ξ of the minimum target edge length ξ·(mean boundary edge) (default 0.6)
enum xi_t { xi };
/// whether α and β may be halved so that the surface relaxes (default true)
enum relax_surface_t { relax_surface };
/// local-global iterations per region and round (default 20)
enum local_iterations_t { local_iterations };
/// whether the barrier stages run (default true)
enum barrier_fallback_t { barrier_fallback };
/// whether the inversion-free pull-back runs when the surface error exceeds the tolerance (default true)
enum pull_back_t { pull_back };
/// whether the ASJ smoothing runs (default true)
enum asj_smoothing_t { asj_smoothing };
/// whether a valid 1→8 refinement is optimised at a coarse level first
/// (default true, false with `Method::paper`)
enum coarse_level_start_t { coarse_level_start };
/// whether each MSJ stage runs the edge-angle optimiser where the max-min
/// smoothing falls short (default false, true with `Method::paper`)
enum edge_angle_stages_t { edge_angle_stages };
/// the whole `internal::Optimization_schedule`, replacing the method's (the
/// benchmark's ablation runs the pipeline without each stage in turn through it)
enum schedule_t { schedule };

} // namespace hex_mesh_internal_np

#undef CGAL_HMO_PUBLIC_PARAMETER

namespace Hexahedral_mesh_optimization {
namespace internal {

/// `np` followed by the parameter `Tag` = `value`: how the tool, the Python
/// binding and the benchmark set the package's internal parameters
template <class Tag, class V, class T, class NpTag, class Base>
CGAL::Named_function_parameters<V, Tag, CGAL::Named_function_parameters<T, NpTag, Base> >
add_internal_parameter(const CGAL::Named_function_parameters<T, NpTag, Base>& np, Tag, const V& value)
{
  return CGAL::Named_function_parameters<V, Tag, CGAL::Named_function_parameters<T, NpTag, Base> >(value, np);
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization

#ifndef CGAL_PARAMETERS_INTERFACE_HAS_HEX_MESH_OPTIMIZATION

namespace Hexahedral_mesh_optimization {
namespace internal {

#define CGAL_HMO_PARAMETER_LIST(X) \
  X(reference_surface) X(reference_vertex_point_map) X(sharp_angle) X(reference_feature_angle) X(stop_flag) \
  X(target_msj) X(surface_tolerance) X(local_surface_tolerance) X(method) X(paper_recipe) X(volume_tolerance) X(outside_tolerance)

/// What the package's free functions of `CGAL::parameters` return: CGAL's
/// named parameters (every function that takes them takes these), with the
/// package's parameters as member functions too, so that a chain may go on
/// with them; a CGAL parameter's member function returns CGAL's own class,
/// after which only CGAL's parameters chain (see the top of this file).
template <class T, class Tag, class Base = CGAL::internal_np::No_property>
struct Hex_mesh_named_parameters : CGAL::Named_function_parameters<T, Tag, Base>
{
  typedef CGAL::Named_function_parameters<T, Tag, Base> Cgal_parameters;
  Hex_mesh_named_parameters(const T& v) : Cgal_parameters(v) {}
  Hex_mesh_named_parameters(const T& v, const Base& b) : Cgal_parameters(v, b) {}

#define CGAL_HMO_MEMBER(NAME)                                                                    \
  template <class K>                                                                             \
  Hex_mesh_named_parameters<K, CGAL::hex_mesh_internal_np::NAME##_t, Cgal_parameters>            \
  NAME(const K& k) const                                                                         \
  {                                                                                              \
    return Hex_mesh_named_parameters<K, CGAL::hex_mesh_internal_np::NAME##_t, Cgal_parameters>(k, *this); \
  }
  CGAL_HMO_PARAMETER_LIST(CGAL_HMO_MEMBER)
#undef CGAL_HMO_MEMBER
};

} // namespace internal
} // namespace Hexahedral_mesh_optimization

namespace parameters {

#define CGAL_HMO_FREE_FUNCTION(NAME)                                                             \
  template <class K>                                                                             \
  Hexahedral_mesh_optimization::internal::Hex_mesh_named_parameters<K, CGAL::hex_mesh_internal_np::NAME##_t> \
  NAME(const K& k)                                                                               \
  {                                                                                              \
    return Hexahedral_mesh_optimization::internal::Hex_mesh_named_parameters<K, CGAL::hex_mesh_internal_np::NAME##_t>(k); \
  }
CGAL_HMO_PARAMETER_LIST(CGAL_HMO_FREE_FUNCTION)
#undef CGAL_HMO_FREE_FUNCTION

} // namespace parameters

#undef CGAL_HMO_PARAMETER_LIST

#endif // CGAL_PARAMETERS_INTERFACE_HAS_HEX_MESH_OPTIMIZATION

} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_PARAMETERS_H
