// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Quality improvement on meshes of our own: the staged MSJ schedule (stage
// targets in order, MSJ never lower from one stage to the next, the schedule
// stopping at the user's target), the never-worse guarantee against an
// independent recount, the surface staying on the reference, the whole
// pipeline (untangle + improve) on a tangled grid, and the LCC overload.

#include "test_meshes.h"
#include "test_util.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Hexahedral_mesh_optimization/Linear_cell_complex_hex_mesh.h>
#include <CGAL/Linear_cell_complex_for_combinatorial_map.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/hex_mesh_quality.h>
#include <CGAL/hex_mesh_surface_error.h>
#include <CGAL/improve_hex_mesh_quality.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/Boundary_restoration.h>

#include <cmath>
#include <stdexcept>
#include <array>
#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace test_improve_quality {

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point;
typedef CGAL::Indexed_hex_mesh<Point> Mesh;
typedef CGAL::Linear_cell_complex_traits<3, K> LCC_traits;
typedef CGAL::Linear_cell_complex_for_combinatorial_map<3, 3, LCC_traits> LCC;
namespace HMO = CGAL::Hexahedral_mesh_optimization;
namespace INP = CGAL::hex_mesh_internal_np;
using CGAL::Hexahedral_mesh_optimization::internal::add_internal_parameter;

/// n×n×n grid of unit cubes bent into a cylindrical shell sector
static Mesh shell(int n, double bend)
{
  Mesh m;
  for(int k = 0; k <= n; ++k)
    for(int j = 0; j <= n; ++j)
      for(int i = 0; i <= n; ++i)
      {
        const double r = n + k, a = bend * i / n;
        m.points.emplace_back(r * std::cos(a), r * std::sin(a), j);
      }
  m.hexahedra = hmo_test::structured_hexes(n, n, n);
  return m;
}

static bool on_boundary(std::size_t v, int n)
{
  const std::size_t i = v % (n + 1), j = (v / (n + 1)) % (n + 1), k = v / ((n + 1) * (n + 1));
  return i == 0 || j == 0 || k == 0 || i == std::size_t(n) || j == std::size_t(n) || k == std::size_t(n);
}

/// interior vertices moved at random (amplitude × edge), the mesh kept valid
static void perturb_interior(Mesh& m, int n, double amplitude, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1., 1.);
  for(std::size_t v = 0; v < m.points.size(); ++v)
    if(!on_boundary(v, n)) m.points[v] = m.points[v] + amplitude * K::Vector_3(u(rng), u(rng), u(rng));
}

/// MSJ recomputed from the public per-element function
static double recount_msj(const Mesh& m)
{
  double msj = 2.;
  for(const auto& h : m.hexahedra)
  {
    std::array<Point, 8> c;
    for(int i = 0; i < 8; ++i) c[i] = m.points[h[i]];
    msj = (std::min)(msj, CGAL::hex_scaled_jacobian(c));
  }
  return msj;
}

/// records the stages in the order the visitor sees them
struct Recorder : HMO::Default_optimization_visitor
{
  std::vector<HMO::Stage_report> finished;
  std::vector<std::string> started;
  void stage_started(const std::string& name, std::size_t) { started.push_back(name); }
  void stage_finished(const HMO::Stage_report& r) { finished.push_back(r); }
};

static void test_stage_schedule()
{
  const int n = 5;
  Mesh m = shell(n, 1.2);
  perturb_interior(m, n, 0.3, 3);
  const Mesh input = m;
  const double msj0 = recount_msj(m);
  HMO_CHECK(msj0 > 0.);
  HMO_CHECK(msj0 < 0.5);

  Recorder rec;
  const HMO::Optimization_result r =
    CGAL::improve_hex_mesh_quality(m, add_internal_parameter(CGAL::parameters::visitor(std::ref(rec)), INP::asj_smoothing, false));
  // independent recount
  HMO_CHECK_CLOSE(r.msj_before, msj0, 1e-12);
  HMO_CHECK_CLOSE(r.msj_after, recount_msj(m), 1e-12);
  HMO_CHECK(r.inverted_after == 0);
  HMO_CHECK(r.msj_after > msj0 + 0.2); // a perturbed shell is easy to repair
  // targets 0.1, 0.2, ... in order, each stage starting where the last one ended
  std::vector<double> targets;
  for(const HMO::Stage_report& s : r.stages)
    if(s.name.rfind("msj>=", 0) == 0) targets.push_back(std::stod(s.name.substr(5)));
  HMO_CHECK(targets.size() >= 2);
  double previous = msj0;
  for(std::size_t i = 0; i < r.stages.size(); ++i)
  {
    HMO_CHECK(r.stages[i].msj_after >= previous - 1e-12); // the MSJ never goes down
    previous = r.stages[i].msj_after;
  }
  // multiples of 0.1, increasing (a target the MSJ already passed is
  // skipped); the last may be the highest aimed at, 0.999
  // (Optimization_schedule::excellent_msj) instead of 1
  for(std::size_t i = 0; i < targets.size(); ++i)
    if(i + 1 < targets.size() || targets[i] != HMO::internal::Optimization_schedule().excellent_msj)
      HMO_CHECK_CLOSE(targets[i] * 10., std::round(targets[i] * 10.), 1e-9);
  for(std::size_t i = 1; i < targets.size(); ++i) HMO_CHECK(targets[i] > targets[i - 1]);
  HMO_CHECK(targets.front() <= msj0 + 0.1 + 1e-9);
  // every stage but the last reached its target; the last one ended the schedule
  for(std::size_t i = 0; i + 1 < targets.size(); ++i)
  {
    std::size_t at = 0;
    for(std::size_t s = 0; s < r.stages.size(); ++s)
      if(r.stages[s].name.rfind("msj>=", 0) == 0 && at++ == i) HMO_CHECK(r.stages[s].msj_after >= targets[i]);
  }
  HMO_CHECK(rec.finished.size() == r.stages.size());
  HMO_CHECK(rec.started.size() == r.stages.size());
  // the boundary stays on the input's boundary within the tolerance (+ sampling slack)
  const double err = CGAL::hex_mesh_surface_error(m, input);
  HMO_CHECK(err <= 0.005 * 1.5);
  HMO_CHECK_CLOSE(err, r.surface_error, 1e-6);

  // a target: the schedule stops there and says it succeeded
  Mesh t = input;
  const HMO::Optimization_result rt = CGAL::improve_hex_mesh_quality(t, add_internal_parameter(CGAL::parameters::target_msj(0.3), INP::asj_smoothing, false));
  HMO_CHECK(rt.success);
  HMO_CHECK(rt.msj_after >= 0.3);
  for(const HMO::Stage_report& s : rt.stages)
    if(s.name.rfind("msj>=", 0) == 0) HMO_CHECK(std::stod(s.name.substr(5)) <= 0.3 + 1e-9);

  // ASJ smoothing on top never lowers the MSJ the stages reached
  Mesh a = input;
  const HMO::Optimization_result ra = CGAL::improve_hex_mesh_quality(a, CGAL::parameters::target_msj(0.3));
  HMO_CHECK(ra.msj_after >= 0.3);
  HMO_CHECK(ra.asj_after >= rt.asj_after - 1e-12);
}

