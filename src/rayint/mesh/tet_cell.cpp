// Eq. 9 of Williams & Max (1992) per linear tetrahedron (see tet_cell.hpp).
#include "rayint/mesh/tet_cell.hpp"

#include <Eigen/LU>

namespace rayint {

LinearTetField fit_linear_tet(const std::array<Vec3, 4>& x, const std::array<double, 4>& s) {
  Eigen::Matrix3d edges;
  Eigen::Vector3d rhs;
  for (int k = 0; k < 3; ++k) {
    edges.row(k) = (x[static_cast<std::size_t>(k + 1)] - x[0]).transpose();
    rhs[k] = s[static_cast<std::size_t>(k + 1)] - s[0];
  }
  LinearTetField f;
  f.anchor = x[0];
  f.anchor_scalar = s[0];
  f.gradient = edges.fullPivLu().solve(rhs);
  return f;
}

}  // namespace rayint
