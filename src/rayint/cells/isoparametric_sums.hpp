#pragma once
// The sums every isoparametric cell evaluates from its shape functions (cells/linear_cells.cpp,
// cells/quadratic_isoparametric.cpp): x(p) = sum_i N_i x_i, f(p) = sum_i N_i f_i and
// J(p) = [dx/dr dx/ds dx/dt] with dN in VTK's InterpolateDerivs layout (dN[j n + i] = dN_i/dp_j),
// and the inverse map both cell kinds share (the exact linear inverse of an affine cell, else
// newton_inverse_map).
#include <Eigen/Core>
#include <utility>

#include "rayint/cells/linear_cells.hpp"
#include "rayint/geometry/vec3.hpp"

namespace rayint {

inline Vec3 weighted_position(const Vec3* x, const double* N, int n) {
  Vec3 s = Vec3::Zero();
  for (int i = 0; i < n; ++i) s += N[i] * x[i];
  return s;
}

inline double weighted_value(const double* f, const double* N, int n) {
  double s = 0.0;
  for (int i = 0; i < n; ++i) s += N[i] * f[i];
  return s;
}

inline Eigen::Matrix3d jacobian_from_derivatives(const Vec3* x, const double* dN, int n) {
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < n; ++i) J.col(j) += dN[j * n + i] * x[i];
  return J;
}

// Cell: LinearCell or QuadraticCell (x, affine, affine_inverse, affine_origin); shapes(p, N, dN)
// as newton_inverse_map takes it.
template <class Cell, class Shapes>
InverseMap isoparametric_inverse_map(const Cell& cell, int n, const Vec3& world, const Vec3& start, Shapes&& shapes) {
  if (cell.affine) {
    InverseMap out;
    out.p = cell.affine_inverse * (world - cell.affine_origin);
    out.converged = out.p.allFinite();
    return out;
  }
  return newton_inverse_map(cell.x.data(), n, world, start, std::forward<Shapes>(shapes));
}

}  // namespace rayint
