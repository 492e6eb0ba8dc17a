// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Scaled Jacobian on analytic cases, mesh quality statistics on a generated
// grid, the linear cell complex conversion (sewing by index, round trip,
// adapter), and the published figures of the shared benchmark meshes.

#include "test_util.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/hex_mesh_io.h>
#include <CGAL/Hexahedral_mesh_optimization/Linear_cell_complex_hex_mesh.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/lcc_hex_mesh_io.h>
#include <CGAL/Linear_cell_complex_for_combinatorial_map.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Exact_rational.h>
#include <CGAL/hex_mesh_quality.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/Quality/scaled_jacobian.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace test_quality_and_lcc {

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Point_3 Point;
typedef CGAL::Indexed_hex_mesh<Point> Mesh;
typedef CGAL::Linear_cell_complex_traits<3, K> LCC_traits;
typedef CGAL::Linear_cell_complex_for_combinatorial_map<3, 3, LCC_traits> LCC;
typedef std::array<Point, 8> Hex_points;

namespace {

Hex_points box(double a, double b, double c)
{
  return {Point(0, 0, 0), Point(a, 0, 0), Point(a, b, 0), Point(0, b, 0),
          Point(0, 0, c), Point(a, 0, c), Point(a, b, c), Point(0, b, c)};
}

template <class F>
Hex_points transformed(const Hex_points& h, F f)
{
  Hex_points r;
  for(int i = 0; i < 8; ++i)
    r[i] = f(h[i]);
  return r;
}

void test_scaled_jacobian()
{
  const double tol = 1e-12;
  const Hex_points cube = box(1, 1, 1);
  HMO_CHECK_CLOSE(CGAL::hex_scaled_jacobian(cube), 1., tol);
  HMO_CHECK_CLOSE(CGAL::hex_corner_scaled_jacobian(cube), 1., tol);

  // an affinely scaled box, rotated and translated: still 1
  const double ca = std::cos(0.7), sa = std::sin(0.7);
  const Hex_points moved = transformed(box(2, 3, 5), [&](const Point& p) {
    return Point(ca * p.x() - sa * p.y() + 10, sa * p.x() + ca * p.y() - 4, p.z() + 1);
  });
  HMO_CHECK_CLOSE(CGAL::hex_scaled_jacobian(moved), 1., tol);
  HMO_CHECK_CLOSE(CGAL::hex_corner_scaled_jacobian(moved), 1., tol);

  // shear x += s z: every corner frame and the principal axes are
  // (1,0,0), (0,1,0), (s,0,1) up to signs: 1 / sqrt(1 + s^2)
  for(double s : {0.5, 1., 3.})
  {
    const Hex_points sheared = transformed(cube, [s](const Point& p) {
      return Point(p.x() + s * p.z(), p.y(), p.z());
    });
    HMO_CHECK_CLOSE(CGAL::hex_scaled_jacobian(sheared), 1. / std::sqrt(1. + s * s), tol);
    HMO_CHECK_CLOSE(CGAL::hex_corner_scaled_jacobian(sheared), 1. / std::sqrt(1. + s * s), tol);
  }

  // vertex 0 mirrored through the centre, to (1,1,1): the frame at corner 0 is
  // (0,-1,-1), (-1,0,-1), (-1,-1,0): det -2, lengths sqrt(2)^3, so -1/sqrt(2);
  // corners 1, 3, 4 become flat (0); the centre gives 16 / 11^1.5 > 0
  Hex_points mirrored = cube;
  mirrored[0] = Point(1, 1, 1);
  HMO_CHECK_CLOSE(CGAL::hex_scaled_jacobian(mirrored), -1. / std::sqrt(2.), tol);
  HMO_CHECK_CLOSE(CGAL::hex_corner_scaled_jacobian(mirrored), -1. / std::sqrt(2.), tol);
  HMO_CHECK(CGAL::hex_scaled_jacobian(mirrored) < 0);

  // the whole element inside out (top and bottom swapped): -1
  const Hex_points inside_out = {cube[4], cube[5], cube[6], cube[7], cube[0], cube[1], cube[2], cube[3]};
  HMO_CHECK_CLOSE(CGAL::hex_scaled_jacobian(inside_out), -1., tol);

  // a collapsed edge (vertex 1 on vertex 0): 0, not inverted, not good
  Hex_points collapsed = cube;
  collapsed[1] = collapsed[0];
  HMO_CHECK(CGAL::hex_scaled_jacobian(collapsed) == 0.);
  HMO_CHECK(CGAL::hex_corner_scaled_jacobian(collapsed) == 0.);

  // nearly collapsed, far from the origin: vertex 1 a few ulps from vertex 0
  // (the edge is noise, whatever value its direction gives) counts as
  // collapsed; at 1e-5 of the other edges it still has its exact value
  Hex_points far = cube;
  for(Point& p : far) p = Point(p.x() + 1e3, p.y() + 1e3, p.z() + 1e3);
  Hex_points nearly = far;
  nearly[1] = Point(far[0].x() + 1e-12, far[0].y(), far[0].z());
  HMO_CHECK(CGAL::hex_scaled_jacobian(nearly) == 0.);
  Hex_points short_edge = cube;
  short_edge[1] = Point(1e-5, 0, 0);
  short_edge[2] = Point(1e-5, 1, 0);
  short_edge[5] = Point(1e-5, 0, 1);
  short_edge[6] = Point(1e-5, 1, 1);
  HMO_CHECK_CLOSE(CGAL::hex_scaled_jacobian(short_edge), 1., tol);
}

/// nx x ny x nz unit cubes, vertex (i,j,k) has index i + (nx+1) (j + (ny+1) k)
Mesh grid(int nx, int ny, int nz)
{
  Mesh m;
  for(int k = 0; k <= nz; ++k)
    for(int j = 0; j <= ny; ++j)
      for(int i = 0; i <= nx; ++i)
        m.points.push_back(Point(i, j, k));
  auto v = [&](int i, int j, int k) { return std::size_t(i + (nx + 1) * (j + (ny + 1) * k)); };
  for(int k = 0; k < nz; ++k)
    for(int j = 0; j < ny; ++j)
      for(int i = 0; i < nx; ++i)
        m.hexahedra.push_back({v(i, j, k), v(i + 1, j, k), v(i + 1, j + 1, k), v(i, j + 1, k),
                               v(i, j, k + 1), v(i + 1, j, k + 1), v(i + 1, j + 1, k + 1), v(i, j + 1, k + 1)});
  return m;
}

/// the 3x2x2 grid with grid corner (0,0,0) (in hex 0 only) mirrored through
/// the centre of hex 0: it lands on the interior vertex (1,1,1)
Mesh tangled_grid()
{
  Mesh m = grid(3, 2, 2);
  m.points[0] = Point(1, 1, 1);
  return m;
}

void test_quality_statistics()
{
  const Mesh m = tangled_grid();
  const std::vector<double> sj = CGAL::hex_mesh_scaled_jacobians(m);
  HMO_CHECK(sj.size() == 12);
  HMO_CHECK_CLOSE(sj[0], -1. / std::sqrt(2.), 1e-12);
  for(std::size_t h = 1; h < sj.size(); ++h)
    HMO_CHECK_CLOSE(sj[h], 1., 1e-12);

  const CGAL::Hex_mesh_quality q = CGAL::hex_mesh_quality(m);
  HMO_CHECK(q.hexes == 12);
  HMO_CHECK(q.vertices == 36);
  HMO_CHECK(q.inverted == 1);
  HMO_CHECK_CLOSE(q.msj, -1. / std::sqrt(2.), 1e-12);
  HMO_CHECK_CLOSE(q.asj, (11. - 1. / std::sqrt(2.)) / 12., 1e-12);
  HMO_CHECK(int(q.histogram.size()) == CGAL::Hex_mesh_quality::histogram_bins);
  std::size_t total = 0;
  for(std::size_t c : q.histogram)
    total += c;
  HMO_CHECK(total == 12);
  // -0.707 falls in [-0.8, -0.7) (bin 2), 1 in the last bin
  HMO_CHECK(q.histogram[2] == 1);
  HMO_CHECK(q.histogram[CGAL::Hex_mesh_quality::histogram_bins - 1] == 11);
  HMO_CHECK_CLOSE(CGAL::Hex_mesh_quality::bin_lower(2), -0.8, 1e-12);
  HMO_CHECK_CLOSE(CGAL::Hex_mesh_quality::bin_upper(2), -0.7, 1e-12);

  const CGAL::Hex_mesh_quality empty = CGAL::hex_mesh_quality(Mesh());
  HMO_CHECK(empty.hexes == 0 && empty.inverted == 0);
}

std::size_t number_of_volumes(const LCC& lcc)
{
  return lcc.one_dart_per_cell<3>().size();
}

/// every dart: 3-sewn iff its face (sorted vertex set) is shared by two
/// hexes of `m`, and then its beta3 runs the other way along the same edge
void check_sewing(const LCC& lcc, const Mesh& m)
{
  std::map<std::array<std::size_t, 4>, int> face_count;
  for(const auto& h : m.hexahedra)
    for(const auto& f : CGAL::Hexahedral_mesh_optimization::internal::lcc_hex_faces)
    {
      std::array<std::size_t, 4> key = {h[f[0]], h[f[1]], h[f[2]], h[f[3]]};
      std::sort(key.begin(), key.end());
      ++face_count[key];
    }
  std::map<LCC::Vertex_attribute_const_handle, std::size_t> index;
  std::size_t i = 0;
  for(auto it = lcc.vertex_attributes().begin(); it != lcc.vertex_attributes().end(); ++it)
    index[it] = i++;

  std::size_t sewn = 0, free3 = 0, wrong = 0;
  for(auto d = lcc.darts().begin(); d != lcc.darts().end(); ++d)
  {
    std::array<std::size_t, 4> key;
    LCC::Dart_const_handle x = d;
    for(int k = 0; k < 4; ++k, x = lcc.beta(x, 1))
      key[k] = index[lcc.vertex_attribute(x)];
    std::sort(key.begin(), key.end());
    const bool interior = face_count[key] == 2;
    if(lcc.is_free<3>(d))
    {
      ++free3;
      if(interior)
        ++wrong;
    }
    else
    {
      ++sewn;
      LCC::Dart_const_handle e = lcc.beta(d, 3);
      if(!interior || lcc.vertex_attribute(e) != lcc.vertex_attribute(lcc.beta(d, 1)) ||
         lcc.vertex_attribute(lcc.beta(e, 1)) != lcc.vertex_attribute(d))
        ++wrong;
    }
  }
  std::size_t interior_faces = 0, boundary_faces = 0;
  for(const auto& fc : face_count)
    (fc.second == 2 ? interior_faces : boundary_faces) += 1;
  HMO_CHECK(wrong == 0);
  HMO_CHECK(sewn == 8 * interior_faces);
  HMO_CHECK(free3 == 4 * boundary_faces);
}

void test_linear_cell_complex()
{
  const Mesh m = tangled_grid();
  LCC lcc;
  std::string message;
  HMO_CHECK(CGAL::build_linear_cell_complex(m, lcc, &message));
  HMO_CHECK(message.empty());
  HMO_CHECK(lcc.is_valid());
  HMO_CHECK(number_of_volumes(lcc) == 12);
  HMO_CHECK(lcc.vertex_attributes().size() == 36);
  HMO_CHECK(lcc.number_of_darts() == 12 * 24);
  // 3x2x2 grid: 20 interior faces (40 face records) and 32 boundary faces;
  // vertex 0 sits on vertex (1,1,1) but is still sewn by index
  check_sewing(lcc, m);

  // the geometry of each 3-cell is the MEDIT hex: same scaled Jacobian,
  // same statistics
  const std::vector<double> sj_mesh = CGAL::hex_mesh_scaled_jacobians(m);
  const std::vector<double> sj_lcc = CGAL::hex_mesh_scaled_jacobians(lcc);
  HMO_CHECK(sj_lcc.size() == sj_mesh.size());
  for(std::size_t h = 0; h < sj_mesh.size() && h < sj_lcc.size(); ++h)
    HMO_CHECK_CLOSE(sj_lcc[h], sj_mesh[h], 1e-15);
  const CGAL::Hex_mesh_quality qm = CGAL::hex_mesh_quality(m), ql = CGAL::hex_mesh_quality(lcc);
  HMO_CHECK(ql.hexes == qm.hexes && ql.vertices == qm.vertices && ql.inverted == qm.inverted);
  HMO_CHECK(ql.msj == qm.msj && ql.asj == qm.asj && ql.histogram == qm.histogram);

  // round trip
  Mesh back;
  HMO_CHECK(CGAL::indexed_hex_mesh_from_linear_cell_complex(lcc, back));
  HMO_CHECK(back.points == m.points);
  HMO_CHECK(back.hexahedra == m.hexahedra);

  // the walk gives the same hexahedron from any of its 24 darts: a hex with
  // no symmetry has the same scaled Jacobian from every start
  {
    Hex_points p = box(1, 1.3, 0.8);
    p[6] = Point(1.2, 1.5, 0.9);
    p[1] = Point(1.1, 0.1, -0.05);
    Mesh one;
    one.points.assign(p.begin(), p.end());
    one.hexahedra.push_back({0, 1, 2, 3, 4, 5, 6, 7});
    LCC single;
    HMO_CHECK(CGAL::build_linear_cell_complex(one, single));
    const double expected = CGAL::hex_scaled_jacobian(p);
    std::size_t count = 0;
    for(auto d = single.darts().begin(); d != single.darts().end(); ++d, ++count)
    {
      const auto f = CGAL::Hexahedral_mesh_optimization::internal::lcc_hexahedron_faces(
          single, LCC::Dart_const_handle(d));
      const std::array<LCC::Dart_const_handle, 8> v = {
          f[0], single.beta(f[0], 0), single.beta(f[1], 0), single.beta(f[4], 0),
          single.beta(f[0], 1), single.beta(f[0], 1, 1), single.beta(f[1], 1, 1), single.beta(f[5], 1)};
      Hex_points q;
      for(int i = 0; i < 8; ++i)
        q[i] = single.point(v[i]);
      HMO_CHECK_CLOSE(CGAL::hex_scaled_jacobian(q), expected, 1e-14);
    }
    HMO_CHECK(count == 24);
  }

  // write_back through the adapter moves the vertex attributes
  {
    namespace HMOI = CGAL::Hexahedral_mesh_optimization::internal;
    HMOI::Hex_mesh_arrays a = HMOI::extract_hex_mesh(lcc, K());
    a.points[0] = {0., 0., 0.};
    HMOI::write_back_points(a, lcc, K());
    const CGAL::Hex_mesh_quality fixed = CGAL::hex_mesh_quality(lcc);
    HMO_CHECK(fixed.inverted == 0);
    HMO_CHECK_CLOSE(fixed.msj, 1., 1e-12);
  }

  // non-manifold: a third hex on an interior face
  {
    Mesh bad = grid(2, 1, 1);
    const std::size_t n = bad.points.size();
    for(int i = 0; i < 4; ++i)
      bad.points.push_back(Point(1, 0.5 * i, 2));
    // reuse the face (1, 4, 10, 7) shared by hexes 0 and 1 as the bottom of a third one
    bad.hexahedra.push_back({1, 4, 10, 7, n, n + 1, n + 2, n + 3});
    LCC l;
    std::string why;
    HMO_CHECK(!CGAL::build_linear_cell_complex(bad, l, &why));
    HMO_CHECK(why.find("not manifold") != std::string::npos);
    HMO_CHECK(l.number_of_darts() == 0);
  }

  // one hex numbered inside out: its shared face has the wrong orientation
  {
    Mesh bad = grid(2, 1, 1);
    auto& h = bad.hexahedra[1];
    h = {h[4], h[5], h[6], h[7], h[0], h[1], h[2], h[3]};
    LCC l;
    std::string why;
    HMO_CHECK(!CGAL::build_linear_cell_complex(bad, l, &why));
    HMO_CHECK(why.find("orientation") != std::string::npos);
  }

  // an index out of range
  {
    Mesh bad = grid(1, 1, 1);
    bad.hexahedra[0][3] = 99;
    LCC l;
    std::string why;
    HMO_CHECK(!CGAL::build_linear_cell_complex(bad, l, &why));
    HMO_CHECK(why.find("99") != std::string::npos);
  }

  // a 3-cell that is not a hexahedron
  {
    LCC l;
    l.make_tetrahedron(Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(0, 0, 1));
    Mesh out;
    std::string why;
    HMO_CHECK(!CGAL::indexed_hex_mesh_from_linear_cell_complex(l, out, &why));
    HMO_CHECK(why.find("not a hexahedron") != std::string::npos);
    bool thrown = false;
    try { CGAL::hex_mesh_quality(l); } catch(const std::invalid_argument&) { thrown = true; }
    HMO_CHECK(thrown);
  }

  // I/O through the linear cell complex: write, read back, same mesh
  {
    const std::string file = "test_quality_and_lcc_roundtrip.vtk";
    CGAL::IO::Hex_mesh_fields fields;
    fields.cell_scalars.push_back({"scaled_jacobian", CGAL::hex_mesh_scaled_jacobians(lcc)});
    CGAL::IO::Hex_mesh_io_error err;
    HMO_CHECK(CGAL::IO::write_hex_mesh(file, lcc, fields, &err));
    LCC read_back;
    std::vector<std::string> warnings;
    HMO_CHECK(CGAL::IO::read_hex_mesh(file, read_back, &err, &warnings));
    HMO_CHECK(warnings.empty());
    Mesh a, b;
    HMO_CHECK(CGAL::indexed_hex_mesh_from_linear_cell_complex(lcc, a));
    HMO_CHECK(CGAL::indexed_hex_mesh_from_linear_cell_complex(read_back, b));
    HMO_CHECK(a.points == b.points && a.hexahedra == b.hexahedra);
    std::remove(file.c_str());

    LCC none;
    HMO_CHECK(!CGAL::IO::read_hex_mesh("no_such_file.mesh", none, &err));
    HMO_CHECK(err.what().find("no_such_file.mesh") != std::string::npos);
    LCC tet;
    tet.make_tetrahedron(Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(0, 0, 1));
    HMO_CHECK(!CGAL::IO::write_hex_mesh(file, tet, CGAL::IO::Hex_mesh_fields(), &err));
    HMO_CHECK(err.what().find("not a hexahedron") != std::string::npos);
    HMO_CHECK(!hmo_test::file_exists(file));
  }

  // another kernel on the LCC side: points are converted both ways
  {
    typedef CGAL::Simple_cartesian<double> SC;
    typedef CGAL::Linear_cell_complex_for_combinatorial_map<3, 3, CGAL::Linear_cell_complex_traits<3, SC> > SC_LCC;
    SC_LCC l;
    HMO_CHECK(CGAL::build_linear_cell_complex(m, l));
    HMO_CHECK(CGAL::hex_mesh_quality(l).inverted == 1);
    Mesh again;
    HMO_CHECK(CGAL::indexed_hex_mesh_from_linear_cell_complex(l, again));
    HMO_CHECK(again.points == m.points && again.hexahedra == m.hexahedra);
  }

  // CGAL's own make_hexahedron (its picture order) + sew3_same_facets reads
  // back as the same grid up to a rotation of each hex: same quality
  {
    const Mesh g = grid(2, 2, 1);
    LCC l;
    for(const auto& h : g.hexahedra)
      l.make_hexahedron(g.points[h[0]], g.points[h[1]], g.points[h[2]], g.points[h[3]],
                        g.points[h[7]], g.points[h[4]], g.points[h[5]], g.points[h[6]]);
    l.sew3_same_facets();
    const CGAL::Hex_mesh_quality q = CGAL::hex_mesh_quality(l);
    HMO_CHECK(q.hexes == 4);
    HMO_CHECK(q.inverted == 0);
    HMO_CHECK_CLOSE(q.msj, 1., 1e-12);
  }
}

/// a row of the tables of the shared data's README.md (asj < -0.5: not given)
struct Published
{
  const char* file;
  std::size_t hexes;
  std::size_t inverted;
  double msj;
  double asj;
};

void test_shared_meshes()
{
  const std::string dir = hmo_test::shared_data_dir();
  if(dir.empty())
    return;
  const Published table[] = {
    {"edge-cone/block_in.mesh", 2520, 31, -0.697, -1},
    {"edge-cone/bunny_in.mesh", 37734, 1, -0.003, -1},
    {"edge-cone/bust_in.mesh", 5258, 30, -0.597, -1},
    {"edge-cone/cap_in.mesh", 4420, 50, -0.937, -1},
    {"edge-cone/hanger_stresstest_in.mesh", 4539, 3930, -0.999, -1},
    {"edge-cone/impeller_stresstest_in.mesh", 11174, 8857, -0.999, -1},
    {"inverted/bunny_dualsheet.vtk", 2832, 45, -0.771, -1},
    {"inverted/hex_torus.vtk", 7380, 121, -0.508, -1},
    {"amips/fertility_gregson11.mesh", 19870, 0, 0.196, 0.911},
    {"amips/rockerarm_li12.vtk", 10600, 0, 0.209, 0.866},
    {"low-quality/kitten_with_bifur_2.mesh", 2928, 0, 0.006, 0.774},
    {"low-quality/cat_2.mesh", 2604, 0, 0.046, 0.858},
    {"low-quality/Dolphin_2.mesh", 4788, 0, 0.034, 0.876},
    {"stress-base/fandisk.vtk", 357, 0, 0.609, 0.936},
    {"stress-base/kitty.vtk", 7083, 0, 0.424, 0.910},
    {"stress-base/hanger.vtk", 4539, 0, 0.599, 0.964},
  };
  for(const Published& p : table)
  {
    const std::string file = dir + "/" + p.file;
    Mesh m;
    CGAL::IO::Hex_mesh_io_error err;
    std::vector<std::string> warnings;
    if(!CGAL::IO::read_hex_mesh(file, m, &err, &warnings))
    {
      std::cerr << "cannot read " << file << ": " << err.what() << std::endl;
      HMO_CHECK(false);
      continue;
    }
    const CGAL::Hex_mesh_quality q = CGAL::hex_mesh_quality(m);
    std::cout << p.file << ": " << q.hexes << " hexes, " << q.inverted << " inverted, MSJ "
              << q.msj << ", ASJ " << q.asj << std::endl;
    HMO_CHECK(q.hexes == p.hexes);
    HMO_CHECK(q.inverted == p.inverted);
    // none of them has a sample within rounding of 0: the certificate
    // refuses exactly the inverted ones
    const CGAL::Hexahedral_mesh_optimization::Validity_certificate c = CGAL::hex_mesh_validity_certificate(m);
    HMO_CHECK(c.hexes == q.hexes && c.not_certified.size() == q.inverted);
    HMO_CHECK_CLOSE(q.msj, p.msj, 0.0005);
    if(p.asj > -0.5)
      HMO_CHECK_CLOSE(q.asj, p.asj, 0.0005);
  }

  // the same figures through a linear cell complex, and its timings
  for(const char* name : {"edge-cone/bunny_in.mesh", "inverted/bunny_dualsheet.vtk", "inverted/hex_torus.vtk"})
  {
    const std::string file = dir + "/" + name;
    Mesh m;
    if(!CGAL::IO::read_hex_mesh(file, m, nullptr, nullptr))
    {
      HMO_CHECK(false);
      continue;
    }
    typedef std::chrono::steady_clock Clock;
    LCC lcc;
    std::string why;
    const auto t0 = Clock::now();
    const bool built = CGAL::build_linear_cell_complex(m, lcc, &why);
    const auto t1 = Clock::now();
    HMO_CHECK(built);
    if(!built)
    {
      std::cerr << name << ": " << why << std::endl;
      continue;
    }
    const CGAL::Hex_mesh_quality ql = CGAL::hex_mesh_quality(lcc);
    const auto t2 = Clock::now();
    const CGAL::Hex_mesh_quality qm = CGAL::hex_mesh_quality(m);
    HMO_CHECK(ql.hexes == qm.hexes && ql.vertices == qm.vertices && ql.inverted == qm.inverted);
    HMO_CHECK(ql.msj == qm.msj && ql.asj == qm.asj);
    Mesh back;
    HMO_CHECK(CGAL::indexed_hex_mesh_from_linear_cell_complex(lcc, back));
    HMO_CHECK(back.points == m.points && back.hexahedra == m.hexahedra);
    check_sewing(lcc, m);
    std::cout << name << ": LCC build " << std::chrono::duration<double>(t1 - t0).count()
              << " s, LCC quality (extract + SJ) " << std::chrono::duration<double>(t2 - t1).count()
              << " s" << std::endl;
  }
}

/// The one hex-frame kernel (internal/Quality/scaled_jacobian.h) every energy uses:
/// frames from their coefficients, samples, and their analytic gradients
/// against central differences.
void test_frame_kernel()
{
  namespace HI = CGAL::Hexahedral_mesh_optimization::internal;
  using namespace CGAL::Hexahedral_mesh_optimization::internal; // Vec3's operators
  typedef HI::Vec3 Vec3;
  auto sample = [](const std::array<Vec3, 8>& p, int s) {
    return s < 8 ? HI::corner_scaled_jacobian(p, s) : HI::centre_scaled_jacobian(p);
  };
  std::array<Vec3, 8> cube;
  const Hex_points b = box(1, 1, 1);
  for(int i = 0; i < 8; ++i) cube[i] = Vec3{b[i].x(), b[i].y(), b[i].z()};

  // the unit cube: every sample is 1, and each is at its maximum (zero gradient)
  double s9[9];
  HI::hex_samples(cube, s9);
  for(int s = 0; s < 9; ++s)
  {
    HMO_CHECK_CLOSE(s9[s], 1., 1e-15);
    for(int c = 0; c < 8; ++c) HMO_CHECK(HI::squared_norm(HI::hex_sample_gradient(cube, s, c, s9[s])) < 1e-24);
  }

  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  auto perturbed_cube = [&] {
    std::array<Vec3, 8> p = cube;
    for(Vec3& x : p) x = x + Vec3{u(rng), u(rng), u(rng)};
    return p;
  };
  int compared = 0;
  for(int trial = 0; trial < 20; ++trial)
  {
    const std::array<Vec3, 8> p = perturbed_cube();
    for(int s = 0; s < 9; ++s)
    {
      // frame s from the coefficients: the corner edges, or the principal axes / 4
      for(int k = 0; k < 3; ++k)
      {
        Vec3 column{0., 0., 0.};
        for(int i = 0; i < 8; ++i) column = column + HI::hex_frame_coefficient(s, i, k) * p[i];
        Vec3 expected;
        if(s < 8) expected = p[HI::hex_corner_edges[s][k]] - p[s];
        else
        {
          Vec3 axes[3];
          HI::principal_axes(p, axes[0], axes[1], axes[2]);
          expected = 0.25 * axes[k];
        }
        HMO_CHECK(HI::norm(column - expected) < 1e-14);
      }
      // the analytic gradient against central differences, every corner
      const double f = sample(p, s);
      for(int c = 0; c < 8; ++c)
      {
        const Vec3 g = HI::hex_sample_gradient(p, s, c, f);
        const bool depends = s == 8 || s == c || HI::hex_corner_edges[s][0] == c ||
                             HI::hex_corner_edges[s][1] == c || HI::hex_corner_edges[s][2] == c;
        Vec3 fd{0., 0., 0.};
        const double h = 1e-6;
        for(int d = 0; d < 3; ++d)
        {
          std::array<Vec3, 8> q = p, r = p;
          q[c][d] += h;
          r[c][d] -= h;
          fd[d] = (sample(q, s) - sample(r, s)) / (2. * h);
        }
        HMO_CHECK(HI::norm(g - fd) < 1e-7 * (1. + HI::norm(fd)));
        if(!depends) HMO_CHECK(HI::squared_norm(g) == 0.);
        ++compared;
      }
    }
    // the corner samples of corner c are the ones whose gradient at c can be non-zero
    for(int c = 0; c < 8; ++c)
      for(int s = 0; s < 8; ++s)
      {
        const int* dep = HI::corner_samples_of_corner(c);
        const bool listed = std::find(dep, dep + 4, s) != dep + 4;
        if(!listed) HMO_CHECK(HI::squared_norm(HI::hex_sample_gradient(p, s, c, sample(p, s))) == 0.);
      }
  }
  HMO_CHECK(compared == 20 * 9 * 8);

  // all the weighted sample gradients of a hex at once, against the
  // per-(sample, corner) gradients
  for(int trial = 0; trial < 5; ++trial)
  {
    const std::array<Vec3, 8> p = perturbed_cube();
    double f[9], w[9];
    HI::hex_samples(p, f);
    for(int s = 0; s < 9; ++s) w[s] = 0.1 * (s + 1) + 0.05 * trial;
    w[trial] = 0.; // a frame skipped
    std::array<Vec3, 8> all;
    for(Vec3& g : all) g = Vec3{0., 0., 0.};
    HI::add_weighted_sample_gradients(p, f, w, all);
    for(int c = 0; c < 8; ++c)
    {
      Vec3 expected{0., 0., 0.};
      for(int s = 0; s < 9; ++s) expected = expected + w[s] * HI::hex_sample_gradient(p, s, c, f[s]);
      HMO_CHECK(HI::norm(all[c] - expected) < 1e-12 * (1. + HI::norm(expected)));
    }
  }

  // a known sheared hex: x += 0.5 z gives 1/sqrt(1.25) at every sample
  std::array<Vec3, 8> sheared = cube;
  for(Vec3& x : sheared) x[0] += 0.5 * x[2];
  HI::hex_samples(sheared, s9);
  for(int s = 0; s < 9; ++s) HMO_CHECK_CLOSE(s9[s], 1. / std::sqrt(1.25), 1e-14);

  // the samples of one moving corner (Corner_dependent_samples, the ASJ
  // trials) against the 9 samples recomputed, at the corner itself and
  // elsewhere, inverted positions included; a vanishing edge counts as 0
  std::uniform_real_distribution<double> far(-1.5, 1.5);
  int moved = 0;
  for(int trial = 0; trial < 20; ++trial)
  {
    const std::array<Vec3, 8> p = perturbed_cube();
    for(int c = 0; c < 8; ++c)
    {
      HI::Corner_dependent_samples frames;
      frames.set(p, c);
      const int* dep = HI::corner_samples_of_corner(c);
      for(int k = 0; k < 4; ++k)
      {
        std::array<Vec3, 8> q = p;
        if(k == 1) q[c] = q[c] + Vec3{far(rng), far(rng), far(rng)};
        if(k == 2) q[c] = q[HI::hex_corner_edges[c][0]];            // on a neighbour: vanishing edge
        if(k == 3) q[c] = 2. * q[HI::hex_corner_edges[c][1]] - q[c]; // folded through a neighbour
        double expected[9], got[5];
        HI::hex_samples(q, expected);
        frames.evaluate(q[c], got);
        for(int j = 0; j < 4; ++j) HMO_CHECK(std::abs(got[j] - expected[dep[j]]) < 1e-13);
        HMO_CHECK(std::abs(got[4] - expected[8]) < 1e-13);
        if(k == 2) HMO_CHECK(got[0] == 0. && got[1] == 0.);
        ++moved;
      }
    }
  }
  HMO_CHECK(moved == 20 * 8 * 4);

  // the early-exit trial (scaled_jacobian_if_above, the max-min smoothing's
  // line searches): the exact value when every sample beats the threshold,
  // otherwise a sample at or below it; both cases met many times
  int exact = 0, stopped = 0;
  for(int trial = 0; trial < 200; ++trial)
  {
    std::array<Vec3, 8> p = perturbed_cube();
    if(trial % 3 == 0) p[trial % 8] = p[trial % 8] + Vec3{far(rng), far(rng), far(rng)};
    double s[9];
    HI::hex_samples(p, s);
    const double sj = HI::scaled_jacobian(p);
    for(double threshold : {-1.5, sj - 1e-12, sj, s[8], 0.5, 2.})
    {
      const double got = HI::scaled_jacobian_if_above(p, threshold);
      if(sj > threshold)
      {
        HMO_CHECK(got == sj);
        ++exact;
      }
      else
      {
        HMO_CHECK(!(got > threshold));
        HMO_CHECK(std::find(s, s + 9, got) != s + 9);
        ++stopped;
      }
    }
  }
  HMO_CHECK(exact > 200 && stopped > 200);
}

/// the exact sign of det[q - p, r - p, t - p] for double points, in
/// rationals: the certificate's reference, computed apart from it
CGAL::Sign exact_sign(const std::array<double, 3>& p, const std::array<double, 3>& q, const std::array<double, 3>& r,
                      const std::array<double, 3>& t)
{
  typedef CGAL::Exact_rational Q;
  Q a[3], b[3], c[3];
  for(int d = 0; d < 3; ++d)
  {
    a[d] = Q(q[d]) - Q(p[d]);
    b[d] = Q(r[d]) - Q(p[d]);
    c[d] = Q(t[d]) - Q(p[d]);
  }
  return CGAL::sign(a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                    a[2] * (b[0] * c[1] - b[1] * c[0]));
}

/// Parallelepipeds whose three edge vectors are coplanar to within about
/// 1e-17 of their lengths: every Jacobian sample is then within rounding of
/// 0. The certificate must give the exact sign of all 9 (computed here in
/// rationals from the coordinates), where the rounded scaled Jacobian's sign
/// is wrong for some of them.
void test_validity_certificate()
{
  namespace HI = CGAL::Hexahedral_mesh_optimization::internal;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(-1., 1.);
  std::uniform_real_distribution<double> tiny(-3e-17, 3e-17);
  Mesh m;
  std::vector<std::size_t> expected_uncertified;
  int double_wrong = 0, positive = 0;
  for(int k = 0; k < 2000; ++k)
  {
    const std::array<double, 3> o{{10. + u(random), u(random), u(random)}};
    const std::array<double, 3> e1{{1. + 0.3 * u(random), 0.3 * u(random), 0.3 * u(random)}};
    const std::array<double, 3> e2{{0.3 * u(random), 1. + 0.3 * u(random), 0.3 * u(random)}};
    const double a = 0.5 + 0.2 * u(random), b = 0.5 + 0.2 * u(random);
    const std::array<double, 3> n{{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]}};
    const double t = tiny(random);
    std::array<double, 3> e3;
    for(int d = 0; d < 3; ++d) e3[d] = a * e1[d] + b * e2[d] + t * n[d];
    std::array<std::array<double, 3>, 8> p;
    for(int d = 0; d < 3; ++d)
    {
      p[0][d] = o[d];
      p[1][d] = o[d] + e1[d];
      p[3][d] = o[d] + e2[d];
      p[4][d] = o[d] + e3[d];
      p[2][d] = p[1][d] + e2[d];
      p[5][d] = p[1][d] + e3[d];
      p[7][d] = p[3][d] + e3[d];
      p[6][d] = p[2][d] + e3[d];
    }
    // the exact signs of the 9 samples, from the coordinates
    bool valid = true;
    for(int i = 0; i < 8; ++i)
    {
      const int* n = HI::hex_corner_edges[i];
      valid = valid && exact_sign(p[i], p[n[0]], p[n[1]], p[n[2]]) == CGAL::POSITIVE;
    }
    {
      typedef CGAL::Exact_rational Q;
      Q x[3][3];
      for(int j = 0; j < 3; ++j)
        for(int d = 0; d < 3; ++d)
        {
          Q sum(0);
          for(int c = 0; c < 4; ++c) sum += Q(p[HI::hex_axis_plus[j][c]][d]) - Q(p[HI::hex_axis_minus[j][c]][d]);
          x[j][d] = sum;
        }
      const Q det = x[0][0] * (x[1][1] * x[2][2] - x[1][2] * x[2][1]) - x[0][1] * (x[1][0] * x[2][2] - x[1][2] * x[2][0]) +
                    x[0][2] * (x[1][0] * x[2][1] - x[1][1] * x[2][0]);
      valid = valid && CGAL::sign(det) == CGAL::POSITIVE;
    }
    Hex_points h;
    std::array<std::size_t, 8> ids;
    for(int i = 0; i < 8; ++i)
    {
      h[i] = Point(p[i][0], p[i][1], p[i][2]);
      ids[i] = m.points.size();
      m.points.push_back(h[i]);
    }
    m.hexahedra.push_back(ids);
    if(!valid) expected_uncertified.push_back(m.hexahedra.size() - 1);
    positive += valid;
    const bool double_says_valid = CGAL::hex_scaled_jacobian(h) > 0.;
    double_wrong += double_says_valid != valid;
  }
  const CGAL::Hexahedral_mesh_optimization::Validity_certificate c = CGAL::hex_mesh_validity_certificate(m);
  std::cout << "validity certificate: " << c.certified_valid() << " of " << c.hexes << " certified, "
            << positive << " valid by exact rationals; the rounded scaled Jacobian's sign was wrong on "
            << double_wrong << std::endl;
  HMO_CHECK(c.hexes == 2000);
  HMO_CHECK(c.not_certified == expected_uncertified);
  HMO_CHECK(double_wrong > 0);           // the case is one rounding gets wrong
  HMO_CHECK(positive > 100 && positive < 1900); // both signs occur

