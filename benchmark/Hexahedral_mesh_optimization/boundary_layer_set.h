// The boundary-layer class of the stress set: generated graded meshes of a
// wall (first layer 1e-4 to 1e-2 of the model, geometric growth 1.1 to 1.5,
// planar or curved), a few vertices of layers 2-4 pushed below the layer
// under them, and the measures a CFD user checks after a repair: did the
// first layer keep its height, did the wall vertices stay on the wall, how
// many vertices moved for each one that had to.
//
// Included by benchmark_hex_mesh_optimization.cpp (one translation unit),
// after its `Mesh`, `K` and `HMO` definitions.

#ifndef HMO_BENCHMARK_BOUNDARY_LAYER_SET_H
#define HMO_BENCHMARK_BOUNDARY_LAYER_SET_H

#include <CGAL/Hexahedral_mesh_optimization/internal/Surface/surface_distance.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace boundary_layer {

/// One generated wall mesh. Vertex (i, j, k) is `id(i, j, k)`, k = 0 on the
/// wall, k counting the layers away from it; hexes in MEDIT/VTK order.
struct Case
{
  Mesh mesh;                  // as generated (valid, every SJ 1 on the planar wall)
  Mesh input;                 // `mesh` with the pushed vertices: what the optimiser receives
  bool curved = false;        // wall z = 0 (planar) or the cylinder r = 1 (curved)
  std::size_t nx = 0, ny = 0, nz = 0;
  double first_layer = 0.;    // height of the first layer, relative to the model's size 1
  double growth = 0.;         // ratio between the heights of consecutive layers
  std::vector<std::size_t> pushed; // the vertices moved to invert their hexes

  std::size_t id(std::size_t i, std::size_t j, std::size_t k) const { return i + (nx + 1) * (j + (ny + 1) * k); }
};

/// The draw of `seed`: odd seeds a planar wall, even seeds a curved one;
/// 16-30 columns a side, 12-25 layers; first layer 10^U(-4, -2); growth
/// U(1.1, 1.5), layers capped at the size of the cells along the wall (the
/// core of a CFD mesh); 4-16 pushed vertices, never two within two steps.
inline Case make_case(unsigned seed)
{
  Case c;
  std::mt19937 rng(seed);
  auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  auto integer = [&](int a, int b) { return std::uniform_int_distribution<int>(a, b)(rng); };
  c.curved = seed % 2 == 0;
  c.nx = c.ny = std::size_t(integer(16, 30));
  c.nz = std::size_t(integer(12, 25));
  c.first_layer = std::pow(10., uniform(-4., -2.));
  c.growth = uniform(1.1, 1.5);
  const double core = 1. / double(c.nx);
  std::vector<double> s(c.nz + 1, 0.); // distance of layer k from the wall
  for(std::size_t k = 1; k <= c.nz; ++k)
    s[k] = s[k - 1] + (std::min)(core, c.first_layer * std::pow(c.growth, double(k - 1)));

  const double pi = 3.14159265358979323846;
  for(std::size_t k = 0; k <= c.nz; ++k)
    for(std::size_t j = 0; j <= c.ny; ++j)
      for(std::size_t i = 0; i <= c.nx; ++i)
      {
        const double u = double(i) / double(c.nx), v = double(j) / double(c.ny);
        if(!c.curved) c.mesh.points.push_back(K::Point_3(u, v, s[k]));
        else
        {
          // a quarter of the cylinder of radius 1 around the y axis, layers outward
          const double r = 1. + s[k], t = 0.5 * pi * u;
          c.mesh.points.push_back(K::Point_3(r * std::cos(t), v, r * std::sin(t)));
        }
      }
  for(std::size_t k = 0; k < c.nz; ++k)
    for(std::size_t j = 0; j < c.ny; ++j)
      for(std::size_t i = 0; i < c.nx; ++i)
      {
        std::array<std::size_t, 8> h = {{c.id(i, j, k), c.id(i + 1, j, k), c.id(i + 1, j + 1, k), c.id(i, j + 1, k),
                                         c.id(i, j, k + 1), c.id(i + 1, j, k + 1), c.id(i + 1, j + 1, k + 1),
                                         c.id(i, j + 1, k + 1)}};
        if(c.curved) std::swap(h[1], h[3]), std::swap(h[5], h[7]); // the cylinder's frame turns the other way
        c.mesh.hexahedra.push_back(h);
      }

  // push vertices of layers 2-4 below the layer under them, along their column
  c.input = c.mesh;
  const int count = integer(4, 16);
  std::vector<char> blocked(c.mesh.points.size(), 0);
  for(int attempt = 0; int(c.pushed.size()) < count && attempt < 1000; ++attempt)
  {
    const std::size_t i = std::size_t(integer(1, int(c.nx) - 1)), j = std::size_t(integer(1, int(c.ny) - 1));
    const std::size_t k = std::size_t(integer(2, int((std::min)(std::size_t(4), c.nz - 1))));
    const std::size_t v = c.id(i, j, k);
    if(blocked[v]) continue;
    const double depth = uniform(0.2, 0.8); // how far below layer k - 1, as a share of layer k - 1's height
    const K::Point_3& below = c.mesh.points[c.id(i, j, k - 1)];
    const K::Point_3& below2 = c.mesh.points[c.id(i, j, k - 2)];
    c.input.points[v] = below + depth * (below2 - below);
    c.pushed.push_back(v);
    for(std::size_t kk = k - 2; kk <= (std::min)(k + 2, c.nz); ++kk)
      for(std::size_t jj = (std::max)(j, std::size_t(2)) - 2; jj <= (std::min)(j + 2, c.ny); ++jj)
        for(std::size_t ii = (std::max)(i, std::size_t(2)) - 2; ii <= (std::min)(i + 2, c.nx); ++ii)
          blocked[c.id(ii, jj, kk)] = 1;
  }
  return c;
}

