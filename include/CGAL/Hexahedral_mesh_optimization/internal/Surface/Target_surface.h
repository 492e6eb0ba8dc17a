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

#ifndef CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_TARGET_SURFACE_H
#define CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_TARGET_SURFACE_H

#include <CGAL/license/Hexahedral_mesh_optimization.h>

// The target surface Ω_t of Section 3.1 and the per-iteration boundary
// constraints of Eq. 6.
//
// A `Target_surface` holds
// - the reference surface: a triangle soup in an AABB tree (by default the
//   boundary of the input hex mesh, each quad cut both ways into 4
//   overlapping triangles as the paper does, so that no diagonal is chosen);
// - Ω_t: the boundary vertices of the hex mesh after Laplacian smoothing
//   within the boundary quad mesh, each step followed by a projection onto
//   the reference (closest point);
// - the feature classification of Ω_t (dihedral-angle threshold θ): regular,
//   sharp (on a feature line) and corner vertices, and the feature lines as
//   polylines of Ω_t.
// Given the current positions it fills one `Boundary_constraint` per mesh
// vertex; it knows nothing of the energy or the solver.
//
// Choices where the paper is vague (Section 3.1):
// - Projection: the closest point on the reference (AABB tree). The paper's
//   "perpendicular ray to every triangle plane, keep the closest hit inside
//   its triangle" is the closest point whenever that lies inside a triangle,
//   and has no answer near creases; the closest point always has one.
// - Smoothing: uniform Laplacian over the boundary edges, λ = 0.5 per step,
//   then projection, 20 steps. A regular vertex moves in its tangent plane
//   (the component along the area-weighted vertex normal is removed). Creases
//   are kept while smoothing, but only strong ones: before each step the
//   features are detected with a stricter threshold (`smoothing_feature_angle`,
//   135°); a corner stays, a sharp vertex moves along its feature line (the
//   Laplacian projected on the chord of its two feature neighbours, so that a
//   curved line does not shrink). With θ = 165° instead, the many edges at
//   155–170° of coarse curved regions flicker in and out of the feature set
//   from one step to the next and the smoothing folds quads; with no crease
//   kept at all, the creases of CAD models are cut and their corners
//   multiply. 135° keeps the strong creases and corners of CAD parts and
//   unfolds most of a tangled input's boundary quads.
// - Folds: during the first half of the steps (`masked_fraction`), no
//   feature is detected at the vertices of non-convex (folded, bow-tie)
//   boundary quads of the input, so that a fold of a tangled boundary is
//   smoothed out instead of being kept as a crease (features detected on a
//   tangled input are spurious there). Masking all vertices of inverted hexes
//   instead was tried and cut real creases (a rim vertex of a cylinder lying on
//   a flat interior hex).
// - Features: an edge of the Ω_t quad mesh is sharp when the dihedral angle
//   between its two quads, 180° − angle(n1, n2) with n the quad normals
//   (cross product of the diagonals), is below θ; concave and convex creases
//   alike. A non-manifold boundary edge (shared by 4 quads) is sharp: no
//   tangent plane exists there. Degenerate quads (zero normal) make no edge
//   sharp. (PMP::detect_sharp_edges does the same test on a Surface_mesh;
//   it is not used because it would need a manifold Surface_mesh of the
//   quads rebuilt at every smoothing step, and cannot take the fold mask.)
// - Seeds (`feature_seed_angle`; the named parameter `crease_seed_angle` of
//   the quality stages, off by default): with a seed
//   angle below θ, only the edges below it start creases; an edge below θ
//   is sharp only where it continues a crease from one of its ends, turning
//   by less than `crease_continuation_turn` (60°; `continue_creases`), as a
//   hysteresis threshold keeps
//   the weak parts of strong edges in an image. The many edges at 150°-165°
//   of coarse curved regions otherwise make short creases that meet in
//   spurious corners.
// - Fragments: the sharp edges form chains (split at vertices of sharp degree
//   ≠ 2). A chain of fewer than `min_feature_edges` edges that dangles (an
//   end of sharp degree 1) or forms an isolated closed loop is dropped;
//   repeated until stable, since dropping a spur can merge two chains. Short
//   chains between two junctions are kept (a narrow chamfer is a feature).
// - Classes: sharp degree 0 → regular, 2 → sharp, 1 (end of a feature line)
//   or ≥ 3 → corner.
// - Feature recovery (`reference_feature_angle` > 0, set by the pipelines
//   for a reference given by the user): the creases and corners come from
//   the reference itself (Reference_features.h), matched to boundary chains
//   and vertices (Feature_recovery.h) on the boundary smoothed
//   `matching_smoothing_rounds` times; the chain and corner vertices go onto
//   them, the others are projected and smoothed around them
//   (`smoothed_around_features`), and the smoothing, fold masks and
//   dihedral classification above are not used. A reference without clear
//   creases falls back to them.
// - Sharp anchors: the closest point on the vertex's own feature line, looked
//   for within ±`feature_search_window` segments of the vertex's place on the
//   line (covers whole lines up to twice that length; keeps a vertex from
//   jumping to a distant part of a line folding back near itself, and bounds
//   the cost).
// - Normals of regular anchors: interpolated (barycentric) from per-corner
//   normals of the reference that average only the incident triangles whose
//   normal is within 180° − θ of the corner's own triangle (so creases are
//   not blurred), then oriented along the outward normal of Ω_t at the
//   vertex: a reference of any orientation works.

