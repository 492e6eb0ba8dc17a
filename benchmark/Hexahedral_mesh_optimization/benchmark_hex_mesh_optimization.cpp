// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Benchmark over the shared data, and scaling runs on generated meshes.
//
//   benchmark_hex_mesh_optimization [DATA_DIR] [--untangle] [--only SUBSTRING]
//                                   [--threads N | --threads-compare] [--no-paper-method]
//   benchmark_hex_mesh_optimization [DATA_DIR] --scaling [--scaling-max-hexes N]
//                                   [--untangle] [--only SUBSTRING] [--threads N | --threads-compare]
//   benchmark_hex_mesh_optimization [DATA_DIR] --stress [--stress-seeds N] [--only SUBSTRING] [--threads N]
//   benchmark_hex_mesh_optimization [DATA_DIR] --ablate [--ablate-only NAME] [--stress-seeds N] [--only SUBSTRING]
//   any mode: [--variant NAME] [--results FILE]
//
// DATA_DIR defaults to HMO_SHARED_DATA_DIR (../shared/data seen from the
// repository root). Every mode prints a Markdown table; with --results FILE
// (RESULTS.md beside this file) it also replaces that mode's section of FILE,
// between "<!-- begin MODE -->" and "<!-- end MODE -->", with what it printed.
//
// Modes:
//   default    : the whole pipeline `CGAL::optimize_hex_mesh` (untangle,
//                pull-back, MSJ stages, ASJ smoothing) on the untangling
//                inputs, on the stress tests below and on the valid meshes
//                of amips/ and low-quality/. On a row with a published Xu &
//                Chen surface error, that error is the surface tolerance
//                given to the quality stages (the comparison asks for an
//                error no larger than the paper's); elsewhere the default
//                0.005. On the rows with Xu & Chen's own figures (the 8
//                published rows, fandisk and kitty), the column "paper method" runs the
//                paper's pipeline alone (`Method::paper`, same tolerance,
//                under the last thread setting): MSJ / ASJ / surface error /
//                seconds read -> write, and how many elements it left
//                inverted; --no-paper-method skips it.
//   --untangle : `CGAL::untangle_hex_mesh` on every untangling input, plus
//                stress tests made by perturbing the valid meshes of
//                stress-base/ until at least 80 % of their hexes are inverted
//                (fixed seed, so runs compare), twice: the interior vertices
//                only (the boundary stays on the surface; the paper's fandisk
//                error, 0.0048, suggests that is what it did) and every
//                vertex (the boundary must also be found again).
//   In both, bunny_dualsheet runs twice: with its own boundary as reference
//   and with surfaces/bunny_reference.obj; both errors are also measured
//   against the obj. The published figures are printed beside ours. When
//   DATA_DIR is absent the program prints one line and exits with status 0.
//   Columns of these two modes:
//     seconds     : wall time of read -> optimise -> write: reading the input,
//                   the optimiser call, and writing the output with
//                   `CGAL::IO::write_hex_mesh` to a temporary file in /tmp
//                   (same format as the input; deleted afterwards). The
//                   stress tests' perturbation and the benchmark's own
//                   measurements (surface distances) are not counted;
//     optimiser s : the optimiser's own `Optimization_result::seconds`;
//     hash        : 64-bit FNV-1a (offset 0xcbf29ce484222325, prime
//                   0x100000001b3) over the output's vertex coordinates: for
//                   every point in order, x, y, z, each double's IEEE-754 bit
//                   pattern fed least significant byte first (the memory
//                   order on x86). Same input and options give the same hash
//                   when the optimiser is deterministic.
//
//   --scaling  : scaling cases on generated meshes, each run in its own
//                forked process (one at a time):
//                  grid n=50 (125k hexes) and n=100 (1M hexes), 1 % of the
//                  hexes inverted (make_grid below, seed 1), with
//                  `CGAL::untangle_hex_mesh` and with `CGAL::optimize_hex_mesh`;
//                  amips/fertility_gregson11.mesh refined 1->8 once (159k
//                  hexes) and twice (1.27M hexes), with `CGAL::optimize_hex_mesh`
//                  (refine_1_to_8 below; the fertility rows are skipped when
//                  DATA_DIR is absent, the grid rows run anyway).
//                Every case uses the optimiser's default parameters. Columns:
//                inverted and MSJ before and after (from the result), set-up
//                s (from the optimiser call to the visitor's first
//                `stage_started`; "–" when no stage started), total s (wall
//                time of the optimiser call; "(time limit)" when the result
//                says its time limit fired), peak memory (the child
//                process's maximum resident set size from wait4(): it
//                includes generating the input and the few MB the process
//                inherited from the parent, printed above the table), hash
//                (as above). Generating the input is not timed.
//
//   --stress   : the stress sets (`stress_sets` below), the yardstick of the
//                pipeline's stages: every valid mesh of the shared data
//                (stress-base/, amips/, low-quality/, the published outputs
//                of edge-cone/ and hexopt/) × three modes (interior vertices
//                perturbed, every vertex perturbed, boundary-locked
//                inversions) × N seeds (default 10), the amplitude, the
//                direction distribution and the share of vertices moved
//                drawn per seed (`perturb_for_stress`), each optimised with
//                the unperturbed boundary as reference and the tolerance
//                0.005. One line per mesh and mode, totals per mode and over
//                the set: pass rates (0 inverted, MSJ ≥ unperturbed, error
//                within the tolerance), MSJ and error distributions, time per
//                10k hexes (the optimiser call). With --stress-write DIR,
//                every perturbed input is written there (MEDIT), with the
//                reference surface of each mesh (OFF) and one line per run in
//                DIR/stress_runs.tsv, so that a run can be repeated with the
//                tool:
//                  hexmesh-optimize DIR/<input>.mesh out.mesh
//                    --reference DIR/<mesh>_reference.off
//   --paper    : `Method::paper` with the recipe of each published run of
//                the paper on its 8 rows (`paper_rows()`, from
//                ../shared/paper/SCRIPTS.md), the published error as the
//                surface tolerance; with --cotrik DEST (the folder given to
//                ../shared/peers/build_cotrik.sh), the authors' own tools too,
//                with the same recipe (`cotrik_run()`). Columns: MSJ / ASJ /
//                surface error (Hausdorff to the input's boundary) / seconds.
//   --ablate   : the default pipeline, then without each of its stages in
//                turn (`ablations()`), over the 8 published rows and the
//                stress sets (--stress-seeds per mesh and mode): one line per
//                variant. A stage stays in the default where its removal
//                costs measurably.
//
// Options:
//   --untangle              the --untangle mode; with --scaling, only the
//                           `untangle_hex_mesh` cases
//   --only SUBSTRING        only the rows (or scaling cases) whose name
//                           contains SUBSTRING
//   --threads N             run under tbb::global_control(max_allowed_parallelism, N)
//                           (without it: TBB's default parallelism)
//   --threads-compare       run every row (or scaling case) twice, under 1
//                           and under 2 threads: both wall times ("s (1 thr)",
//                           "s (2 thr)"), both optimiser times and the hash,
//                           or "hash mismatch" with both hashes when the two
//                           outputs differ (the other columns are the 1-thread
//                           run's; in --scaling, one row per thread count)
//   --scaling               the scaling mode above
//   --scaling-max-hexes N   with --scaling, skip the cases of more than N
//                           hexes (e.g. 200000: only the 125k and 159k cases)
//   --variant NAME          run the first of --ablate's variants whose name
//                           contains NAME instead of the default pipeline
//   --results FILE          see above
//   -h, --help              this text
// --threads and --threads-compare need TBB (CGAL_LINKED_WITH_TBB); without it
// they are refused (exit status 2), as is any unknown option.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/hex_mesh_io.h>
#include <CGAL/Hexahedral_mesh_optimization/Optimization_result.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Mesh/Refinement_hierarchy.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/surface_distance.h>
#include <CGAL/hex_mesh_quality.h>
#include <CGAL/hex_mesh_surface_error.h>
#include <CGAL/improve_hex_mesh_quality.h>
#include <CGAL/untangle_hex_mesh.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/global_control.h>
#endif

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Indexed_hex_mesh<K::Point_3> Mesh;
namespace HMO = CGAL::Hexahedral_mesh_optimization;
namespace INP = CGAL::hex_mesh_internal_np;
typedef std::chrono::steady_clock Clock;

#include "boundary_layer_set.h" // uses Mesh, K and HMO

static double seconds_since(Clock::time_point t)
{
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// ---------------------------------------------------------------------------
// Published figures

struct Published { std::string row[10]; };

static std::map<std::string, Published> read_published(const std::string& csv)
{
  std::map<std::string, Published> m;
  std::ifstream in(csv);
  std::string line;
  while(std::getline(in, line))
  {
    if(line.empty() || line[0] == '#') continue;
    std::stringstream ss(line);
    Published p;
    for(int i = 0; i < 10 && std::getline(ss, p.row[i], ','); ++i) {}
    m[p.row[0]] = p;
  }
  return m;
}

static std::string fig(const std::string& msj, const std::string& asj, const std::string& err)
{
  if(msj.empty()) return "–";
  return msj + " / " + asj + " / " + err;
}

// ---------------------------------------------------------------------------
// Output hash, threads, the visitor

/// 64-bit FNV-1a over the IEEE-754 bit patterns of the coordinates, x, y, z
/// of every point in order, each double least significant byte first
static std::uint64_t coordinates_hash(const Mesh& m)
{
  std::uint64_t h = 0xcbf29ce484222325ull;
  for(const K::Point_3& p : m.points)
    for(const double c : {p.x(), p.y(), p.z()})
    {
      std::uint64_t bits;
      std::memcpy(&bits, &c, sizeof bits);
      for(int b = 0; b < 8; ++b)
      {
        h ^= (bits >> (8 * b)) & 0xffu;
        h *= 0x100000001b3ull;
      }
    }
  return h;
}

static std::string hex16(std::uint64_t h)
{
  char b[24];
  std::snprintf(b, sizeof b, "%016" PRIx64, h);
  return b;
}

/// the parallelism of one run: TBB's default (`threads` 0) or at most
/// `threads` threads, for the lifetime of the object
class Thread_limit
{
public:
  explicit Thread_limit(int threads)
  {
#ifdef CGAL_LINKED_WITH_TBB
    if(threads > 0)
      m_control.reset(new tbb::global_control(tbb::global_control::max_allowed_parallelism, std::size_t(threads)));
#else
    (void)threads;
#endif
  }

private:
#ifdef CGAL_LINKED_WITH_TBB
  std::unique_ptr<tbb::global_control> m_control;
#endif
};

/// records when the first stage starts: the optimiser's set-up time
struct Setup_visitor : HMO::Default_optimization_visitor
{
  Clock::time_point start = Clock::now();
  double setup_seconds = -1.;

  void stage_started(const std::string& /*name*/, std::size_t /*bad_elements*/)
  {
    if(setup_seconds < 0.) setup_seconds = seconds_since(start);
  }
};


/// The optimiser calls, all with the same parameter types (each instantiation
/// of the optimiser costs compile time): untangling or the whole pipeline,
/// with or without a reference surface, the package's method or the paper's
/// (`paper`). `tolerance` is the pipeline's surface tolerance (its default
/// is 0.005).
/// the package method's schedule of every run, and whether its pull-back
/// runs (`--ablate` changes them)
static HMO::internal::Optimization_schedule g_schedule;
static bool g_pull_back = true;
/// the recipe of the paper's method's runs (`--paper` sets each row's)
static HMO::Paper_recipe g_recipe;

static HMO::Optimization_result run_optimiser(Mesh& mesh, bool untangle_only, const HMO::internal::Triangle_surface& reference,
                                              double tolerance, Setup_visitor& visitor, bool paper = false)
{
  typedef HMO::internal::Optimization_schedule Schedule;
  using HMO::internal::add_internal_parameter;
  const auto np = CGAL::parameters::method(paper ? HMO::Method::paper : HMO::Method::package)
                    .paper_recipe(g_recipe)
                    .visitor(std::ref(visitor));
  const auto npm = add_internal_parameter(add_internal_parameter(np, INP::schedule, paper ? Schedule::paper() : g_schedule),
                                          INP::pull_back, paper || g_pull_back);
  visitor.start = Clock::now();
  if(untangle_only)
    return reference.is_empty() ? CGAL::untangle_hex_mesh(mesh, npm)
                                : CGAL::untangle_hex_mesh(mesh, add_internal_parameter(npm, INP::reference_surface, reference));
  const auto npt = add_internal_parameter(npm, INP::surface_tolerance, tolerance);
  return reference.is_empty() ? CGAL::optimize_hex_mesh(mesh, npt)
                              : CGAL::optimize_hex_mesh(mesh, add_internal_parameter(npt, INP::reference_surface, reference));
}

// ---------------------------------------------------------------------------
// Input generators

/// Perturbs vertices by random vectors of growing amplitude until at least
/// `fraction` of the hexes are inverted: every vertex, or (`interior_only`)
/// only the interior ones, so that the boundary stays on the surface.
static std::size_t perturb(Mesh& m, double fraction, unsigned seed, bool interior_only)
{
  const Mesh base = m;
  double mean = 0.;
  for(const auto& h : m.hexahedra) mean += std::sqrt(CGAL::squared_distance(m.points[h[0]], m.points[h[1]]));
  mean /= m.hexahedra.size();
  std::vector<char> on_boundary(m.points.size(), 0);
  if(interior_only)
    for(std::size_t v : HMO::internal::extract_boundary(HMO::internal::make_hex_mesh_arrays(m, K())).vertices)
      on_boundary[v] = 1;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1., 1.);
  for(double amp = 0.3; amp < 100.; amp *= 1.15)
  {
    for(std::size_t i = 0; i < m.points.size(); ++i)
      if(!on_boundary[i]) m.points[i] = base.points[i] + amp * mean * K::Vector_3(u(rng), u(rng), u(rng));
    const auto q = CGAL::hex_mesh_quality(m);
    if(q.inverted >= fraction * m.hexahedra.size()) return q.inverted;
  }
  return CGAL::hex_mesh_quality(m).inverted;
}

