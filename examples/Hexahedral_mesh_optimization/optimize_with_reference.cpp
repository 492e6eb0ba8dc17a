// The whole pipeline (`CGAL::optimize_hex_mesh()`: untangling, then the
// quality stages) with the boundary kept on a reference surface, and a
// visitor that prints progress as the stages run.
//
//   optimize_with_reference [mesh.{mesh,vtk,vtu}] [reference.{obj,off,ply,stl}] [target MSJ]
//   (defaults: data/bunny_dualsheet.vtk, data/bunny_reference.obj, 0.2)
//
// Also shows the reference-surface functions of CGAL/hex_mesh_surface_error.h:
// `IO::read_reference_surface()`, `hex_mesh_reference_fit()` (the test the
// optimisation makes before it moves anything), and both overloads of
// `hex_mesh_surface_distance()` and `hex_mesh_surface_error()` (against a
// triangle mesh, and against the boundary of another hexahedral mesh).

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Hexahedral_mesh_optimization/IO/hex_mesh_io.h>
#include <CGAL/Hexahedral_mesh_optimization/Indexed_hex_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/hex_mesh_surface_error.h>
#include <CGAL/improve_hex_mesh_quality.h>

#include <cstdlib>
#include <functional>
#include <iostream>
#include <string>

#ifndef HMO_EXAMPLE_DATA_DIR // set by CMakeLists.txt
#define HMO_EXAMPLE_DATA_DIR "data"
#endif

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef CGAL::Indexed_hex_mesh<K::Point_3> Mesh;
typedef CGAL::Surface_mesh<K::Point_3> Surface;
namespace HMO = CGAL::Hexahedral_mesh_optimization;

// A visitor derives from the default one (every hook does nothing) and
// overrides the hooks it needs. It is passed by reference with
// `std::ref()`, so that the counts it keeps are the caller's.
struct Print_progress : HMO::Default_optimization_visitor
{
  int stages = 0;

  void stage_started(const std::string& name, std::size_t bad_elements)
  {
    ++stages;
    std::cout << "  [" << name << "] started";
    if(bad_elements > 0)
      std::cout << ", " << bad_elements << " elements to fix";
    std::cout << std::endl;
  }
  void round_finished(const std::string& /*stage*/, int /*round*/, std::size_t /*bad_elements_left*/)
  {
    // called after every round of the iterative stages: a progress bar
    // would be updated here
  }
  void stage_finished(const HMO::Stage_report& r)
  {
    std::cout << "  [" << r.name << "] done: inverted " << r.inverted_before << " -> " << r.inverted_after
              << ", MSJ " << r.msj_after << std::endl;
  }
};

int main(int argc, char* argv[])
{
  const std::string mesh_file = (argc > 1) ? argv[1] : std::string(HMO_EXAMPLE_DATA_DIR "/bunny_dualsheet.vtk");
  const std::string surface_file = (argc > 2) ? argv[2] : std::string(HMO_EXAMPLE_DATA_DIR "/bunny_reference.obj");
  const double target_msj = (argc > 3) ? std::atof(argv[3]) : 0.2;

  Mesh mesh;
  CGAL::IO::Hex_mesh_io_error error;
  if(!CGAL::IO::read_hex_mesh(mesh_file, mesh, &error))
  {
    std::cerr << error.what() << std::endl;
    return 1;
  }
  const Mesh input = mesh; // kept to measure how far the boundary moves

  // The reference surface: any polygon soup CGAL reads, repaired, oriented
  // and triangulated into a Surface_mesh.
  Surface reference;
  std::string why;
  if(!CGAL::IO::read_reference_surface(surface_file, reference, &why))
  {
    std::cerr << why << std::endl;
    return 1;
  }

  // Does the reference fit the mesh boundary? The optimisation makes the
  // same test and throws `Reference_mismatch` for a surface in another
  // frame or of another object; asking first gives the measures.
  const HMO::Reference_fit fit = CGAL::hex_mesh_reference_fit(mesh, reference);
  std::cout << "reference " << surface_file << ": "
            << (fit.verdict == HMO::Reference_fit::fits      ? "fits the boundary"
                : fit.verdict == HMO::Reference_fit::distant ? "fits, but the boundary starts far from it"
                                                             : "does not fit")
            << " (boundary to reference: median " << fit.median_mesh_to_reference << ", max "
            << fit.max_mesh_to_reference << " of the diagonal)" << std::endl;
  if(fit.verdict == HMO::Reference_fit::mismatched)
  {
    std::cerr << fit.message << std::endl;
    return 1;
  }
  std::cout << "surface error before: " << CGAL::hex_mesh_surface_error(mesh, reference) << std::endl;

  // The reference surface and the visitor are named parameters: the
  // package's parameters start the chain, CGAL's own (`visitor`) follow.
  Print_progress progress;
  const HMO::Optimization_result r = CGAL::optimize_hex_mesh(
    mesh, CGAL::parameters::reference_surface(reference).target_msj(target_msj).visitor(std::ref(progress)));

  std::cout << "optimised in " << progress.stages << " stages: inverted " << r.inverted_before << " -> "
            << r.inverted_after << ", MSJ " << r.msj_before << " -> " << r.msj_after << std::endl;
  for(const std::string& w : r.warnings)
    std::cout << "warning: " << w << std::endl;

  // Where the boundary ended up: the one-sided distances to the reference
  // (model units), and the surface error (Hausdorff distance over the
  // reference's bounding-box diagonal), against the reference surface and
  // against the boundary of the input.
  const CGAL::Hex_mesh_surface_distance d = CGAL::hex_mesh_surface_distance(mesh, reference);
  std::cout << "boundary to reference " << d.mesh_to_reference << ", reference to boundary " << d.reference_to_mesh
            << " (diagonal " << d.reference_diagonal << ")" << std::endl;
  std::cout << "surface error after: " << CGAL::hex_mesh_surface_error(mesh, reference)
            << " (the optimiser measured " << r.surface_error << "); against the input's boundary: "
            << CGAL::hex_mesh_surface_error(mesh, input) << std::endl;
  // the same against the boundary of the input, as distances in model units
  const CGAL::Hex_mesh_surface_distance from_input = CGAL::hex_mesh_surface_distance(mesh, input);
  std::cout << "output boundary to input boundary " << from_input.mesh_to_reference << ", input boundary to output boundary "
            << from_input.reference_to_mesh << std::endl;
  return (r.inverted_after == 0 && progress.stages > 0) ? 0 : 1;
}