#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Boundary_constraint.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Feature_recovery.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Reference_features.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_arrays.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Hex_mesh_boundary.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/parallel_for_each_index.h>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace CGAL {
namespace Hexahedral_mesh_optimization {
namespace internal {

struct Target_surface_parameters
{
  /// Laplacian smoothing iterations of the boundary (paper: 20); 0 only projects
  unsigned int smoothing_iterations = 20;
  /// λ in p ← p + λ·(tangential Laplacian)
  double smoothing_step = 0.5;
  /// fraction of the iterations, at the start, during which features are
  /// ignored at the vertices of folded (non-convex) boundary quads
  double masked_fraction = 0.5;
  /// the smoothing stops early once an iteration moves no vertex by more
  /// than this fraction of the mean boundary edge length (a boundary the
  /// smoothing leaves where it is, such as a grid's flat faces, then costs
  /// one iteration, not all of them)
  double smoothing_convergence = 1e-9;
  /// project after every smoothing step (true) or once at the end
  bool project_every_iteration = true;
  /// θ in degrees: an edge is sharp when its dihedral angle is below θ (180° = flat)
  double feature_angle = 165.;
  /// creases start at edges whose dihedral angle is below this, and go on
  /// along the edges below θ that continue them (`continue_creases`); 180
  /// (the default) or θ: every edge below θ is a crease. The quality stages
  /// set it from `Optimization_schedule::crease_seed_angle`
  double feature_seed_angle = 180.;
  /// with seeds, a crease goes on along a weak edge that turns from it by
  /// less than this, in degrees (a sharper turn is a corner, not a crease
  /// going on)
  double crease_continuation_turn = 60.;
  /// the (stricter) threshold for the creases kept while smoothing
  double smoothing_feature_angle = 135.;
  /// dangling or isolated feature fragments with fewer edges are dropped
  std::size_t min_feature_edges = 3;
  /// half-width, in segments, of the search for a sharp vertex's anchor on its line
  std::size_t feature_search_window = 64;
  /// feature recovery from the reference (Feature_recovery.h): the creases
  /// of the reference are its edges with a dihedral angle below this, in
  /// degrees; 0 (the default): no recovery, the features are those of Ω_t.
  /// The pipelines set it for a reference given by the user
  double reference_feature_angle = 0.;
  /// dangling or closed reference creases shorter than this many mean
  /// boundary edges of the mesh are dropped (noise of a scanned surface)
  double min_reference_feature_length = 2.;
  /// the reference has features only when at least half of its edges
  /// sharp at `reference_feature_angle` are still sharp at that angle minus
  /// this many degrees (Reference_features.h; 0: not checked)
  double reference_feature_clear_margin = 30.;
  /// edges of the reference (pairs of indices into its points) given as
  /// creases by the user (`edge_is_constrained_map`), added to those found
  std::vector<std::array<std::size_t, 2> > reference_creases;
  Feature_recovery_parameters recovery;
};

/// what feature recovery found (all zero when it did not run)
struct Feature_recovery_summary
{
  bool attempted = false; ///< recovery was asked for (`reference_feature_angle` > 0)
  bool recovered = false; ///< the reference's features replaced Ω_t's classification
  std::size_t reference_corners = 0, corners_matched = 0;
  std::size_t reference_curves = 0, curves_recovered = 0;
  /// the reference's edges sharp at the angle, and at it minus the clear margin
  std::size_t sharp_edges = 0, clearly_sharp_edges = 0;
  double angle = 0., clear_margin = 0.;
  bool polygon_mesh = true; ///< the reference could be made a polygon mesh
  bool topological = false; ///< the creases were followed along the mesh's own crease edges as well
};

/// the summary in words, for a stage report
inline std::string describe(const Feature_recovery_summary& s)
{
  if(!s.recovered)
  {
    std::ostringstream d;
    d << "not used: ";
    if(!s.polygon_mesh) d << "the reference is not a polygon mesh (non-manifold or not orientable)";
    else if(s.sharp_edges == 0) d << "the reference has no edge below " << s.angle << " degrees";
    else if(s.clear_margin > 0. && 2 * s.clearly_sharp_edges < s.sharp_edges)
      d << "the reference's creases are not clear (" << s.sharp_edges << " edges below " << s.angle << " degrees, "
        << s.clearly_sharp_edges << " below " << s.angle - s.clear_margin << ")";
    else d << "no crease of the reference is long enough";
    d << "; the boundary is classified by its dihedral angles";
    return d.str();
  }
  return std::to_string(s.corners_matched) + " of " + std::to_string(s.reference_corners)
       + " reference corners matched to boundary vertices, " + std::to_string(s.curves_recovered) + " of "
       + std::to_string(s.reference_curves) + " reference creases followed by chains of boundary edges"
       + (s.topological ? " (and by the edges on one hex or on three and more)" : "");
}

class Target_surface
{
public:
  // plain double arithmetic for the closest-point queries: with filtered
  // predicates the sphere-box tests of a flat (axis-aligned) boundary fall
  // back to exact arithmetic, and a distance needs no exactness
  typedef CGAL::Simple_cartesian<double> K;
  typedef K::Point_3 Point_3;
  typedef K::Triangle_3 Triangle_3;
  typedef std::vector<Triangle_3>::const_iterator Triangle_iterator;
  typedef CGAL::AABB_triangle_primitive<K, Triangle_iterator> Primitive;
  typedef CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>> Tree;

  static constexpr std::size_t npos = Hex_mesh_boundary::npos;

  /// A feature line of Ω_t: boundary indices along it. An open line starts
  /// and ends at corners; a closed one (no corner on it) does not repeat its
  /// first vertex.
  struct Feature_line
  {
    std::vector<std::size_t> vertices;
    std::vector<std::size_t> edges; // boundary edge ids, edges[i] joins vertices[i], vertices[i+1 (mod n)]
    bool closed = false;
  };

  /// Reference = the boundary of `mesh` itself (scenario 2 of Section 3.1).
  explicit Target_surface(const Hex_mesh_arrays& mesh,
                          const Target_surface_parameters& param = Target_surface_parameters())
    : Target_surface(mesh, extract_boundary(mesh), param)
  {}

  /// The same, with the boundary of `mesh` already extracted
  /// (`extract_boundary(mesh)`, e.g. `Hex_mesh_topology::boundary()`).
  Target_surface(const Hex_mesh_arrays& mesh, const Hex_mesh_boundary& boundary,
                 const Target_surface_parameters& param = Target_surface_parameters())
    : param_(param), boundary_(boundary), n_vertices_(mesh.number_of_vertices())
  {
    CGAL_precondition(boundary.boundary_index.size() == mesh.number_of_vertices());
    std::vector<Vec3> sp;
    std::vector<Tri> st;
    triangulate_boundary(boundary_, mesh.points, Quad_split::both_diagonals, sp, st);
    build_reference(sp, st);
    compute_target(mesh);
    pin_constrained_vertices(mesh);
  }

  /// Reference = a triangle soup (scenario 1 of Section 3.1), any orientation.
  Target_surface(const Hex_mesh_arrays& mesh,
                 const std::vector<Vec3>& reference_points,
                 const std::vector<Tri>& reference_triangles,
                 const Target_surface_parameters& param = Target_surface_parameters())
    : Target_surface(mesh, extract_boundary(mesh), reference_points, reference_triangles, param)
  {}

  /// The same, with the boundary of `mesh` already extracted.
  Target_surface(const Hex_mesh_arrays& mesh,
                 const Hex_mesh_boundary& boundary,
                 const std::vector<Vec3>& reference_points,
                 const std::vector<Tri>& reference_triangles,
                 const Target_surface_parameters& param = Target_surface_parameters())
    : param_(param), boundary_(boundary), n_vertices_(mesh.number_of_vertices())
  {
    CGAL_precondition(boundary.boundary_index.size() == mesh.number_of_vertices());
    build_reference(reference_points, reference_triangles);
    compute_target(mesh);
    pin_constrained_vertices(mesh);
  }

