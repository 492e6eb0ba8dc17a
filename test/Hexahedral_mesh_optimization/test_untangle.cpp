// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Untangling on synthetic tangled meshes of our own: perturbed grids, an
// inverted element on the boundary, a corner element, a curved block; the
// monotonicity of the edge-angle stage and of every stage's report; the
// surface error bound where the boundary was clean or must come back; the
// result object against an independent recount; the never-worse guarantee;
// the LCC overload.

#include "test_meshes.h"
#include "test_util.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Hexahedral_mesh_optimization/Linear_cell_complex_hex_mesh.h>
#include <CGAL/Linear_cell_complex_for_combinatorial_map.h>
#include <CGAL/hex_mesh_quality.h>
#include <CGAL/untangle_hex_mesh.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Pipeline/Hex_mesh_untangler.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/global_control.h>
#endif

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace test_untangle {

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point;
typedef CGAL::Indexed_hex_mesh<Point> Mesh;
typedef CGAL::Linear_cell_complex_traits<3, K> LCC_traits;
typedef CGAL::Linear_cell_complex_for_combinatorial_map<3, 3, LCC_traits> LCC;
namespace HMO = CGAL::Hexahedral_mesh_optimization;

/// n×n×n grid of unit cubes; `bend` > 0 bends it into a cylindrical shell sector
static Mesh grid(int n, double bend = 0.)
{
  Mesh m;
  for(int k = 0; k <= n; ++k)
    for(int j = 0; j <= n; ++j)
      for(int i = 0; i <= n; ++i)
      {
        if(bend == 0.) { m.points.emplace_back(i, j, k); continue; }
        const double r = n + k, a = bend * i / n;
        m.points.emplace_back(r * std::cos(a), r * std::sin(a), j);
      }
  m.hexahedra = hmo_test::structured_hexes(n, n, n);
  return m;
}

static std::size_t recount_inverted(const Mesh& m)
{
  std::size_t n = 0;
  for(const auto& h : m.hexahedra)
  {
    std::array<Point, 8> c;
    for(int i = 0; i < 8; ++i) c[i] = m.points[h[i]];
    if(CGAL::hex_scaled_jacobian(c) < 0.) ++n;
  }
  return n;
}

/// records the bad counts the edge-angle stage reports after each round
struct Recording_visitor : HMO::Default_optimization_visitor
{
  std::vector<std::size_t> left;
  std::vector<std::string> stages;
  void round_finished(const std::string& stage, int, std::size_t bad)
  {
    if(stage == "edge-angle") left.push_back(bad);
  }
  void stage_finished(const HMO::Stage_report& r) { stages.push_back(r.name); }
};

/// `max_surface_error` < 0: not checked; `boundary_kept`: the inversions
/// are all freed by the interior, so no vertex on the grid's faces may move
static void check_untangled(Mesh& m, const char* what, double max_surface_error = -1., bool boundary_kept = false)
{
  const Mesh input = m;
  const std::size_t before = recount_inverted(m);
  HMO_CHECK(before > 0);
  Recording_visitor vis;
  const HMO::Optimization_result r = CGAL::untangle_hex_mesh(m, CGAL::parameters::visitor(std::ref(vis)));
  const std::size_t after = recount_inverted(m);
  std::cout << what << ": inverted " << before << " -> " << after << ", MSJ " << r.msj_after
            << ", surface error " << r.surface_error << ", " << r.seconds << " s" << std::endl;
  HMO_CHECK(r.inverted_before == before);
  HMO_CHECK(r.inverted_after == after);
  HMO_CHECK(after == 0);
  HMO_CHECK(r.success);
  // the barrier with the boundary fixed first, then the edge-angle optimiser
  // on what it left, if it left anything
  HMO_CHECK(r.stages.size() >= 2 && r.stages[0].name == "interior");
  if(r.stages.size() >= 2)
  {
    if(r.stages[0].inverted_after > 0) HMO_CHECK(r.stages[1].name == "edge-angle");
    else
      for(const HMO::Stage_report& s : r.stages) HMO_CHECK(s.name != "edge-angle" && s.name != "barrier");
  }
  if(boundary_kept)
  {
    HMO_CHECK(r.stages[0].inverted_after == 0);
    double lo = 1e300, hi = -1e300;
    for(const Point& p : input.points) { lo = (std::min)(lo, p.x()); hi = (std::max)(hi, p.x()); }
    std::size_t on_faces = 0;
    for(std::size_t v = 0; v < m.points.size(); ++v)
    {
      const Point& p = input.points[v];
      const bool on_face = p.x() == lo || p.x() == hi || p.y() == lo || p.y() == hi || p.z() == lo || p.z() == hi;
      if(!on_face) continue;
      ++on_faces;
      HMO_CHECK(m.points[v] == p);
    }
    HMO_CHECK(on_faces > 0);
  }
  HMO_CHECK_CLOSE(r.msj_after, CGAL::hex_mesh_quality(m).msj, 1e-12);
  for(std::size_t i = 1; i < vis.left.size(); ++i) HMO_CHECK(vis.left[i] <= vis.left[i - 1]);
  HMO_CHECK(vis.stages.size() == r.stages.size());
  // every stage reports a count that does not rise, and the stages chain
  for(std::size_t i = 0; i < r.stages.size(); ++i)
  {
    HMO_CHECK(r.stages[i].inverted_after <= r.stages[i].inverted_before);
    if(i > 0) HMO_CHECK(r.stages[i].inverted_before == r.stages[i - 1].inverted_after);
  }
  // ... the surface pass, then the give-back
  HMO_CHECK(r.stages.size() >= 2 && r.stages.back().name == "give-back" && r.stages[r.stages.size() - 2].name == "surface");
  if(max_surface_error >= 0.) HMO_CHECK(r.surface_error <= max_surface_error);
}

/// The elements left inverted are listed with their reason: a corner hex
/// whose grid corner is pushed inside is "locked" (its inverted corner frame
/// has only boundary vertices); hexes inverted by the grid's centre vertex
/// (interior) are "region_exhausted", or "time_limit" when the stop fired.
static void test_unresolved_elements()
{
  namespace HMOI = HMO::internal;
  Mesh m = grid(2);
  m.points[0] = Point(0.8, 0.8, 0.8);   // grid corner: boundary, and so are its 3 neighbours in hex 0
  m.points[13] = Point(2.6, 2.6, 2.6);  // the grid's centre (1, 1, 1): interior
  const HMOI::Hex_mesh_arrays a = HMOI::make_hex_mesh_arrays(m, K());
  const std::size_t inverted = recount_inverted(m);
  HMO_CHECK(inverted >= 2);
  const std::vector<HMO::Unresolved_element> u = HMOI::unresolved_elements(a, false);
  HMO_CHECK(u.size() == inverted);
  std::size_t locked = 0, exhausted = 0;
  for(const HMO::Unresolved_element& e : u)
  {
    HMO_CHECK(e.scaled_jacobian < 0.);
    HMO_CHECK_CLOSE(e.scaled_jacobian, CGAL::hex_mesh_scaled_jacobians(m)[e.hex], 1e-12);
    if(e.reason == HMO::Unresolved_element::locked) ++locked;
    if(e.reason == HMO::Unresolved_element::region_exhausted) ++exhausted;
  }
  HMO_CHECK(!u.empty() && u[0].hex == 0 && u[0].reason == HMO::Unresolved_element::locked);
  HMO_CHECK(u[0].details.find("corner 0 (vertex 0)") != std::string::npos);
  HMO_CHECK(exhausted >= 1);
  HMO_CHECK(locked + exhausted == u.size());
  for(const HMO::Unresolved_element& e : HMOI::unresolved_elements(a, true))
    HMO_CHECK(e.reason != HMO::Unresolved_element::region_exhausted);

  // through the public function, stopped at once by its time limit: every
  // element still inverted is listed
  Mesh stopped = m;
  const HMO::Optimization_result r = CGAL::untangle_hex_mesh(stopped, CGAL::parameters::maximum_running_time(1e-9));
  HMO_CHECK(r.time_limit_reached);
  HMO_CHECK(r.inverted_after > 0 && r.unresolved.size() == r.inverted_after);
  // run to the end, nothing is left and nothing is listed
  Mesh whole = m;
  const HMO::Optimization_result full = CGAL::untangle_hex_mesh(whole);
  HMO_CHECK(full.unresolved.size() == full.inverted_after);
}

/// The surface stage (`pull_back_to_surface`) on a 6^3 grid (spacing 0.025,
/// the pipeline's normalised scale) whose boundary was blown up by 10 % off
/// its reference (the cube) and whose centre vertex was pushed through its
/// cells: the inverted hexes stay as they are, and the boundary still comes
/// back. Before the inverted hexes were pinned, the one region the
/// displaced boundary makes refused to move at all.
static void test_surface_stage_with_inverted_hex()
{
  namespace HI = HMO::internal;
  using HI::operator+;
  using HI::operator-;
  using HI::operator*;
  const int n = 6;
  const double h = 0.025, side = n * h;
  HI::Hex_mesh_arrays m;
  for(int k = 0; k <= n; ++k)
    for(int j = 0; j <= n; ++j)
      for(int i = 0; i <= n; ++i) m.points.push_back({i * h, j * h, k * h});
  m.hexes = hmo_test::structured_hexes(n, n, n);
  const HI::Hex_mesh_topology topo(m);
  const HI::Vec3 centre{0.5 * side, 0.5 * side, 0.5 * side};
  for(std::size_t v = 0; v < m.points.size(); ++v)
    if(topo.is_boundary_vertex(v)) m.points[v] = centre + 1.1 * (m.points[v] - centre);
  const std::size_t middle = 3 + 7 * (3 + 7 * 3);
  m.points[middle][0] += 1.5 * h;
  // the reference: the cube's 6 faces, 2 triangles each
  std::vector<HI::Vec3> rp;
  for(int c = 0; c < 8; ++c) rp.push_back({(c & 1) * side, ((c >> 1) & 1) * side, ((c >> 2) & 1) * side});
  const std::vector<HI::Tri> rt = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                                   {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  const HI::Target_surface ts(m, topo.boundary(), rp, rt);
  auto off_the_cube = [&](const std::vector<HI::Vec3>& p) {
    double worst = 0.;
    for(std::size_t v : topo.boundary_vertices())
    {
      double d = 0.;
      for(int k = 0; k < 3; ++k) d = (std::max)(d, (std::max)(p[v][k] - side, -p[v][k]));
      worst = (std::max)(worst, d);
    }
    return worst;
  };
  std::vector<std::size_t> inverted;
  for(std::size_t c = 0; c < m.hexes.size(); ++c)
    if(HI::is_inverted(HI::scaled_jacobian(m, c))) inverted.push_back(c);
  HMO_CHECK(!inverted.empty());
  std::vector<HI::Vec3> p = m.points;
  std::size_t regions = 0;
  HI::pull_back_to_surface(topo, ts, p, 0.1 * h, 4, nullptr, &regions);
  HI::Hex_mesh_arrays after = m;
  after.points = p;
  std::size_t inverted_after = 0;
  for(std::size_t c = 0; c < after.hexes.size(); ++c) inverted_after += HI::is_inverted(HI::scaled_jacobian(after, c));
  std::size_t pinned_moved = 0;
  for(std::size_t c : inverted)
    for(std::size_t v : m.hexes[c]) pinned_moved += p[v] != m.points[v];
  std::cout << "surface stage with " << inverted.size() << " inverted hexes inside: " << regions
            << " regions, boundary off the cube " << off_the_cube(m.points) / h << " -> " << off_the_cube(p) / h
            << " edges" << std::endl;
  HMO_CHECK(regions > 0);
  HMO_CHECK(off_the_cube(p) < 0.5 * off_the_cube(m.points));
  HMO_CHECK(inverted_after <= inverted.size());
  HMO_CHECK(pinned_moved == 0);
}

// The topology's edges, on a 7 × 5 × 4 grid whose hexes are shuffled: as
// many as the grid has, each hex edge's id names its two vertices, the ids
// in the order the hexes first meet the edges, the valences 4 / 2 / 1 inside,
// on a face and on the box's edges, and the same ids on one thread.
static void test_topology_edges()
{
  namespace HMOI = CGAL::Hexahedral_mesh_optimization::internal;
  const std::size_t nx = 7, ny = 5, nz = 4;
  HMOI::Hex_mesh_arrays m = hmo_test::grid(nx, ny, nz);
  std::mt19937 rng(3);
  std::shuffle(m.hexes.begin(), m.hexes.end(), rng);
  auto check = [&](const HMOI::Hex_mesh_topology& t) {
    HMO_CHECK(t.number_of_edges() ==
              nx * (ny + 1) * (nz + 1) + (nx + 1) * ny * (nz + 1) + (nx + 1) * (ny + 1) * nz);
    std::size_t next = 0;
    std::vector<char> met(t.number_of_edges(), 0);
    std::vector<int> valence(t.number_of_edges(), 0);
    for(std::size_t h = 0; h < m.hexes.size(); ++h)
      for(int k = 0; k < 12; ++k)
      {
        const std::size_t e = t.hex_edge(h, k);
        const std::size_t a = m.hexes[h][HMOI::hex_edges[k][0]], b = m.hexes[h][HMOI::hex_edges[k][1]];
        HMO_CHECK(e < t.number_of_edges());
        HMO_CHECK(t.edge(e)[0] == (std::min)(a, b) && t.edge(e)[1] == (std::max)(a, b));
        HMO_CHECK(t.edge_id(a, b) == e);
        if(!met[e]) { HMO_CHECK(e == next); ++next; met[e] = 1; }
        ++valence[e];
      }
    for(std::size_t e = 0; e < t.number_of_edges(); ++e)
    {
      HMO_CHECK(valence[e] == t.edge_valence(e));
      int on_box = 0;
      for(int d = 0; d < 3; ++d)
      {
        const double mid = 0.5 * (m.points[t.edge(e)[0]][d] + m.points[t.edge(e)[1]][d]);
        on_box += std::abs(mid) < 1e-12 || std::abs(mid - 1.) < 1e-12;
      }
      HMO_CHECK(valence[e] == (on_box == 0 ? 4 : on_box == 1 ? 2 : 1));
    }
  };
  const HMOI::Hex_mesh_topology threads(m);
  check(threads);
#ifdef CGAL_LINKED_WITH_TBB
  tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  const HMOI::Hex_mesh_topology one(m);
  check(one);
  for(std::size_t h = 0; h < m.hexes.size(); ++h)
    for(int k = 0; k < 12; ++k) HMO_CHECK(one.hex_edge(h, k) == threads.hex_edge(h, k));
#endif
}

/// The foldover-free energy's analytic gradient against central
/// differences, with and without its volume term, ε > 0 and ε = 0, on a
/// perturbed 3x3x3 grid, every vertex free, the boundary ones anchored where
/// they were before the perturbation (with sliding), one interior vertex
/// pushed across its cell when ε > 0; and the volume term grows when one of
/// two hexes smaller than its frame size shrinks.
static void test_barrier_energy_gradient()
{
  namespace HMOI = CGAL::Hexahedral_mesh_optimization::internal;
  for(int inverted = 0; inverted < 2; ++inverted)
  {
    HMOI::Hex_mesh_arrays m = hmo_test::grid(3, 3, 3);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-0.08, 0.08);
    const HMOI::Hex_mesh_topology topo(m);
    HMOI::Local_region region;
    for(std::size_t h = 0; h < m.hexes.size(); ++h) region.hexes.push_back(h);
    std::vector<HMOI::Boundary_constraint> bc(m.points.size());
    std::size_t pushed = 0;
    for(std::size_t v = 0; v < m.points.size(); ++v)
    {
      region.free_vertices.push_back(v);
      if(topo.is_boundary_vertex(v))
      {
        bc[v].type = HMOI::Vertex_class::regular;
        bc[v].anchor = m.points[v];
        bc[v].direction = HMOI::Vec3{0., 0., 1.};
      }
      else pushed = v;
      for(int d = 0; d < 3; ++d) m.points[v][d] += u(rng);
    }
    if(inverted) m.points[pushed][0] += 0.6; // past its neighbour 1/3 further
    for(double theta : {0., 0.1, 1.})
    {
      HMOI::Barrier_untangler b(topo, region, bc, 3.);
      b.set_sliding_weight(0.5);
      b.set_volume_weight(theta);
      const double eps = inverted ? 1e-3 : 0.;
      Eigen::VectorXd g, unused;
      const double scale = 1. / 27.; // the grid's edge cubed
      const double e = b.energy_at(m.points, eps, scale, g);
      HMO_CHECK(std::isfinite(e) && g.size() == Eigen::Index(3 * region.free_vertices.size()));
      double worst = 0., largest = 0.;
      for(std::size_t i = 0; i < region.free_vertices.size(); ++i)
        for(int d = 0; d < 3; ++d)
        {
          const double h = 1e-6;
          std::vector<HMOI::Vec3> p = m.points;
          p[region.free_vertices[i]][d] += h;
          const double up = b.energy_at(p, eps, scale, unused);
          p[region.free_vertices[i]][d] -= 2. * h;
          const double down = b.energy_at(p, eps, scale, unused);
          worst = (std::max)(worst, std::abs((up - down) / (2. * h) - g[Eigen::Index(3 * i) + d]));
          largest = (std::max)(largest, std::abs(g[Eigen::Index(3 * i) + d]));
        }
      std::printf("barrier gradient: inverted %d theta %g: largest %g, worst difference %g\n", inverted, theta, largest, worst);
      HMO_CHECK(largest > 0. && worst <= 1e-5 * largest);
    }
  }
  // two hexes of 0.5 x 1 x 1, the first shrunk to half its length, frame
  // size 1: the volume term grows (the shape term sees only the first
  // hex's new proportions)
  HMOI::Hex_mesh_arrays m = hmo_test::grid(2, 1, 1);
  const HMOI::Hex_mesh_topology topo(m);
  HMOI::Local_region region;
  region.hexes = {0, 1};
  std::vector<HMOI::Boundary_constraint> bc(m.points.size());
  Eigen::VectorXd g;
  auto energies = [&](double theta) {
    HMOI::Barrier_untangler b(topo, region, bc, 0.);
    b.set_volume_weight(theta);
    std::vector<HMOI::Vec3> p = m.points;
    const double before = b.energy_at(p, 1e-3, 1., g);
    for(HMOI::Vec3& q : p) if(q[0] < 0.75) q = HMOI::Vec3{0.5 * q[0] + 0.25, q[1], q[2]}; // the first hex half as long
    return std::make_pair(before, b.energy_at(p, 1e-3, 1., g));
  };
  const auto shape = energies(0.), with_volume = energies(1.);
  HMO_CHECK(with_volume.first > shape.first);
  HMO_CHECK(with_volume.second - shape.second > with_volume.first - shape.first);
}

HMO_TEST_MAIN(test_untangle)
{
  HMO_CASE(test_topology_edges());
  HMO_CASE(test_barrier_energy_gradient());
  HMO_CASE(test_unresolved_elements());
  HMO_CASE(test_surface_stage_with_inverted_hex());
  // 1. a perturbed 6x6x6 grid with interior vertices pushed across their cells
  {
    Mesh m = grid(6);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-0.9, 0.9);
    for(std::size_t v = 0; v < m.points.size(); ++v)
    {
      const Point& p = m.points[v];
      const bool interior = p.x() > 0 && p.x() < 6 && p.y() > 0 && p.y() < 6 && p.z() > 0 && p.z() < 6;
      if(interior) m.points[v] = p + K::Vector_3(u(rng), u(rng), u(rng));
    }
    // the boundary was not touched: the interior alone untangles it, and
    // no boundary vertex moves
    check_untangled(m, "perturbed grid", 0.01, true);
  }
  // 2. an inverted element touching the boundary: a top-face vertex pushed below the layer under it
  {
    Mesh m = grid(4);
    for(Point& p : m.points)
      if(p.x() == 2 && p.y() == 2 && p.z() == 4) p = Point(2.1, 1.9, 2.6);
    // the surface must relax to free it; the "surface" stage brings it back
    // (without that stage: 0.058 of the diagonal; with it: 0.0097)
    check_untangled(m, "boundary element", 0.02);
  }
  // 3. a corner element: the mesh corner pushed through its hex
  {
    Mesh m = grid(4);
    m.points[0] = Point(1.6, 1.5, 1.7);
    check_untangled(m, "corner element");
  }
  // 4. a curved block with a tangled interior
  {
    Mesh m = grid(5, 1.2);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-0.8, 0.8);
    const Mesh ref = grid(5, 1.2);
    const auto boundary = [&](std::size_t v) {
      const int i = v % 6, j = (v / 6) % 6, k = v / 36;
      return i == 0 || i == 5 || j == 0 || j == 5 || k == 0 || k == 5;
    };
    for(std::size_t v = 0; v < m.points.size(); ++v)
      if(!boundary(v)) m.points[v] = ref.points[v] + K::Vector_3(u(rng), u(rng), u(rng));
    check_untangled(m, "curved block", 0.01);
  }
  // 4b. a tangled layer right under the top face (untouched boundary with a
  // feature rim): the boundary must stay within 1 % of the diagonal
  {
    Mesh m = grid(6);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-0.95, 0.95);
    for(Point& p : m.points)
    {
      const bool interior = p.x() > 0 && p.x() < 6 && p.y() > 0 && p.y() < 6 && p.z() > 0 && p.z() < 6;
      if(interior && p.z() >= 4) p = p + K::Vector_3(u(rng), u(rng), 1.2 * u(rng));
    }
    check_untangled(m, "tangled layer under the top face", 0.01);
  }
  // 5. never worse: with no room to act, the input comes back unchanged
  {
    Mesh m = grid(3);
    m.points[21] = Point(2.7, 2.6, 2.8); // interior vertex (1,1,1) pushed out of its cells
    const Mesh input = m;
    const HMO::Optimization_result r = CGAL::untangle_hex_mesh(
      m, CGAL::Hexahedral_mesh_optimization::internal::add_internal_parameter(
               CGAL::parameters::number_of_iterations(0), CGAL::hex_mesh_internal_np::barrier_fallback, false));
    HMO_CHECK(r.inverted_after == r.inverted_before);
    HMO_CHECK(recount_inverted(m) == recount_inverted(input));
    HMO_CHECK(CGAL::hex_mesh_quality(m).msj >= CGAL::hex_mesh_quality(input).msj);
    HMO_CHECK(!r.success);
  }
  // 6. the LCC overload gives the same untangled result as the indexed mesh
  {
    Mesh m = grid(4);
    m.points[31] = Point(2.8, 2.7, 2.9); // interior vertex (1,1,1)
    LCC lcc;
    std::string message;
    HMO_CHECK(CGAL::build_linear_cell_complex(m, lcc, &message));
    const std::size_t before = CGAL::hex_mesh_quality(lcc).inverted;
    HMO_CHECK(before > 0);
    const HMO::Optimization_result r = CGAL::untangle_hex_mesh(lcc);
    HMO_CHECK(r.inverted_before == before);
    HMO_CHECK(CGAL::hex_mesh_quality(lcc).inverted == 0);
    HMO_CHECK(r.success);
  }
  return hmo_test::report(argv[0]);
}

} // namespace test_untangle