static void test_turn_focus_band()
{
  // the named parameter reaches the turns: a wider band reshapes more of the
  // mesh, so the result differs; both keep the guarantees. Out of (0, 1] it
  // is refused before anything moves. A sheared wedge, so that the MSJ stays
  // far below most elements (on a shell every element ends above 0.99, all
  // within any band of the MSJ, and both bands give the same mesh).
  const int n = 5;
  Mesh input;
  for(int k = 0; k <= n; ++k)
    for(int j = 0; j <= n; ++j)
      for(int i = 0; i <= n; ++i)
      {
        const double z = k * (1. - 0.8 * i / n) + 0.8 * i;
        input.points.emplace_back(i + 0.5 * z, j, z);
      }
  input.hexahedra = hmo_test::structured_hexes(n, n, n);
  perturb_interior(input, n, 0.1, 3);
  Mesh narrow = input, wide = input;
  const HMO::Optimization_result rn = CGAL::improve_hex_mesh_quality(narrow, add_internal_parameter(CGAL::parameters::default_values(), INP::turn_focus_band, 0.05));
  const HMO::Optimization_result rw = CGAL::improve_hex_mesh_quality(wide, add_internal_parameter(CGAL::parameters::default_values(), INP::turn_focus_band, 0.6));
  HMO_CHECK(rn.inverted_after == 0 && rw.inverted_after == 0);
  HMO_CHECK(rn.msj_after > rn.msj_before && rw.msj_after > rw.msj_before);
  HMO_CHECK_CLOSE(rn.msj_after, recount_msj(narrow), 1e-12);
  HMO_CHECK_CLOSE(rw.msj_after, recount_msj(wide), 1e-12);
  HMO_CHECK(narrow.points != wide.points);
  // a bad number throws std::invalid_argument naming it, the mesh untouched
  const auto refused = [&input](const char* name, auto call) {
    Mesh b = input;
    bool thrown = false;
    try { call(b); }
    catch(const std::invalid_argument& e) { thrown = std::string(e.what()).find(name) != std::string::npos; }
    HMO_CHECK(thrown);
    HMO_CHECK(b.points == input.points);
  };
  for(const double bad : {0., -0.1, 1.5, std::nan("")})
    refused("turn_focus_band", [bad](Mesh& b) { CGAL::improve_hex_mesh_quality(b, add_internal_parameter(CGAL::parameters::default_values(), INP::turn_focus_band, bad)); });
  // the other numbers the library takes are checked alike (NaN included)
  for(const double bad : {-1.5, 1.5, std::nan("")})
    refused("target_msj", [bad](Mesh& b) { CGAL::improve_hex_mesh_quality(b, CGAL::parameters::target_msj(bad)); });
  for(const double bad : {-0.1, 1.5, std::nan("")})
  {
    refused("surface_tolerance", [bad](Mesh& b) { CGAL::optimize_hex_mesh(b, CGAL::parameters::surface_tolerance(bad)); });
    refused("surface_tolerance", [bad](Mesh& b) { CGAL::untangle_hex_mesh(b, CGAL::parameters::surface_tolerance(bad)); });
  }
  // the untangling's numbers, through all three functions, and the time limit
  const double nan = std::nan("");
  for(int f = 0; f < 3; ++f)
  {
    const auto through = [f](auto np) {
      return [f, np](Mesh& b) {
        if(f == 0) CGAL::untangle_hex_mesh(b, np);
        else if(f == 1) CGAL::improve_hex_mesh_quality(b, np);
        else CGAL::optimize_hex_mesh(b, np);
      };
    };
    for(const double bad : {-1., 181., nan})
    {
      refused("sharp_angle", through(CGAL::parameters::sharp_angle(bad)));
      refused("reference_feature_angle", through(CGAL::parameters::reference_feature_angle(bad)));
    }
    for(const double bad : {-1., 2e12, nan})
    {
      refused("alpha", through(add_internal_parameter(CGAL::parameters::default_values(), INP::alpha, bad)));
      refused("beta", through(add_internal_parameter(CGAL::parameters::default_values(), INP::beta, bad)));
    }
    for(const double bad : {-0.1, 11., nan}) refused("xi", through(add_internal_parameter(CGAL::parameters::default_values(), INP::xi, bad)));
    refused("local_iterations", through(add_internal_parameter(CGAL::parameters::default_values(), INP::local_iterations, 0)));
    refused("number_of_iterations", through(CGAL::parameters::number_of_iterations(-1)));
    for(const double bad : {-1., nan}) refused("maximum_running_time", through(CGAL::parameters::maximum_running_time(bad)));
  }
  for(const double bad : {-1., 181., nan})
    refused("crease_seed_angle", [bad](Mesh& b) { CGAL::improve_hex_mesh_quality(b, add_internal_parameter(CGAL::parameters::default_values(), INP::crease_seed_angle, bad)); });
}

static void test_never_worse()
{
  // a perfect grid cannot be improved: it comes back as it was, MSJ 1
  const int n = 3;
  Mesh g;
  {
    for(int k = 0; k <= n; ++k)
      for(int j = 0; j <= n; ++j)
        for(int i = 0; i <= n; ++i) g.points.emplace_back(i, j, k);
    g.hexahedra = hmo_test::structured_hexes(n, n, n);
  }
  const HMO::Optimization_result r = CGAL::improve_hex_mesh_quality(g);
  HMO_CHECK_CLOSE(r.msj_after, 1., 1e-9);
  HMO_CHECK(r.msj_after >= r.msj_before - 1e-12);
  HMO_CHECK_CLOSE(recount_msj(g), 1., 1e-9);
}