  // the AABB tree refers into `ref_triangles_`: no copies
  Target_surface(const Target_surface&) = delete;
  Target_surface& operator=(const Target_surface&) = delete;
  Target_surface(Target_surface&&) = default;
  Target_surface& operator=(Target_surface&&) = default;

  // ------------------------------------------------------------ queries

  /// Fills `out` (resized to the number of mesh vertices) with the class of
  /// every vertex and, for boundary vertices, the anchor v̄ and direction of
  /// Eq. 6 for the current positions: regular → closest point on the
  /// reference and the unit outward normal there; sharp → closest point on
  /// its feature line and the unit tangent there; corner → its Ω_t position.
  /// Interior vertices get `Vertex_class::interior` and a zero anchor.
  void update_constraints(const std::vector<Vec3>& current_points,
                          std::vector<Boundary_constraint>& out) const
  {
    CGAL_precondition(current_points.size() == n_vertices_);
    out.assign(n_vertices_, Boundary_constraint());
    for(std::size_t bi = 0; bi < boundary_.vertices.size(); ++bi)
    {
      const std::size_t v = boundary_.vertices[bi];
      Boundary_constraint& c = out[v];
      c.type = classes_[v];
      const Vec3& p = current_points[v];
      switch(c.type)
      {
      case Vertex_class::regular:
        c = sliding_constraint(v, p);
        break;
      case Vertex_class::sharp:
        closest_on_feature_line(bi, p, c.anchor, c.direction);
        break;
      default: // corner
        c.anchor = omega_[bi];
        break;
      }
    }
  }

  /// The constraint of one boundary vertex `v` at position `p` (what
  /// `update_constraints()` computes for it), for the per-vertex moves of
  /// the quality stages.
  Boundary_constraint constraint_at(std::size_t v, const Vec3& p) const
  {
    Boundary_constraint c;
    c.type = classes_[v];
    const std::size_t bi = boundary_.boundary_index[v];
    switch(c.type)
    {
    case Vertex_class::interior:
      break;
    case Vertex_class::regular:
      c = sliding_constraint(v, p);
      break;
    case Vertex_class::sharp:
      closest_on_feature_line(bi, p, c.anchor, c.direction);
      break;
    default:
      c.anchor = omega_[bi];
      break;
    }
    return c;
  }

  /// The constraint of a regular vertex for the boundary vertex `v` at `p`,
  /// whatever its class: the closest point on the reference and the normal
  /// there, oriented outward. A sharp or corner vertex given this constraint
  /// slides on the surface instead of staying on its feature line or place.
  Boundary_constraint sliding_constraint(std::size_t v, const Vec3& p) const
  {
    Boundary_constraint c;
    c.type = Vertex_class::regular;
    const std::size_t bi = boundary_.boundary_index[v];
    closest_on_reference(p, c.anchor, &c.direction);
    if(dot(c.direction, outward_[bi]) < 0.)
      c.direction = -1. * c.direction;
    if(!(squared_norm(c.direction) > 0.)) // cannot happen with non-degenerate triangles
      c.direction = outward_[bi];
    return c;
  }

  /// Moves every boundary vertex of `points` onto its anchor (see
  /// `update_constraints()`); interior vertices are left alone.
  void project_to_target(std::vector<Vec3>& points) const
  {
    std::vector<Boundary_constraint> c;
    update_constraints(points, c);
    for(std::size_t v : boundary_.vertices)
      points[v] = c[v].anchor;
  }

  /// Positions with every boundary vertex at its Ω_t position (interior
  /// vertices copied from `points`): the goal of the pull-back (Section 3.3).
  void target_points(std::vector<Vec3>& points) const
  {
    for(std::size_t bi = 0; bi < boundary_.vertices.size(); ++bi)
      points[boundary_.vertices[bi]] = omega_[bi];
  }

  /// closest point on the reference surface, and optionally the (crease
  /// aware, interpolated) unit normal there, in the reference's orientation
  void closest_on_reference(const Vec3& p, Vec3& q, Vec3* normal = nullptr) const
  {
    const auto pp = tree_->closest_point_and_primitive(Point_3(p[0], p[1], p[2]));
    q = {pp.first.x(), pp.first.y(), pp.first.z()};
    if(normal == nullptr)
      return;
    const std::size_t t = std::size_t(pp.second - ref_triangles_.begin());
    const Tri& tri = ref_tris_[t];
    const Vec3& a = ref_points_[tri[0]];
    const Vec3& b = ref_points_[tri[1]];
    const Vec3& c = ref_points_[tri[2]];
    const Vec3 n = cross(b - a, c - a);
    const double nn = squared_norm(n);
    Vec3 r = ref_face_normals_[t];
    if(nn > 0.)
    {
      // barycentric coordinates of q
      const double l0 = dot(cross(c - b, q - b), n) / nn;
      const double l1 = dot(cross(a - c, q - c), n) / nn;
      const double l2 = 1. - l0 - l1;
      const Vec3 s = l0 * ref_corner_normals_[t][0] + l1 * ref_corner_normals_[t][1]
                   + l2 * ref_corner_normals_[t][2];
      const double ls = norm(s);
      if(ls > 0.)
        r = (1. / ls) * s;
    }
    *normal = r;
  }

  /// the index (in `reference_triangles()`) of the reference triangle closest to p
  std::size_t closest_triangle(const Vec3& p) const
  {
    return std::size_t(tree_->closest_point_and_primitive(Point_3(p[0], p[1], p[2])).second - ref_triangles_.begin());
  }

  /// Applies p ← s·p + t to the reference, Ω_t and the feature lines
  /// (used when the mesh is normalised before optimising, and back).
  void transform(double s, const Vec3& t)
  {
    for(Vec3& p : ref_points_)
      p = s * p + t;
    for(Vec3& p : omega_)
      p = s * p + t;
    for(std::vector<Vec3>& c : reference_creases_)
      for(Vec3& p : c)
        p = s * p + t;
    if(s < 0.)
      for(Vec3& n : outward_)
        n = -1. * n;
    const std::vector<Vec3> pts = ref_points_;
    const std::vector<Tri> tris = ref_tris_;
    build_reference(pts, tris);
    mean_edge_length_ *= std::abs(s);
  }

  // ------------------------------------------------------------ accessors

