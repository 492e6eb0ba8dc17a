// Untangles a hexahedral mesh held in a linear cell complex
// (`CGAL::Linear_cell_complex_for_combinatorial_map<3,3>`) with
// `CGAL::untangle_hex_mesh()`: only vertex positions move, the combinatorial
// map is left as it is.
//
//   untangle_lcc [mesh.{mesh,vtk,vtu}]   (default: data/bunny_dualsheet.vtk)
//
// Prints the quality of the complex before and after, what each stage of the
// untangling did, and whether the result is certified valid.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/lcc_hex_mesh_io.h>
#include <CGAL/Hexahedral_mesh_optimization/Linear_cell_complex_hex_mesh.h>
#include <CGAL/Linear_cell_complex_for_combinatorial_map.h>
#include <CGAL/hex_mesh_quality.h>
#include <CGAL/untangle_hex_mesh.h>

#include <iostream>
#include <string>
#include <vector>

#ifndef HMO_EXAMPLE_DATA_DIR // set by CMakeLists.txt
#define HMO_EXAMPLE_DATA_DIR "data"
#endif

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Linear_cell_complex_for_combinatorial_map<3, 3, CGAL::Linear_cell_complex_traits<3, K> > LCC;

int main(int argc, char* argv[])
{
  const std::string fname = (argc > 1) ? argv[1] : std::string(HMO_EXAMPLE_DATA_DIR "/bunny_dualsheet.vtk");

  // Read the file straight into the complex: one 3-cell per hexahedron,
  // 3-sewn along the faces the hexahedra share.
  LCC lcc;
  CGAL::IO::Hex_mesh_io_error error;
  if(!CGAL::IO::read_hex_mesh(fname, lcc, &error))
  {
    std::cerr << error.what() << std::endl;
    return 1;
  }

  const CGAL::Hex_mesh_quality before = CGAL::hex_mesh_quality(lcc);
  std::cout << "input: " << before.hexes << " hexahedra, " << before.inverted << " inverted, MSJ " << before.msj
            << std::endl;

  // Untangle with the default parameters: the boundary stays on the input's
  // own boundary. The result says what was done (never a bare bool).
  const CGAL::Hexahedral_mesh_optimization::Optimization_result r = CGAL::untangle_hex_mesh(lcc);
  for(const CGAL::Hexahedral_mesh_optimization::Stage_report& s : r.stages)
    std::cout << "  stage " << s.name << ": inverted " << s.inverted_before << " -> " << s.inverted_after
              << " in " << s.rounds << " rounds" << std::endl;
  std::cout << "untangled: inverted " << r.inverted_before << " -> " << r.inverted_after << ", MSJ " << r.msj_before
            << " -> " << r.msj_after << ", surface error " << r.surface_error << std::endl;

  // The positions were written back into the vertex attributes of the
  // complex: its quality now says the same as the result.
  const CGAL::Hex_mesh_quality after = CGAL::hex_mesh_quality(lcc);
  std::cout << "output: " << after.hexes << " hexahedra, " << after.inverted << " inverted, MSJ " << after.msj
            << std::endl;

  // The rounded scaled Jacobian can be wrong in sign within a few ulps of 0;
  // the certificate decides the sign of the Jacobian exactly.
  const CGAL::Hexahedral_mesh_optimization::Validity_certificate c = CGAL::hex_mesh_validity_certificate(lcc);
  std::cout << "certified valid: " << c.certified_valid() << " of " << c.hexes << std::endl;

  for(const CGAL::Hexahedral_mesh_optimization::Unresolved_element& e : r.unresolved)
    std::cout << "  still inverted: hexahedron " << e.hex << " (" << e.details << ")" << std::endl;
  return (r.success && after.inverted == 0 && c.all_valid()) ? 0 : 1;
}
