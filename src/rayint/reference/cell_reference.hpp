#pragma once
// The independent 50-digit reference for the ray integral through one linear VTK cell in its own
// (isoparametric) interpolation: the quantity cells/cell_integral.hpp computes in double.
// Williams & Max (1992) Eq. 4 with the transfer functions of Sec. 3.1 applied to the scalar
// f(t) = sum_i N_i(p(t)) f_i, p(t) the inverse map of the ray point, on a chord [t_near, t_far].
// See cell_reference.cpp for the methods and the error bound.
//
// Independence from the double path: nothing here includes cells/ (this area cannot see it). The
// shape functions are written again from VTK's definitions (vtkTetra, vtkVoxel, vtkHexahedron,
// vtkWedge, vtkPyramid InterpolationFunctions), in cpp_bin_float_50; the quadratic cells' (ids
// 24-27, 29, 32, curved ones too) from the textbook P2 tetrahedron, 20-node serendipity brick,
// 15-node serendipity prism, 27-node Lagrange brick and 18-node (P2 x Lagrange) prism on VTK's
// parametric nodes, and vtkQuadraticPyramid's own formulas (sign-factored per node), differentiated by forward-mode dual numbers (the
// double path builds them from a Vandermonde inverse instead, cells/quadratic_cells.hpp); the inverse map is Newton
// with Cramer's rule in 50 digits; the crossings and critical points are found on the true
// scalar (each evaluation an inverse map), not on an interpolant; the quadrature is Boost's
// 61-point Gauss-Kronrod in 50 digits (reference_detail::gauss_kronrod_rule, as
// poly_reference.cpp) with doubling to 1e-36. What it shares with the double path is the idea of
// representing f on a smooth piece by a Chebyshev series; here each piece between true crossings
// gets its own series to a tail of 1e-42, and the series is checked against direct inverse-map
// evaluation at 7 interior points (it must agree to 1e-40 of the value scale, else the degree
// doubles).
#include <array>
#include <vector>

#include "rayint/model/transfer_function.hpp"

namespace rayint {

struct CellReferenceInput {
  int vtk_id = 12;  // 10 tetra, 11 voxel, 12 hexahedron, 13 wedge, 14 pyramid; quadratic: 24 tetra,
                    // 25 hexahedron, 26 wedge, 27 pyramid, 29 triquadratic hexahedron, 32
                    // biquadratic-quadratic wedge (VTK's node order, curved cells too)
  std::vector<std::array<double, 3>> nodes;      // VTK node order
  std::vector<double> values;                    // node scalars
  std::array<double, 3> origin{}, direction{};   // ray origin + t direction
  double t_near = 0.0, t_far = 0.0;              // the chord, inside the cell
};

struct CellReference {
  Rgb emission{};        // light leaving t_near toward the eye, nothing entering at t_far
  Rgb optical_depth{};
  Rgb emission_error{};  // absolute bound per channel (quadrature + series + rounding)
  Rgb depth_error{};
  int pieces = 0;        // smooth pieces between true crossings and critical points
  int evaluations = 0;   // 50-digit inverse maps
  int max_degree = 0;    // largest Chebyshev degree used
};

// Throws std::invalid_argument for bad input (unknown id, node/value counts, non-finite data,
// bad transfer functions) and std::runtime_error when a Newton solve, a series or the
// quadrature misses its target within its budget.
CellReference reference_cell_chord(const TransferFunctions& tf, const CellReferenceInput& input);

}  // namespace rayint