/// the position of corner q of a hexahedron in its own (a, b, c) frame, MEDIT/VTK
/// order: 0-3 the bottom face (c = 0) counter-clockwise seen from above, q+4 above q
static const int hex_corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                     {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};

static double scaled_jacobian_of(const Mesh& m, std::size_t h)
{
  std::array<K::Point_3, 8> p;
  for(int q = 0; q < 8; ++q) p[q] = m.points[m.hexahedra[h][q]];
  return CGAL::hex_scaled_jacobian(p);
}

/// The stress sets' modes: interior vertices perturbed (the boundary stays
/// on the surface), every vertex perturbed (the boundary must be found
/// again), and boundary-locked inversions (a few boundary vertices pushed
/// through the opposite face of one of their hexes: only a move of the
/// surface can free them).
enum Stress_mode { stress_interior, stress_all, stress_locked };
static const char* const stress_mode_names[3] = {"interior", "all vertices", "boundary-locked"};
static const char* const stress_mode_files[3] = {"interior", "all", "locked"};

/// what one stress input was drawn with
struct Stress_draw
{
  double amplitude = 0.;      // in local edge lengths (the largest; boundary-locked: the push depth)
  std::string directions;     // sphere, ball or anisotropic (boundary-locked: "through a face")
  double fraction = 0.;       // of the eligible vertices moved
  std::size_t moved = 0;
};

/// Draws one stress input from `base` (seeded by `seed` and `mode`, so that
/// runs compare). Interior and every-vertex modes: the amplitude (0.2 to 0.8
/// local edge lengths), the direction distribution (uniform on the sphere,
/// uniform in the ball, or anisotropic: a Gaussian squashed along two random
/// axes to 0.05-0.5 of the third, in the ball) and the fraction of the
/// eligible vertices moved (0.2 to 1) are drawn per seed; the local edge
/// length of a vertex is the mean length of the mesh edges at it.
/// Boundary-locked: 1 to 4 boundary vertices, no two in one hex, each moved
/// to 1.2-1.8 times the way to the centre of a face of one of its hexes that
/// does not hold it, and only kept where that hex ends inverted.
static Stress_draw perturb_for_stress(Mesh& m, Stress_mode mode, unsigned seed)
{
  std::seed_seq sq{seed, unsigned(mode) + 1u};
  std::mt19937 rng(sq);
  std::uniform_real_distribution<double> u01(0., 1.);
  std::normal_distribution<double> g(0., 1.);
  const std::size_t nv = m.points.size();
  std::vector<double> sum(nv, 0.);
  std::vector<int> count(nv, 0);
  static const int edges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                   {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  for(const auto& h : m.hexahedra)
    for(const auto& e : edges)
    {
      const double l = std::sqrt(CGAL::squared_distance(m.points[h[e[0]]], m.points[h[e[1]]]));
      for(int k = 0; k < 2; ++k) { sum[h[e[k]]] += l; ++count[h[e[k]]]; }
    }
  std::vector<char> boundary(nv, 0);
  for(std::size_t v : HMO::internal::extract_boundary(HMO::internal::make_hex_mesh_arrays(m, K())).vertices)
    boundary[v] = 1;
  Stress_draw d;
  if(mode == stress_locked)
  {
    // the 6 faces of a hex (MEDIT/VTK corner order)
    static const int faces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    std::vector<std::vector<std::size_t>> hexes_at(nv);
    for(std::size_t h = 0; h < m.hexahedra.size(); ++h)
      for(std::size_t v : m.hexahedra[h]) hexes_at[v].push_back(h);
    std::vector<std::size_t> candidates;
    for(std::size_t v = 0; v < nv; ++v) if(boundary[v]) candidates.push_back(v);
    std::vector<char> blocked(nv, 0);
    const int wanted = 1 + int(u01(rng) * 4.);
    d.directions = "through a face";
    d.fraction = 0.;
    for(int attempt = 0; attempt < 200 && int(d.moved) < wanted && !candidates.empty(); ++attempt)
    {
      const std::size_t v = candidates[std::size_t(u01(rng) * candidates.size()) % candidates.size()];
      const double depth = 1.2 + 0.6 * u01(rng);
      if(blocked[v]) continue;
      const std::size_t h = hexes_at[v][std::size_t(u01(rng) * hexes_at[v].size()) % hexes_at[v].size()];
      const auto& hex = m.hexahedra[h];
      std::vector<int> opposite;
      for(int f = 0; f < 6; ++f)
      {
        bool holds = false;
        for(int q = 0; q < 4; ++q) holds = holds || hex[faces[f][q]] == v;
        if(!holds) opposite.push_back(f);
      }
      const int f = opposite[std::size_t(u01(rng) * opposite.size()) % opposite.size()];
      K::Vector_3 c(0., 0., 0.);
      for(int q = 0; q < 4; ++q) c = c + (m.points[hex[faces[f][q]]] - CGAL::ORIGIN);
      const K::Point_3 centre = CGAL::ORIGIN + c / 4.;
      const K::Point_3 old = m.points[v];
      m.points[v] = old + depth * (centre - old);
      if(!(scaled_jacobian_of(m, h) < 0.)) { m.points[v] = old; continue; }
      for(std::size_t hh : hexes_at[v])
        for(std::size_t w : m.hexahedra[hh]) blocked[w] = 1;
      d.amplitude = (std::max)(d.amplitude, depth);
      ++d.moved;
    }
    return d;
  }
  d.amplitude = 0.2 + 0.6 * u01(rng);
  const int distribution = int(u01(rng) * 3.) % 3;
  d.directions = distribution == 0 ? "sphere" : distribution == 1 ? "ball" : "anisotropic";
  d.fraction = 0.2 + 0.8 * u01(rng);
  // anisotropic: a random orthonormal frame, the second and third axes squashed
  K::Vector_3 axes[3] = {K::Vector_3(1, 0, 0), K::Vector_3(0, 1, 0), K::Vector_3(0, 0, 1)};
  double squash[3] = {1., 1., 1.};
  if(distribution == 2)
  {
    K::Vector_3 a(g(rng), g(rng), g(rng)), b(g(rng), g(rng), g(rng));
    a = a / std::sqrt(a.squared_length());
    b = b - (b * a) * a;
    b = b / std::sqrt(b.squared_length());
    axes[0] = a; axes[1] = b; axes[2] = CGAL::cross_product(a, b);
    squash[1] = 0.05 + 0.45 * u01(rng);
    squash[2] = 0.05 + 0.45 * u01(rng);
  }
  for(std::size_t v = 0; v < nv; ++v)
  {
    // drawn for every vertex, moved or not: the draws of a vertex do not depend on the mode
    const double pick = u01(rng), radius = u01(rng);
    K::Vector_3 dir(g(rng), g(rng), g(rng));
    if(count[v] == 0 || (mode == stress_interior && boundary[v]) || pick >= d.fraction) continue;
    if(distribution == 2) dir = squash[0] * dir.x() * axes[0] + squash[1] * dir.y() * axes[1] + squash[2] * dir.z() * axes[2];
    const double n = std::sqrt(dir.squared_length());
    if(!(n > 0.)) continue;
    const double length = distribution == 0 ? 1. : std::cbrt(radius);
    m.points[v] = m.points[v] + (d.amplitude * length * sum[v] / count[v] / n) * dir;
    ++d.moved;
  }
  return d;
}

/// An n×n×n grid of the unit cube (edge 1/n), vertex i + (n+1)(j + (n+1)k) at
/// (i, j, k)/n, hexes in MEDIT/VTK order. Then interior vertices drawn at
/// random (std::mt19937 seeded with `seed`), never two in one hex, are moved
/// by a random vector (uniform direction, length 0.6-0.9 of the spacing)
/// until at least `fraction_inverted` of the hexes are inverted (scaled
/// Jacobian < 0). Since no hex holds two moved vertices, each one's inverted
/// hexes form an independent region. `displaced`, if given, receives the
/// number of vertices moved.
static Mesh make_grid(std::size_t n, double fraction_inverted, unsigned seed, std::size_t* displaced = nullptr)
{
  Mesh m;
  const std::size_t n1 = n + 1;
  const auto id = [n1](std::size_t i, std::size_t j, std::size_t k) { return i + n1 * (j + n1 * k); };
  m.points.reserve(n1 * n1 * n1);
  for(std::size_t k = 0; k <= n; ++k)
    for(std::size_t j = 0; j <= n; ++j)
      for(std::size_t i = 0; i <= n; ++i)
        m.points.push_back(K::Point_3(double(i) / double(n), double(j) / double(n), double(k) / double(n)));
  m.hexahedra.reserve(n * n * n);
  for(std::size_t k = 0; k < n; ++k)
    for(std::size_t j = 0; j < n; ++j)
      for(std::size_t i = 0; i < n; ++i)
        m.hexahedra.push_back({{id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k),
                                id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)}});
  if(displaced) *displaced = 0;
  if(n < 2 || fraction_inverted <= 0.) return m;

  const double spacing = 1. / double(n);
  const std::size_t hexes = n * n * n;
  const double target = fraction_inverted * double(hexes);
  std::vector<char> blocked(m.points.size(), 0); // within one step of a moved vertex
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(1, n - 1);
  std::normal_distribution<double> gauss(0., 1.);
  std::uniform_real_distribution<double> length(0.6, 0.9);
  std::size_t inverted = 0;
  for(std::size_t attempt = 0; double(inverted) < target && attempt < 20 * hexes; ++attempt)
  {
    const std::size_t i = pick(rng), j = pick(rng), k = pick(rng); // in declaration order
    const std::size_t v = id(i, j, k);
    if(blocked[v]) continue;
    double d[3], norm2 = 0.;
    do
    {
      norm2 = 0.;
      for(double& c : d)
      {
        c = gauss(rng);
        norm2 += c * c;
      }
    } while(norm2 < 1e-12);
    const double scale = length(rng) * spacing / std::sqrt(norm2);
    m.points[v] = m.points[v] + K::Vector_3(scale * d[0], scale * d[1], scale * d[2]);
    if(displaced) ++*displaced;
    for(std::size_t c = k - 1; c <= k + 1; ++c)
      for(std::size_t b = j - 1; b <= j + 1; ++b)
        for(std::size_t a = i - 1; a <= i + 1; ++a)
          blocked[id(a, b, c)] = 1;
    // the 8 hexes around v: only v moved in them
    for(std::size_t c = k - 1; c <= k; ++c)
      for(std::size_t b = j - 1; b <= j; ++b)
        for(std::size_t a = i - 1; a <= i; ++a)
          if(scaled_jacobian_of(m, a + n * (b + n * c)) < 0.) ++inverted;
  }
  return m;
}