/// A valid mesh whose MSJ already meets the target is returned as it is,
/// measured and certified, with one stage that says so; a target above its
/// MSJ runs the stages.
static void test_nothing_to_do()
{
  const int n = 4;
  Mesh m = shell(n, 1.0);
  perturb_interior(m, n, 0.15, 3);
  const Mesh input = m;
  const double msj = CGAL::hex_mesh_quality(m).msj;
  HMO_CHECK(msj > 0.2 && msj < 0.95);
  Recorder rec;
  const HMO::Optimization_result r =
    CGAL::optimize_hex_mesh(m, CGAL::parameters::target_msj(msj - 0.05).visitor(std::ref(rec)));
  HMO_CHECK(m.points == input.points);
  HMO_CHECK(r.success && r.inverted_after == 0);
  HMO_CHECK(r.msj_before == msj && r.msj_after == msj);
  HMO_CHECK(r.certificate.hexes == m.hexahedra.size() && r.certificate.not_certified.empty());
  HMO_CHECK(r.surface_error == 0.);
  HMO_CHECK(r.stages.size() == 1 && r.stages[0].name == "at target");
  HMO_CHECK(rec.started.size() == 1 && rec.finished.size() == 1);
  // the same mesh with a target above its MSJ: the stages run and raise it
  Mesh again = input;
  const HMO::Optimization_result up = CGAL::improve_hex_mesh_quality(again, CGAL::parameters::target_msj(msj + 0.05));
  HMO_CHECK(up.stages.size() > 1 && up.msj_after > msj);
}

static void test_pipeline_on_tangled_mesh()
{
  // a shell with interior vertices pushed through their neighbours
  const int n = 5;
  Mesh m = shell(n, 1.0);
  perturb_interior(m, n, 0.9, 11);
  const std::size_t inverted = CGAL::hex_mesh_quality(m).inverted;
  HMO_CHECK(inverted > 0);
  const Mesh input = m;
  const HMO::Optimization_result r = CGAL::optimize_hex_mesh(m);
  HMO_CHECK(r.inverted_before == inverted);
  HMO_CHECK(r.inverted_after == 0);
  HMO_CHECK(CGAL::hex_mesh_quality(m).inverted == 0);
  HMO_CHECK(r.msj_after > 0.3);
  HMO_CHECK_CLOSE(r.msj_after, recount_msj(m), 1e-12);
  // the untangling stages come first, the quality stages after
  HMO_CHECK(!r.stages.empty());
  HMO_CHECK(r.stages.front().name == "interior");
  // ... the final ASJ smoothing, the give-back, then the projection onto
  // the surface (each with its check, when undone)
  std::size_t last = r.stages.empty() ? 0 : r.stages.size() - 1;
  if(last > 0 && r.stages[last].name == "check") --last;
  HMO_CHECK(last > 0 && r.stages[last].name == "projection");
  --last;
  if(last > 0 && r.stages[last].name == "check") --last;
  HMO_CHECK(last > 0 && r.stages[last].name == "give-back" && r.stages[last - 1].name == "asj");
  HMO_CHECK(CGAL::hex_mesh_surface_error(m, input) <= 0.01);
}

static void test_paper_method()
{
  // the paper's method alone: its stages only, in its order, never worse
  // (a 4³ shell in the sanitizer build: its blocks are checked against the
  // surface move by move)
  const int n = hmo_test::sanitized ? 4 : 5;
  Mesh m = shell(n, 1.0);
  perturb_interior(m, n, 0.6, 5);
  const CGAL::Hex_mesh_quality q0 = CGAL::hex_mesh_quality(m);
  HMO_CHECK(q0.inverted > 0);
  const HMO::Optimization_result r = CGAL::optimize_hex_mesh(m, CGAL::parameters::method(HMO::Method::paper));
  HMO_CHECK(r.inverted_after <= q0.inverted);
  if(r.inverted_after == q0.inverted) HMO_CHECK(r.msj_after >= q0.msj - 1e-12);
  HMO_CHECK_CLOSE(r.msj_after, recount_msj(m), 1e-12);
  HMO_CHECK(!r.stages.empty());
  HMO_CHECK(r.stages.front().name == "edge-angle");
  bool msj_stage = false;
  for(const HMO::Stage_report& s : r.stages)
  {
    // none of the package's additions
    HMO_CHECK(s.name != "interior" && s.name != "barrier" && s.name != "surface" &&
              s.name != "surface restoration" && s.name != "max-min");
    if(s.name.rfind("msj>=", 0) == 0)
    {
      msj_stage = true;
      // the stage's work is the edge-angle optimiser
      HMO_CHECK(s.details.find("edge-angle") != std::string::npos || s.msj_after >= std::stod(s.name.substr(5)));
      HMO_CHECK(s.details.find("max-min") == std::string::npos);
    }
  }
  HMO_CHECK(msj_stage || r.inverted_after > 0);
  // (it ends as the authors' scripts do: the ASJ smoothing, then the boundary projected keeping the MSJ)
  if(r.inverted_after == 0)
    HMO_CHECK(r.stages.size() >= 2 && r.stages.back().name == "projection" &&
              r.stages[r.stages.size() - 2].name == "asj");
  // the package's pipeline on the same input does at least as well
  Mesh p = shell(n, 1.0);
  perturb_interior(p, n, 0.6, 5);
  const HMO::Optimization_result rp = CGAL::optimize_hex_mesh(p);
  HMO_CHECK(rp.inverted_after == 0);
  HMO_CHECK(rp.stages.front().name == "interior");
}

static void test_paper_recipe()
{
  // a published run's recipe: its target in one MSJ stage, the SLIM
  // pull-back toward the input's vertices when α ended below its threshold
  const int n = 5;
  Mesh m = shell(n, 1.0);
  perturb_interior(m, n, 0.6, 5);
  const Mesh input = m;
  HMO::Paper_recipe recipe;
  recipe.alpha = recipe.beta = 100.;
  recipe.pull_back_below_alpha = 1e12;
  recipe.target_msj = 0.3;
  recipe.msj_in_steps = false;
  const HMO::Optimization_result r =
    CGAL::optimize_hex_mesh(m, CGAL::parameters::paper_recipe(recipe).method(HMO::Method::paper));
  HMO_CHECK(r.inverted_after == 0);
  for(const HMO::Stage_report& s : r.stages)
    HMO_CHECK(s.name.rfind("msj>=", 0) != 0 || s.name == "msj>=0.3");
  // the pull-back puts the boundary back on the input's, the MSJ stage keeps it within the tolerance
  HMO_CHECK(CGAL::hex_mesh_surface_error(m, input) <= 0.005);
  // package mode ignores the recipe: the same output with and without it
  Mesh a = input, b = input;
  CGAL::optimize_hex_mesh(a, CGAL::parameters::paper_recipe(recipe));
  CGAL::optimize_hex_mesh(b);
  HMO_CHECK(a.points == b.points);
}

