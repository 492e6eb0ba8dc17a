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

#ifndef CGAL_UNTANGLE_HEX_MESH_H
#define CGAL_UNTANGLE_HEX_MESH_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

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

#include <boost/property_map/property_map.hpp>
#include <boost/unordered_map.hpp>

#include <array>
#include <atomic>
#include <string>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

struct No_reference_surface {};

/// the edges of `tm` that `ecm` marks, as pairs of soup indices (`index`)
template <class TriangleMesh, class Index, class EdgeIsConstrainedMap>
void constrained_edges_to_soup(const TriangleMesh& tm, const Index& index, const EdgeIsConstrainedMap& ecm,
                               std::vector<std::array<std::size_t, 2> >& creases)
{
  for(auto e : edges(tm))
    if(get(ecm, e)) creases.push_back({index.at(source(e, tm)), index.at(target(e, tm))});
}

template <class TriangleMesh, class Index>
void constrained_edges_to_soup(const TriangleMesh&, const Index&, CGAL::internal_np::Param_not_found,
                               std::vector<std::array<std::size_t, 2> >&)
{}

/// The reference surface, a FaceListGraph, as a triangle soup (polygons
/// fanned): its points read through the `reference_vertex_point_map` of
/// `np` (default: its own `vertex_point` map) with the kernel of their
/// type, and the edges the `edge_is_constrained_map` of `np` marks, as
/// pairs of soup indices.
template <class TriangleMesh, class NamedParameters>
void reference_to_soup(const TriangleMesh& tm, const NamedParameters& np, std::vector<Vec3>& points,
                       std::vector<Tri>& tris, std::vector<std::array<std::size_t, 2> >& creases)
{
  const auto vpm = parameters::choose_parameter(parameters::get_parameter(np, hex_mesh_internal_np::reference_vertex_point_map),
                                                get_const_property_map(CGAL::vertex_point, tm));
  typedef typename boost::property_traits<typename std::decay<decltype(vpm)>::type>::value_type Point;
  face_graph_to_triangle_soup(tm, vpm, typename Kernel_traits<Point>::Kernel(), points, tris);
  boost::unordered_map<typename boost::graph_traits<TriangleMesh>::vertex_descriptor, std::size_t> index;
  for(auto v : vertices(tm)) index.emplace(v, index.size()); // the soup's order
  constrained_edges_to_soup(tm, index, parameters::get_parameter(np, CGAL::internal_np::edge_is_constrained), creases);
}

template <class NamedParameters>
void reference_to_soup(const No_reference_surface&, const NamedParameters&, std::vector<Vec3>&, std::vector<Tri>&,
                       std::vector<std::array<std::size_t, 2> >&)
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
  checked_parameter("paper_recipe untangle_rings", r.untangle_rings, 1., 1e9);
  return r;
}

