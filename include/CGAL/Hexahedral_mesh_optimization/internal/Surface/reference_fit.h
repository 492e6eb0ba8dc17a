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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_REFERENCE_FIT_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_REFERENCE_FIT_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// Does a reference surface fit the mesh it is given with? (see
// Reference_fit.h for the verdicts). Checked before any stage moves a vertex:
// a reference in another coordinate frame would otherwise run the whole
// pipeline and write a mesh far off its surface without a word.
//
// The thresholds (`Reference_fit_thresholds`): a mismatch needs half of the
// vertices of one surface beyond 5 % of the diagonal, bounding boxes that do
// not meet, or diagonals a factor 2 apart: far beyond any perturbation of a
// boundary, and several times what a mesh and its own reference measure
// (RESULTS.md of the benchmark has the shared meshes' figures). Medians, so
// that a few stray vertices (a perturbed CAD mesh) make a warning, not an
// error.

#include <CGAL/Hexahedral_mesh_optimization/Reference_fit.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_boundary.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/surface_distance.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

struct Reference_fit_thresholds
{
  /// largest ratio between the two bounding-box diagonals
  double diagonal_ratio = 2.;
  /// largest median vertex distance, relative to the reference diagonal
  double far_median = 0.05;
};

namespace reference_fit_detail {

inline CGAL::Bbox_3 bbox_of(const std::vector<Vec3>& points)
{
  CGAL::Bbox_3 b;
  for(const Vec3& p : points) b += CGAL::Bbox_3(p[0], p[1], p[2], p[0], p[1], p[2]);
  return b;
}

inline Vec3 centre_of(const CGAL::Bbox_3& b)
{
  return Vec3{0.5 * (b.xmin() + b.xmax()), 0.5 * (b.ymin() + b.ymax()), 0.5 * (b.zmin() + b.zmax())};
}

inline std::string interval_text(const CGAL::Bbox_3& b)
{
  std::ostringstream os;
  os << "[" << b.xmin() << ", " << b.xmax() << "] x [" << b.ymin() << ", " << b.ymax() << "] x [" << b.zmin()
     << ", " << b.zmax() << "]";
  return os.str();
}

/// distances of `points` to the triangles (`tri_points`, `tris`): median and maximum
inline void vertex_distances(const std::vector<Vec3>& points, const std::vector<Vec3>& tri_points,
                             const std::vector<Tri>& tris, double& median, double& maximum)
{
  using namespace surface_distance_detail;
  std::vector<Soup_triangle> t;
  t.reserve(tris.size());
  auto point = [&](std::size_t i) { return Soup_point(tri_points[i][0], tri_points[i][1], tri_points[i][2]); };
  for(const Tri& f : tris) t.push_back(Soup_triangle(point(f[0]), point(f[1]), point(f[2])));
  Soup_tree tree(t.begin(), t.end());
  tree.accelerate_distance_queries();
  std::vector<double> d(points.size());
  for(std::size_t i = 0; i < points.size(); ++i)
    d[i] = std::sqrt(tree.squared_distance(Soup_point(points[i][0], points[i][1], points[i][2])));
  maximum = d.empty() ? 0. : *std::max_element(d.begin(), d.end());
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  median = d.empty() ? 0. : d[d.size() / 2];
}

} // namespace reference_fit_detail