static void test_lcc()
{
  const int n = 4;
  Mesh m = shell(n, 1.0);
  perturb_interior(m, n, 0.4, 5);
  LCC lcc;
  std::string why;
  HMO_CHECK(CGAL::build_linear_cell_complex(m, lcc, &why));
  const double before = CGAL::hex_mesh_quality(lcc).msj;
  const HMO::Optimization_result r = CGAL::improve_hex_mesh_quality(lcc, CGAL::parameters::target_msj(0.5));
  HMO_CHECK_CLOSE(r.msj_before, before, 1e-12);
  HMO_CHECK_CLOSE(CGAL::hex_mesh_quality(lcc).msj, r.msj_after, 1e-12);
  HMO_CHECK(r.msj_after >= 0.5);
}

/// The surface restoration stage: boundary vertices slid along a curved
/// face come back to their home positions (the surface error with them),
/// and no element falls below the floor.
static void test_boundary_restoration()
{
  using namespace HMO::internal;
  const int n = 4;
  const Mesh m = shell(n, 0.8);
  Hex_mesh_arrays input = make_hex_mesh_arrays(m, K());
  Hex_mesh_arrays a = input;
  // slide the inner-face vertices (k = 0, 0 < i < n) along the arc by a
  // third of an edge: the quads cut the cylinder, the mesh stays valid
  std::size_t slid = 0;
  for(int j = 0; j <= n; ++j)
    for(int i = 1; i < n; ++i)
    {
      const std::size_t v = std::size_t(j * (n + 1) + i);
      const double r = n, t = 0.8 * (i + 0.35) / n;
      a.points[v] = Vec3{r * std::cos(t), r * std::sin(t), double(j)};
      ++slid;
    }
  const double err_before = relative_surface_error(a, input);
  HMO_CHECK(err_before > 1e-3);
  const double msj_before = quality_statistics(a).msj;
  HMO_CHECK(msj_before > 0.);

  const Hex_mesh_topology topo(a);
  const Hex_mesh_boundary boundary = extract_boundary(input);
  std::vector<Vec3> ref_points;
  std::vector<Tri> ref_tris;
  triangulate_boundary(boundary, input.points, Quad_split::diagonal_02, ref_points, ref_tris);
  const Surface_guard guard(boundary, ref_points, ref_tris, input.points);
  Boundary_restoration_settings bs;
  bs.floor = msj_before;
  const Boundary_restoration_report br = restore_boundary(topo, guard, boundary.vertices, input.points, a.points, bs);
  HMO_CHECK(br.moves >= slid);
  HMO_CHECK(br.distance_before > 0.25); // an arc of 0.07 rad at radius 4
  HMO_CHECK(br.distance_after < 1e-12);
  HMO_CHECK(relative_surface_error(a, input) < 1e-9);
  HMO_CHECK(quality_statistics(a).msj >= msj_before - 1e-12);

  // a floor above what home allows: nothing moves below it
  Hex_mesh_arrays b = input;
  b.points[std::size_t(2 * (n + 1) + 2)] = b.points[std::size_t(2 * (n + 1) + 2)] + Vec3{0., 0., 0.3};
  const double msj_b = quality_statistics(b).msj;
  Boundary_restoration_settings high;
  high.floor = 2.; // min(floor, local minimum): no hex may get worse than it is
  restore_boundary(topo, guard, boundary.vertices, input.points, b.points, high);
  HMO_CHECK(quality_statistics(b).msj >= msj_b - 1e-12);
}

/// A reference surface that does not fit (moved far away) makes the three
/// functions throw Reference_mismatch before anything moves; one the
/// boundary starts off (the mesh's boundary grown by 5 %) runs, with a warning.
static void test_reference_fit()
{
  typedef CGAL::Surface_mesh<Point> Surface;
  Mesh m = shell(3, 0.5);
  auto boundary_of = [&](double scale, double shift) {
    using namespace HMO::internal;
    const Hex_mesh_arrays a = make_hex_mesh_arrays(m, K());
    std::vector<Vec3> pts;
    std::vector<Tri> tris;
    triangulate_boundary(extract_boundary(a), a.points, Quad_split::diagonal_02, pts, tris);
    Surface s;
    for(const Vec3& p : pts) s.add_vertex(Point(scale * p[0] + shift, scale * p[1], scale * p[2]));
    for(const Tri& t : tris)
      s.add_face(Surface::Vertex_index(t[0]), Surface::Vertex_index(t[1]), Surface::Vertex_index(t[2]));
    return s;
  };
  const Surface far = boundary_of(10., 1000.);
  const Mesh before = m;
  int thrown = 0;
  try { CGAL::improve_hex_mesh_quality(m, CGAL::parameters::reference_surface(far)); }
  catch(const HMO::Reference_mismatch& e)
  {
    ++thrown;
    HMO_CHECK(std::string(e.what()).find("do not overlap") != std::string::npos);
  }
  try { CGAL::optimize_hex_mesh(m, CGAL::parameters::reference_surface(far)); }
  catch(const HMO::Reference_mismatch&) { ++thrown; }
  try { CGAL::untangle_hex_mesh(m, CGAL::parameters::reference_surface(far)); }
  catch(const std::invalid_argument&) { ++thrown; } // Reference_mismatch is one
  HMO_CHECK(thrown == 3);
  HMO_CHECK(m.points == before.points); // untouched

  // the boundary scaled by 1.05 about the origin (the shell's axis): every
  // vertex 0.15 to 0.3 off, 2 to 4 % of the diagonal, under the 5 % of a
  // mismatch
  const Surface grown = boundary_of(1.05, 0.);
  Mesh moved = before; // (m stays as it is: `boundary_of` reads it)
  const HMO::Optimization_result r =
    CGAL::improve_hex_mesh_quality(moved, CGAL::parameters::reference_surface(grown));
  HMO_CHECK(!r.warnings.empty() && r.warnings[0].find("starts off the reference") != std::string::npos);
  // the quality stages keep the surface error where it was: the vertices
  // still beyond the tolerance are listed, with a second warning
  HMO_CHECK(!r.off_surface.empty());
  HMO_CHECK(r.warnings.size() == 2 && r.warnings[1].find("farther from the reference surface") != std::string::npos);
  Mesh again = before;
  const HMO::Optimization_result r_own =
    CGAL::improve_hex_mesh_quality(again, CGAL::parameters::reference_surface(boundary_of(1., 0.)));
  HMO_CHECK(r_own.warnings.empty());
}