  // the unit cube and an inverted one
  Mesh two;
  const Hex_points cube = box(1, 1, 1);
  const Hex_points mirrored = transformed(cube, [](const Point& q) { return Point(-q.x() + 3., q.y(), q.z()); });
  for(const Hex_points& hx : {cube, mirrored})
  {
    std::array<std::size_t, 8> ids;
    for(int i = 0; i < 8; ++i) { ids[i] = two.points.size(); two.points.push_back(hx[i]); }
    two.hexahedra.push_back(ids);
  }
  const CGAL::Hexahedral_mesh_optimization::Validity_certificate c2 = CGAL::hex_mesh_validity_certificate(two);
  HMO_CHECK(c2.certified_valid() == 1 && c2.not_certified == std::vector<std::size_t>{1} && !c2.all_valid());
}

} // namespace

HMO_TEST_MAIN(test_quality_and_lcc)
{
  HMO_CASE(test_scaled_jacobian());
  HMO_CASE(test_validity_certificate());
  HMO_CASE(test_frame_kernel());
  HMO_CASE(test_quality_statistics());
  HMO_CASE(test_linear_cell_complex());
  HMO_CASE(test_shared_meshes());
  return hmo_test::report("test_quality_and_lcc");
}

} // namespace test_quality_and_lcc
