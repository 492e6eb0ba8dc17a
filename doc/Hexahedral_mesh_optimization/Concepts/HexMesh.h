/*!
\ingroup PkgHexahedralMeshOptimizationConcepts
\cgalConcept

The concept `HexMesh` describes the all-hexahedral meshes the functions of
this package take (`CGAL::untangle_hex_mesh()`,
`CGAL::improve_hex_mesh_quality()`, `CGAL::optimize_hex_mesh()`,
`CGAL::hex_mesh_quality()`, ...): a set of vertices, each with a point, and
a set of hexahedra, each given by its 8 vertices. The functions never change
the connectivity: they read the mesh once and write back the points of the
vertices they moved, through the vertex point map.

A model provides:
- a vertex descriptor, the key type of the vertex property maps
  (`vertex_point_map`, `vertex_is_constrained_map`);
- its vertices in a fixed order, which is the order of the vertex indices
  the functions report (e.g. in `Hexahedral_mesh_optimization::Unresolved_element`);
- its hexahedra in a fixed order, each as 8 vertices in MEDIT/VTK order
  (vertices 0-3 form the bottom face, vertex `i+4` lies above vertex `i`,
  and a well-shaped hexahedron has a positive Jacobian at every corner);
- a default vertex point map, readable and writable, whose value type is
  the `Point_3` of a model of `HexMeshOptimizationTraits`.

The models are the three types listed below, through the package's own
adapter (the concept has no free functions a user could provide for another
type): any other type given to a function of the package fails to compile
with a `static_assert` whose message names this concept.

| Model | vertex descriptor | vertex order | hexahedra |
| :---- | :---------------- | :----------- | :-------- |
| `CGAL::Indexed_hex_mesh<Point_3>` | `std::size_t` | `points` | `hexahedra` |
| `CGAL::Linear_cell_complex_for_combinatorial_map<3,3,Traits,Items,Alloc>` | `Vertex_attribute_const_handle` | `vertex_attributes()` | its 3-cells, which must be combinatorial hexahedra (`std::invalid_argument` otherwise), in the order of their first dart, with the orientation of their darts |
| `CGAL::Linear_cell_complex_for_generalized_map<3,3,Traits,Items,Alloc>` | `Vertex_attribute_const_handle` | `vertex_attributes()` | the same; a generalized map is not oriented: each connected component takes the orientation under which the sum of the corner Jacobian determinants of its hexahedra is positive |

The linear cell complexes are models with any items (the vertex attribute
must carry a point, as `Cell_attribute_with_point` does) and any traits;
include `CGAL/Hexahedral_mesh_optimization/Linear_cell_complex_hex_mesh.h`
for them.

\cgalHasModel `CGAL::Indexed_hex_mesh`
\cgalHasModel `CGAL::Linear_cell_complex_for_combinatorial_map` (dimension 3, ambient dimension 3)
\cgalHasModel `CGAL::Linear_cell_complex_for_generalized_map` (dimension 3, ambient dimension 3)

\sa `HexMeshOptimizationTraits`
*/
class HexMesh
{
public:
}; /* end HexMesh */