  const Target_surface_parameters& parameters() const { return param_; }
  const Hex_mesh_boundary& boundary() const { return boundary_; }
  std::size_t number_of_vertices() const { return n_vertices_; }
  /// class of every mesh vertex
  const std::vector<Vertex_class>& vertex_classes() const { return classes_; }
  Vertex_class vertex_class(std::size_t v) const { return classes_[v]; }
  /// Ω_t positions, indexed by boundary index (`boundary().vertices[i]` is the mesh vertex)
  const std::vector<Vec3>& target_positions() const { return omega_; }
  /// Ω_t position of mesh vertex `v`, which must be a boundary vertex
  const Vec3& target_position(std::size_t v) const { return omega_[boundary_.boundary_index[v]]; }
  /// unit outward normals of Ω_t, by boundary index
  const std::vector<Vec3>& target_normals() const { return outward_; }
  /// mean length of the boundary edges of Ω_t
  double mean_boundary_edge_length() const { return mean_edge_length_; }
  /// for each boundary edge (ids of `boundary().edges`): is it on a feature line of Ω_t
  const std::vector<unsigned char>& sharp_edges() const { return sharp_edge_; }
  const std::vector<Feature_line>& feature_lines() const { return lines_; }
  std::size_t number_of_vertices_of_class(Vertex_class c) const
  {
    return std::size_t(std::count(classes_.begin(), classes_.end(), c));
  }
  const std::vector<Vec3>& reference_points() const { return ref_points_; }
  const std::vector<Tri>& reference_triangles() const { return ref_tris_; }
  /// the reference's creases as polylines (a closed one repeats its first
  /// point) when feature recovery ran and found some; empty otherwise
  const std::vector<std::vector<Vec3>>& reference_creases() const { return reference_creases_; }
  /// Moves Ω_t to `points` (every boundary vertex on the reference): the
  /// feature lines then pass through the vertices as they are, so that the
  /// later stages' projections keep them there (Surface_fitting.h)
  void move_target_to(const std::vector<Vec3>& points)
  {
    for(std::size_t bi = 0; bi < boundary_.vertices.size(); ++bi) omega_[bi] = points[boundary_.vertices[bi]];
  }
  /// what feature recovery found (`Target_surface_parameters::reference_feature_angle`)
  const Feature_recovery_summary& feature_recovery_summary() const { return summary_; }

private:
  // ------------------------------------------------------------ reference
  void build_reference(const std::vector<Vec3>& points, const std::vector<Tri>& tris)
  {
    ref_points_ = points;
    ref_tris_.clear();
    for(const Tri& t : tris) // drop degenerate triangles (collapsed quads): they add no surface
      if(squared_norm(cross(points[t[1]] - points[t[0]], points[t[2]] - points[t[0]])) > 0.)
        ref_tris_.push_back(t);
    CGAL_precondition(!ref_tris_.empty());

    ref_triangles_.clear();
    ref_triangles_.reserve(ref_tris_.size());
    ref_face_normals_.assign(ref_tris_.size(), Vec3{0., 0., 0.});
    std::vector<double> area(ref_tris_.size(), 0.);
    for(std::size_t i = 0; i < ref_tris_.size(); ++i)
    {
      const Tri& t = ref_tris_[i];
      const Vec3 &a = points[t[0]], &b = points[t[1]], &c = points[t[2]];
      ref_triangles_.emplace_back(Point_3(a[0], a[1], a[2]), Point_3(b[0], b[1], b[2]),
                                  Point_3(c[0], c[1], c[2]));
      const Vec3 n = cross(b - a, c - a);
      area[i] = norm(n);
      if(area[i] > 0.)
        ref_face_normals_[i] = (1. / area[i]) * n;
    }
    tree_.reset(new Tree(ref_triangles_.begin(), ref_triangles_.end()));
    tree_->accelerate_distance_queries();

    // crease-aware corner normals
    std::vector<std::pair<std::size_t, std::size_t>> pairs;
    pairs.reserve(3 * ref_tris_.size());
    for(std::size_t i = 0; i < ref_tris_.size(); ++i)
      for(int k = 0; k < 3; ++k)
        pairs.emplace_back(ref_tris_[i][k], i);
    std::vector<std::size_t> off, list;
    boundary_detail::build_csr(ref_points_.size(), pairs, off, list);
    const double cos_max = std::cos((180. - param_.feature_angle) * CGAL_PI / 180.);
    ref_corner_normals_.resize(ref_tris_.size());
    for(std::size_t i = 0; i < ref_tris_.size(); ++i)
      for(int k = 0; k < 3; ++k)
      {
        const std::size_t v = ref_tris_[i][k];
        Vec3 s{0., 0., 0.};
        for(std::size_t j = off[v]; j < off[v + 1]; ++j)
        {
          const std::size_t f = list[j];
          if(dot(ref_face_normals_[f], ref_face_normals_[i]) >= cos_max)
            s = s + area[f] * ref_face_normals_[f];
        }
        const double l = norm(s);
        ref_corner_normals_[i][k] = l > 0. ? (1. / l) * s : ref_face_normals_[i];
      }
  }

  // ------------------------------------------------------------ Ω_t
  std::size_t bidx(std::size_t v) const { return boundary_.boundary_index[v]; }

  // area-weighted vertex normals (unit) of the boundary quad mesh at positions P (boundary indexed)
  void vertex_normals(const std::vector<Vec3>& P, std::vector<Vec3>& n) const
  {
    n.assign(P.size(), Vec3{0., 0., 0.});
    for(const auto& q : boundary_.quads)
    {
      const std::size_t a = bidx(q[0]), b = bidx(q[1]), c = bidx(q[2]), d = bidx(q[3]);
      const Vec3 qn = cross(P[c] - P[a], P[d] - P[b]);
      n[a] = n[a] + qn; n[b] = n[b] + qn; n[c] = n[c] + qn; n[d] = n[d] + qn;
    }
    for(Vec3& x : n)
    {
      const double l = norm(x);
      if(l > 0.)
        x = (1. / l) * x;
    }
  }

  // a quad is convex when each corner turns the same way as its normal (the
  // cross product of its diagonals): false for bow-ties, darts and folds
  static bool quad_is_convex(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d)
  {
    const Vec3 n = cross(c - a, d - b);
    const Vec3 p[4] = {a, b, c, d};
    for(int i = 0; i < 4; ++i)
      if(!(dot(cross(p[(i + 1) % 4] - p[i], p[(i + 3) % 4] - p[i]), n) > 0.))
        return false;
    return true;
  }

  /// the closest point of the reference to `p`, the search starting from
  /// `hint`, a point of the reference
  Vec3 closest_on_reference_from(const Vec3& p, const Vec3& hint) const
  {
    const Point_3 q = tree_->closest_point(Point_3(p[0], p[1], p[2]), Point_3(hint[0], hint[1], hint[2]));
    return {q.x(), q.y(), q.z()};
  }

  /// Ω_t (Section 3.1): the boundary smoothed along its surface and its
  /// feature lines, projected onto the reference; then its classification,
  /// feature lines and outward normals
  /// A boundary vertex the user constrained (`Hex_mesh_arrays::constrained`)
  /// is a corner whose Ω_t position is where it is: every constraint,
  /// projection and snap onto the target then leaves it in place.
  void pin_constrained_vertices(const Hex_mesh_arrays& mesh)
  {
    for(std::size_t bi = 0; bi < boundary_.vertices.size(); ++bi)
    {
      const std::size_t v = boundary_.vertices[bi];
      if(!mesh.is_constrained(v)) continue;
      classes_[v] = Vertex_class::corner;
      omega_[bi] = mesh.points[v];
    }
  }