/// How the reference (`ref_points`, `ref_tris`) fits the boundary of `mesh`;
/// `tolerance` is the surface tolerance, relative to the reference diagonal.
inline Reference_fit measure_reference_fit(const Hex_mesh_arrays& mesh, const std::vector<Vec3>& ref_points,
                                           const std::vector<Tri>& ref_tris, double tolerance,
                                           const Reference_fit_thresholds& th = Reference_fit_thresholds())
{
  using namespace reference_fit_detail;
  Reference_fit fit;
  fit.tolerance = tolerance;
  const Hex_mesh_boundary b = extract_boundary(mesh);
  std::vector<Vec3> bpoints;
  std::vector<Tri> btris;
  triangulate_boundary(b, mesh.points, Quad_split::diagonal_02, bpoints, btris);
  std::vector<Vec3> used; // the reference vertices that are on a triangle
  {
    std::vector<char> on(ref_points.size(), 0);
    for(const Tri& t : ref_tris) for(std::size_t i : t) on[i] = 1;
    for(std::size_t i = 0; i < ref_points.size(); ++i) if(on[i]) used.push_back(ref_points[i]);
  }
  const CGAL::Bbox_3 mb = bbox_of(bpoints), rb = bbox_of(used);
  fit.mesh_diagonal = diagonal(mb);
  fit.reference_diagonal = diagonal(rb);
  fit.boxes_overlap = CGAL::do_overlap(mb, rb);
  std::ostringstream why;
  if(bpoints.empty() || used.empty() || !(fit.reference_diagonal > 0.))
  {
    fit.verdict = Reference_fit::mismatched;
    fit.message = used.empty() || !(fit.reference_diagonal > 0.) ? "the reference surface has no extent"
                                                                  : "the mesh has no boundary";
    return fit;
  }
  const double rd = fit.reference_diagonal;
  fit.centre_offset = norm(centre_of(mb) - centre_of(rb)) / rd;
  vertex_distances(bpoints, ref_points, ref_tris, fit.median_mesh_to_reference, fit.max_mesh_to_reference);
  vertex_distances(used, bpoints, btris, fit.median_reference_to_mesh, fit.max_reference_to_mesh);
  fit.median_mesh_to_reference /= rd; fit.max_mesh_to_reference /= rd;
  fit.median_reference_to_mesh /= rd; fit.max_reference_to_mesh /= rd;

  const double ratio = fit.mesh_diagonal / rd;
  std::vector<std::string> reasons;
  if(!fit.boxes_overlap) reasons.push_back("the bounding boxes do not overlap");
  if(ratio > th.diagonal_ratio || ratio < 1. / th.diagonal_ratio)
  {
    std::ostringstream r;
    r << "the bounding-box diagonals differ by a factor of " << (ratio > 1. ? ratio : 1. / ratio);
    reasons.push_back(r.str());
  }
  if(fit.median_mesh_to_reference > th.far_median)
  {
    std::ostringstream r;
    r << "half the mesh boundary vertices are farther than " << fit.median_mesh_to_reference
      << " reference diagonals from the reference";
    reasons.push_back(r.str());
  }
  if(fit.median_reference_to_mesh > th.far_median)
  {
    std::ostringstream r;
    r << "half the reference vertices are farther than " << fit.median_reference_to_mesh
      << " reference diagonals from the mesh boundary";
    reasons.push_back(r.str());
  }
  if(!reasons.empty())
  {
    fit.verdict = Reference_fit::mismatched;
    why << "the reference surface does not fit the mesh (another coordinate frame, or another object?): ";
    for(std::size_t i = 0; i < reasons.size(); ++i) why << (i ? "; " : "") << reasons[i];
    why << " (mesh boundary in " << interval_text(mb) << ", reference in " << interval_text(rb) << ")";
    fit.message = why.str();
    return fit;
  }
  const double far = (std::max)(fit.max_mesh_to_reference, fit.max_reference_to_mesh);
  if(far > tolerance)
  {
    fit.verdict = Reference_fit::distant;
    why << "the mesh boundary starts off the reference surface: up to " << fit.max_mesh_to_reference
        << " reference diagonals from it (median " << fit.median_mesh_to_reference
        << "), and the reference up to " << fit.max_reference_to_mesh
        << " from the boundary, for a surface tolerance of " << tolerance
        << "; the optimisation moves the boundary onto the reference";
    fit.message = why.str();
  }
  return fit;
}

/// The check of the optimisation functions: throws `Reference_mismatch`
/// when the reference (if any) does not fit `mesh`, and returns the warning
/// of a distant one (empty otherwise).
inline std::string require_reference_fit(const Hex_mesh_arrays& mesh, const std::vector<Vec3>* ref_points,
                                         const std::vector<Tri>* ref_tris, double tolerance)
{
  if(!ref_points || !ref_tris) return std::string();
  const Reference_fit fit = measure_reference_fit(mesh, *ref_points, *ref_tris, tolerance);
  if(fit.verdict == Reference_fit::mismatched) throw Reference_mismatch(fit.message);
  return fit.message;
}

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_REFERENCE_FIT_H