/// Properties over 105 perturbed variants of small meshes built here (grids
/// and a cylinder, every vertex or the interior ones moved by 0.1 to 0.7 of
/// the mean edge in random directions; fixed seeds): the whole pipeline never
/// returns a mesh worse than its input (inverted count, then MSJ, and the
/// count not certified valid), never a NaN or infinite coordinate, keeps the
/// connectivity, and is certified valid whenever it reports 0 inverted.
static void test_properties()
{
  int variants = 0, tangled = 0, untangled = 0, kept = 0;
  std::size_t inverted_before = 0, inverted_after = 0;
  // 3 of them in the sanitizer build (every run goes through the same
  // stages): the 3 meshes, both sets of moving vertices, small and large
  // amplitudes
  for(int v = 0; v < 105; ++v)
  {
    if(hmo_test::sanitized && v != 0 && v != 25 && v != 104) continue;
    const hmo_test::HMOI::Hex_mesh_arrays base =
      v % 3 == 0 ? hmo_test::grid(4, 4, 4) : v % 3 == 1 ? hmo_test::grid(6, 3, 2, 2., 1., 0.7)
                                                        : hmo_test::cylinder(4, 3, 1.5);
    Mesh m;
    for(const auto& p : base.points) m.points.emplace_back(p[0], p[1], p[2]);
    m.hexahedra.assign(base.hexes.begin(), base.hexes.end());
    // mean edge length
    double edge = 0.;
    for(const auto& h : m.hexahedra)
      for(int e = 0; e < 4; ++e) edge += std::sqrt(CGAL::squared_distance(m.points[h[e]], m.points[h[(e + 1) % 4]]));
    edge /= 4. * double(m.hexahedra.size());
    // which vertices move: all (even variants) or those off the box faces
    std::vector<bool> boundary(m.points.size(), false);
    {
      std::map<std::array<std::size_t, 4>, int> faces;
      for(const auto& h : m.hexahedra)
        for(const auto& f : {std::array<int, 4>{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}})
        {
          std::array<std::size_t, 4> q{h[f[0]], h[f[1]], h[f[2]], h[f[3]]};
          std::sort(q.begin(), q.end());
          ++faces[q];
        }
      for(const auto& f : faces)
        if(f.second == 1)
          for(std::size_t w : f.first) boundary[w] = true;
    }
    std::mt19937 rng(1000 + v);
    std::normal_distribution<double> g(0., 1.);
    const double amplitude = 0.1 + 0.6 * double(v % 7) / 6.;
    for(std::size_t w = 0; w < m.points.size(); ++w)
    {
      K::Vector_3 d(g(rng), g(rng), g(rng));
      d = d / std::sqrt(d.squared_length());
      if(v % 2 == 1 && boundary[w]) continue;
      m.points[w] = m.points[w] + amplitude * edge * d;
    }
    const Mesh input = m;
    const CGAL::Hex_mesh_quality q0 = CGAL::hex_mesh_quality(m);
    const HMO::Validity_certificate c0 = CGAL::hex_mesh_validity_certificate(m);
    const HMO::Optimization_result r = CGAL::optimize_hex_mesh(m);
    const CGAL::Hex_mesh_quality q1 = CGAL::hex_mesh_quality(m);
    const HMO::Validity_certificate c1 = CGAL::hex_mesh_validity_certificate(m);
    ++variants;
    tangled += q0.inverted > 0;
    untangled += q0.inverted > 0 && q1.inverted == 0;
    kept += r.kept_input;
    inverted_before += q0.inverted;
    inverted_after += q1.inverted;
    bool finite = true;
    for(const Point& p : m.points) finite = finite && std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z());
    HMO_CHECK(finite);
    HMO_CHECK(m.hexahedra == input.hexahedra && m.points.size() == input.points.size());
    HMO_CHECK(q1.inverted <= q0.inverted);
    if(q1.inverted == q0.inverted) HMO_CHECK(q1.msj >= q0.msj - 1e-12);
    HMO_CHECK(c1.not_certified.size() <= c0.not_certified.size());
    HMO_CHECK(r.inverted_after == q1.inverted && r.certificate.not_certified == c1.not_certified);
    if(q1.inverted == 0) HMO_CHECK(c1.all_valid());
    if(q1.inverted > q0.inverted || !finite)
      std::cerr << "variant " << v << ": inverted " << q0.inverted << " -> " << q1.inverted << std::endl;
  }
  std::cout << "properties: " << variants << " variants, " << tangled << " tangled (" << inverted_before
            << " inverted hexes), " << untangled << " of them untangled, " << inverted_after
            << " inverted left in all; " << kept << " returned their input" << std::endl;
}