/// every hex split into 8 (`HMO::internal::refine_1_to_8`: the input's
/// points keep their indices; only points and hexahedra are produced, no
/// MEDIT boundary entities)
static Mesh refine_1_to_8(const Mesh& in)
{
  const HMO::internal::Hex_mesh_arrays r = HMO::internal::refine_1_to_8(HMO::internal::make_hex_mesh_arrays(in, K()));
  Mesh out;
  out.points.reserve(r.points.size());
  for(const HMO::internal::Vec3& p : r.points) out.points.push_back(K::Point_3(p[0], p[1], p[2]));
  out.hexahedra.assign(r.hexes.begin(), r.hexes.end());
  return out;
}

// ---------------------------------------------------------------------------
// The benchmark rows (default and --untangle modes)

struct Row_run
{
  std::string error;                              // empty on success
  Mesh input;                                     // the optimiser's input (if asked for)
  Mesh output;
  HMO::internal::Triangle_surface reference;      // given to the optimiser (empty: the input's boundary)
  HMO::Optimization_result result;
  double seconds = 0.;                            // read + optimise + write
  std::uint64_t hash = 0;
};

static std::string extension_of(const std::string& name)
{
  const std::size_t dot = name.rfind('.');
  std::string e = dot == std::string::npos ? std::string(".mesh") : name.substr(dot);
  for(char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

/// One run of a row: read, (stress tests: perturb), optimise, write to a
/// temporary file, under at most `threads` threads (0: TBB's default)
static Row_run run_row(const std::string& dir, const std::string& name, bool stress, bool interior_only,
                       const HMO::internal::Triangle_surface* obj, double tolerance, bool untangle_only,
                       int threads, bool keep_input, bool paper = false)
{
  static int counter = 0;
  Row_run run;
  const Thread_limit limit(threads);
  Mesh mesh;
  CGAL::IO::Hex_mesh_io_error err;
  std::vector<std::string> warnings;
  const Clock::time_point read_start = Clock::now();
  if(!CGAL::IO::read_hex_mesh(dir + "/" + name, mesh, &err, &warnings))
  {
    run.error = std::string("read error: ") + err.what();
    return run;
  }
  const double read_seconds = seconds_since(read_start);
  if(stress)
  {
    // the surface error of a stress test is measured against the unperturbed mesh
    HMO::internal::boundary_surface(HMO::internal::make_hex_mesh_arrays(mesh, K()), run.reference);
    perturb(mesh, 0.8, 1, interior_only);
  }
  else if(obj)
    run.reference = *obj;
  if(keep_input) run.input = mesh;

  const std::string tmp = "/tmp/hmo_benchmark_" + std::to_string(::getpid()) + "_" + std::to_string(counter++) +
                          extension_of(name);
  Setup_visitor visitor;
  const Clock::time_point start = Clock::now();
  run.result = run_optimiser(mesh, untangle_only, run.reference, tolerance, visitor, paper);
  const bool written = CGAL::IO::write_hex_mesh(tmp, mesh, CGAL::IO::Hex_mesh_fields(), &err);
  run.seconds = read_seconds + seconds_since(start);
  std::remove(tmp.c_str());
  if(!written) run.error = std::string("write error: ") + err.what();
  run.hash = coordinates_hash(mesh);
  run.output = std::move(mesh);
  return run;
}

/// The paper-method column of a row: `Method::paper` on the same input with
/// the same tolerance, under `threads`; MSJ / ASJ / surface error / seconds
/// read -> write, and the elements it left inverted
static std::string paper_method_figures(const std::string& dir, const std::string& name, bool stress,
                                        bool interior_only, const HMO::internal::Triangle_surface* obj,
                                        double tolerance, int threads)
{
  const Row_run p = run_row(dir, name, stress, interior_only, obj, tolerance, false, threads, false, true);
  if(!p.error.empty()) return p.error;
  char b[128];
  std::snprintf(b, sizeof b, "%.3f / %.3f / %.4f / %.2f s", p.result.msj_after, p.result.asj_after,
                p.result.surface_error, p.seconds);
  std::string figures = b;
  if(p.result.inverted_after > 0) figures += ", " + std::to_string(p.result.inverted_after) + " inverted";
  return figures;
}

static int benchmark_rows(const std::string& dir, bool untangle_only, const std::string& only,
                          const std::vector<int>& thread_runs, bool paper_column)
{
  const auto published = read_published(HMO_PUBLISHED_CSV);
  std::vector<std::string> inputs = {
    "edge-cone/block_in.mesh", "edge-cone/bunny_in.mesh", "edge-cone/bust_in.mesh", "edge-cone/cap_in.mesh",
    "edge-cone/hanger_stresstest_in.mesh", "edge-cone/impeller_stresstest_in.mesh",
    "inverted/bunny_dualsheet.vtk", "inverted/bunny_dualsheet.vtk+obj", "inverted/hex_torus.vtk",
    "stress-base/fandisk.vtk+interior", "stress-base/kitty.vtk+interior", "stress-base/hanger.vtk+interior",
    "stress-base/fandisk.vtk", "stress-base/kitty.vtk", "stress-base/hanger.vtk"};
  if(!untangle_only)
    for(const char* n : {"amips/rockerarm_li12.vtk", "amips/fertility_gregson11.mesh", "low-quality/kitten_with_bifur_2.mesh",
                         "low-quality/cat_2.mesh", "low-quality/Dolphin_2.mesh"})
      inputs.push_back(n);
  HMO::internal::Triangle_surface bunny_obj;
  CGAL::IO::read_reference_surface(dir + "/surfaces/bunny_reference.obj", bunny_obj);

  const bool compare = thread_runs.size() > 1;
  std::string time_columns, time_rule;
  if(compare)
  {
    time_columns = "s (1 thr) | s (2 thr) | optimiser s (1 thr) | optimiser s (2 thr)";
    time_rule = "---:|---:|---:|---:";
  }
  else if(thread_runs[0] > 0)
  {
    const std::string t = " (" + std::to_string(thread_runs[0]) + " thr)";
    time_columns = "seconds" + t + " | optimiser s" + t;
    time_rule = "---:|---:";
  }
  else
  {
    time_columns = "seconds | optimiser s";
    time_rule = "---:|---:";
  }
  std::cout << "| model | hexes | inverted in | inverted out | MSJ out | ASJ out | surface error (metro's normaliser) | "
            << time_columns << " | hash | stages | paper method MSJ/ASJ/err/s | edge-cone MSJ/ASJ/err | Xu & Chen MSJ/ASJ/err |\n"
            << "|---|---:|---:|---:|---:|---:|---:|" << time_rule << "|---|---|---|---|---|\n";
  for(const std::string& row : inputs)
  {
    if(!only.empty() && row.find(only) == std::string::npos) continue;
    const auto ends_with = [&row](const std::string& tail) {
      return row.size() > tail.size() && row.compare(row.size() - tail.size(), tail.size(), tail) == 0;
    };
    const bool with_obj = ends_with("+obj"), interior_only = ends_with("+interior");
    const std::string name = row.substr(0, row.find('+'));
    const bool stress = name.rfind("stress-base/", 0) == 0;
    const auto it = published.find(name);
    double tolerance = 0.005;
    if(it != published.end() && !it->second.row[9].empty()) tolerance = std::stod(it->second.row[9]);

    std::vector<Row_run> runs;
    for(std::size_t t = 0; t < thread_runs.size(); ++t)
    {
      runs.push_back(run_row(dir, name, stress, interior_only, with_obj ? &bunny_obj : nullptr, tolerance,
                             untangle_only, thread_runs[t], t == 0));
      if(!runs.back().error.empty()) break;
    }
    if(!runs.back().error.empty())
    {
      std::cout << "| " << row << " | " << runs.back().error << " |" << std::endl;
      continue;
    }
    const Row_run& run = runs[0];
    const HMO::Optimization_result& r = run.result;
    const Mesh& mesh = run.output;

    std::string stages;
    for(const auto& s : r.stages)
    {
      char b[96];
      if(s.name.rfind("msj", 0) == 0) continue; // the staged targets: the MSJ column says where they ended
      std::snprintf(b, sizeof b, "%s %zu→%zu %.1fs", s.name.c_str(), s.inverted_before, s.inverted_after, s.seconds);
      stages += (stages.empty() ? "" : ", ") + std::string(b);
    }
    if(r.time_limit_reached) stages += "; time limit reached";
    if(!untangle_only) stages += "; tolerance " + std::to_string(tolerance).substr(0, 6);
    if(name == "inverted/bunny_dualsheet.vtk" && !bunny_obj.is_empty())
      stages += "; error vs bunny_reference.obj " + std::to_string(CGAL::hex_mesh_surface_error(mesh, bunny_obj)).substr(0, 6);
    // the papers' figures come from metro, which divides by the diagonal of
    // the union of both boxes enlarged by 2 % per side (surface_distance.h):
    // shown in brackets, to compare like with like
    HMO::internal::Triangle_surface measured_against = run.reference;
    if(measured_against.is_empty())
      HMO::internal::boundary_surface(HMO::internal::make_hex_mesh_arrays(run.input, K()), measured_against);
    const HMO::internal::Surface_distance sd =
      HMO::internal::surface_distance(HMO::internal::make_hex_mesh_arrays(mesh, K()), measured_against);

    std::string times, hash = hex16(run.hash);
    char b[64];
    for(const Row_run& x : runs)
    {
      std::snprintf(b, sizeof b, "%.2f | ", x.seconds);
      times += b;
    }
    for(const Row_run& x : runs)
    {
      std::snprintf(b, sizeof b, "%.2f | ", x.result.seconds);
      times += b;
    }
    if(compare && runs[1].hash != run.hash)
      hash = "hash mismatch: " + hex16(run.hash) + " (1 thr), " + hex16(runs[1].hash) + " (2 thr)";

    char line[1024];
    std::snprintf(line, sizeof line, "| %s%s | %zu | %zu | %zu | %.3f | %.3f | %.4f (%.4f) | %s%s | %s |",
                  name.c_str(), stress ? (interior_only ? " (interior perturbed)" : " (all vertices perturbed)") : (with_obj ? " (reference .obj)" : ""), mesh.hexahedra.size(), r.inverted_before,
                  r.inverted_after, r.msj_after, r.asj_after, r.surface_error, sd.metro_relative(), times.c_str(),
                  hash.c_str(), stages.c_str());
    // the paper's method on the rows with the paper's own figures
    const bool paper_row = paper_column && !untangle_only && it != published.end() && !it->second.row[7].empty();
    std::cout << line << ' '
              << (paper_row ? paper_method_figures(dir, name, stress, interior_only, with_obj ? &bunny_obj : nullptr,
                                                   tolerance, thread_runs.back())
                            : "–")
              << " | "
              << (it != published.end() ? fig(it->second.row[4], it->second.row[5], it->second.row[6]) : "–") << " | "
              << (it != published.end() ? fig(it->second.row[7], it->second.row[8], it->second.row[9]) : "–") << " |"
              << std::endl;
  }
  return 0;
}

// ---------------------------------------------------------------------------
// --stress

/// `name` (a path under the data folder) as a file name stem: "low-quality/cat_2.mesh" -> "low-quality_cat_2"
static std::string stem_of(const std::string& name)
{
  std::string s = name.substr(0, name.rfind('.'));
  std::replace(s.begin(), s.end(), '/', '_');
  return s;
}

/// `--stress-write`: the perturbed inputs, the references and the table of
/// the runs, into an existing folder
class Stress_writer
{
public:
  explicit Stress_writer(const std::string& dir) : m_dir(dir)
  {
    if(m_dir.empty()) return;
    m_runs.open(m_dir + "/stress_runs.tsv");
    m_runs << std::setprecision(10); // as the tool's --report
    m_runs << "input\treference\tamplitude\tinverted_in\tinverted_out\tmsj_out\tasj_out\tsurface_error\tseconds"
              "\tdirections\tfraction_moved\tvertices_moved\n";
  }
  bool enabled() const { return !m_dir.empty(); }
  bool good() const { return !enabled() || bool(m_runs); }

  /// writes the reference of mesh `name`; returns its path
  std::string write_reference(const std::string& name, const HMO::internal::Triangle_surface& reference)
  {
    const std::string path = m_dir + "/" + stem_of(name) + "_reference.off";
    if(!CGAL::IO::write_polygon_mesh(path, reference, CGAL::parameters::stream_precision(17)))
      std::cerr << "benchmark_hex_mesh_optimization: could not write " << path << "\n";
    return path;
  }

  /// writes the perturbed input of a run; returns its path
  std::string write_input(const std::string& name, const std::string& mode, int seed, const Mesh& mesh)
  {
    const std::string path = m_dir + "/" + stem_of(name) + "_" + mode + "_seed" + std::to_string(seed) + ".mesh";
    CGAL::IO::Hex_mesh_io_error err;
    if(!CGAL::IO::write_hex_mesh(path, mesh, CGAL::IO::Hex_mesh_fields(), &err))
      std::cerr << "benchmark_hex_mesh_optimization: " << err.what() << "\n";
    return path;
  }

  void add_run(const std::string& input, const std::string& reference, const Stress_draw& draw,
               const HMO::Optimization_result& r)
  {
    m_runs << input << '\t' << reference << '\t' << draw.amplitude << '\t' << r.inverted_before << '\t'
           << r.inverted_after << '\t' << r.msj_after << '\t' << r.asj_after << '\t' << r.surface_error << '\t'
           << r.seconds << '\t' << draw.directions << '\t' << draw.fraction << '\t' << draw.moved << std::endl;
  }

private:
  std::string m_dir;
  std::ofstream m_runs;
};

/// the valid meshes of the shared data that the stress sets perturb
static const std::vector<std::string>& stress_meshes()
{
  static const std::vector<std::string> meshes = {
    "stress-base/fandisk.vtk", "stress-base/hanger.vtk", "stress-base/kitty.vtk",
    "amips/rockerarm_li12.vtk", "amips/fertility_gregson11.mesh",
    "low-quality/kitten_with_bifur_2.mesh", "low-quality/cat_2.mesh", "low-quality/Dolphin_2.mesh",
    "edge-cone/published/block_edgecone.mesh", "edge-cone/published/bust_edgecone.mesh",
    "edge-cone/published/cap_edgecone.mesh", "edge-cone/published/hanger_stresstest_edgecone.mesh",
    "edge-cone/published/impeller_stresstest_edgecone.mesh", "edge-cone/published/bunny_edgecone.mesh",
    "hexopt/published/mid2FemOpt.vtk"};
  return meshes;
}

/// the q-quantile of `v` (nearest rank)
static double quantile_of(std::vector<double> v, double q)
{
  if(v.empty()) return 0.;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, std::size_t(q * double(v.size())))];
}