  void compute_target(const Hex_mesh_arrays& mesh)
  {
    const std::vector<Vec3>& mesh_points = mesh.points;
    if(param_.reference_feature_angle > 0. && recover_target(mesh))
    {
      orient_target();
      return;
    }
    omega_ = smoothed_boundary(mesh_points);
    classify_target(mesh_points);
    orient_target();
  }

  /// the vertices of folded boundary quads: their "features" are not
  /// trusted while the smoothing starts
  std::vector<unsigned char> folded_quad_vertices(const std::vector<Vec3>& P) const
  {
    std::vector<unsigned char> mask(boundary_.vertices.size(), 0);
    for(const auto& q : boundary_.quads)
    {
      const std::size_t c[4] = {bidx(q[0]), bidx(q[1]), bidx(q[2]), bidx(q[3])};
      if(!quad_is_convex(P[c[0]], P[c[1]], P[c[2]], P[c[3]]))
        for(std::size_t v : c)
          mask[v] = 1;
    }
    return mask;
  }

  /// one smoothing step of boundary vertex bi (Q[bi] from the positions P):
  /// a regular vertex toward the mean of its neighbours in its tangent
  /// plane, a vertex of a feature line along the line, a corner stays
  Vec3 smoothing_step(const std::vector<Vec3>& P, std::size_t bi, const std::vector<unsigned char>& sharp,
                      const std::vector<std::size_t>& degree, const std::vector<Vec3>& normals) const
  {
    const std::size_t d = degree[bi];
    if(d != 0 && d != 2)
      return P[bi]; // corner: stays
    Vec3 mean{0., 0., 0.};
    std::size_t count = 0;
    Vec3 ends[2];
    const auto er = boundary_.edges_of(bi);
    for(const std::size_t* e = er.first; e != er.second; ++e)
    {
      if(d == 2 && !sharp[*e])
        continue;
      const Vec3& x = P[bidx(boundary_.opposite(*e, boundary_.vertices[bi]))];
      if(d == 2)
        ends[count] = x;
      mean = mean + x;
      ++count;
    }
    if(count == 0)
      return P[bi];
    Vec3 L = (1. / double(count)) * mean - P[bi];
    if(d == 0) // tangential: in the tangent plane
      L = L - dot(L, normals[bi]) * normals[bi];
    else // along the feature line: its chord direction at the vertex
    {
      Vec3 t = ends[1] - ends[0];
      const double lt = norm(t);
      L = lt > 0. ? (dot(L, t) / (lt * lt)) * t : Vec3{0., 0., 0.};
    }
    return P[bi] + param_.smoothing_step * L;
  }

  /// the boundary after `smoothing_iterations` smoothing steps, each vertex
  /// from the previous positions only (on all threads, the same result),
  /// projected onto the reference
  std::vector<Vec3> smoothed_boundary(const std::vector<Vec3>& mesh_points) const
  {
    const std::size_t nb = boundary_.vertices.size();
    std::vector<Vec3> P(nb), Q(nb), normals;
    for(std::size_t i = 0; i < nb; ++i)
      P[i] = mesh_points[boundary_.vertices[i]];
    const std::vector<unsigned char> mask = folded_quad_vertices(P);
    const unsigned int iters = param_.smoothing_iterations;
    const unsigned int masked = (std::min)(iters,
      static_cast<unsigned int>(std::lround(param_.masked_fraction * iters)));
    std::vector<unsigned char> sharp;
    std::vector<std::size_t> degree;
    std::vector<Vec3> last_projection;
    // the early stop: only once the features at folded quads count (if any)
    const bool folded = std::find(mask.begin(), mask.end(), 1) != mask.end();
    const double still = CGAL::square( // squared: a move this small is none
      param_.smoothing_convergence * mean_boundary_edge([&mesh_points](std::size_t v) { return mesh_points[v]; }));
    auto moved_nothing = [&] {
      for(std::size_t bi = 0; bi < nb; ++bi)
        if(squared_norm(Q[bi] - P[bi]) > still) return false;
      return true;
    };
    for(unsigned int it = 0; it < iters; ++it)
    {
      detect_features(P, param_.smoothing_feature_angle, sharp, degree, it < masked ? &mask : nullptr);
      vertex_normals(P, normals);
      parallel_for_each_index(nb, [&](std::size_t bi) { Q[bi] = smoothing_step(P, bi, sharp, degree, normals); }, 256);
      const bool may_stop = !folded || it + 1 >= masked;
      // (projected once at the end: a step that moved nothing is the end)
      bool converged = may_stop && !param_.project_every_iteration && it + 1 < iters && moved_nothing();
      if(param_.project_every_iteration || it + 1 == iters || converged)
      {
        // each query starts from the vertex's last projection (a point of
        // the reference): the same closest points, without the tree's
        // nearest-neighbour search and with a tight radius from the start
        // (the smoothing moves a vertex by a fraction of an edge)
        const bool hinted = last_projection.size() == nb;
        parallel_for_each_index(nb, [&](std::size_t bi) {
          if(hinted) Q[bi] = closest_on_reference_from(Q[bi], last_projection[bi]);
          else closest_on_reference(Q[bi], Q[bi]);
        }, 256);
        last_projection = Q;
        if(param_.project_every_iteration && may_stop) converged = moved_nothing();
      }
      std::swap(P, Q);
      if(converged) break;
    }
    if(iters == 0)
      for(std::size_t bi = 0; bi < nb; ++bi)
        closest_on_reference(P[bi], P[bi]);
    return P;
  }

  /// the classes of Ω_t's vertices (regular, sharp, corner), its corners
  /// put back, and its feature lines
  void classify_target(const std::vector<Vec3>& mesh_points)
  {
    const std::size_t nb = boundary_.vertices.size();
    std::vector<std::size_t> degree;
    detect_features(omega_, param_.feature_angle, sharp_edge_, degree, nullptr, param_.feature_seed_angle);
    classes_.assign(n_vertices_, Vertex_class::interior);
    for(std::size_t bi = 0; bi < nb; ++bi)
      classes_[boundary_.vertices[bi]] = class_of_sharp_degree(degree[bi]);
    // corners: back at the input's own position (projected on the
    // reference). The smoothing keeps only the corners of the 135° set in
    // place; a vertex that is a corner only at θ (a tip, the end of a
    // feature line) slides while smoothing, and the surface error (Hausdorff
    // against the input boundary) is then at least the distance it slid;
    // putting it back removes that part of the error.
    for(std::size_t bi = 0; bi < nb; ++bi)
      if(degree[bi] != 0 && degree[bi] != 2)
        closest_on_reference(mesh_points[boundary_.vertices[bi]], omega_[bi]);
    index_lines(degree);
  }