/// A cylinder (27 hexes, twisted) refined twice: the refinement is
/// recognised from the connectivity alone, both levels, with the coarse
/// hexes those refined (same corners, same orientation); carried down,
/// positions give the refinement's points; meshes that are no refinement
/// are not recognised. Then the coarse-level start of the quality stages
/// moves a valid refined mesh (a bent grid) to a start of higher MSJ.
static void test_coarse_level_start()
{
  namespace I = HMO::internal;
  I::Hex_mesh_arrays m = hmo_test::cylinder(3, 3, 1.5);
  for(I::Vec3& p : m.points) // a twist about the axis, growing with the height
  {
    const double a = 0.5 * p[2], x = p[0], y = p[1];
    p[0] = std::cos(a) * x - std::sin(a) * y;
    p[1] = std::sin(a) * x + std::cos(a) * y;
  }
  const I::Hex_mesh_arrays r1 = I::refine_1_to_8(m), r2 = I::refine_1_to_8(r1);
  HMO_CHECK(r2.hexes.size() == 8 * 8 * 27);

  I::Refinement_level l1, l0;
  HMO_CHECK(I::recognise_refinement(r2, l1));
  HMO_CHECK(l1.coarse.hexes.size() == r1.hexes.size());
  HMO_CHECK(I::recognise_refinement(l1.coarse, l0));
  HMO_CHECK(l0.coarse.hexes.size() == m.hexes.size());
  // the coarse hexes are r1's (the refinement keeps the coarse points'
  // indices), up to a rotation: the same vertex sets and scaled Jacobians
  std::map<std::array<std::size_t, 8>, double> r1_sj;
  for(std::size_t h = 0; h < r1.hexes.size(); ++h)
  {
    std::array<std::size_t, 8> key = r1.hexes[h];
    std::sort(key.begin(), key.end());
    r1_sj[key] = I::scaled_jacobian(r1.corners(h));
  }
  std::size_t matched = 0;
  for(std::size_t h = 0; h < l1.coarse.hexes.size(); ++h)
  {
    std::array<std::size_t, 8> key;
    for(int q = 0; q < 8; ++q) key[q] = l1.coarse_to_fine[l1.coarse.hexes[h][q]];
    std::sort(key.begin(), key.end());
    const auto it = r1_sj.find(key);
    if(it != r1_sj.end() && std::abs(it->second - I::scaled_jacobian(l1.coarse.corners(h))) < 1e-12) ++matched;
  }
  HMO_CHECK(matched == r1.hexes.size());
  // positions carried down two levels are the refinement's points
  std::vector<I::Vec3> fine = I::prolongate(l1, I::prolongate(l0, l0.coarse.points));
  double worst = 0.;
  for(std::size_t v = 0; v < fine.size(); ++v) worst = (std::max)(worst, I::norm(I::operator-(fine[v], r2.points[v])));
  HMO_CHECK(fine.size() == r2.points.size() && worst < 1e-12);
  // no refinement: the original 27 hexes, a 3×4×4 grid, and a refined mesh
  // with one hex split along a face (its children no longer 8 around a centre)
  I::Refinement_level none;
  HMO_CHECK(!I::recognise_refinement(m, none));
  HMO_CHECK(!I::recognise_refinement(hmo_test::grid(3, 4, 4), none));
  I::Hex_mesh_arrays broken = r1;
  std::swap(broken.hexes[0][0], broken.hexes[0][1]);
  HMO_CHECK(!I::recognise_refinement(broken, none));

  // the start, on a 4×4×4 grid whose interior is bent (a smooth shift, zero
  // on the boundary) refined twice, the schedule's size floor lowered to it
  // (in the sanitizer build a 2×2×2 grid, its centre bent, refined once: the
  // same two levels, a reference of 192 triangles instead of 6144 for the
  // coarse level's surface checks)
  I::Hex_mesh_arrays bent = hmo_test::sanitized ? hmo_test::grid(2, 2, 2) : hmo_test::grid(4, 4, 4);
  for(I::Vec3& p : bent.points)
  {
    const double w = 0.2 * std::sin(CGAL_PI * p[0]) * std::sin(CGAL_PI * p[1]) * std::sin(CGAL_PI * p[2]);
    p[0] += w;
    p[1] += 0.5 * w;
  }
  const I::Hex_mesh_arrays bent2 =
    hmo_test::sanitized ? I::refine_1_to_8(bent) : I::refine_1_to_8(I::refine_1_to_8(bent));
  I::Quality_settings s;
  s.schedule.coarse_level_min_hexes = 8;
  I::Hex_mesh_arrays mesh = bent2;
  const double msj_in = I::quality_statistics(mesh).msj;
  std::vector<I::Vec3> points;
  std::vector<I::Tri> triangles;
  I::Quality_settings fine_settings;
  HMO::Optimization_result res;
  Recorder rec;
  const bool used = I::coarse_level_start(mesh, s, rec, points, triangles, fine_settings, res);
  HMO_CHECK(used);
  HMO_CHECK(!res.stages.empty() && res.stages.back().name == "coarse level");
  HMO_CHECK(res.msj_before == msj_in);
  const I::Quality_statistics q = I::quality_statistics(mesh);
  HMO_CHECK(q.inverted == 0 && q.msj > msj_in + 0.05);
  HMO_CHECK(fine_settings.reference_points == &points && !triangles.empty());
  std::cout << "coarse-level start on the bent grid (" << bent2.hexes.size() << " hexahedra): MSJ "
            << msj_in << " -> " << q.msj
            << (res.stages.empty() ? std::string() : " (" + res.stages.back().details + ")") << std::endl;
  // the paper's schedule has no such start
  I::Quality_settings paper = s;
  paper.schedule = I::Optimization_schedule::paper();
  I::Hex_mesh_arrays untouched = bent2;
  HMO::Optimization_result none_result;
  HMO_CHECK(!I::coarse_level_start(untouched, paper, rec, points, triangles, fine_settings, none_result));
  HMO_CHECK(untouched.points == bent2.points && none_result.stages.empty());
}

// ------------------------------------------------ constrained vertices, stage by stage

namespace HMOI = CGAL::Hexahedral_mesh_optimization::internal;
using HMOI::operator+;
using HMOI::operator*;

/// A visitor of the untangler and of the improver (internal drivers, which
/// work on the caller's arrays in place, normalised) that watches the
/// vertices between its events: at every event, a vertex not where it was at
/// the previous event was moved by the stage the event names. It collects
/// those stage names for the constrained vertices (`moved_constrained`: must
/// stay empty) and for the others (`moved_free`: the stages that did move
/// something). The drivers' final safety net (`restore_unmoved_vertices()`)
/// comes after the last event, so it cannot hide a stage's move from this.
struct Constrained_watch : HMO::Default_optimization_visitor
{
  const HMOI::Hex_mesh_arrays* mesh = nullptr;
  std::vector<HMOI::Vec3> last;
  std::vector<std::string> events;
  std::set<std::string> moved_constrained, moved_free;

  void look(const std::string& stage)
  {
    events.push_back(stage);
    if(last.size() == mesh->points.size())
      for(std::size_t v = 0; v < last.size(); ++v)
        if(mesh->points[v] != last[v]) (mesh->is_constrained(v) ? moved_constrained : moved_free).insert(stage);
    last = mesh->points;
  }
  void stage_started(const std::string& name, std::size_t) { look(name); }
  void round_finished(const std::string& stage, int, std::size_t) { look(stage); }
  void stage_finished(const HMO::Stage_report& r) { look(r.name); }
};

static std::string names(const std::set<std::string>& s)
{
  std::string out;
  for(const std::string& n : s) out += (out.empty() ? "" : ", ") + n;
  return out;
}

/// the 4 × 4 × 4 grid of unit cubes, every vertex with i + j + k odd
/// constrained (each free vertex has only constrained neighbours along the
/// edges), and with `tangled` two free vertices pushed through their
/// neighbours: (2, 2, 2) past (3, 3, 3), and (1, 1, 2) out through the
/// boundary face x = 0
static HMOI::Hex_mesh_arrays constrained_grid(bool tangled)
{
  HMOI::Hex_mesh_arrays m = hmo_test::grid(4, 4, 4, 4., 4., 4.);
  m.constrained.assign(m.points.size(), 0);
  for(std::size_t v = 0; v < m.points.size(); ++v)
  {
    const std::size_t i = v % 5, j = (v / 5) % 5, k = v / 25;
    m.constrained[v] = (i + j + k) % 2;
  }
  if(tangled)
  {
    m.points[2 + 5 * 2 + 25 * 2] = HMOI::Vec3{3.4, 3.4, 3.4};
    m.points[1 + 5 * 1 + 25 * 2] = HMOI::Vec3{-0.4, -0.4, 2.};
  }
  return m;
}

