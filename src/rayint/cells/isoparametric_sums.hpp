#pragma once
// The sums every isoparametric cell evaluates from its shape functions (cells/linear_cells.cpp,
// cells/quadratic_isoparametric.cpp): x(p) = sum_i N_i x_i, f(p) = sum_i N_i f_i and
// J(p) = [dx/dr dx/ds dx/dt] with dN in VTK's InterpolateDerivs layout (dN[j n + i] = dN_i/dp_j),
// the inverse map both cell kinds share (the exact linear inverse of an affine cell, else
// newton_inverse_map), and the steps of make_linear_cell / make_quadratic_cell that are the same
// for both (finite nodes copied, extent, affine fit).
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "rayint/cells/linear_cells.hpp"
#include "rayint/cells/quadratic_cells.hpp"
#include "rayint/cells/quadratic_isoparametric.hpp"
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

// Each cell kind's node count and shape functions, by overload, for the templates below.
inline int node_count(const LinearCell& c) { return linear_node_count(c.type); }
inline int node_count(const QuadraticCell& c) { return quadratic_node_count(c.type); }
inline void shape_functions(const LinearCell& c, const Vec3& p, double* N) { linear_shape_functions(c.type, p, N); }
inline void shape_functions(const QuadraticCell& c, const Vec3& p, double* N) { quadratic_shape_functions(c.type, p, N); }
inline void shape_derivatives(const LinearCell& c, const Vec3& p, double* dN) { linear_shape_derivatives(c.type, p, dN); }
inline void shape_derivatives(const QuadraticCell& c, const Vec3& p, double* dN) {
  quadratic_shape_derivatives(c.type, p, dN);
}

// Cell: LinearCell or QuadraticCell (both hold at most kMaxNewtonNodes nodes).
template <class Cell>
Vec3 isoparametric_position(const Cell& cell, const Vec3& p) {
  double N[kMaxNewtonNodes];
  shape_functions(cell, p, N);
  return weighted_position(cell.x.data(), N, node_count(cell));
}

template <class Cell>
double isoparametric_scalar(const Cell& cell, const Vec3& p) {
  double N[kMaxNewtonNodes];
  shape_functions(cell, p, N);
  return weighted_value(cell.value.data(), N, node_count(cell));
}

template <class Cell>
Eigen::Matrix3d isoparametric_jacobian(const Cell& cell, const Vec3& p) {
  double dN[3 * kMaxNewtonNodes];
  shape_derivatives(cell, p, dN);
  return jacobian_from_derivatives(cell.x.data(), dN, node_count(cell));
}

// The affine cell's exact inverse, else newton_inverse_map from `start`.
template <class Cell>
InverseMap isoparametric_inverse_map(const Cell& cell, const Vec3& world, const Vec3& start) {
  if (cell.affine) {
    InverseMap out;
    out.p = cell.affine_inverse * (world - cell.affine_origin);
    out.converged = out.p.allFinite();
    return out;
  }
  return newton_inverse_map(cell.x.data(), node_count(cell), world, start, [&](const Vec3& p, double* N, double* dN) {
    shape_functions(cell, p, N);
    shape_derivatives(cell, p, dN);
  });
}

// make_*_cell: the n nodes and values into cell.x and cell.value; a non-finite one throws
// std::invalid_argument "<who>: node coordinates and values must be finite". Returns the largest
// |coordinate| (the scale of the affine test).
template <class Cell>
double copy_finite_nodes(Cell& c, const std::vector<Vec3>& nodes, const std::vector<double>& values, int n,
                         const std::string& who) {
  double magnitude = 0.0;
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (!nodes[k].allFinite() || !std::isfinite(values[k]))
      throw std::invalid_argument(who + ": node coordinates and values must be finite");
    c.x[k] = nodes[k];
    c.value[k] = values[k];
    magnitude = std::max(magnitude, nodes[k].cwiseAbs().maxCoeff());
  }
  return magnitude;
}

// The largest distance between two of the points x[0..count).
inline double largest_distance(const Vec3* x, int count) {
  double d = 0.0;
  for (int i = 0; i < count; ++i)
    for (int j = i + 1; j < count; ++j) d = std::max(d, (x[i] - x[j]).norm());
  return d;
}

// The candidate affine map x(p) = x[0] + A p through the nodes at the unit points
// (axis_node[a]: the node at reference point e_a), and the largest deviation |x_k - x(ref_k)|
// (max norm) of the n nodes from it.
struct AffineFit {
  Eigen::Matrix3d A;
  double residual = 0.0;
};
inline AffineFit fit_affine(const Vec3* x, const std::vector<Vec3>& ref, int n, const int axis_node[3]) {
  AffineFit f;
  for (int a = 0; a < 3; ++a) f.A.col(a) = x[axis_node[a]] - x[0];
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    f.residual = std::max(f.residual, (x[i] - x[0] - f.A * ref[k]).cwiseAbs().maxCoeff());
  }
  return f;
}

}  // namespace rayint