/// One line of the stress table: runs of one mesh in one mode, or of all.
struct Stress_totals
{
  int runs = 0, untangled = 0, within = 0, above = 0;
  std::size_t inverted_min = std::size_t(-1), inverted_max = 0;
  std::vector<double> msj, error, seconds_per_10k;
  double seconds = 0.;

  void add(const HMO::Optimization_result& r, double msj0, std::size_t hexes, double seconds_run, double tolerance)
  {
    ++runs;
    if(r.inverted_after == 0) ++untangled;
    if(r.surface_error <= tolerance) ++within;
    if(r.msj_after >= msj0) ++above;
    inverted_min = (std::min)(inverted_min, r.inverted_before);
    inverted_max = (std::max)(inverted_max, r.inverted_before);
    msj.push_back(r.msj_after);
    error.push_back(r.surface_error);
    seconds_per_10k.push_back(seconds_run * 1e4 / double(hexes));
    seconds += seconds_run;
  }

  std::string pct(int n) const
  {
    char b[48];
    std::snprintf(b, sizeof b, "%d (%.0f %%)", n, runs ? 100. * n / runs : 0.);
    return b;
  }
};

/// The stress sets: every valid mesh of the shared data (`stress_meshes()`)
/// × the three modes (`Stress_mode`) × `seeds` draws
/// (`perturb_for_stress`), each optimised by `CGAL::optimize_hex_mesh` with
/// the unperturbed boundary as reference and the default tolerance (0.005),
/// timed from the call to its return. One line per mesh and mode, then the
/// totals per mode and of the whole set: pass rates (0 inverted; surface
/// error within the tolerance; MSJ at or above the unperturbed mesh's), the
/// MSJ and error distributions, the time per 10k hexes.
/// A mesh of the stress set as read: its unperturbed MSJ and its boundary,
/// the reference of every run on it.
struct Stress_base
{
  std::string name;
  Mesh mesh;
  double msj = 0.;
  HMO::internal::Triangle_surface reference;
};

/// Reads the stress mesh `name` (under `dir`); false with `error` when it cannot be read.
static bool read_stress_base(const std::string& dir, const std::string& name, Stress_base& base, std::string& error)
{
  CGAL::IO::Hex_mesh_io_error err;
  base.name = name;
  if(!CGAL::IO::read_hex_mesh(dir + "/" + name, base.mesh, &err))
  {
    error = err.what();
    return false;
  }
  base.msj = CGAL::hex_mesh_quality(base.mesh).msj;
  HMO::internal::boundary_surface(HMO::internal::make_hex_mesh_arrays(base.mesh, K()), base.reference);
  return true;
}

/// One run of the stress set: `base` perturbed in `mode` with `seed`, then
/// optimised against its unperturbed boundary (the optimiser call timed).
struct Stress_run
{
  Mesh input;
  Stress_draw draw;
  HMO::Optimization_result result;
  double seconds = 0.;
};

static Stress_run run_stress_case(const Stress_base& base, Stress_mode mode, unsigned seed, double tolerance)
{
  Stress_run run;
  run.input = base.mesh;
  run.draw = perturb_for_stress(run.input, mode, seed);
  Mesh mesh = run.input;
  Setup_visitor visitor;
  const Clock::time_point start = Clock::now();
  run.result = run_optimiser(mesh, false, base.reference, tolerance, visitor);
  run.seconds = seconds_since(start);
  return run;
}

static int stress_sets(const std::string& dir, const std::string& only, int seeds, int threads,
                       const std::string& write_dir)
{
  Stress_writer writer(write_dir);
  if(!writer.good())
  {
    std::cerr << "benchmark_hex_mesh_optimization: cannot write " << write_dir << "/stress_runs.tsv\n";
    return 1;
  }
  const double tolerance = 0.005;
  std::cout << "Stress sets: " << seeds << " seeds per mesh and mode (amplitude, directions and share of vertices "
            << "drawn per seed), reference = the unperturbed boundary, surface tolerance " << tolerance << "\n\n"
            << "| mesh | mode | hexes | MSJ unperturbed | runs | 0 inverted | MSJ ≥ unperturbed | error ≤ tolerance | "
               "inverted in | MSJ out min / median | error median / max | s per 10k hexes median / max |\n"
            << "|---|---|---:|---:|---:|---:|---:|---:|---|---|---|---|\n";
  Stress_totals total[4];
  const Thread_limit limit(threads);
  auto line_of = [&](const Stress_totals& t) {
    char b[512];
    std::snprintf(b, sizeof b, "%d | %s | %s | %s | %zu–%zu | %.3f / %.3f | %.4f / %.4f | %.2f / %.2f |", t.runs,
                  t.pct(t.untangled).c_str(), t.pct(t.above).c_str(), t.pct(t.within).c_str(),
                  t.runs ? t.inverted_min : 0, t.inverted_max, quantile_of(t.msj, 0.), quantile_of(t.msj, 0.5),
                  quantile_of(t.error, 0.5), quantile_of(t.error, 1.), quantile_of(t.seconds_per_10k, 0.5),
                  quantile_of(t.seconds_per_10k, 1.));
    return std::string(b);
  };
  for(const std::string& name : stress_meshes())
  {
    if(!only.empty() && name.find(only) == std::string::npos) continue;
    Stress_base base;
    std::string error;
    if(!read_stress_base(dir, name, base, error))
    {
      std::cout << "| " << name << " | read error: " << error << " |" << std::endl;
      continue;
    }
    const std::string reference_path = writer.enabled() ? writer.write_reference(name, base.reference) : std::string();
    for(int mode = 0; mode < 3; ++mode)
    {
      Stress_totals line;
      for(int k = 0; k < seeds; ++k)
      {
        const Stress_run run = run_stress_case(base, Stress_mode(mode), unsigned(k + 1), tolerance);
        if(writer.enabled())
          writer.add_run(writer.write_input(name, stress_mode_files[mode], k + 1, run.input), reference_path, run.draw,
                         run.result);
        for(Stress_totals* t : {&line, &total[mode], &total[3]})
          t->add(run.result, base.msj, base.mesh.hexahedra.size(), run.seconds, tolerance);
      }
      char head[256];
      std::snprintf(head, sizeof head, "| %s | %s | %zu | %.3f | ", name.c_str(), stress_mode_names[mode],
                    base.mesh.hexahedra.size(), base.msj);
      std::cout << head << line_of(line) << std::endl;
    }
  }
  for(int mode = 0; mode < 4; ++mode)
    if(total[mode].runs > 0)
      std::cout << "| **all** | " << (mode < 3 ? stress_mode_names[mode] : "**every mode**") << " | | | "
                << line_of(total[mode]) << "\n";
  if(total[3].runs > 0)
  {
    const Stress_totals& t = total[3];
    char b[1024];
    std::snprintf(b, sizeof b, "\nDistributions over the %d runs (quantiles 0 / 0.1 / 0.5 / 0.9 / 1): MSJ out %.3f / %.3f / %.3f / "
                "%.3f / %.3f; surface error %.4f / %.4f / %.4f / %.4f / %.4f; s per 10k hexes %.2f / %.2f / %.2f / "
                "%.2f / %.2f; %.0f s in all\n",
                t.runs, quantile_of(t.msj, 0.), quantile_of(t.msj, 0.1), quantile_of(t.msj, 0.5),
                quantile_of(t.msj, 0.9), quantile_of(t.msj, 1.), quantile_of(t.error, 0.), quantile_of(t.error, 0.1),
                quantile_of(t.error, 0.5), quantile_of(t.error, 0.9), quantile_of(t.error, 1.),
                quantile_of(t.seconds_per_10k, 0.), quantile_of(t.seconds_per_10k, 0.1),
                quantile_of(t.seconds_per_10k, 0.5), quantile_of(t.seconds_per_10k, 0.9),
                quantile_of(t.seconds_per_10k, 1.), t.seconds);
    std::cout << b;
  }
  std::cout << std::flush;
  return 0;
}

