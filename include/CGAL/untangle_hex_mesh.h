// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Package: Hexahedral_mesh_optimization

#ifndef CGAL_UNTANGLE_HEX_MESH_H
#define CGAL_UNTANGLE_HEX_MESH_H

#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/Hexahedral_mesh_optimization/Optimization_result.h>
#include <CGAL/Hexahedral_mesh_optimization/parameters.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/checked_parameters.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_boundary.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/Hex_mesh_untangler.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/reference_fit.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/unresolved_elements.h>

#include <CGAL/Kernel_traits.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <atomic>
#include <string>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

struct No_reference_surface {};

/// a FaceListGraph as a triangle soup (polygons fanned), its points read
/// through its own `vertex_point` map
template <class TriangleMesh, class GeomTraits>
void face_graph_to_soup(const TriangleMesh& tm, const GeomTraits& gt, std::vector<Vec3>& points, std::vector<Tri>& tris)
{
  face_graph_to_triangle_soup(tm, get(CGAL::vertex_point, tm), gt, points, tris);
}

template <class GeomTraits>
void face_graph_to_soup(const No_reference_surface&, const GeomTraits&, std::vector<Vec3>&, std::vector<Tri>&)
{}

/// the `stop_flag` named parameter, or null
template <class NamedParameters>
const std::atomic<bool>* stop_flag_parameter(const NamedParameters& np)
{
  return parameters::choose_parameter(parameters::get_parameter(np, hex_mesh_internal_np::stop_flag),
                                      static_cast<const std::atomic<bool>*>(nullptr));
}

/// the `paper_recipe` named parameter, checked; default: the generic recipe
template <class NamedParameters>
Paper_recipe paper_recipe_parameter(const NamedParameters& np)
{
  Paper_recipe r = parameters::choose_parameter(parameters::get_parameter(np, hex_mesh_internal_np::paper_recipe),
                                                Paper_recipe());
  for(double* a : {&r.sharp_angle, &r.msj_sharp_angle}) checked_parameter("paper_recipe angle", *a, 0., 180.);
  for(double* w : {&r.alpha, &r.beta, &r.msj_alpha, &r.msj_beta, &r.pull_back_below_alpha})
    checked_parameter("paper_recipe alpha/beta", *w, 0., 1e12);
  checked_parameter("paper_recipe xi", r.xi, 0., 10.);
  checked_parameter("paper_recipe msj_xi", r.msj_xi, 0., 10.);
  checked_parameter("paper_recipe target_msj", r.target_msj, -1., 1.);
  checked_parameter("paper_recipe pull_back_iterations", r.pull_back_iterations, 0., 1e9);
  return r;
}