/// the untangler's settings and the reference surface (as a soup) from named
/// parameters (the time limit, which starts when it is made, is the caller's)
template <class NamedParameters>
void read_untangle_parameters(const NamedParameters& np, Untangle_settings& s, std::vector<Vec3>& ref_points,
                              std::vector<Tri>& ref_tris, std::vector<std::array<std::size_t, 2> >& ref_creases)
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
  if(paper) s.rings = recipe.untangle_rings;
  if(paper) s.allow_big_step = recipe.untangle_big_step;
  s.relax_surface = choose_parameter(get_parameter(np, hex_mesh_internal_np::relax_surface), true);
  s.local_iterations = static_cast<int>(checked_parameter(
    "local_iterations", choose_parameter(get_parameter(np, hex_mesh_internal_np::local_iterations), 20), 1., 1e9));
  s.max_rounds = static_cast<int>(checked_parameter(
    "number_of_iterations", choose_parameter(get_parameter(np, internal_np::number_of_iterations), 60), 0., 1e9));
  s.barrier_fallback = choose_parameter(get_parameter(np, hex_mesh_internal_np::barrier_fallback), true);
  s.schedule = choose_parameter(get_parameter(np, hex_mesh_internal_np::schedule),
                                method == Method::paper ? Optimization_schedule::paper() : Optimization_schedule());
  reference_to_soup(
    choose_parameter(get_parameter(np, hex_mesh_internal_np::reference_surface), No_reference_surface()),
    np, ref_points, ref_tris, ref_creases);
  if(!ref_tris.empty())
  {
    s.reference_points = &ref_points;
    s.reference_triangles = &ref_tris;
    s.reference_creases = &ref_creases;
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
energy on the 9 Jacobian samples of each hex, with a
strong boundary weight first and weaker ones only for what stays inverted.
A last stage ("surface") pulls the boundary back toward the target surface
with the same energy used as a true barrier, so that no element inverts on
the way. The result never has more inverted elements than the input: when
nothing better is found the input is returned as it was. The result's
`stages` say what each stage did.

Every stage ends on convergence or on a work cap counted in rounds, passes
or iterations, never on the clock: the same input and parameters give the
same output on any machine, under any load and with any number of threads.

\tparam HexMesh a model of `HexMesh`

\param mesh the mesh, optimised in place
\param np an optional sequence of named parameters among the ones listed below
  (the package's parameters start the chain, CGAL's follow: see the user manual)

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
  \cgalParamNBegin{local_surface_tolerance}
    \cgalParamDescription{a fraction of the local edge length: the boundary vertices left farther from the reference than `surface_tolerance` or this fraction of the shortest edge at the vertex in the input are listed in `Optimization_result::off_surface`, with a warning; a negative value: none; NaN throws `std::invalid_argument`}
    \cgalParamType{`double`}
    \cgalParamDefault{none (`surface_tolerance` alone)}
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
  \cgalParamNBegin{number_of_iterations}
    \cgalParamDescription{maximum number of rounds of the edge-angle stage; at least 0 (`std::invalid_argument` otherwise)}
    \cgalParamType{`int`}
    \cgalParamDefault{60}
  \cgalParamNEnd
  \cgalParamNBegin{method}
    \cgalParamDescription{`Hexahedral_mesh_optimization::Method::package`: the stages above; `Method::paper`: the edge-angle stage alone, as in the paper (no barrier stages, no hand-over)}
    \cgalParamType{`Hexahedral_mesh_optimization::Method`}
    \cgalParamDefault{`Method::package`}
  \cgalParamNEnd
  \cgalParamNBegin{maximum_running_time}
    \cgalParamDescription{a hard stop, in seconds of wall-clock time from the call: when it is reached every stage stops at its next safe point, the mesh returned is the last state reached (never worse than the input) and the result's `time_limit_reached` is true. It decides nothing else: without it (the default) the stages run to convergence. It is at least 0 (`std::invalid_argument` otherwise). It is CGAL's own named parameter `CGAL::parameters::maximum_running_time` (the package declares no `time_limit`: CGAL 5.5's Mesh_3 headers declare `CGAL::parameters::time_limit` as a Boost.Parameter keyword; from CGAL 5.6 on, CGAL's `time_limit` is another name of the same parameter).}
    \cgalParamType{`double`}
    \cgalParamDefault{none}
  \cgalParamNEnd
  \cgalParamNBegin{stop_flag}
    \cgalParamDescription{a flag another thread or a signal handler may set to stop the run: it is then a hard stop like `maximum_running_time` (every stage stops at its next safe point, the mesh returned is the last state reached, never worse than the input), and the result's `interrupted` is true}
    \cgalParamType{`const std::atomic<bool>*`}
    \cgalParamDefault{none}
  \cgalParamNEnd
  \cgalParamNBegin{vertex_point_map}
    \cgalParamDescription{a property map associating points to the vertices of `mesh`; only the vertices that moved are written back (`put()`), the others keep their points exactly, whatever the kernel}
    \cgalParamType{a model of `ReadWritePropertyMap` whose key type is the vertex descriptor of `HexMesh` and whose value type is the `Point_3` of `geom_traits`}
    \cgalParamDefault{the points of the mesh}
  \cgalParamNEnd
  \cgalParamNBegin{vertex_is_constrained_map}
    \cgalParamDescription{a property map saying which vertices are constrained: a constrained vertex never moves, in any stage (untangling, surface pull-back, smoothing); an inverted hexahedron that only moving constrained vertices could free is reported in `Optimization_result::unresolved` with the reason `constrained`}
    \cgalParamType{a model of `ReadablePropertyMap` whose key type is the vertex descriptor of `HexMesh` and whose value type is `bool`}
    \cgalParamDefault{no vertex is constrained}
  \cgalParamNEnd
  \cgalParamNBegin{reference_vertex_point_map}
    \cgalParamDescription{with `reference_surface`: the points of its vertices}
    \cgalParamType{a model of `ReadablePropertyMap` whose key type is the vertex descriptor of the reference surface and whose value type is a point of a CGAL kernel}
    \cgalParamDefault{`get_const_property_map(CGAL::vertex_point, reference)`}
  \cgalParamNEnd
  \cgalParamNBegin{edge_is_constrained_map}
    \cgalParamDescription{with `reference_surface` and feature recovery (`reference_feature_angle` above 0): edges of the reference that are creases whatever their dihedral angle, added to those detected; the mesh boundary recovers them as it recovers the detected ones}
    \cgalParamType{a model of `ReadablePropertyMap` whose key type is the edge descriptor of the reference surface and whose value type is `bool`}
    \cgalParamDefault{no edge is given}
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
  typedef HMO::internal::Hex_mesh_parameters<HexMesh, CGAL_NP_CLASS> Mesh_parameters;

  HMO::internal::Time_limit time_limit(HMO::internal::time_limit_parameter(np));
  time_limit.watch(HMO::internal::stop_flag_parameter(np));
  HMO::Default_optimization_visitor default_visitor;
  auto&& visitor = choose_parameter(parameters::get_parameter_reference(np, internal_np::visitor), default_visitor);

  HMO::internal::Untangle_settings s;
  s.time_limit = &time_limit;
  std::vector<HMO::internal::Vec3> ref_points;
  std::vector<HMO::internal::Tri> ref_tris;
  std::vector<std::array<std::size_t, 2> > ref_creases;
  HMO::internal::read_untangle_parameters(np, s, ref_points, ref_tris, ref_creases);

  const double tolerance = HMO::internal::surface_tolerance_parameter(np);
  const double local_tolerance = HMO::internal::local_surface_tolerance_parameter(np);

  HMO::internal::Hex_mesh_arrays arrays = Mesh_parameters::extract(mesh, np);
  const std::vector<HMO::internal::Vec3> read = arrays.points;
  const std::string warning =
    HMO::internal::require_reference_fit(arrays, s.reference_points, s.reference_triangles, tolerance);
  HMO::internal::Hex_mesh_untangler<typename std::remove_reference<decltype(visitor)>::type> untangler(s, visitor);
  const HMO::internal::Hex_mesh_arrays input = arrays;
  HMO::Optimization_result result = untangler.run(arrays);
  if(!warning.empty()) result.warnings.push_back(warning);
  HMO::internal::report_off_surface_vertices(arrays, input, s.reference_points, s.reference_triangles, tolerance,
                                             local_tolerance, result);
  if(result.inverted_after > 0)
    result.unresolved = HMO::internal::unresolved_elements(arrays, result.time_limit_reached || result.interrupted);
  Mesh_parameters::write_back(arrays, read, mesh, np);
  return result;
}

} // namespace CGAL

#endif // CGAL_UNTANGLE_HEX_MESH_H