// ---------------------------------------------------------------------------
// --boundary-layer

/// `--stage-details` with `--boundary-layer`: the same case untangled only
/// (what the untangling alone moves and breaks), then every stage of the
/// whole run `r` with its details
static void boundary_layer_stage_details(const boundary_layer::Case& c,
                                         const HMO::internal::Reference_distance_index& index,
                                         const HMO::Optimization_result& r)
{
  HMO::internal::Triangle_surface reference;
  HMO::internal::boundary_surface(HMO::internal::make_hex_mesh_arrays(c.mesh, K()), reference);
  Mesh mesh = c.input;
  Setup_visitor visitor;
  const HMO::Optimization_result u = run_optimiser(mesh, true, reference, 0.005, visitor);
  const boundary_layer::Measures m = boundary_layer::measure(c, mesh, index);
  char b[256];
  std::snprintf(b, sizeof b, "    untangling only: inverted %zu, columns within 10 %% %.1f %%, wall error %.1e, moved %zu\n",
                u.inverted_after, 100. * m.columns_within, m.wall_error, m.moved);
  std::cout << b;
  for(const auto& s : r.stages)
    std::cout << "    " << s.name << ": MSJ " << s.msj_after << "; " << s.details << "\n";
  std::cout << std::flush;
}

/// The boundary-layer class (`boundary_layer_set.h`): `seeds` generated wall
/// meshes with pushed vertices, each optimised by `CGAL::optimize_hex_mesh`
/// with defaults and the generated boundary as reference. One line per run,
/// then the pass rates of the repair criteria: 0 inverted; at least 99 % of
/// the wall columns with their first-layer height within 10 %; wall vertices
/// on the wall to 1e-9 of the diagonal; at most 10 vertices moved per pushed one.
static int boundary_layer_sets(int seeds, int threads, bool stage_details)
{
  const Thread_limit limit(threads);
  std::cout << "Boundary-layer class: graded wall meshes (planar for odd seeds, curved for even ones), vertices of "
               "layers 2-4 pushed below the layer under them; reference = the generated boundary, default options\n\n"
            << "| seed | wall | hexes | first layer | growth | pushed | inverted in → out | MSJ out | columns within "
               "10 % | worst height change | wall error / diagonal | vertices moved | moved per pushed | s |\n"
            << "|---:|---|---:|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|\n";
  int runs = 0, untangled = 0, heights = 0, on_wall = 0, local = 0;
  std::vector<double> per_pushed, wall_errors, height_share;
  for(int k = 1; k <= seeds; ++k)
  {
    const boundary_layer::Case c = boundary_layer::make_case(unsigned(k));
    HMO::internal::Triangle_surface reference;
    HMO::internal::boundary_surface(HMO::internal::make_hex_mesh_arrays(c.mesh, K()), reference);
    const HMO::internal::Reference_distance_index index(reference);
    Mesh mesh = c.input;
    Setup_visitor visitor;
    const Clock::time_point start = Clock::now();
    const HMO::Optimization_result r = run_optimiser(mesh, false, reference, 0.005, visitor);
    const double seconds = seconds_since(start);
    const boundary_layer::Measures m = boundary_layer::measure(c, mesh, index);
    ++runs;
    untangled += r.inverted_after == 0;
    heights += m.columns_within >= 0.99;
    on_wall += m.wall_error <= 1e-9;
    local += m.moved_per_pushed <= 10.;
    per_pushed.push_back(m.moved_per_pushed);
    wall_errors.push_back(m.wall_error);
    height_share.push_back(m.columns_within);
    char b[512];
    std::snprintf(b, sizeof b, "| %d | %s | %zu | %.2g | %.2f | %zu | %zu → %zu | %.3f | %.1f %% | %.0f %% | %.1e | %zu | %.0f | %.2f |",
                  k, c.curved ? "curved" : "planar", c.mesh.hexahedra.size(), c.first_layer, c.growth,
                  c.pushed.size(), r.inverted_before, r.inverted_after, r.msj_after, 100. * m.columns_within,
                  100. * m.worst_height_change, m.wall_error, m.moved, m.moved_per_pushed, seconds);
    std::cout << b << std::endl;
    if(stage_details) boundary_layer_stage_details(c, index, r);
  }
  auto pct = [&](int n) {
    char b[48];
    std::snprintf(b, sizeof b, "%d of %d (%.0f %%)", n, runs, runs ? 100. * n / runs : 0.);
    return std::string(b);
  };
  std::cout << "\nPass rates: 0 inverted " << pct(untangled) << "; ≥ 99 % of the columns with their first layer within 10 % "
            << pct(heights) << "; wall vertices on the wall to 1e-9 of the diagonal " << pct(on_wall)
            << "; at most 10 vertices moved per pushed vertex " << pct(local) << "\n";
  char b[512];
  std::snprintf(b, sizeof b, "Medians: columns within 10 %% %.1f %%, wall error %.1e, moved per pushed %.0f\n",
                100. * quantile_of(height_share, 0.5), quantile_of(wall_errors, 0.5), quantile_of(per_pushed, 0.5));
  std::cout << b << std::flush;
  return 0;
}

// ---------------------------------------------------------------------------
// --ablate

/// A variant of the default pipeline: one stage turned off.
struct Ablation
{
  std::string name;
  std::function<void(HMO::internal::Optimization_schedule&, bool& pull_back)> change;
};

static std::vector<Ablation> ablations()
{
  typedef HMO::internal::Optimization_schedule S;
  return {
    {"default", [](S&, bool&) {}},
    {"no repair region", [](S& s, bool&) { s.repair_region = false; }},
    {"no input-shape ideal", [](S& s, bool&) { s.barrier_input_shape_sj = 2.; }},
    {"no give-back", [](S& s, bool&) { s.give_back = false; }},
    {"no interior barrier", [](S& s, bool&) { s.interior_stage = false; }},
    {"no edge-angle untangling", [](S& s, bool&) { s.edge_angle_stage = false; }},
    {"edge-angle untangling of 8 rounds", [](S& s, bool&) { s.edge_angle_rounds = 8; }},
    {"edge-angle untangling of 4 rounds", [](S& s, bool&) { s.edge_angle_rounds = 4; }},
    {"no barrier untangling", [](S& s, bool&) { s.barrier_stage = false; }},
    {"no untangler surface pass", [](S& s, bool&) { s.surface_stage = false; }},
    {"no untangle-again rounds", [](S& s, bool&) { s.untangle_again_rounds = 0; }},
    {"no SLIM pull-back", [](S&, bool& p) { p = false; }},
    {"no surface fit", [](S& s, bool&) { s.surface_fitting = false; }},
    {"no restoration", [](S& s, bool&) { s.restoration = false; }},
    {"no coarse-level start", [](S& s, bool&) { s.coarse_level_start = false; }},
    {"no max-min smoothing", [](S& s, bool&) { s.msj_stage_max_min = false; }},
    {"no turns", [](S& s, bool&) { s.max_turns = 0; }},
    {"no global ASJ start", [](S& s, bool&) { s.final_asj_global_iterations = 0; }},
    {"no final ASJ smoothing", [](S& s, bool&) { s.asj_passes = 0; s.final_asj_global_iterations = 0; }}};
}

/// What one variant did over the set.
struct Ablation_totals
{
  int rows = 0, rows_met = 0; // the published rows: MSJ ≥ Xu & Chen's with the error ≤ theirs
  double rows_seconds = 0.;
  std::vector<double> row_msj;
  Stress_totals stress;
};

/// `--ablate`: the default pipeline, then without each stage in turn
/// (`ablations()`, or those whose name contains `variant`), over the 8
/// published rows (whole tool runs, the published error as tolerance) and
/// the stress sets (`seeds` per mesh and mode). A stage earns its place when
/// its removal costs: fewer rows met, fewer stress runs untangled or within
/// the tolerance, lower MSJ. One line per variant.
static int ablate(const std::string& dir, const std::string& only, const std::string& variant, int seeds,
                  int threads)
{
  const auto published = read_published(HMO_PUBLISHED_CSV);
  const std::vector<std::string> rows = {
    "edge-cone/block_in.mesh", "edge-cone/bunny_in.mesh", "edge-cone/bust_in.mesh", "edge-cone/cap_in.mesh",
    "edge-cone/hanger_stresstest_in.mesh", "edge-cone/impeller_stresstest_in.mesh", "amips/rockerarm_li12.vtk",
    "amips/fertility_gregson11.mesh"};
  std::cout << "Ablation: the 8 published rows (tolerance: the paper's error) and the stress sets (" << seeds
            << " seeds per mesh and mode, tolerance 0.005)\n\n"
            << "| variant | rows: MSJ ≥ published, error ≤ published | rows: MSJ each | rows s | stress runs | "
               "0 inverted | error ≤ 0.005 | MSJ ≥ unperturbed | MSJ min / median | error median / max | stress s |\n"
            << "|---|---:|---|---:|---:|---:|---:|---:|---|---|---:|\n";
  const Thread_limit limit(threads);
  std::vector<Stress_base> bases; // read once for every variant
  for(const std::string& name : stress_meshes())
  {
    if(!only.empty() && name.find(only) == std::string::npos) continue;
    Stress_base base;
    std::string error;
    if(read_stress_base(dir, name, base, error)) bases.push_back(std::move(base));
  }
  for(const Ablation& a : ablations())
  {
    if(!variant.empty() && a.name != "default" && a.name.find(variant) == std::string::npos) continue;
    g_schedule = HMO::internal::Optimization_schedule();
    g_pull_back = true;
    a.change(g_schedule, g_pull_back);
    Ablation_totals t;
    std::string row_msj;
    for(const std::string& name : rows)
    {
      if(!only.empty() && name.find(only) == std::string::npos) continue;
      const auto it = published.find(name);
      double tolerance = 0.005;
      if(it != published.end() && !it->second.row[9].empty()) tolerance = std::stod(it->second.row[9]);
      const Row_run run = run_row(dir, name, false, false, nullptr, tolerance, false, threads, false);
      if(!run.error.empty()) { std::cout << "| " << a.name << " | " << name << ": " << run.error << " |\n"; continue; }
      const HMO::Optimization_result& r = run.result;
      const double paper_msj = it != published.end() && !it->second.row[7].empty() ? std::stod(it->second.row[7]) : 2.;
      ++t.rows;
      if(r.inverted_after == 0 && r.msj_after >= paper_msj && r.surface_error <= tolerance) ++t.rows_met;
      t.rows_seconds += run.seconds;
      char b[32];
      std::snprintf(b, sizeof b, "%s%.3f", row_msj.empty() ? "" : " ", r.msj_after);
      row_msj += b;
    }
    for(const Stress_base& base : bases)
      for(int mode = 0; mode < 3; ++mode)
        for(int k = 0; k < seeds; ++k)
        {
          const Stress_run run = run_stress_case(base, Stress_mode(mode), unsigned(k + 1), 0.005);
          t.stress.add(run.result, base.msj, base.mesh.hexahedra.size(), run.seconds, 0.005);
        }
    char line[1024];
    std::snprintf(line, sizeof line, "| %s | %d of %d | %s | %.1f | ", a.name.c_str(), t.rows_met, t.rows,
                  row_msj.c_str(), t.rows_seconds);
    const Stress_totals& st = t.stress;
    char tail[512];
    std::snprintf(tail, sizeof tail, "%d | %s | %s | %s | %.3f / %.3f | %.4f / %.4f | %.1f |", st.runs,
                  st.pct(st.untangled).c_str(), st.pct(st.within).c_str(), st.pct(st.above).c_str(),
                  quantile_of(st.msj, 0.), quantile_of(st.msj, 0.5), quantile_of(st.error, 0.5),
                  quantile_of(st.error, 1.), st.seconds);
    std::strncat(line, tail, sizeof line - std::strlen(line) - 1);
    std::cout << line << std::endl;
  }
  return 0;
}