/// the untangler's settings and the reference surface (as a soup) from named
/// parameters (the time limit, which starts when it is made, is the caller's)
template <class NamedParameters, class GeomTraits>
void read_untangle_parameters(const NamedParameters& np, const GeomTraits& gt, Untangle_settings& s,
                              std::vector<Vec3>& ref_points, std::vector<Tri>& ref_tris)
{
  using parameters::choose_parameter;
  using parameters::get_parameter;
  const Method method = choose_parameter(get_parameter(np, hex_mesh_internal_np::method), Method::package);
  // the paper's method: the recipe's values where no named parameter is given
  const bool paper = method == Method::paper;
  const Paper_recipe recipe = paper_recipe_parameter(np);
  // (the ranges are those of the tool and of the Python binding)
  s.sharp_angle = checked_parameter(
    "sharp_angle", choose_parameter(get_parameter(np, hex_mesh_internal_np::sharp_angle), paper ? recipe.sharp_angle : 165.),
    0., 180.);
  s.reference_feature_angle = checked_parameter(
    "reference_feature_angle",
    choose_parameter(get_parameter(np, hex_mesh_internal_np::reference_feature_angle), 150.), 0., 180.);
  s.alpha = checked_parameter(
    "alpha", choose_parameter(get_parameter(np, hex_mesh_internal_np::alpha), paper ? recipe.alpha : 1000.), 0., 1e12);
  s.beta = checked_parameter(
    "beta", choose_parameter(get_parameter(np, hex_mesh_internal_np::beta), paper ? recipe.beta : 1000.), 0., 1e12);
  s.xi = checked_parameter("xi", choose_parameter(get_parameter(np, hex_mesh_internal_np::xi), paper ? recipe.xi : 0.6),
                           0., 10.);
  s.global_region = paper && recipe.global;
  s.relax_surface = choose_parameter(get_parameter(np, hex_mesh_internal_np::relax_surface), true);
  s.local_iterations = static_cast<int>(checked_parameter(
    "local_iterations", choose_parameter(get_parameter(np, hex_mesh_internal_np::local_iterations), 20), 1., 1e9));
  s.max_rounds = static_cast<int>(checked_parameter(
    "number_of_iterations", choose_parameter(get_parameter(np, internal_np::number_of_iterations), 60), 0., 1e9));
  s.barrier_fallback = choose_parameter(get_parameter(np, hex_mesh_internal_np::barrier_fallback), true);
  s.schedule = choose_parameter(get_parameter(np, hex_mesh_internal_np::schedule),
                                method == Method::paper ? Optimization_schedule::paper() : Optimization_schedule());
  face_graph_to_soup(
    choose_parameter(get_parameter(np, hex_mesh_internal_np::reference_surface), No_reference_surface()),
    gt, ref_points, ref_tris);
  if(!ref_tris.empty())
  {
    s.reference_points = &ref_points;
    s.reference_triangles = &ref_tris;
  }
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization

/*!
\ingroup PkgHexahedralMeshOptimizationRef

\brief Untangles a hexahedral mesh: moves its vertices, never its
connectivity, until no element has a non-positive Verdict scaled Jacobian,
keeping the boundary on a reference surface.

The method is Sections 3.1 and 3.2 of Xu & Chen, "Hexahedral mesh quality
improvement via edge-angle optimization" (Computers & Graphics, 2018): local
regions around the inverted elements, the unified edge-angle energy with the
boundary and feature constraints of its Eq. 6, solved by a local-global
linearisation with monotone rollback (the number of inverted elements never
rises from one accepted step to the next), and the paper's ξ / α / β schedule
that lets the surface relax when it must. What that stage leaves (also
regions of more than 3000 hexes, and what is still inverted after 8 rounds
without progress) is handed to a second stage, a foldover-free barrier
energy on the 9 Jacobian samples of each hex (`barrier_fallback`), with a
strong boundary weight first and weaker ones only for what stays inverted.
A last stage ("surface") pulls the boundary back toward the target surface
with the same energy used as a true barrier, so that no element inverts on
the way. The result never has more inverted elements than the input: when
nothing better is found the input is returned as it was. The result's
`stages` say what each stage did.

Every stage ends on convergence or on a work cap counted in rounds, passes
or iterations, never on the clock: the same input and parameters give the
same output on any machine, under any load and with any number of threads.

\tparam HexMesh `Indexed_hex_mesh` or `Linear_cell_complex_for_combinatorial_map<3,3>`
  (include `CGAL/Hexahedral_mesh_optimization/Linear_cell_complex_hex_mesh.h` for the latter)

\param mesh the mesh, optimised in place
\param np an optional sequence of named parameters among the ones listed below
  (the package's own parameters live in `CGAL::hex_mesh_parameters`)

\cgalNamedParamsBegin
  \cgalParamNBegin{reference_surface}
    \cgalParamDescription{a triangle (or polygon) mesh the boundary must stay on. It is checked against the mesh boundary before anything moves (`hex_mesh_reference_fit()`): one in another coordinate frame or of another object throws `Hexahedral_mesh_optimization::Reference_mismatch`, the mesh untouched; one the boundary starts far from adds a warning to the result}
    \cgalParamType{a model of `FaceListGraph` with an internal vertex point map, e.g. `Surface_mesh`}
    \cgalParamDefault{the boundary of the input mesh}
  \cgalParamNEnd
  \cgalParamNBegin{surface_tolerance}
    \cgalParamDescription{surface error, relative to the reference's bounding-box diagonal, beyond which a reference the boundary starts from gets a warning; in [0, 1] (`std::invalid_argument` otherwise)}
    \cgalParamType{`double`}
    \cgalParamDefault{0.005}
  \cgalParamNEnd
  \cgalParamNBegin{sharp_angle}
    \cgalParamDescription{θ in degrees: boundary edges whose dihedral angle is below it are features; in [0, 180] (`std::invalid_argument` otherwise)}
    \cgalParamType{`double`}
    \cgalParamDefault{165}
  \cgalParamNEnd
  \cgalParamNBegin{reference_feature_angle}
    \cgalParamDescription{with `reference_surface`: the reference's edges with a dihedral angle below this, in degrees, are its creases; chains of boundary edges are matched to them and to their corners, and follow them (feature recovery), in place of the features found with `sharp_angle`. A reference without clear creases (fewer than half of the edges below this angle are also below it minus 30 degrees, as on a faceted organic surface) keeps the classification by `sharp_angle`. 0 turns recovery off; in [0, 180] (`std::invalid_argument` otherwise)}
    \cgalParamType{`double`}
    \cgalParamDefault{150}
  \cgalParamNEnd
  \cgalParamNBegin{alpha}
    \cgalParamDescription{initial weight of the feature and corner constraints; in [0, 1e12] (`std::invalid_argument` otherwise)}
    \cgalParamType{`double`}
    \cgalParamDefault{1000}
  \cgalParamNEnd
  \cgalParamNBegin{beta}
    \cgalParamDescription{initial weight of the tangent-plane constraint; in [0, 1e12] (`std::invalid_argument` otherwise)}
    \cgalParamType{`double`}
    \cgalParamDefault{1000}
  \cgalParamNEnd
  \cgalParamNBegin{xi}
    \cgalParamDescription{initial ξ: target edge lengths are at least ξ times the mean boundary edge length; in [0, 10] (`std::invalid_argument` otherwise)}
    \cgalParamType{`double`}
    \cgalParamDefault{0.6}
  \cgalParamNEnd
  \cgalParamNBegin{relax_surface}
    \cgalParamDescription{whether α and β may be halved when the untangling stalls (the surface then moves)}
    \cgalParamType{`bool`}
    \cgalParamDefault{`true`}
  \cgalParamNEnd
  \cgalParamNBegin{local_iterations}
    \cgalParamDescription{local-global iterations per region and round; at least 1 (`std::invalid_argument` otherwise)}
    \cgalParamType{`int`}
    \cgalParamDefault{20}
  \cgalParamNEnd
  \cgalParamNBegin{number_of_iterations}
    \cgalParamDescription{maximum number of rounds of the edge-angle stage; at least 0 (`std::invalid_argument` otherwise)}
    \cgalParamType{`int`}
    \cgalParamDefault{60}
  \cgalParamNEnd
  \cgalParamNBegin{barrier_fallback}
    \cgalParamDescription{whether the barrier stages run: with the boundary fixed before the edge-angle stage, and on what the edge-angle stage leaves}
    \cgalParamType{`bool`}
    \cgalParamDefault{`true`}
  \cgalParamNEnd
  \cgalParamNBegin{method}
    \cgalParamDescription{`Hexahedral_mesh_optimization::Method::package`: the stages above; `Method::paper`: the edge-angle stage alone, as in the paper (no barrier stages, no hand-over)}
    \cgalParamType{`Hexahedral_mesh_optimization::Method`}
    \cgalParamDefault{`Method::package`}
  \cgalParamNEnd
  \cgalParamNBegin{time_limit}
    \cgalParamDescription{a hard stop, in seconds of wall-clock time from the call: when it is reached every stage stops at its next safe point, the mesh returned is the last state reached (never worse than the input) and the result's `time_limit_reached` is true. It decides nothing else: without it (the default) the stages run to convergence. It is at least 0 (`std::invalid_argument` otherwise).}
    \cgalParamType{`double`}
    \cgalParamDefault{none}
  \cgalParamNEnd
  \cgalParamNBegin{stop_flag}
    \cgalParamDescription{a flag another thread or a signal handler may set to stop the run: it is then a hard stop like `time_limit` (every stage stops at its next safe point, the mesh returned is the last state reached, never worse than the input), and the result's `interrupted` is true}
    \cgalParamType{`const std::atomic<bool>*`}
    \cgalParamDefault{none}
  \cgalParamNEnd
  \cgalParamNBegin{visitor}
    \cgalParamDescription{an object notified of stages and rounds}
    \cgalParamType{a class with the functions of `Hexahedral_mesh_optimization::Default_optimization_visitor`}
    \cgalParamDefault{`Hexahedral_mesh_optimization::Default_optimization_visitor`}
  \cgalParamNEnd
  \cgalParamNBegin{geom_traits}
    \cgalParamDescription{an instance of a geometric traits class}
    \cgalParamType{a model of `HexMeshOptimizationTraits`}
    \cgalParamDefault{the kernel of the mesh's point type}
  \cgalParamNEnd
\cgalNamedParamsEnd

\returns what was done: inverted count and MSJ before and after, surface
  error, time and a report per stage; the elements still inverted, if any,
  each with the reason it was not freed (`Optimization_result::unresolved`);
  the warnings (`Optimization_result::warnings`).
*/
template <class HexMesh, class CGAL_NP_TEMPLATE_PARAMETERS>
Hexahedral_mesh_optimization::Optimization_result
untangle_hex_mesh(HexMesh& mesh, const CGAL_NP_CLASS& np = parameters::default_values())
{
  namespace HMO = Hexahedral_mesh_optimization;
  using parameters::choose_parameter;
  using parameters::get_parameter;
  typedef HMO::internal::Hex_mesh_adapter<HexMesh> Adapter;
  typedef typename Kernel_traits<typename Adapter::Point>::Kernel Default_traits;

  HMO::internal::Time_limit time_limit(HMO::internal::time_limit_parameter(np));
  time_limit.watch(HMO::internal::stop_flag_parameter(np));
  const auto gt = choose_parameter(get_parameter(np, internal_np::geom_traits), Default_traits());
  HMO::Default_optimization_visitor default_visitor;
  auto&& visitor = choose_parameter(parameters::get_parameter_reference(np, internal_np::visitor), default_visitor);

  HMO::internal::Untangle_settings s;
  s.time_limit = &time_limit;
  std::vector<HMO::internal::Vec3> ref_points;
  std::vector<HMO::internal::Tri> ref_tris;
  HMO::internal::read_untangle_parameters(np, gt, s, ref_points, ref_tris);

  HMO::internal::Hex_mesh_arrays arrays = Adapter::extract(mesh, gt);
  const std::string warning = HMO::internal::require_reference_fit(
    arrays, s.reference_points, s.reference_triangles,
    HMO::internal::surface_tolerance_parameter(np));
  HMO::internal::Hex_mesh_untangler<typename std::remove_reference<decltype(visitor)>::type> untangler(s, visitor);
  HMO::Optimization_result result = untangler.run(arrays);
  if(!warning.empty()) result.warnings.push_back(warning);
  if(result.inverted_after > 0)
    result.unresolved = HMO::internal::unresolved_elements(arrays, result.time_limit_reached || result.interrupted);
  Adapter::write_back(arrays, mesh, gt);
  return result;
}

} // namespace CGAL

#endif // CGAL_UNTANGLE_HEX_MESH_H