  /// the class of a boundary vertex with `degree` sharp edges: 0 regular,
  /// 2 sharp, 1 (the end of a line) or more than 2 corner
  static Vertex_class class_of_sharp_degree(std::size_t degree)
  {
    return degree == 0 ? Vertex_class::regular : degree == 2 ? Vertex_class::sharp : Vertex_class::corner;
  }

  /// the feature lines of `sharp_edge_` and each sharp vertex's place on its line
  void index_lines(const std::vector<std::size_t>& degree)
  {
    const std::size_t nb = boundary_.vertices.size();
    extract_lines(sharp_edge_, degree, lines_);
    line_of_.assign(nb, npos);
    place_on_line_.assign(nb, npos);
    for(std::size_t l = 0; l < lines_.size(); ++l)
    {
      const Feature_line& fl = lines_[l];
      for(std::size_t i = 0; i < fl.vertices.size(); ++i)
        if(degree[fl.vertices[i]] == 2)
        {
          line_of_[fl.vertices[i]] = l;
          place_on_line_[fl.vertices[i]] = i;
        }
    }
  }

  // ------------------------------------------------------------ feature recovery

  /// Ω_t from the reference's own features (Feature_recovery.h): the
  /// boundary projected onto the reference, its chains and corners put on the
  /// reference's creases and corners, the other vertices smoothed around
  /// them; false (nothing done) when the reference has no features
  bool recover_target(const Hex_mesh_arrays& mesh)
  {
    const std::vector<Vec3>& mesh_points = mesh.points;
    const std::size_t nb = boundary_.vertices.size();
    const double h = mean_boundary_edge([&mesh_points](std::size_t v) { return mesh_points[v]; });
    const Reference_features rf = detect_reference_features(ref_points_, ref_tris_, param_.reference_feature_angle,
      param_.crease_continuation_turn, param_.min_reference_feature_length * h, param_.reference_feature_clear_margin,
      param_.reference_creases);
    summary_ = Feature_recovery_summary();
    summary_.attempted = true;
    summary_.sharp_edges = rf.sharp_edges;
    summary_.clearly_sharp_edges = rf.clearly_sharp_edges;
    summary_.angle = param_.reference_feature_angle;
    summary_.clear_margin = param_.reference_feature_clear_margin;
    summary_.polygon_mesh = rf.polygon_mesh;
    if(rf.empty())
      return false;
    // matched on the vertices' own positions, smoothed: closest points
    // would gather the vertices around a convex crease or corner onto it
    const std::vector<Vec3> P_match = matching_positions(mesh_points);
    std::vector<std::size_t> quad_patch(boundary_.quads.size());
    parallel_for_each_index(boundary_.quads.size(), [&](std::size_t q) {
      const auto& Q = boundary_.quads[q];
      const Vec3 c = 0.25 * (P_match[bidx(Q[0])] + P_match[bidx(Q[1])] + P_match[bidx(Q[2])] + P_match[bidx(Q[3])]);
      quad_patch[q] = rf.triangle_patch[closest_triangle(c)];
    }, 256);
    const std::vector<unsigned char> edge_hexes = count_boundary_edge_hexes(boundary_, mesh.hexes);
    Feature_recovery_parameters recovery_param = param_.recovery;
    recovery_param.corner_turn = param_.crease_continuation_turn;
    Feature_recovery recovery(boundary_, P_match, h, quad_patch, edge_hexes, recovery_param);
    const Recovered_features rec = recovery.run(rf);
    summary_.recovered = true;
    summary_.reference_corners = rec.corners;
    summary_.corners_matched = rec.corners_matched;
    summary_.reference_curves = rec.curves;
    summary_.curves_recovered = rec.curves_recovered;
    summary_.topological = rec.topological;
    std::vector<Vec3> P(nb);
    parallel_for_each_index(nb, [&](std::size_t bi) {
      if(rec.placed[bi]) P[bi] = rec.position[bi];
      else closest_on_reference(P_match[bi], P[bi]);
    }, 256);
    omega_ = smoothed_around_features(P, rec.placed);
    reference_creases_.clear();
    for(const Reference_feature_curve& c : rf.curves) reference_creases_.push_back(c.polyline());

    sharp_edge_ = rec.sharp_edge;
    std::vector<std::size_t> degree;
    compute_degree(sharp_edge_, degree);
    classes_.assign(n_vertices_, Vertex_class::interior);
    for(std::size_t bi = 0; bi < nb; ++bi)
      classes_[boundary_.vertices[bi]] = rec.is_corner[bi] ? Vertex_class::corner : class_of_sharp_degree(degree[bi]);
    index_lines(degree);
    return true;
  }

  /// the boundary positions feature recovery matches on:
  /// `matching_smoothing_rounds` of p ← p/2 + (mean of the neighbours)/2
  std::vector<Vec3> matching_positions(const std::vector<Vec3>& mesh_points) const
  {
    const std::size_t nb = boundary_.vertices.size();
    std::vector<Vec3> P(nb), Q(nb);
    for(std::size_t bi = 0; bi < nb; ++bi) P[bi] = mesh_points[boundary_.vertices[bi]];
    for(unsigned int round = 0; round < param_.recovery.matching_smoothing_rounds; ++round)
    {
      parallel_for_each_index(nb, [&](std::size_t bi) {
        Vec3 sum{0., 0., 0.};
        double n = 0.;
        const auto er = boundary_.edges_of(bi);
        for(const std::size_t* e = er.first; e != er.second; ++e)
        {
          sum = sum + P[bidx(boundary_.opposite(*e, boundary_.vertices[bi]))];
          n += 1.;
        }
        Q[bi] = n > 0. ? 0.5 * P[bi] + (0.5 / n) * sum : P[bi];
      }, 256);
      P.swap(Q);
    }
    return P;
  }