// ---------------------------------------------------------------------------
// --scaling

struct Scaling_case
{
  std::string name;
  std::size_t grid_n = 0;     // a grid case when > 0
  int refinement_levels = 0;  // otherwise fertility refined this many times
  bool untangle_only = false;
  std::size_t hexes = 0;
};

/// The child's side: generate, optimise, send the measurements over `fd` as
/// one tab-separated line ("ok", hexes, inverted in/out, MSJ in/out, set-up
/// s, total s, time limit flag, hash; or "error", message).
static void scaling_child(const Scaling_case& c, const std::string& fertility, int threads, int fd)
{
  std::string message;
  {
    const Thread_limit limit(threads);
    Mesh mesh;
    bool ok = true;
    if(c.grid_n > 0)
      mesh = make_grid(c.grid_n, 0.01, 1);
    else
    {
      CGAL::IO::Hex_mesh_io_error err;
      if(!CGAL::IO::read_hex_mesh(fertility, mesh, &err))
      {
        message = std::string("error\tread error: ") + err.what() + "\n";
        ok = false;
      }
      for(int l = 0; ok && l < c.refinement_levels; ++l) mesh = refine_1_to_8(mesh);
    }
    if(ok)
    {
      Setup_visitor visitor;
      const HMO::internal::Triangle_surface no_reference;
      const Clock::time_point start = Clock::now();
      const HMO::Optimization_result r = run_optimiser(mesh, c.untangle_only, no_reference, 0.005, visitor);
      const double total = seconds_since(start);
      char b[512];
      std::snprintf(b, sizeof b, "ok\t%zu\t%zu\t%zu\t%.3f\t%.3f\t%.2f\t%.2f\t%d\t%s\n", mesh.hexahedra.size(),
                    r.inverted_before, r.inverted_after, r.msj_before, r.msj_after, visitor.setup_seconds, total,
                    int(r.time_limit_reached), hex16(coordinates_hash(mesh)).c_str());
      message = b;
    }
  }
  const char* p = message.data();
  std::size_t left = message.size();
  while(left > 0)
  {
    const ssize_t w = ::write(fd, p, left);
    if(w <= 0) break;
    p += w;
    left -= std::size_t(w);
  }
}

static std::vector<std::string> split_tabs(const std::string& s)
{
  std::vector<std::string> f;
  std::stringstream ss(s);
  std::string x;
  while(std::getline(ss, x, '\t')) f.push_back(x);
  return f;
}

/// Runs one case in a forked child and prints its row. Returns the output's
/// hash ("" when the child failed).
static std::string run_scaling_case(const Scaling_case& c, const std::string& fertility, int threads,
                                    const std::string& label, const std::string& compare_with)
{
  int fds[2];
  if(::pipe(fds) != 0)
  {
    std::cout << "| " << label << " | pipe() failed |" << std::endl;
    return "";
  }
  std::cout.flush();
  std::fflush(stdout);
  const pid_t pid = ::fork();
  if(pid < 0)
  {
    ::close(fds[0]);
    ::close(fds[1]);
    std::cout << "| " << label << " | fork() failed |" << std::endl;
    return "";
  }
  if(pid == 0)
  {
    ::close(fds[0]);
    scaling_child(c, fertility, threads, fds[1]);
    ::close(fds[1]);
    ::_exit(0);
  }
  ::close(fds[1]);
  std::string message;
  char buffer[4096];
  for(;;)
  {
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if(n <= 0) break;
    message.append(buffer, std::size_t(n));
  }
  ::close(fds[0]);
  int status = 0;
  struct rusage usage;
  std::memset(&usage, 0, sizeof usage);
  while(::wait4(pid, &status, 0, &usage) < 0 && errno == EINTR) {}
  const double peak_mb = double(usage.ru_maxrss) / 1024.; // ru_maxrss is in KiB on Linux

  if(!message.empty() && message.back() == '\n') message.pop_back();
  const std::vector<std::string> f = split_tabs(message);
  if(f.size() != 10 || f[0] != "ok")
  {
    std::string why = f.size() >= 2 && f[0] == "error" ? f[1] : "no result";
    if(WIFSIGNALED(status)) why += ", killed by signal " + std::to_string(WTERMSIG(status));
    else if(WIFEXITED(status) && WEXITSTATUS(status) != 0) why += ", exit status " + std::to_string(WEXITSTATUS(status));
    char b[64];
    std::snprintf(b, sizeof b, "%.0f", peak_mb);
    std::cout << "| " << label << " | " << c.hexes << " | " << why << " | | | | | | " << b << " | |" << std::endl;
    return "";
  }
  const double setup = std::stod(f[6]);
  std::string hash = f[9];
  if(!compare_with.empty() && compare_with != hash) hash += " (hash mismatch with " + compare_with + ")";
  char line[1024];
  std::snprintf(line, sizeof line, "| %s | %s | %s | %s | %s | %s | %s | %s%s | %.0f | %s |", label.c_str(),
                f[1].c_str(), f[2].c_str(), f[3].c_str(), f[4].c_str(), f[5].c_str(),
                setup < 0. ? "–" : f[6].c_str(), f[7].c_str(), f[8] == "1" ? " (time limit)" : "", peak_mb,
                hash.c_str());
  std::cout << line << std::endl;
  return f[9];
}

static int scaling(const std::string& dir, bool have_data, bool untangle_only, const std::string& only,
                   std::size_t max_hexes, const std::vector<int>& thread_runs)
{
  const std::string fertility = dir + "/amips/fertility_gregson11.mesh";
  std::size_t fertility_hexes = 0;
  if(have_data)
  {
    Mesh m;
    CGAL::IO::Hex_mesh_io_error err;
    if(CGAL::IO::read_hex_mesh(fertility, m, &err)) fertility_hexes = m.hexahedra.size();
    else std::cout << "cannot read " << fertility << " (" << err.what() << "): its rows are skipped\n";
  }
  else
    std::cout << "shared data folder " << dir << " is absent: the fertility rows are skipped\n";

  std::vector<Scaling_case> cases;
  const auto grid = [&](std::size_t n, bool u) {
    Scaling_case c;
    c.name = "grid n=" + std::to_string(n) + ", 1 % inverted, " + (u ? "--untangle" : "pipeline");
    c.grid_n = n;
    c.untangle_only = u;
    c.hexes = n * n * n;
    cases.push_back(c);
  };
  const auto refined = [&](int levels) {
    Scaling_case c;
    c.name = "fertility_gregson11 refined " + std::to_string(levels) + (levels == 1 ? " level" : " levels") + ", pipeline";
    c.refinement_levels = levels;
    c.hexes = fertility_hexes << (3 * levels);
    cases.push_back(c);
  };
  grid(50, true);
  grid(50, false);
  refined(1);
  grid(100, true);
  grid(100, false);
  refined(2);

  struct rusage self;
  ::getrusage(RUSAGE_SELF, &self);
  std::cout << "scaling: grids of the unit cube with 1 % of their hexes inverted (seed 1); optimiser defaults; "
            << "each case in its own process, whose peak memory includes the parent's "
            << self.ru_maxrss / 1024 << " MB\n\n"
            << "| case | hexes | inverted in | inverted out | MSJ in | MSJ out | set-up s | total s | peak memory MB | hash |\n"
            << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
  for(const Scaling_case& c : cases)
  {
    if(!only.empty() && c.name.find(only) == std::string::npos) continue;
    if(untangle_only && !c.untangle_only) continue;
    if(c.grid_n == 0 && fertility_hexes == 0) continue;
    if(max_hexes > 0 && c.hexes > max_hexes)
    {
      std::cout << "| " << c.name << " | " << c.hexes << " | skipped (more than " << max_hexes << " hexes) | | | | | | | |"
                << std::endl;
      continue;
    }
    std::string first_hash;
    for(std::size_t t = 0; t < thread_runs.size(); ++t)
    {
      const std::string label =
        thread_runs[t] > 0 ? c.name + " (" + std::to_string(thread_runs[t]) + " thr)" : c.name;
      const std::string h = run_scaling_case(c, fertility, thread_runs[t], label, t > 0 ? first_hash : "");
      if(t == 0) first_hash = h;
    }
  }
  return 0;
}

// ---------------------------------------------------------------------------

// ---------------------------------------------------------------------------
// --results FILE: the tables also go into a section of a Markdown file

