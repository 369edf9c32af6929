#pragma once
// VTK's quadratic volume cells in VTK's parametric coordinates (vtkQuadraticTetra,
// vtkQuadraticHexahedron, vtkQuadraticWedge, vtkTriQuadraticHexahedron, vtkBiQuadraticQuadraticWedge): node order, parametric node coordinates, shape
// functions and their derivatives -- the building blocks an isoparametric treatment of these
// cells needs (inverse map by Newton, as cells/linear_cells.hpp does for the linear ones). Not yet
// used by a traversal; straight-edged tet10 meshes are integrated by mesh/quadratic_tets.hpp.
//
// Interpolation spaces (each unisolvent on its nodes, so the nodal basis is unique and equals
// VTK's whatever formulas VTK writes):
//   quadratic tetra (10 nodes)      P2: 1, r, s, t, r^2, s^2, t^2, rs, st, rt;
//   quadratic hexahedron (20)       serendipity: P2 and r^2 s, r^2 t, s^2 r, s^2 t, t^2 r,
//                                   t^2 s, rst, r^2 st, rs^2 t, rst^2 (superlinear degree <= 2);
//   quadratic wedge (15)            {1, r, s, r^2, rs, s^2} x {1, t} + t^2, r t^2, s t^2;
//   triquadratic hexahedron (27)    Q2: r^a s^b t^c, a, b, c <= 2 (vtkTriQuadraticHexahedron);
//   biquadratic-quadratic wedge (18) {1, r, s, r^2, rs, s^2} x {1, t, t^2}
//                                   (vtkBiQuadraticQuadraticWedge).
// The two spaces of the 27- and 18-node cells were read off VTK 9.1 itself: a least-squares fit
// of its weights at 600 random points to every monomial of total degree <= 6 leaves 1.3e-13 and
// uses exactly these monomials.
// Method: N(p) = V^-T m(p) with m the monomials above and V the Vandermonde matrix of the nodes
// (V_ij = m_j(node_i), inverted once in double: entries are 0, 1/2, 1 and their products, its
// condition number is <= 1e3); dN = V^-T dm/dp. The 27- and 18-node cells are evaluated as
// products instead (1-D Lagrange in r, s, t; the P2 triangle times Lagrange in t): their 27 x 27
// Vandermonde inverse rounds to 1.4e-14 per weight, too coarse for the inverse map's 4e-15 step
// test (Newton then stalls); the products round to ~1e-16. Accuracy (tests/test_quadratic_cells.cpp,
// [cells][quadratic]): against VTK 9.1's InterpolateFunctions / InterpolateDerivs at 10 random
// parametric points per type (tests/fixtures/cells/vtk_quadratic_cells.json, written by
// scripts/cells/vtk_quadratic_fixture.py): parametric nodes identical; worst |N - VTK| 1.8e-16
// (tetra), 1.1e-15 (hexahedron), 4.4e-16 (wedge); worst |dN - VTK| 0, 1.8e-15, 5.6e-16.
//
// Quadratic pyramid (vtkQuadraticPyramid, 13 nodes: corners 0-4, then the mid-edge nodes of
// (0,1) (1,2) (2,3) (3,0) (0,4) (1,4) (2,4) (3,4)): VTK's domain is the unit cube whose top face
// t = 1 collapses onto the apex (as vtkPyramid); its InterpolationFunctions are polynomials of
// degree <= 2 in each of r, s, t (in (a, b, c) = 2p - 1: corners -(1 -+ a)(1 -+ b)(1 - c)(...)/16,
// base mid-edge nodes (1 - a^2)(1 -+ b)(1 - c)(2 +- b +- bc)/8 and the like, the apex
// c(1 + c)/2, the apex edges (1 -+ a)(1 -+ b)(1 - c^2)/4), written here as VTK writes them and
// evaluated on a forward-mode dual number, so dN is the exact derivative of N. VTK's own
// InterpolationDerivs are NOT the derivatives of its functions (VTK 9.1 and 9.2 keep the
// derivatives of an older set: they differ from central differences of InterpolationFunctions
// by up to 0.79 at 200 random points, measured with python3-vtk9 9.1); VTK's probe uses the
// functions (EvaluateLocation) and its Newton the inconsistent derivatives, which still converge
// to the functions' inverse, only slower. The functions' traces on the faces are the 8-node
// serendipity quadrilateral (base, t = 0) and the 6-node P2 triangle in the collapsed
// coordinates (the four sides), so a pyramid13 shares its faces exactly with hex20, wedge15 and
// tet10 neighbours. Accuracy: |N - VTK| and |dN - central differences of VTK's N| in
// tests [cells][quadratic] (measured figures there).
// The gmsh permutations of the cell-type table (cells/cell_types.cpp) are checked there too,
// against gmsh's documented edge lists.
#include <vector>

#include "rayint/geometry/vec3.hpp"

namespace rayint {

// VTK's type ids: quadratic tetra, quadratic hexahedron, quadratic wedge, triquadratic hexahedron
// (27 nodes), biquadratic-quadratic wedge (18 nodes),
// quadratic pyramid (27, 13 nodes).
enum class QuadraticCellType : int {
  tetra = 24, hexahedron = 25, wedge = 26, pyramid = 27, triquadratic_hexahedron = 29, biquadratic_wedge = 32
};

bool quadratic_cell_type_from_vtk(int vtk_id, QuadraticCellType& type);
int quadratic_node_count(QuadraticCellType type);  // 10, 20, 15, 27, 18; pyramid 13
// VTK's parametric node coordinates (vtkCell::GetParametricCoords), VTK's node order.
const std::vector<Vec3>& quadratic_reference_nodes(QuadraticCellType type);
// N[i] for every node at parametric point p (N has quadratic_node_count entries).
void quadratic_shape_functions(QuadraticCellType type, const Vec3& p, double* N);
// dN laid out as VTK's InterpolateDerivs: dN[i] = dN_i/dr, dN[n + i] = dN_i/ds, dN[2n + i] = dN_i/dt.
void quadratic_shape_derivatives(QuadraticCellType type, const Vec3& p, double* dN);

// The factors of the product cells, shared with their curved faces (quadratic_isoparametric:
// the 9-node quadrilateral and 6-node triangle patches).
// 1-D quadratic Lagrange functions on the nodes 0, 1/2, 1 (l[3]) and their derivatives (dl[3]).
void lagrange_1d(double u, double* l, double* dl);
// The 6-node (P2) triangle on (r, s): corners L(2L - 1) for L = 1 - r - s, r, s, then the edges
// (0,1) (1,2) (2,0) 4 La Lb; N[6] and its derivatives dr[6], ds[6].
void p2_triangle(double r, double s, double* N, double* dr, double* ds);

}  // namespace rayint