  /// `smoothing_iterations` tangential Laplacian steps of the vertices not
  /// `fixed`, each followed by a projection onto the reference (the
  /// smoothing of Ω_t, with the recovered features held in place)
  std::vector<Vec3> smoothed_around_features(std::vector<Vec3> P, const std::vector<unsigned char>& fixed) const
  {
    const std::size_t nb = P.size();
    std::vector<Vec3> Q = P, normals;
    std::vector<std::size_t> degree(nb, 0); // 0: tangential Laplacian; 1: stays
    for(std::size_t bi = 0; bi < nb; ++bi) degree[bi] = fixed[bi] ? 1 : 0;
    const std::vector<unsigned char> no_sharp_edges(boundary_.edges.size(), 0);
    const double still = CGAL::square(param_.smoothing_convergence * mean_boundary_edge([&](std::size_t v) { return P[bidx(v)]; }));
    for(unsigned int it = 0; it < param_.smoothing_iterations; ++it)
    {
      vertex_normals(P, normals);
      parallel_for_each_index(nb, [&](std::size_t bi) {
        Q[bi] = fixed[bi] ? P[bi] : closest_on_reference_from(smoothing_step(P, bi, no_sharp_edges, degree, normals), P[bi]);
      }, 256);
      bool moved = false;
      for(std::size_t bi = 0; bi < nb && !moved; ++bi) moved = squared_norm(Q[bi] - P[bi]) > still;
      std::swap(P, Q);
      if(!moved) break;
    }
    return P;
  }

  /// outward normals of Ω_t (the quads are outward for positive hexes; if
  /// the enclosed signed volume is negative, the numbering is mirrored) and
  /// its mean edge length
  void orient_target()
  {
    vertex_normals(omega_, outward_);
    double volume = 0.;
    for(const auto& q : boundary_.quads)
    {
      const Vec3 &a = omega_[bidx(q[0])], &b = omega_[bidx(q[1])],
                 &c = omega_[bidx(q[2])], &d = omega_[bidx(q[3])];
      volume += dot(a, cross(b, c)) + dot(a, cross(c, d));
    }
    if(volume < 0.)
      for(Vec3& n : outward_)
        n = -1. * n;

    mean_edge_length_ = mean_boundary_edge([this](std::size_t v) { return omega_[bidx(v)]; });
  }

  /// the mean length of the boundary edges, `point(v)` the position of
  /// mesh vertex v
  template <class Point_of>
  double mean_boundary_edge(Point_of point) const
  {
    double sum = 0.;
    for(const auto& e : boundary_.edges) sum += norm(point(e[1]) - point(e[0]));
    return boundary_.edges.empty() ? 0. : sum / double(boundary_.edges.size());
  }

  // ------------------------------------------------------------ features

  // sharp edges of the quad mesh at positions P (boundary indexed), with the
  // short fragments removed; `degree` = number of sharp edges per vertex
  void detect_features(const std::vector<Vec3>& P,
                       double angle,
                       std::vector<unsigned char>& sharp,
                       std::vector<std::size_t>& degree,
                       const std::vector<unsigned char>* mask = nullptr,
                       double seed_angle = 180.) const
  {
    const std::size_t nq = boundary_.quads.size();
    std::vector<Vec3> qn(nq);
    for(std::size_t q = 0; q < nq; ++q)
    {
      const auto& Qd = boundary_.quads[q];
      const Vec3 n = cross(P[bidx(Qd[2])] - P[bidx(Qd[0])], P[bidx(Qd[3])] - P[bidx(Qd[1])]);
      const double l = norm(n);
      qn[q] = l > 0. ? (1. / l) * n : Vec3{0., 0., 0.};
    }
    // dihedral < θ  <=>  angle(n1, n2) > 180° − θ  <=>  n1·n2 < cos(180° − θ)
    const std::size_t ne = boundary_.edges.size();
    std::vector<double> normal_cosine(ne, 1.); // n1·n2 across each edge (1: flat or undefined)
    for(std::size_t q = 0; q < nq; ++q)
      for(int i = 0; i < 4; ++i)
      {
        const std::size_t r = boundary_.quad_neighbors[q][i];
        if(r == npos || r < q)
          continue;
        if(squared_norm(qn[q]) == 0. || squared_norm(qn[r]) == 0.)
          continue;
        normal_cosine[boundary_.quad_edges[q][i]] = dot(qn[q], qn[r]);
      }
    auto below = [&](double a) {
      const double cos_max = std::cos((180. - a) * CGAL_PI / 180.);
      std::vector<unsigned char> s(ne, 0);
      for(std::size_t e = 0; e < ne; ++e)
      {
        const bool masked = mask != nullptr && ((*mask)[bidx(boundary_.edges[e][0])] || (*mask)[bidx(boundary_.edges[e][1])]);
        s[e] = !masked && (!boundary_.edge_is_manifold[e] || normal_cosine[e] < cos_max) ? 1 : 0;
      }
      return s;
    };
    sharp = below(angle);
    if(seed_angle < angle)
    {
      const std::vector<unsigned char> weak = sharp;
      sharp = below(seed_angle);
      continue_creases(P, weak, sharp);
    }

    // drop short dangling / isolated fragments, until stable
    std::vector<Feature_line> lines;
    for(;;)
    {
      compute_degree(sharp, degree);
      extract_lines(sharp, degree, lines);
      bool removed = false;
      for(const Feature_line& l : lines)
      {
        if(l.edges.size() >= param_.min_feature_edges)
          continue;
        const bool dangling = l.closed || degree[l.vertices.front()] == 1
                                       || degree[l.vertices.back()] == 1;
        if(!dangling)
          continue;
        for(std::size_t e : l.edges)
          sharp[e] = 0;
        removed = true;
      }
      if(!removed)
        break;
    }
  }

  // Hysteresis along the creases: from each end of a crease (a vertex with
  // one sharp edge), the crease goes on along the `weak` edge of that vertex
  // that turns least from it, if it turns by less than
  // `crease_continuation_turn`; repeated until
  // no end goes on (the vertices in index order, round after round: the same
  // result on any run). A weak edge that continues no crease stays flat, so
  // the many edges at 150°-165° of a coarse curved region no longer make
  // short creases that meet each other in spurious corners.
  void continue_creases(const std::vector<Vec3>& P, const std::vector<unsigned char>& weak,
                        std::vector<unsigned char>& sharp) const
  {
    const double least_cosine = std::cos(param_.crease_continuation_turn * CGAL_PI / 180.);
    std::vector<std::size_t> degree;
    compute_degree(sharp, degree);
    const std::size_t nb = boundary_.vertices.size();
    for(bool grew = true; grew;)
    {
      grew = false;
      for(std::size_t bi = 0; bi < nb; ++bi)
      {
        if(degree[bi] != 1) continue;
        const std::size_t v = boundary_.vertices[bi];
        const std::size_t *first = boundary_.edges_of(bi).first, *last = boundary_.edges_of(bi).second;
        Vec3 incoming{0., 0., 0.};
        for(const std::size_t* e = first; e != last; ++e)
          if(sharp[*e]) incoming = P[bi] - P[bidx(boundary_.opposite(*e, v))];
        const double li = norm(incoming);
        if(!(li > 0.)) continue;
        std::size_t best = npos;
        double best_cosine = least_cosine;
        for(const std::size_t* e = first; e != last; ++e)
        {
          if(sharp[*e] || !weak[*e]) continue;
          const Vec3 out = P[bidx(boundary_.opposite(*e, v))] - P[bi];
          const double lo = norm(out);
          if(!(lo > 0.)) continue;
          const double c = dot(incoming, out) / (li * lo);
          if(c > best_cosine) { best_cosine = c; best = *e; }
        }
        if(best == npos) continue;
        sharp[best] = 1;
        ++degree[bidx(boundary_.edges[best][0])];
        ++degree[bidx(boundary_.edges[best][1])];
        grew = true;
      }
    }
  }