/// What a repair did to a boundary-layer case.
struct Measures
{
  double columns_within = 0.;   // share of wall columns whose first-layer height changed by at most 10 %
  double worst_height_change = 0.; // largest relative change of a first-layer height
  double wall_error = 0.;       // largest distance of a wall vertex to the reference / its diagonal
  std::size_t moved = 0;        // vertices moved by more than 1 % of their shortest input edge
  double moved_per_pushed = 0.;
};

/// Compares `out` with the generated mesh: its unperturbed geometry
/// `c.mesh` for the first-layer heights and the local edge lengths, the
/// optimiser's input `c.input` for the moves.
inline Measures measure(const Case& c, const Mesh& out,
                        const HMO::internal::Reference_distance_index& reference)
{
  Measures m;
  auto length = [](const K::Point_3& a, const K::Point_3& b) { return std::sqrt(CGAL::squared_distance(a, b)); };
  std::size_t within = 0, columns = 0;
  for(std::size_t j = 0; j <= c.ny; ++j)
    for(std::size_t i = 0; i <= c.nx; ++i)
    {
      const std::size_t w = c.id(i, j, 0), a = c.id(i, j, 1);
      const double h0 = length(c.mesh.points[w], c.mesh.points[a]);
      const double change = std::abs(length(out.points[w], out.points[a]) / h0 - 1.);
      ++columns;
      if(change <= 0.1) ++within;
      m.worst_height_change = (std::max)(m.worst_height_change, change);
      const K::Point_3& p = out.points[w];
      const double d2 = reference.tree().squared_distance(
        HMO::internal::surface_distance_detail::Soup_point(p.x(), p.y(), p.z()));
      m.wall_error = (std::max)(m.wall_error, std::sqrt(d2) / reference.diagonal());
    }
  m.columns_within = double(within) / double(columns);

  const Mesh& in = c.input;
  std::vector<double> shortest(in.points.size(), 1e300);
  static const int edges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                   {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  for(const auto& h : c.mesh.hexahedra) // the generated mesh's edges: the local size the mesher meant
    for(const auto& e : edges)
    {
      const double l = length(c.mesh.points[h[e[0]]], c.mesh.points[h[e[1]]]);
      for(int q : e) shortest[h[q]] = (std::min)(shortest[h[q]], l);
    }
  for(std::size_t v = 0; v < in.points.size(); ++v)
    if(length(in.points[v], out.points[v]) > 0.01 * shortest[v]) ++m.moved;
  m.moved_per_pushed = c.pushed.empty() ? 0. : double(m.moved) / double(c.pushed.size());
  return m;
}

} // namespace boundary_layer

#endif // HMO_BENCHMARK_BOUNDARY_LAYER_SET_H
