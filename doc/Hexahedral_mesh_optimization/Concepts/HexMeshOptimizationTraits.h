/*!
\ingroup PkgHexahedralMeshOptimizationConcepts
\cgalConcept

The concept `HexMeshOptimizationTraits` describes the geometric traits a
function of this package needs to read the coordinates of the points of a
hexahedral mesh and to construct points when it writes the optimised
positions back. The numerical core works on `double` copies of the
coordinates: the traits are used once when a mesh is read into it and once
when the result is written back.

\cgalHasModel All models of the `Kernel` concept, for instance
`CGAL::Exact_predicates_inexact_constructions_kernel` and
`CGAL::Simple_cartesian<double>`; also
`CGAL::Linear_cell_complex_traits<3, K>` for such a kernel `K`.

\sa `CGAL::hex_mesh_quality()`
\sa `CGAL::hex_scaled_jacobian()`
*/
class HexMeshOptimizationTraits
{
public:

/// \name Types
/// @{

/*!
The number type of the coordinates. It must be constructible from `double`,
and `CGAL::to_double()` must be defined for it.
*/
typedef unspecified_type FT;

/*!
The point type.
*/
typedef unspecified_type Point_3;

/*!
A functor with `FT operator()(const Point_3& p) const` returning the
\f$ x\f$-coordinate of `p`.
*/
typedef unspecified_type Compute_x_3;

/*!
A functor with `FT operator()(const Point_3& p) const` returning the
\f$ y\f$-coordinate of `p`.
*/
typedef unspecified_type Compute_y_3;

/*!
A functor with `FT operator()(const Point_3& p) const` returning the
\f$ z\f$-coordinate of `p`.
*/
typedef unspecified_type Compute_z_3;

/*!
A functor with `Point_3 operator()(const FT& x, const FT& y, const FT& z) const`
constructing the point of coordinates \f$ (x, y, z)\f$.
*/
typedef unspecified_type Construct_point_3;

/// @}

/// \name Operations
/// @{

/*!
returns a `Compute_x_3` functor.
*/
Compute_x_3 compute_x_3_object() const;

/*!
returns a `Compute_y_3` functor.
*/
Compute_y_3 compute_y_3_object() const;

/*!
returns a `Compute_z_3` functor.
*/
Compute_z_3 compute_z_3_object() const;

/*!
returns a `Construct_point_3` functor.
*/
Construct_point_3 construct_point_3_object() const;

/// @}

}; /* end HexMeshOptimizationTraits */