  void compute_degree(const std::vector<unsigned char>& sharp, std::vector<std::size_t>& degree) const
  {
    degree.assign(boundary_.vertices.size(), 0);
    for(std::size_t e = 0; e < boundary_.edges.size(); ++e)
      if(sharp[e])
      {
        ++degree[bidx(boundary_.edges[e][0])];
        ++degree[bidx(boundary_.edges[e][1])];
      }
  }

  // chains of sharp edges split at vertices of degree != 2; closed loops of degree-2 vertices last
  void extract_lines(const std::vector<unsigned char>& sharp,
                     const std::vector<std::size_t>& degree,
                     std::vector<Feature_line>& lines) const
  {
    lines.clear();
    std::vector<unsigned char> used(boundary_.edges.size(), 0);
    auto walk = [&](std::size_t start, std::size_t first_edge, Feature_line& l)
    {
      std::size_t cur = start, e = first_edge;
      l.vertices.push_back(cur);
      for(;;)
      {
        used[e] = 1;
        l.edges.push_back(e);
        cur = bidx(boundary_.opposite(e, boundary_.vertices[cur]));
        if(degree[cur] != 2)
        {
          l.vertices.push_back(cur);
          return;
        }
        std::size_t next = npos;
        const auto er = boundary_.edges_of(cur);
        for(const std::size_t* f = er.first; f != er.second; ++f)
          if(sharp[*f] && !used[*f])
            next = *f;
        if(next == npos) // closed loop back at its start
        {
          l.closed = true;
          return;
        }
        l.vertices.push_back(cur);
        e = next;
      }
    };
    for(std::size_t bi = 0; bi < boundary_.vertices.size(); ++bi)
    {
      if(degree[bi] == 0 || degree[bi] == 2)
        continue;
      const auto er = boundary_.edges_of(bi);
      for(const std::size_t* e = er.first; e != er.second; ++e)
        if(sharp[*e] && !used[*e])
        {
          lines.emplace_back();
          walk(bi, *e, lines.back());
        }
    }
    for(std::size_t bi = 0; bi < boundary_.vertices.size(); ++bi)
    {
      if(degree[bi] != 2)
        continue;
      const auto er = boundary_.edges_of(bi);
      for(const std::size_t* e = er.first; e != er.second; ++e)
        if(sharp[*e] && !used[*e])
        {
          lines.emplace_back();
          walk(bi, *e, lines.back());
          break;
        }
    }
  }

  // closest point on the feature line of sharp boundary vertex `bi`, and the unit tangent there
  void closest_on_feature_line(std::size_t bi, const Vec3& p, Vec3& q, Vec3& tangent) const
  {
    const Feature_line& l = lines_[line_of_[bi]];
    const std::size_t n = l.vertices.size();
    const std::size_t nseg = l.closed ? n : n - 1;
    const std::size_t i = place_on_line_[bi];
    const std::size_t w = param_.feature_search_window;

    // candidate segments j (from vertices[j] to vertices[j+1 mod n])
    long lo, hi;
    if(l.closed && 2 * w >= nseg)
    {
      lo = 0;
      hi = long(nseg) - 1;
    }
    else
    {
      lo = long(i) - long(w);
      hi = long(i) + long(w) - 1;
      if(!l.closed)
      {
        lo = (std::max)(lo, 0L);
        hi = (std::min)(hi, long(nseg) - 1);
      }
    }
    double best = std::numeric_limits<double>::max();
    std::size_t best_seg = 0;
    double best_t = 0.;
    for(long jj = lo; jj <= hi; ++jj)
    {
      const std::size_t j = std::size_t((jj % long(nseg) + long(nseg)) % long(nseg));
      const Vec3& a = omega_[l.vertices[j]];
      const Vec3& b = omega_[l.vertices[(j + 1) % n]];
      const Vec3 ab = b - a;
      const double ll = squared_norm(ab);
      double t = ll > 0. ? dot(p - a, ab) / ll : 0.;
      t = (std::max)(0., (std::min)(1., t));
      const double d = squared_norm(p - (a + t * ab));
      if(d < best)
      {
        best = d;
        best_seg = j;
        best_t = t;
      }
    }
    const Vec3& a = omega_[l.vertices[best_seg]];
    const Vec3& b = omega_[l.vertices[(best_seg + 1) % n]];
    q = a + best_t * (b - a);
    Vec3 t = b - a;
    // at a joint of the polyline, the mean of the two segment directions
    auto unit = [](const Vec3& x) { const double lx = norm(x); return lx > 0. ? (1. / lx) * x : x; };
    t = unit(t);
    if(best_t == 0. && (l.closed || best_seg > 0))
    {
      const std::size_t pj = (best_seg + nseg - 1) % nseg;
      t = unit(t + unit(a - omega_[l.vertices[pj]]));
    }
    else if(best_t == 1. && (l.closed || best_seg + 1 < nseg))
    {
      const std::size_t nj = (best_seg + 1) % nseg;
      t = unit(t + unit(omega_[l.vertices[(nj + 1) % n]] - b));
    }
    tangent = t;
  }

  Target_surface_parameters param_;
  Hex_mesh_boundary boundary_;
  std::size_t n_vertices_ = 0;

  // reference surface
  std::vector<Vec3> ref_points_;
  std::vector<Tri> ref_tris_;
  std::vector<Triangle_3> ref_triangles_;
  std::vector<Vec3> ref_face_normals_;
  std::vector<std::array<Vec3, 3>> ref_corner_normals_;
  std::unique_ptr<Tree> tree_;

  // Ω_t
  std::vector<Vec3> omega_;
  std::vector<Vec3> outward_;
  std::vector<Vertex_class> classes_;
  std::vector<unsigned char> sharp_edge_;
  std::vector<Feature_line> lines_;
  std::vector<std::size_t> line_of_, place_on_line_;
  double mean_edge_length_ = 0.;
  Feature_recovery_summary summary_;
  std::vector<std::vector<Vec3>> reference_creases_;
};

} // namespace internal
} // namespace Hexahedral_mesh_optimization
} // namespace CGAL

#endif // CGAL_HEXAHEDRAL_MESH_OPTIMIZATION_INTERNAL_SURFACE_TARGET_SURFACE_H
