// Copyright (c) 2026 Hexahedral_mesh_optimization contributors.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Untangling benchmark: every untangling input of the shared data, plus
// stress tests made by perturbing the valid meshes of stress-base/ until at
// least 80 % of their hexes are inverted (fixed seed, so runs compare). Prints
// a Markdown table with the published figures beside ours.
//
//   benchmark_hex_mesh_optimization [DATA_DIR] [--only SUBSTRING]

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/hex_mesh_io.h>
#include <CGAL/Hexahedral_mesh_optimization/internal/surface_distance.h>
#include <CGAL/hex_mesh_quality.h>
#include <CGAL/untangle_hex_mesh.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Indexed_hex_mesh<K::Point_3> Mesh;
namespace HMO = CGAL::Hexahedral_mesh_optimization;

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

/// Perturbs every vertex by a random vector of growing amplitude until at
/// least `fraction` of the hexes are inverted.
static std::size_t perturb(Mesh& m, double fraction, unsigned seed)
{
  const Mesh base = m;
  double mean = 0.;
  for(const auto& h : m.hexahedra) mean += std::sqrt(CGAL::squared_distance(m.points[h[0]], m.points[h[1]]));
  mean /= m.hexahedra.size();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1., 1.);
  for(double amp = 0.3;; amp *= 1.15)
  {
    for(std::size_t i = 0; i < m.points.size(); ++i)
      m.points[i] = base.points[i] + amp * mean * K::Vector_3(u(rng), u(rng), u(rng));
    const auto q = CGAL::hex_mesh_quality(m);
    if(q.inverted >= fraction * m.hexahedra.size()) return q.inverted;
  }
}

int main(int argc, char** argv)
{
  std::string dir = HMO_SHARED_DATA_DIR, only;
  for(int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if(a == "--only" && i + 1 < argc) only = argv[++i];
    else dir = a;
  }
  struct stat st;
  if(::stat((dir + "/README.md").c_str(), &st) != 0)
  {
    std::cout << "shared data folder " << dir << " is absent: nothing to benchmark" << std::endl;
    return 0;
  }
  const auto published = read_published(HMO_PUBLISHED_CSV);
  const std::vector<std::string> inputs = {
    "edge-cone/block_in.mesh", "edge-cone/bunny_in.mesh", "edge-cone/bust_in.mesh", "edge-cone/cap_in.mesh",
    "edge-cone/hanger_stresstest_in.mesh", "edge-cone/impeller_stresstest_in.mesh",
    "inverted/bunny_dualsheet.vtk", "inverted/hex_torus.vtk",
    "stress-base/fandisk.vtk", "stress-base/kitty.vtk", "stress-base/hanger.vtk"};

  std::cout << "| model | hexes | inverted in | inverted out | MSJ out | ASJ out | surface error | seconds | stages | edge-cone MSJ/ASJ/err | Xu & Chen MSJ/ASJ/err |\n"
            << "|---|---:|---:|---:|---:|---:|---:|---:|---|---|---|\n";
  for(const std::string& name : inputs)
  {
    if(!only.empty() && name.find(only) == std::string::npos) continue;
    Mesh mesh;
    CGAL::IO::Hex_mesh_io_error err;
    std::vector<std::string> warnings;
    if(!CGAL::IO::read_hex_mesh(dir + "/" + name, mesh, &err, &warnings))
    {
      std::cout << "| " << name << " | read error: " << err.what() << " |\n";
      continue;
    }
    const bool stress = name.rfind("stress-base/", 0) == 0;
    HMO::internal::Triangle_surface reference;
    if(stress)
    {
      // the surface error of a stress test is measured against the unperturbed mesh
      HMO::internal::boundary_surface(HMO::internal::make_hex_mesh_arrays(mesh, K()), reference);
      perturb(mesh, 0.8, 1);
    }
    HMO::Optimization_result r = stress
      ? CGAL::untangle_hex_mesh(mesh, CGAL::hex_mesh_parameters::reference_surface(reference))
      : CGAL::untangle_hex_mesh(mesh);
    std::string stages;
    for(const auto& s : r.stages)
      stages += (stages.empty() ? "" : ", ") + s.name + " " + std::to_string(s.inverted_before) + "→" + std::to_string(s.inverted_after);
    const auto it = published.find(name);
    char line[512];
    std::snprintf(line, sizeof line, "| %s%s | %zu | %zu | %zu | %.3f | %.3f | %.4f | %.2f | %s |",
                  name.c_str(), stress ? " (perturbed)" : "", mesh.hexahedra.size(), r.inverted_before,
                  r.inverted_after, r.msj_after, r.asj_after, r.surface_error, r.seconds, stages.c_str());
    std::cout << line << ' '
              << (it != published.end() ? fig(it->second.row[4], it->second.row[5], it->second.row[6]) : "–") << " | "
              << (it != published.end() ? fig(it->second.row[7], it->second.row[8], it->second.row[9]) : "–") << " |"
              << std::endl;
  }
  return 0;
}