/// the boundary of the box [0, 4]³, two triangles a face
static void box_reference(std::vector<HMOI::Vec3>& points, std::vector<HMOI::Tri>& triangles)
{
  const HMOI::Hex_mesh_arrays cube = hmo_test::grid(1, 1, 1, 4., 4., 4.);
  HMOI::triangulate_boundary(HMOI::extract_boundary(cube), cube.points, HMOI::Quad_split::diagonal_02, points, triangles);
}

/// checks a watched run: no stage moved a constrained vertex; the stages
/// `expected` ran and moved free vertices
static void check_watch(const Constrained_watch& w, const HMOI::Hex_mesh_arrays& out, const HMOI::Hex_mesh_arrays& in,
                        const std::vector<std::string>& expected, const char* what)
{
  if(!w.moved_constrained.empty())
    std::cerr << what << ": constrained vertices moved in: " << names(w.moved_constrained) << std::endl;
  HMO_CHECK(w.moved_constrained.empty());
  for(const std::string& stage : expected)
  {
    if(!w.moved_free.count(stage))
      std::cerr << what << ": stage " << stage << " moved nothing (stages that did: " << names(w.moved_free) << ")" << std::endl;
    HMO_CHECK(w.moved_free.count(stage) == 1);
  }
  for(std::size_t v = 0; v < in.points.size(); ++v)
    if(in.is_constrained(v)) HMO_CHECK(out.points[v] == in.points[v]);
}

/// the untangler's stages with constrained vertices: "interior", then
/// "edge-angle" alone and "barrier" alone (the schedule's switches), each
/// with "surface" after it
static void test_constrained_untangling_stages()
{
  struct Run
  {
    const char* what;
    bool interior, edge_angle, barrier;
    std::vector<std::string> expected;
  };
  const Run runs[] = {{"interior", true, false, false, {"interior"}},
                      {"edge-angle", false, true, false, {"edge-angle"}},
                      {"barrier", false, false, true, {"barrier"}}};
  for(const Run& run : runs)
  {
    const HMOI::Hex_mesh_arrays input = constrained_grid(true);
    HMO_CHECK(HMOI::quality_statistics(input).inverted > 0);
    HMOI::Hex_mesh_arrays m = input;
    HMOI::Untangle_settings s;
    s.schedule.interior_stage = run.interior;
    s.schedule.edge_angle_stage = run.edge_angle;
    s.schedule.barrier_stage = run.barrier;
    s.barrier_fallback = run.interior || run.barrier;
    Constrained_watch w;
    w.mesh = &m;
    HMOI::Hex_mesh_untangler<Constrained_watch> untangler(s, w);
    const HMO::Optimization_result r = untangler.run(m);
    HMO_CHECK(r.inverted_after < r.inverted_before);
    HMO_CHECK(std::find(w.events.begin(), w.events.end(), "surface") != w.events.end());
    check_watch(w, m, input, run.expected, run.what);
  }
}

/// the improver's stages with constrained vertices, against the box's
/// boundary as reference, on the untangled grid with its interior moved at
/// random and its boundary moved off the reference (the surface fit alone:
/// test_target_surface)
static void test_constrained_quality_stages()
{
  std::vector<HMOI::Vec3> ref_points;
  std::vector<HMOI::Tri> ref_triangles;
  box_reference(ref_points, ref_triangles);
  const HMOI::Hex_mesh_arrays input = [] {
    HMOI::Hex_mesh_arrays rough = constrained_grid(false);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1., 1.);
    for(std::size_t v = 0; v < rough.points.size(); ++v)
    {
      const std::size_t i = v % 5, j = (v / 5) % 5, k = v / 25;
      const int on_faces = (i == 0 || i == 4) + (j == 0 || j == 4) + (k == 0 || k == 4);
      HMOI::Vec3& p = rough.points[v];
      if(on_faces == 0) p = p + 0.3 * HMOI::Vec3{u(rng), u(rng), u(rng)};
      else if(on_faces == 1) // off its face, along the face's normal
        for(int c = 0; c < 3; ++c)
          if(p[c] == 0. || p[c] == 4.) p[c] += 0.08 * u(rng);
    }
    return rough;
  }();
  HMO_CHECK(HMOI::quality_statistics(input).inverted == 0);
  HMOI::Hex_mesh_arrays m = input;
  HMOI::Quality_settings s;
  s.reference_points = &ref_points;
  s.reference_triangles = &ref_triangles;
  s.surface_tolerance = 0.002;
  Constrained_watch w;
  w.mesh = &m;
  HMOI::Hex_mesh_quality_improver<Constrained_watch> improver(s, w);
  improver.run(m, input);
  check_watch(w, m, input, {"pull-back", "surface restoration", "max-min", "asj", "asj-interior", "projection"},
              "rough grid");
}

/// A boundary layer (a grid graded from a flat wall at z = 0, first layer
/// 1e-3, growth 1.3) with one vertex of the second layer pushed below the
/// first: the repair stays where it was broken (issue 49). Only the pushed
/// vertex and vertices of its one-ring (26 in a grid) move; the wall stays
/// exactly flat, and the first-layer heights keep within 10 % of the input's.
/// the unit square's n x n grid over a wall at z = 0, graded in z: first
/// layer 1e-3, growth 1.3, `layers` layers (their heights in `z`)
static Mesh graded_wall_grid(int n, int layers, std::vector<double>& z)
{
  Mesh m;
  z.assign(1, 0.);
  for(int k = 0; k < layers; ++k) z.push_back(z.back() + 1e-3 * std::pow(1.3, k));
  for(int k = 0; k <= layers; ++k)
    for(int j = 0; j <= n; ++j)
      for(int i = 0; i <= n; ++i) m.points.emplace_back(double(i) / n, double(j) / n, z[std::size_t(k)]);
  m.hexahedra = hmo_test::structured_hexes(n, n, layers);
  return m;
}

