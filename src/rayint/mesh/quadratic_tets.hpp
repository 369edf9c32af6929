#pragma once
// Straight-edged quadratic tetrahedra (tet10: VTK_QUADRATIC_TETRA, gmsh's order-2 tetrahedron,
// tetgen -o2) in a tetrahedral mesh: the scalar and its integral along a ray.
//
// Field: with the barycentric coordinates lambda_0..3 of the corners (linear in x), the tet10
// interpolant of VTK (vtkQuadraticTetra::InterpolationFunctions) is
//   f(x) = sum_i f_i lambda_i (2 lambda_i - 1) + sum_(a,b) 4 f_ab lambda_a lambda_b
// over the corners i and the six edges (a, b) (cells/cell_types.hpp, kTet10Edges). This is the
// isoparametric interpolant only when every mid-edge node lies at its edge's midpoint (then the
// geometry map is affine and the lambdas are its inverse): the mesh must have straight edges
// (check_tet10_edges). A mesh with a curved edge is integrated in its isoparametric
// interpolation by the own-cells path instead (mesh/cell_traversal.hpp, cells/
// quadratic_isoparametric.hpp; input/mesh_case_reader.cpp routes it); refuse_curved_tet10 is
// kept for callers that take the tetrahedral path only.
// Along a ray x(t) = x_in + t d the lambdas are linear in t, so f is a quadratic in t: its
// coefficients are the products of the linear factors multiplied out (quadratic_tet_chord; no
// fitting, no division by the chord length).
//
// Integration: the traversal (mesh/tet_traversal.hpp) walks the corners' tetrahedra as for a
// linear mesh and, for a mesh with quadratic tets, gives each crossing its quadratic coefficient
// (CellCrossing::q). poly_ray_from_trace turns the trace into a PolyRay of quadratic segments,
// and QuadraticTraceIntegrator integrates it with grid/trilinear_integral.hpp's polynomial path
// (any degree <= 3): a segment whose range (Bernstein hull) holds a transfer-function breakpoint
// is split at the quadratic's extremum and at every breakpoint crossing (poly::split_points:
// critical point, then TOMS 748 on each monotone stretch); on each piece rho and kappa are
// quadratics in s, the optical depth is their exact antiderivative and the emission is -expm1
// plus Gauss-Legendre on panels of optical depth <= 0.5 (exact to rounding for kappa rho of
// degree 4 times a smooth exponential; trilinear_integral.hpp).
// Accuracy (tests/test_tet10.cpp, [tet10]), double against independent 50-digit references
// (reference/poly_reference.hpp), steep transfer functions with breakpoints crossed:
//   the analytic quadratic q (mesh-free: the cube's chord, q along it in 50 digits), 60 rays
//   through each of six files (gmsh .msh 2.2/4.1/.vtk, meshio and VTK .vtu, TetGen): worst
//   relative error of the intensity 1.8e-15, of the transmittance 2.1e-15;
//   the non-polynomial r per crossing (50-digit barycentrics and shape functions), 40 rays,
//   855 crossings (gmsh, TetGen): worst 1.3e-15.
// The field itself matches VTK's vtkQuadraticTetra at 300 random points to 8.2e-16 (values O(1)).
#include <array>
#include <cstdint>
#include <string>

#include "rayint/geometry/vec3.hpp"
#include "rayint/grid/trilinear_integral.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/mesh/tet_mesh.hpp"
#include "rayint/model/poly_ray.hpp"

namespace rayint {

struct RayTrace;

// A mid-edge node farther than this (relative to its edge's length) from the edge's midpoint
// makes the edge curved. Origin: the writers print coordinates to 16-17 significant digits, so a
// straight edge's node is off by rounding only (measured on the fixtures of gmsh 4.8, meshio's
// and VTK 9.1's binary .vtu: 3.3e-16; TetGen 1.6: 0; meshio's ASCII .vtu, which prints 12
// digits: 1.6e-12, tests [tet10]); 1e-10 leaves that two orders of margin, while gmsh's -order 2
// ball (tet10-sphere-41.msh) is off by more than 1e-3.
inline constexpr double kStraightEdgeTolerance = 1e-10;

struct Tet10EdgeCheck {
  long quadratic_tets = 0;    // tets with mid-edge nodes (edge_nodes entries not all -1)
  double worst_offset = 0.0;  // max |x_node - (x_a + x_b)/2| / |x_b - x_a| over their edges
  std::size_t worst_tet = 0;  // the tet (index in mesh.tets) and edge (0-5) where it is
  int worst_edge = 0;
  bool straight() const { return worst_offset <= kStraightEdgeTolerance; }
};
Tet10EdgeCheck check_tet10_edges(const TetMesh& mesh);

// Throws InputError "<source>: cells[<file cell id>]: quadratic tetra with a curved edge: ..."
// when check_tet10_edges finds an edge beyond kStraightEdgeTolerance.
void refuse_curved_tet10(const TetMesh& mesh, const std::string& source);

// For the paths that integrate linear segments only (shading; gradients; render --compare; eval,
// check, bench and gate take quadratic chords, mesh/quadratic_methods.hpp): throws InputError
// "<source>: cells: N quadratic tetrahedra: <what> takes linear tetrahedra only; `rayint render`
// integrates them with their quadratic interpolation" when the mesh has quadratic tets.
void refuse_quadratic_tets(const TetMesh& mesh, const std::string& source, const std::string& what);

// One tet10's field: corner 0, the gradients of lambda_1..3 (lambda_k = grad[k-1].(x - p0)),
// and the 10 node values in VTK's order (a linear tet of a mixed mesh: edge means).
struct QuadraticTetField {
  Vec3 p0 = Vec3::Zero();
  std::array<Vec3, 3> grad{};
  std::array<double, 10> value{};
};
QuadraticTetField fit_quadratic_tet(const TetMesh& mesh, std::size_t tet);
double quadratic_tet_value(const QuadraticTetField& field, const Vec3& x);
// f(x_in + t d) = c[0] + c[1] t + c[2] t^2.
std::array<double, 3> quadratic_tet_chord(const QuadraticTetField& field, const Vec3& x_in, const Vec3& d);

// The trace as a PolyRay: one segment per crossing, far -> near, scalar(s) with s the distance
// from the crossing's far end: s_out - g s + q s^2 (g: the slope at the far end).
PolyRay poly_ray_from_trace(const RayTrace& trace, const Rgb& background);

class QuadraticTraceIntegrator {
 public:
  explicit QuadraticTraceIntegrator(const TransferFunctions& tf) : poly_(tf) {}
  // `pieces` (optional) gets the smooth pieces integrated (crossings split at breakpoints).
  RayResult integrate(const RayTrace& trace, const Rgb& background, long* pieces = nullptr) const;

 private:
  TrilinearIntegrator poly_;
};

}  // namespace rayint
