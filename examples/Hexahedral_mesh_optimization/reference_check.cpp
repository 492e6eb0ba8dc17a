// The reference-volume check (`CGAL::check_hex_mesh_against_reference()`):
// does a hexahedral mesh fill the volume bounded by a reference surface?
// TetGen tetrahedralises the reference; the check compares the volumes,
// looks for self-intersections of the mesh boundary and for vertices
// outside the reference volume.
//
//   reference_check [mesh.{mesh,vtk,vtu}] [reference.{obj,off,ply,stl}]
//   (defaults: data/bunny_dualsheet.vtk, data/bunny_reference.obj)
//
// Needs TetGen (CGAL_HMO_HAVE_TETGEN, set by the package's CMake target when
// TetGen is found); without it every check reports that TetGen is missing.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/hex_mesh_io.h>
#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/hex_mesh_reference_check.h>
#include <CGAL/hex_mesh_surface_error.h>

#include <iostream>
#include <string>

#ifndef HMO_EXAMPLE_DATA_DIR // set by CMakeLists.txt
#define HMO_EXAMPLE_DATA_DIR "data"
#endif

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Indexed_hex_mesh<K::Point_3> Mesh;
typedef CGAL::Surface_mesh<K::Point_3> Surface;
namespace HMO = CGAL::Hexahedral_mesh_optimization;

int main(int argc, char* argv[])
{
  const std::string mesh_file = (argc > 1) ? argv[1] : std::string(HMO_EXAMPLE_DATA_DIR "/bunny_dualsheet.vtk");
  const std::string surface_file = (argc > 2) ? argv[2] : std::string(HMO_EXAMPLE_DATA_DIR "/bunny_reference.obj");

  Mesh mesh;
  CGAL::IO::Hex_mesh_io_error error;
  if(!CGAL::IO::read_hex_mesh(mesh_file, mesh, &error))
  {
    std::cerr << error.what() << std::endl;
    return 1;
  }
  Surface reference;
  std::string why;
  if(!CGAL::IO::read_reference_surface(surface_file, reference, &why))
  {
    std::cerr << why << std::endl;
    return 1;
  }

  // Against a triangle surface, with a volume tolerance of 2 % (default 1 %)
  // and the default outside tolerance (1 % of the reference's diagonal).
  const HMO::Reference_volume_report report = CGAL::check_hex_mesh_against_reference(
    mesh, reference, CGAL::parameters::volume_tolerance(0.02));
  std::cout << "against " << surface_file << ":\n" << report.summary() << std::endl;
  if(report.has_error())
    return 1; // the reference bounds no volume, or TetGen is missing

  // The report's fields, for a program that decides by itself.
  std::cout << "hex mesh volume " << report.hex_mesh_volume << ", reference volume " << report.reference_volume
            << ": relative difference " << report.relative_volume_difference << std::endl;
  std::cout << "vertices outside the reference volume: " << report.vertices_outside << " ("
            << report.vertices_outside_beyond_tolerance << " beyond the tolerance)" << std::endl;

  // The reference can also be a hexahedral mesh (its boundary, each
  // quadrilateral cut into two triangles, is then the surface), e.g. the
  // input of an optimisation for its output. Against itself, the volumes
  // differ only by the curvature of the faces of the trilinear hexahedra
  // (a non-planar quadrilateral is not its two triangles).
  const HMO::Reference_volume_report self = CGAL::check_hex_mesh_against_reference(mesh, mesh);
  std::cout << "against its own boundary: relative volume difference " << self.relative_volume_difference
            << (self.has_error() ? ", error: " + self.error : std::string()) << std::endl;
  return self.has_error() ? 1 : 0;
}