static void test_boundary_layer_kept()
{
  const int n = 10, layers = 8;
  std::vector<double> z;
  Mesh m = graded_wall_grid(n, layers, z);
  auto id = [&](int i, int j, int k) { return std::size_t(i + (n + 1) * (j + (n + 1) * k)); };
  const Mesh input = m;
  const std::size_t pushed = id(n / 2, n / 2, 2);
  m.points[pushed] = Point(m.points[pushed].x(), m.points[pushed].y(), 0.5 * z[1]);
  HMO_CHECK(CGAL::hex_mesh_quality(m).inverted > 0);
  const HMO::Optimization_result r = CGAL::optimize_hex_mesh(m);
  HMO_CHECK(r.inverted_after == 0);
  std::size_t moved = 0;
  for(std::size_t v = 0; v < m.points.size(); ++v) moved += m.points[v] != input.points[v];
  HMO_CHECK(moved <= 27);
  std::size_t off_wall = 0, changed = 0;
  for(int j = 0; j <= n; ++j)
    for(int i = 0; i <= n; ++i)
    {
      off_wall += m.points[id(i, j, 0)].z() != 0.;
      const double h = m.points[id(i, j, 1)].z() - m.points[id(i, j, 0)].z();
      changed += std::abs(h - z[1]) > 0.1 * z[1];
    }
  HMO_CHECK(off_wall == 0);
  HMO_CHECK(changed == 0);
  std::cout << "boundary layer: inverted " << r.inverted_before << " -> " << r.inverted_after << ", MSJ " << r.msj_after
            << ", " << moved << " vertices moved\n";
}

/// `vertex_is_constrained_map` of an Indexed_hex_mesh: vertex v is constrained when (*mask)[v]
struct Constrained_vertices
{
  typedef std::size_t key_type;
  typedef bool value_type;
  typedef bool reference;
  typedef boost::readable_property_map_tag category;
  const std::vector<bool>* mask;
  friend bool get(const Constrained_vertices& m, std::size_t v) { return (*m.mask)[v]; }
};

/// `local_surface_tolerance`: with it, the boundary of a repaired boundary
/// layer stays within that fraction of each wall vertex's first-cell
/// height, and the report is empty; a boundary vertex that cannot go back
/// (constrained, off its reference) is reported with its distance and what
/// it was allowed, with a warning; NaN is refused
static void test_local_surface_tolerance()
{
  const int n = 8, layers = 6;
  std::vector<double> z;
  Mesh m = graded_wall_grid(n, layers, z);
  auto id = [&](int i, int j, int k) { return std::size_t(i + (n + 1) * (j + (n + 1) * k)); };
  const std::size_t pushed = id(n / 2, n / 2, 2);
  m.points[pushed] = Point(m.points[pushed].x(), m.points[pushed].y(), 0.5 * z[1]);
  HMO_CHECK(CGAL::hex_mesh_quality(m).inverted > 0);
  const double local = 0.01;
  const HMO::Optimization_result r = CGAL::optimize_hex_mesh(m, CGAL::parameters::local_surface_tolerance(local));
  HMO_CHECK(r.inverted_after == 0);
  HMO_CHECK(r.off_surface.empty());
  double worst_wall = 0.;
  for(int j = 0; j <= n; ++j)
    for(int i = 0; i <= n; ++i) worst_wall = (std::max)(worst_wall, std::abs(m.points[id(i, j, 0)].z()));
  HMO_CHECK(worst_wall <= local * z[1]);

  // a constrained wall vertex lifted off the reference (the flat box) stays there: reported
  typedef CGAL::Surface_mesh<Point> Surface;
  std::vector<double> z2;
  Mesh lifted = graded_wall_grid(n, layers, z2);
  Surface box;
  {
    using namespace HMO::internal;
    const Hex_mesh_arrays a = make_hex_mesh_arrays(lifted, K());
    std::vector<Vec3> pts;
    std::vector<Tri> tris;
    triangulate_boundary(extract_boundary(a), a.points, Quad_split::diagonal_02, pts, tris);
    for(const Vec3& p : pts) box.add_vertex(Point(p[0], p[1], p[2]));
    for(const Tri& t : tris) box.add_face(Surface::Vertex_index(t[0]), Surface::Vertex_index(t[1]), Surface::Vertex_index(t[2]));
  }
  const std::size_t held = id(3, 5, 0);
  lifted.points[held] = Point(lifted.points[held].x(), lifted.points[held].y(), 2e-4);
  std::vector<bool> constrained(lifted.points.size(), false);
  constrained[held] = true;
  const Constrained_vertices is_constrained{&constrained};
  const HMO::Optimization_result q = CGAL::improve_hex_mesh_quality(
    lifted, CGAL::parameters::reference_surface(box).local_surface_tolerance(local).vertex_is_constrained_map(is_constrained));
  HMO_CHECK(q.off_surface.size() == 1);
  if(!q.off_surface.empty())
  {
    HMO_CHECK(q.off_surface[0].vertex == held);
    HMO_CHECK(std::abs(q.off_surface[0].distance - 2e-4) <= 1e-12);
    HMO_CHECK(std::abs(q.off_surface[0].local_length - (z2[1] - 2e-4)) <= 1e-12); // its first cell, as given
    HMO_CHECK(q.off_surface[0].allowed <= local * q.off_surface[0].local_length + 1e-15);
  }
  HMO_CHECK(!q.warnings.empty());

  bool refused = false;
  try { CGAL::optimize_hex_mesh(m, CGAL::parameters::local_surface_tolerance(std::nan(""))); }
  catch(const std::invalid_argument&) { refused = true; }
  HMO_CHECK(refused);
  std::cout << "local surface tolerance: wall within " << worst_wall << " (first layer " << z[1] << "), "
            << q.off_surface.size() << " vertex reported\n";
}

HMO_TEST_MAIN(test_improve_quality)
{
  HMO_CASE(test_properties());
  HMO_CASE(test_boundary_restoration());
  HMO_CASE(test_reference_fit());
  HMO_CASE(test_stage_schedule());
  HMO_CASE(test_turn_focus_band());
  HMO_CASE(test_never_worse());
  HMO_CASE(test_nothing_to_do());
  HMO_CASE(test_pipeline_on_tangled_mesh());
  HMO_CASE(test_paper_method());
  HMO_CASE(test_paper_recipe());
  HMO_CASE(test_lcc());
  HMO_CASE(test_coarse_level_start());
  HMO_CASE(test_constrained_untangling_stages());
  HMO_CASE(test_constrained_quality_stages());
  HMO_CASE(test_boundary_layer_kept());
  HMO_CASE(test_local_surface_tolerance());
  return hmo_test::report(argv[0]);
}

} // namespace test_improve_quality