/// A stream buffer that writes to two others: the console and a copy.
class Tee_buffer : public std::streambuf
{
public:
  Tee_buffer(std::streambuf* a, std::streambuf* b) : a_(a), b_(b) {}

protected:
  int overflow(int c) override
  {
    if(c == traits_type::eof()) return traits_type::not_eof(c);
    const bool ok = a_->sputc(char(c)) != traits_type::eof() && b_->sputc(char(c)) != traits_type::eof();
    return ok ? c : traits_type::eof();
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override
  {
    const std::streamsize written = a_->sputn(s, n);
    b_->sputn(s, n);
    return written;
  }
  int sync() override { return a_->pubsync() == 0 && b_->pubsync() == 0 ? 0 : -1; }

private:
  std::streambuf* a_;
  std::streambuf* b_;
};

/// Replaces, in the Markdown file `path`, the text between the lines
/// "<!-- begin NAME -->" and "<!-- end NAME -->" by `table` (the section is
/// appended when absent), so that the benchmark rewrites its own tables and
/// leaves the rest of the file alone. Written through a temporary renamed in
/// place.
static bool write_results_section(const std::string& path, const std::string& name, const std::string& command,
                                  const std::string& table)
{
  std::string text;
  {
    std::ifstream in(path, std::ios::binary);
    if(in) text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const std::string begin = "<!-- begin " + name + " -->\n", end = "<!-- end " + name + " -->\n";
  const std::string section = begin + "Written by `" + command + "`.\n\n" + table + (table.empty() || table.back() == '\n' ? "" : "\n") + end;
  const std::size_t b = text.find(begin), e = b == std::string::npos ? b : text.find(end, b);
  if(b != std::string::npos && e != std::string::npos) text.replace(b, e + end.size() - b, section);
  else text += (text.empty() || text.back() == '\n' ? "\n" : "\n\n") + section;
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    if(!out.flush())
    {
      std::remove(tmp.c_str());
      return false;
    }
  }
  return std::rename(tmp.c_str(), path.c_str()) == 0;
}

// ---------------------------------------------------------------------------
// --paper: `Method::paper` with each published run's recipe

/// θ in degrees from the authors' `cosangle` = cos(180° − θ)
static double theta_of_cosangle(double c) { return 180. - std::acos(c) * 180. / 3.14159265358979323846; }

/// One published run on the shared rows (../shared/paper/SCRIPTS.md): its
/// figures, its parameters as a `Paper_recipe`, and how the authors' tools
/// ran it (`cotrik_run`)
struct Paper_row
{
  std::string file;
  double msj, asj, error; ///< the published result files' figures
  HMO::Paper_recipe recipe;
  bool generic;           ///< the generic script (LocalMeshOpt.sh) rather than a hand-written one
  /// hand-written rows: the untangling call's own arguments, the MSJ call's
  /// extra ones, and the final SmoothMap's iterations and cosangle
  std::string untangle_args, post_cosangle;
  int post_iterations = 20;
};

static std::vector<Paper_row> paper_rows()
{
  std::vector<Paper_row> rows;
  auto generic = [&](const char* file, double msj, double asj, double error, double target, double theta) {
    Paper_row r{file, msj, asj, error, HMO::Paper_recipe(), true, "", "", 20};
    r.recipe.target_msj = target;
    r.recipe.sharp_angle = theta;
    rows.push_back(r);
  };
  // Table 1, hand-written: the untangling's θ is the tools' default (cosangle 0.9397)
  const double theta0 = theta_of_cosangle(0.939692621);
  auto table1 = [&](const char* file, double msj, double asj, double error, const char* untangle,
                    const char* post_cosangle, int post_iterations) -> HMO::Paper_recipe& {
    rows.push_back(Paper_row{file, msj, asj, error, HMO::Paper_recipe(), false, untangle, post_cosangle, post_iterations});
    HMO::Paper_recipe& r = rows.back().recipe;
    r.sharp_angle = theta0;
    r.pull_back_below_alpha = 1e12; // the scripts run SlimHex whatever α ended at
    r.msj_in_steps = false;         // and one MSJ call, straight to the target
    return r;
  };
  {
    HMO::Paper_recipe& r = table1("edge-cone/block_in.mesh", 0.252, 0.857, 0.0027,
      "LocalMeshOpt input=scaled.vtk alpha=100 beta=100 gamma=1.0 anisotropy=0.6 allowBigStep=true minScaledJacobian=0", "0.996", 20);
    r.alpha = r.beta = 100.; r.xi = 0.6;
    r.untangle_rings = 50; // LocalMeshOpt without useSmallBlock: the bad cells grown by blockSize (50) layers
    r.untangle_big_step = true;
    r.msj_alpha = r.msj_beta = 1000.; r.msj_xi = 0.1; r.target_msj = 0.25; r.msj_sharp_angle = theta_of_cosangle(0.996);
  }
  generic("edge-cone/bunny_in.mesh", 0.651, 0.953, 0.0065, 0.65, 170.);
  {
    HMO::Paper_recipe& r = table1("edge-cone/bust_in.mesh", 0.201, 0.869, 0.0088,
      "LocalMeshOpt input=scaled.vtk alpha=100 beta=100 gamma=1.0 anisotropy=0.6 minScaledJacobian=0", "0.9848", 10);
    r.alpha = r.beta = 100.; r.xi = 0.6;
    r.untangle_rings = 50; // as block's
    r.msj_alpha = r.msj_beta = 1000.; r.msj_xi = 0.6; r.target_msj = 0.18;
    r.msj_sharp_angle = theta_of_cosangle(0.9359);
  }
  {
    HMO::Paper_recipe& r = table1("edge-cone/cap_in.mesh", 0.114, 0.775, 0.0053,
      "LocalMeshOpt input=scaled.vtk alpha=200 beta=500 gamma=1.0 anisotropy=0.2 minScaledJacobian=0.4 useSmallBlock=true "
      "blockSize=20", "0.939692621", 10);
    r.alpha = 200.; r.beta = 500.; r.xi = 0.2;
    r.msj_alpha = 500.; r.msj_beta = 1000.; r.msj_xi = 0.2; r.target_msj = 0.1;
  }
  {
    HMO::Paper_recipe& r = table1("edge-cone/hanger_stresstest_in.mesh", 0.723, 0.974, 0.0015,
      "MeshOpt input=scaled.vtk targetSurface=scaled.vtk alpha=20 beta=20 anisotropy=1.2 minScaledJacobian=0.66 "
      "cosangle=0.999 stepSize=0.999 useProjection=false", "0.999", 20);
    r.sharp_angle = r.msj_sharp_angle = theta_of_cosangle(0.999);
    r.global = true; r.alpha = r.beta = 20.; r.xi = 1.2; r.target_msj = 0.66;
    r.msj_alpha = r.msj_beta = 20.; r.msj_xi = 1.2; // (the same run: α, β count as 500 in the MSJ stages)
    r.pull_back_below_alpha = 0.; // no SlimHex
  }
  {
    HMO::Paper_recipe& r = table1("edge-cone/impeller_stresstest_in.mesh", 0.192, 0.934, 0.0005,
      "MeshOpt input=scaled.vtk targetSurface=scaled.vtk alpha=2000 beta=2000 anisotropy=0.02 minScaledJacobian=0.66 "
      "cosangle=0.999 iters=8", "0.99948", 20);
    r.sharp_angle = theta_of_cosangle(0.999);
    r.global = true; r.alpha = r.beta = 2000.; r.xi = 0.02;
    r.msj_alpha = 500.; r.msj_beta = 1250.; r.msj_xi = 0.1; r.target_msj = 0.2;
    r.msj_sharp_angle = theta_of_cosangle(0.99948);
  }
  // the two Table-2 result files (their MSJ swapped in the printed table)
  generic("amips/fertility_gregson11.mesh", 0.602, 0.933, 0.0094, 0.75, 165.);
  generic("amips/rockerarm_li12.vtk", 0.700, 0.939, 0.0079, 0.75, 165.);
  return rows;
}

/// what a run left: inverted, MSJ, ASJ, surface error against the input's boundary
struct Paper_figures
{
  std::string error;
  std::size_t inverted = 0;
  double msj = 0., asj = 0., surface_error = 0., seconds = 0.;
};

static Paper_figures measure_output(const Mesh& input, const Mesh& output, double seconds)
{
  Paper_figures f;
  const auto q = CGAL::hex_mesh_quality(output);
  f.inverted = q.inverted; f.msj = q.msj; f.asj = q.asj; f.seconds = seconds;
  HMO::internal::Triangle_surface boundary;
  HMO::internal::boundary_surface(HMO::internal::make_hex_mesh_arrays(input, K()), boundary);
  f.surface_error = CGAL::hex_mesh_surface_error(output, boundary);
  return f;
}

/// Runs the authors' tools on `in` (VTK) with the row's recipe in the
/// folder `work`, as their scripts do; the result is `work`/result.vtk.
/// Returns false (with `why`) when a tool fails.
static bool cotrik_run(const std::string& bin, const std::string& work, const Paper_row& row, std::string& why)
{
  auto run = [&](const std::string& args) { // one of the tools, its output appended to tools.log
    const std::string cmd = "cd '" + work + "' && '" + bin + "/" + args.substr(0, args.find(' ')) + "'" +
                            args.substr(args.find(' ')) + " >> tools.log 2>&1";
    if(std::system(cmd.c_str()) == 0) return true;
    why = "failed: " + args.substr(0, 60);
    return false;
  };
  auto copy = [&](const std::string& from, const std::string& to) {
    std::ifstream in(work + "/" + from, std::ios::binary);
    std::ofstream out(work + "/" + to, std::ios::binary);
    out << in.rdbuf();
  };
  auto quality = [&](const std::string& file) {
    Mesh m;
    if(!CGAL::IO::read_hex_mesh(work + "/" + file, m)) return CGAL::hex_mesh_quality(Mesh());
    return CGAL::hex_mesh_quality(m);
  };
  auto num = [](double x) { std::ostringstream s; s << std::setprecision(10) << x; return s.str(); };
  const HMO::Paper_recipe& r = row.recipe;
  const std::string cos_untangle = num(std::cos((180. - r.sharp_angle) * 3.14159265358979323846 / 180.));
  const double msj_theta = r.msj_sharp_angle > 0. ? r.msj_sharp_angle : r.sharp_angle;
  const std::string cos_msj = num(std::cos((180. - msj_theta) * 3.14159265358979323846 / 180.));
  if(!run("MeshScale input.vtk scaled.vtk")) return false;
  std::string current = "scaled.vtk", surface = "scaled.vtk";
  // one LocalMeshOpt call toward `target` from `current`; true when it left nothing inverted and the MSJ above target
  auto local = [&](double a, double b, double xi, double target, int block, bool big_step, const std::string& cos) {
    if(!run("LocalMeshOpt input=" + current + " alpha=" + num(a) + " beta=" + num(b) + " gamma=1.0 anisotropy=" +
            num(xi) + " minScaledJacobian=" + num(target) + " cosangle=" + cos + " useSmallBlock=true blockSize=" +
            std::to_string(block) + " localIters=20 iters=20 allowBigStep=" + (big_step ? "true" : "false") +
            " targetSurface=" + surface + " projectToTargetSurface=true"))
      return false;
    const auto q = quality("BestLocalOpt.vtk");
    return q.inverted == 0 && q.msj > target;
  };
  // the scripts' back-off: ξ − 0.1 down to 0.2, then α, β halved and ξ back to its start
  auto with_back_off = [&](double& a, double& b, double xi0, double target, int block, double min_alpha,
                           const std::string& out) {
    double xi = xi0;
    for(;;)
    {
      if(local(a, b, xi, target, block, false, cos_msj)) { copy("BestLocalOpt.vtk", out); return true; }
      if(!why.empty()) return false;
      xi -= 0.1;
      if(xi < 0.2 - 1e-9) { a /= 2.; b /= 2.; xi = xi0; }
      if(a < min_alpha) return false;
    }
  };
  if(row.generic)
  {
    if(!run("SmoothMap orig=scaled.vtk input=scaled.vtk output=smoothed.vtk iters=10 preserveSharpFeature=true cosangle=" +
            cos_untangle))
      return false;
    current = surface = "smoothed.vtk";
    double a = r.alpha, b = r.beta;
    if(quality(current).inverted > 0)
    {
      if(!with_back_off(a, b, r.xi, 0., 100, 1., "untangled.vtk") && !why.empty()) return false;
      current = "untangled.vtk";
      if(a < 500. && !run("SlimHex input=untangled.vtk target=smoothed.vtk result=slim.vtk iters=20")) return false;
      if(a < 500.) current = "slim.vtk";
    }
    for(int k = 1;; ++k)
    {
      double t = k <= 4 ? 0.1 * k : 0.4 + 0.05 * (k - 4);
      if(t > r.target_msj) t = r.target_msj;
      double sa = r.msj_alpha, sb = r.msj_beta;
      if(!with_back_off(sa, sb, r.msj_xi, t, 50, 500., "step.vtk")) { if(!why.empty()) return false; break; }
      current = "step.vtk";
      if(t >= r.target_msj) break;
    }
  }
  else
  {
    // Table 1: one untangling call, SlimHex, one MSJ call (SCRIPTS.md)
    if(!run(row.untangle_args)) return false;
    copy(r.global ? "opt.vtk" : "BestLocalOpt.vtk", "untangled.vtk");
    current = "untangled.vtk";
    if(r.pull_back_below_alpha > 0.)
    {
      if(!run("SlimHex input=untangled.vtk target=scaled.vtk result=slim.vtk iters=20")) return false;
      current = "slim.vtk";
      local(r.msj_alpha, r.msj_beta, r.msj_xi, r.target_msj, 100, false, cos_msj);
      if(!why.empty()) return false;
      copy("BestLocalOpt.vtk", "msj.vtk");
      current = "msj.vtk";
      if(r.global)
      {
        if(!run("SlimHex input=msj.vtk target=scaled.vtk result=slim2.vtk iters=5")) return false;
        current = "slim2.vtk";
      }
    }
  }
  if(!run("SmoothMap orig=scaled.vtk input=" + current + " output=final.vtk iters=" + std::to_string(row.post_iterations) +
          " preserveQuality=true preserveSharpFeature=true cosangle=" + (row.generic ? cos_msj : row.post_cosangle)))
    return false;
  return run("MeshScale final.vtk result.vtk orig=input.vtk");
}

static std::string paper_cell(const Paper_figures& f, double msj, double error)
{
  if(!f.error.empty()) return f.error;
  char b[160];
  std::snprintf(b, sizeof b, "%.3f / %.3f / %.4f / %.1f s%s%s", f.msj, f.asj, f.surface_error, f.seconds,
                f.inverted ? (", " + std::to_string(f.inverted) + " inverted").c_str() : "",
                f.inverted == 0 && f.msj >= 0.9 * msj && f.surface_error <= 1.2 * error ? " ✓" : "");
  return b;
}

/// `Method::paper` with each row's published recipe (and, given the
/// authors' tools, theirs on the same input), beside the published figures
static int paper_recipes(const std::string& dir, const std::string& only, int threads, const std::string& cotrik)
{
  std::cout << "Method::paper with the published recipes (../shared/paper/SCRIPTS.md); surface tolerance: the "
               "published error; ✓: 0 inverted, MSJ ≥ 90 % and error ≤ 1.2 × the published\n\n"
            << "| row | published MSJ / ASJ / err | paper mode MSJ / ASJ / err / s | authors' tools MSJ / ASJ / err / s |\n"
            << "|---|---|---|---|\n";
  int failed = 0;
  for(const Paper_row& row : paper_rows())
  {
    if(!only.empty() && row.file.find(only) == std::string::npos) continue;
    Mesh input;
    if(!CGAL::IO::read_hex_mesh(dir + "/" + row.file, input))
    {
      std::cout << "| " << row.file << " | read error | | |\n";
      ++failed;
      continue;
    }
    g_recipe = row.recipe;
    const Row_run p = run_row(dir, row.file, false, false, nullptr, row.error, false, threads, false, true);
    g_recipe = HMO::Paper_recipe();
    Paper_figures ours;
    if(p.error.empty()) ours = measure_output(input, p.output, p.seconds);
    else ours.error = p.error;
    Paper_figures theirs;
    if(cotrik.empty()) theirs.error = "– (no --cotrik)";
    else
    {
      char tmpl[] = "/tmp/hmo_cotrik_XXXXXX";
      const std::string work = ::mkdtemp(tmpl) ? tmpl : "";
      std::string why;
      const Clock::time_point t = Clock::now();
      const std::string prep = "/usr/bin/python3 '" + cotrik + "/add_boundary_quads.py' '" + dir + "/" + row.file +
                               "' '" + work + "/input.vtk' > /dev/null";
      Mesh out;
      if(work.empty() || std::system(prep.c_str()) != 0) theirs.error = "input conversion failed";
      else if(!cotrik_run(cotrik + "/bin", work, row, why)) theirs.error = why;
      else if(!CGAL::IO::read_hex_mesh(work + "/result.vtk", out)) theirs.error = "no result";
      else theirs = measure_output(input, out, seconds_since(t));
      if(!work.empty() && std::system(("rm -rf '" + work + "'").c_str()) != 0) theirs.error += " (work dir kept)";
    }
    char pub[64];
    std::snprintf(pub, sizeof pub, "%.3f / %.3f / %.4f", row.msj, row.asj, row.error);
    std::cout << "| " << row.file << " | " << pub << " | " << paper_cell(ours, row.msj, row.error) << " | "
              << paper_cell(theirs, row.msj, row.error) << " |" << std::endl;
  }
  return failed ? 1 : 0;
}

static void usage(std::ostream& out)
{
  out << "usage: benchmark_hex_mesh_optimization [DATA_DIR] [--untangle] [--only SUBSTRING]\n"
         "                                       [--threads N | --threads-compare]\n"
         "                                       [--scaling [--scaling-max-hexes N]]\n"
         "  (default)              the whole pipeline on the shared meshes, beside the published figures\n"
         "  --untangle             untangling only (with --scaling: only the untangling cases)\n"
         "  --no-paper-method      skip the paper-method column (the paper's pipeline on the rows with its figures)\n"
         "  --only SUBSTRING       only the rows whose name contains SUBSTRING\n"
         "  --threads N            at most N TBB threads\n"
         "  --threads-compare      every row under 1 and under 2 threads; times and output hashes\n"
         "  --scaling              generated grids (125k, 1M hexes) and refined fertility (159k, 1.27M)\n"
         "  --scaling-max-hexes N  with --scaling, skip the cases of more than N hexes\n"
         "  --stress               stress sets: every valid shared mesh perturbed (interior / all vertices /\n"
         "                         boundary-locked)\n"
         "  --stress-seeds N       with --stress or --ablate, N draws per mesh and mode (default 10);\n"
         "                         with --boundary-layer, N generated meshes\n"
         "  --boundary-layer       the boundary-layer class: generated graded wall meshes with pushed\n"
         "                         vertices; first-layer heights, wall distance, vertices moved\n"
         "  --stage-details        with --boundary-layer, each case also untangled only, and every stage's details\n"
         "  --stress-write DIR     with --stress, write each perturbed input, the reference surfaces and\n"
         "                         a line per run (stress_runs.tsv) into the existing folder DIR\n"
         "  --ablate               the default pipeline, then without each stage in turn, over the 8\n"
         "                         published rows and the stress sets (--stress-seeds per mesh and mode)\n"
         "  --ablate-only NAME     with --ablate, the default and the variants whose name contains NAME\n"
         "  --variant NAME         the first of --ablate's variants whose name contains NAME, in any mode\n"
         "  --paper                the paper's method with each published run's recipe (SCRIPTS.md) on its\n"
         "                         8 rows, beside the published figures\n"
         "  --cotrik DEST          with --paper, also run the authors' tools (build_cotrik.sh DEST) on each row\n"
         "  --results FILE         also write the tables into FILE (Markdown), replacing the section of\n"
         "                         this mode (rows, untangle, scaling, stress or ablation) and keeping the rest\n"
         "DATA_DIR defaults to " HMO_SHARED_DATA_DIR "\n";
}

static bool parse_count(const char* s, long long min, long long& value)
{
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(s, &end, 10);
  if(errno != 0 || end == s || *end != '\0' || v < min) return false;
  value = v;
  return true;
}

int main(int argc, char** argv)
{
  std::string dir = HMO_SHARED_DATA_DIR, only;
  bool untangle_only = false, threads_compare = false, scaling_mode = false, stress_mode = false, paper_column = true;
  long long threads = 0, max_hexes = 0, stress_seeds = 10;
  std::string stress_write, ablate_variant, results, variant;
  bool ablate_mode = false, boundary_layer_mode = false, paper_mode = false, stage_details = false;
  std::string cotrik;
  for(int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if(a == "--only" && has_value) only = argv[++i];
    else if(a == "--untangle") untangle_only = true;
    else if(a == "--no-paper-method") paper_column = false;
    else if(a == "--threads-compare") threads_compare = true;
    else if(a == "--threads" && has_value)
    {
      if(!parse_count(argv[++i], 1, threads))
      {
        std::cerr << "benchmark_hex_mesh_optimization: --threads needs a positive integer\n";
        return 2;
      }
    }
    else if(a == "--scaling") scaling_mode = true;
    else if(a == "--stress") stress_mode = true;
    else if(a == "--boundary-layer") boundary_layer_mode = true;
    else if(a == "--stage-details") stage_details = true;
    else if(a == "--ablate") ablate_mode = true;
    else if(a == "--paper") paper_mode = true;
    else if(a == "--cotrik" && has_value) cotrik = argv[++i];
    else if(a == "--ablate-only" && has_value) ablate_variant = argv[++i];
    else if(a == "--stress-seeds" && has_value)
    {
      if(!parse_count(argv[++i], 1, stress_seeds))
      {
        std::cerr << "benchmark_hex_mesh_optimization: --stress-seeds needs a positive integer\n";
        return 2;
      }
    }
    else if(a == "--stress-write" && has_value) stress_write = argv[++i];
    else if(a == "--results" && has_value) results = argv[++i];
    else if(a == "--variant" && has_value) variant = argv[++i];
    else if(a == "--scaling-max-hexes" && has_value)
    {
      if(!parse_count(argv[++i], 1, max_hexes))
      {
        std::cerr << "benchmark_hex_mesh_optimization: --scaling-max-hexes needs a positive integer\n";
        return 2;
      }
    }
    else if(a == "-h" || a == "--help")
    {
      usage(std::cout);
      return 0;
    }
    else if(!a.empty() && a[0] == '-')
    {
      std::cerr << "benchmark_hex_mesh_optimization: unknown option or missing value: " << a << "\n";
      usage(std::cerr);
      return 2;
    }
    else dir = a;
  }
  if(!stress_write.empty())
  {
    struct stat ws;
    if(!stress_mode || ::stat(stress_write.c_str(), &ws) != 0 || !S_ISDIR(ws.st_mode))
    {
      std::cerr << "benchmark_hex_mesh_optimization: --stress-write needs --stress and an existing folder: "
                << stress_write << "\n";
      return 2;
    }
  }
  if(threads_compare && threads > 0)
  {
    std::cerr << "benchmark_hex_mesh_optimization: --threads and --threads-compare exclude each other\n";
    return 2;
  }
#ifndef CGAL_LINKED_WITH_TBB
  if(threads_compare || threads > 0)
  {
    std::cerr << "benchmark_hex_mesh_optimization: built without TBB: --threads and --threads-compare are unavailable\n";
    return 2;
  }
#endif
  std::vector<int> thread_runs;
  if(threads_compare) thread_runs = {1, 2};
  else thread_runs = {int(threads)};

  if(!variant.empty())
  {
    // one of --ablate's variants, for any mode
    bool found = false;
    for(const Ablation& a : ablations())
      if(a.name != "default" && a.name.find(variant) != std::string::npos && !found)
      {
        a.change(g_schedule, g_pull_back);
        std::cout << "variant: " << a.name << "\n";
        found = true;
      }
    if(!found)
    {
      std::cerr << "benchmark_hex_mesh_optimization: --variant: no variant contains '" << variant << "'\n";
      return 2;
    }
  }
  if(stress_mode && threads_compare)
  {
    std::cerr << "benchmark_hex_mesh_optimization: --stress runs under one thread setting (--threads N)\n";
    return 2;
  }
  struct stat st;
  const bool have_data = ::stat((dir + "/README.md").c_str(), &st) == 0;
  if(!scaling_mode && !boundary_layer_mode && !have_data)
  {
    std::cout << "shared data folder " << dir << " is absent: nothing to benchmark" << std::endl;
    return 0;
  }

  // with --results, everything printed to standard output is also kept
  std::ostringstream copy;
  Tee_buffer tee(std::cout.rdbuf(), copy.rdbuf());
  std::streambuf* const console = std::cout.rdbuf();
  if(!results.empty()) std::cout.rdbuf(&tee);
  int status = 0;
  const char* section = "rows";
  if(scaling_mode)
  {
    section = "scaling";
    status = scaling(dir, have_data, untangle_only, only, std::size_t(max_hexes), thread_runs);
  }
  else if(boundary_layer_mode)
  {
    section = "boundary-layer";
    status = boundary_layer_sets(int(stress_seeds), int(threads), stage_details);
  }
  else if(paper_mode)
  {
    section = "paper";
    status = paper_recipes(dir, only, int(threads), cotrik);
  }
  else if(ablate_mode)
  {
    section = "ablation";
    status = ablate(dir, only, ablate_variant, int(stress_seeds), int(threads));
  }
  else if(stress_mode)
  {
    section = "stress";
    status = stress_sets(dir, only, int(stress_seeds), int(threads), stress_write);
  }
  else
  {
    section = untangle_only ? "untangle" : "rows";
    status = benchmark_rows(dir, untangle_only, only, thread_runs, paper_column);
  }
  std::cout.flush();
  std::cout.rdbuf(console);
  if(!results.empty() && status == 0)
  {
    std::string command = "benchmark_hex_mesh_optimization";
    for(int i = 1; i < argc; ++i)
      if(std::string(argv[i]) == "--results") ++i;
      else if(argv[i] != dir) command += std::string(" ") + argv[i];
    if(!write_results_section(results, section, command, copy.str()))
    {
      std::cerr << "benchmark_hex_mesh_optimization: cannot write " << results << "\n";
      return 1;
    }
  }
  return status;
}
