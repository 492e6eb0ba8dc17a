// Reads a hexahedral mesh, prints its quality (`CGAL::hex_mesh_quality()`),
// then builds a linear cell complex from it and prints the same figures
// computed on the complex; then the scaled Jacobian of each element
// (`CGAL::hex_mesh_scaled_jacobians()`), the worst element's 9-sample and
// 8-corner values computed from its corners (`CGAL::hex_scaled_jacobian()`,
// `CGAL::hex_corner_scaled_jacobian()`), and the exact validity certificate
// (`CGAL::hex_mesh_validity_certificate()`).
//
//   quality_report [mesh.{mesh,vtk,vtu}]   (default: data/bunny_dualsheet.vtk)

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/hex_mesh_io.h>
#include <CGAL/Hexahedral_mesh_optimization/Linear_cell_complex_hex_mesh.h>
#include <CGAL/Linear_cell_complex_for_combinatorial_map.h>
#include <CGAL/hex_mesh_quality.h>

#include <array>
#include <iostream>
#include <string>
#include <vector>

#ifndef HMO_EXAMPLE_DATA_DIR // set by CMakeLists.txt
#define HMO_EXAMPLE_DATA_DIR "data"
#endif

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Indexed_hex_mesh<K::Point_3> Mesh;
typedef CGAL::Linear_cell_complex_for_combinatorial_map<3, 3, CGAL::Linear_cell_complex_traits<3, K> > LCC;

void print(const std::string& what, const CGAL::Hex_mesh_quality& q)
{
  std::cout << what << ": " << q.hexes << " hexahedra, " << q.vertices << " vertices, "
            << q.inverted << " inverted, MSJ " << q.msj << ", ASJ " << q.asj << std::endl;
}

int main(int argc, char* argv[])
{
  const std::string fname = (argc > 1) ? argv[1] : std::string(HMO_EXAMPLE_DATA_DIR "/bunny_dualsheet.vtk");

  Mesh mesh;
  CGAL::IO::Hex_mesh_io_error error;
  std::vector<std::string> warnings;
  if(!CGAL::IO::read_hex_mesh(fname, mesh, &error, &warnings))
  {
    std::cerr << error.what() << std::endl;
    return 1;
  }
  for(const std::string& w : warnings)
    std::cerr << "warning: " << w << std::endl;

  // the indexed mesh
  print("indexed mesh", CGAL::hex_mesh_quality(mesh));

  // the same mesh as a linear cell complex: one 3-cell per hexahedron,
  // 3-sewn along the faces the hexahedra share
  LCC lcc;
  std::string why;
  if(!CGAL::build_linear_cell_complex(mesh, lcc, &why))
  {
    std::cerr << "cannot build the linear cell complex: " << why << std::endl;
    return 1;
  }
  print("linear cell complex", CGAL::hex_mesh_quality(lcc));

  // the scaled Jacobian of each 3-cell, in the order of the 3-cells
  const std::vector<double> sj = CGAL::hex_mesh_scaled_jacobians(lcc);
  std::size_t worst = 0;
  for(std::size_t h = 1; h < sj.size(); ++h)
    if(sj[h] < sj[worst])
      worst = h;
  if(!sj.empty())
    std::cout << "worst element: hexahedron " << worst << " (scaled Jacobian " << sj[worst] << ")" << std::endl;

  // the same value from the 8 corners of that hexahedron (MEDIT/VTK order),
  // and its variant without the centre sample
  if(!sj.empty())
  {
    std::array<K::Point_3, 8> corners;
    for(int i = 0; i < 8; ++i)
      corners[i] = mesh.points[mesh.hexahedra[worst][i]];
    std::cout << "  from its corners: " << CGAL::hex_scaled_jacobian(corners) << " (9 samples), "
              << CGAL::hex_corner_scaled_jacobian(corners) << " (8 corners only)" << std::endl;
  }

  // the rounded scaled Jacobian can have the wrong sign within a few ulps
  // of 0; the certificate decides the sign of the Jacobian exactly
  const CGAL::Hexahedral_mesh_optimization::Validity_certificate c = CGAL::hex_mesh_validity_certificate(mesh);
  std::cout << "certified valid: " << c.certified_valid() << " of " << c.hexes << std::endl;
  return 0;
}
