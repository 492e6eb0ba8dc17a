// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Package: Hexahedral_mesh_optimization

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_PARAMETERS_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_PARAMETERS_H

// The package's own named parameters. CGAL 5.5 offers no way for a package
// to add chainable member functions to `CGAL::Named_function_parameters`, so
// each of them is a free function in `CGAL::hex_mesh_parameters` that takes,
// as an optional last argument, the parameters it is chained to:
//
//   CGAL::untangle_hex_mesh(mesh,
//       CGAL::hex_mesh_parameters::sharp_angle(160.,
//       CGAL::hex_mesh_parameters::reference_surface(surface,
//       CGAL::parameters::number_of_iterations(40))));
//
// CGAL's own parameters (geom_traits, number_of_iterations, verbose,
// visitor) are read as usual.

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

namespace hex_mesh_internal_np {

enum reference_surface_t { reference_surface };
enum sharp_angle_t { sharp_angle };
enum reference_feature_angle_t { reference_feature_angle };
enum crease_seed_angle_t { crease_seed_angle };
enum turn_focus_band_t { turn_focus_band };
enum alpha_t { alpha };
enum beta_t { beta };
enum xi_t { xi };
enum relax_surface_t { relax_surface };
enum local_iterations_t { local_iterations };
enum barrier_fallback_t { barrier_fallback };
enum time_limit_t { time_limit };
enum stop_flag_t { stop_flag };
enum target_msj_t { target_msj };
enum surface_tolerance_t { surface_tolerance };
enum pull_back_t { pull_back };
enum asj_smoothing_t { asj_smoothing };
enum coarse_level_start_t { coarse_level_start };
enum edge_angle_stages_t { edge_angle_stages };
enum method_t { method };
enum paper_recipe_t { paper_recipe };
enum volume_tolerance_t { volume_tolerance };
enum outside_tolerance_t { outside_tolerance };
/// not public API: the whole `internal::Optimization_schedule`, replacing
/// the method's (the benchmark's ablation runs the pipeline without each
/// stage in turn through it)
enum schedule_t { schedule };

} // namespace hex_mesh_internal_np

namespace hex_mesh_parameters {

#define CGAL_HMO_ADD_PARAMETER(NAME)                                                       \
  template <class K, class T, class Tag, class Base>                                       \
  CGAL::Named_function_parameters<K, CGAL::hex_mesh_internal_np::NAME##_t,  \
                                  CGAL::Named_function_parameters<T, Tag, Base> >          \
  NAME(const K& k, const CGAL::Named_function_parameters<T, Tag, Base>& base)              \
  {                                                                                        \
    return CGAL::Named_function_parameters<K, CGAL::hex_mesh_internal_np::NAME##_t, \
                                           CGAL::Named_function_parameters<T, Tag, Base> >(k, base); \
  }                                                                                        \
  template <class K>                                                                       \
  CGAL::Named_function_parameters<K, CGAL::hex_mesh_internal_np::NAME##_t,  \
                                  CGAL::parameters::Default_named_parameters>              \
  NAME(const K& k)                                                                         \
  {                                                                                        \
    return NAME(k, CGAL::parameters::default_values());                                    \
  }

/// a triangle mesh (model of `FaceListGraph`, e.g. `Surface_mesh`) the
/// boundary must stay on; default: the input's own boundary
CGAL_HMO_ADD_PARAMETER(reference_surface)
/// θ in degrees: boundary edges with a smaller dihedral angle are features (default 165)
CGAL_HMO_ADD_PARAMETER(sharp_angle)
/// with a reference surface: the dihedral angle below which its edges are
/// creases that the mesh boundary recovers (default 150; 0: no recovery)
CGAL_HMO_ADD_PARAMETER(reference_feature_angle)
/// quality stages: creases start only at edges below this dihedral angle and
/// the edges below `sharp_angle` only continue them (default 180: every edge
/// below `sharp_angle` is a crease)
CGAL_HMO_ADD_PARAMETER(crease_seed_angle)
/// quality stages: the turns' ASJ pass reshapes the neighbourhood of the
/// elements below MSJ + this band (default 0.15; 0.2 reaches a higher MSJ
/// for more time)
CGAL_HMO_ADD_PARAMETER(turn_focus_band)
/// weight of the feature-line and corner constraints of Eq. 6 (default 1000)
CGAL_HMO_ADD_PARAMETER(alpha)
/// weight of the tangent-plane constraint of Eq. 6 (default 1000)
CGAL_HMO_ADD_PARAMETER(beta)
/// initial ξ of the minimum target edge length ξ·(mean boundary edge) (default 0.6)
CGAL_HMO_ADD_PARAMETER(xi)
/// whether α and β may be halved so that the surface relaxes (default true)
CGAL_HMO_ADD_PARAMETER(relax_surface)
/// local-global iterations per region and round (default 20)
CGAL_HMO_ADD_PARAMETER(local_iterations)
/// whether the barrier stages run, with the boundary fixed before the edge-angle stage and on what it left (default true)
CGAL_HMO_ADD_PARAMETER(barrier_fallback)
/// hard stop in seconds of wall-clock time (default: none); decides nothing else
CGAL_HMO_ADD_PARAMETER(time_limit)
/// a `const std::atomic<bool>*` that another thread or a signal handler may
/// set: the run then stops at its next safe point, as for `time_limit`, and
/// the result's `interrupted` is true (default: none)
CGAL_HMO_ADD_PARAMETER(stop_flag)
/// the MSJ the quality stages aim at; 1 (default): as high as they get it
CGAL_HMO_ADD_PARAMETER(target_msj)
/// largest surface error (relative to the reference's bounding-box diagonal)
/// the quality stages may cause by moving boundary vertices (default 0.005)
CGAL_HMO_ADD_PARAMETER(surface_tolerance)
/// whether the inversion-free pull-back runs when the surface error exceeds the tolerance (default true)
CGAL_HMO_ADD_PARAMETER(pull_back)
/// whether the final ASJ smoothing runs (default true)
CGAL_HMO_ADD_PARAMETER(asj_smoothing)
/// whether a valid mesh recognised as a 1→8 refinement is optimised at a
/// coarse level first (default true, false with `Method::paper`)
CGAL_HMO_ADD_PARAMETER(coarse_level_start)
/// whether each MSJ stage runs the paper's edge-angle optimiser where the
/// max-min smoothing falls short (default: false, true with `Method::paper`)
CGAL_HMO_ADD_PARAMETER(edge_angle_stages)
/// `Hexahedral_mesh_optimization::Method::package` (default) or `Method::paper`
CGAL_HMO_ADD_PARAMETER(method)
/// `Hexahedral_mesh_optimization::Paper_recipe`: a published run's parameters (`Method::paper` only)
CGAL_HMO_ADD_PARAMETER(paper_recipe)
/// largest relative difference between the volume of the hex mesh and the
/// volume bounded by the reference that `check_hex_mesh_against_reference()`
/// accepts (default 0.01)
CGAL_HMO_ADD_PARAMETER(volume_tolerance)
/// distance, as a fraction of the reference's bounding-box diagonal, beyond
/// which a vertex outside the reference volume makes
/// `check_hex_mesh_against_reference()` fail (default 0.01)
CGAL_HMO_ADD_PARAMETER(outside_tolerance)

#undef CGAL_HMO_ADD_PARAMETER

} // namespace hex_mesh_parameters
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_PARAMETERS_H
