// Eq. 9 of Williams & Max (1992) per linear tetrahedron (see tet_cell.hpp for the method and its
// measured accuracy).
#include "rayint/mesh/tet_cell.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/LU>

#include "rayint/mesh/tet_mesh.hpp"

namespace rayint {

LinearTetField fit_linear_tet(const std::array<Vec3, 4>& x, const std::array<double, 4>& s) {
  LinearTetField f;
  f.anchor = x[0];
  f.anchor_scalar = s[0];
  const Vec3 e1 = x[1] - x[0], e2 = x[2] - x[0], e3 = x[3] - x[0];
  // The inverse of the edge matrix [e1; e2; e3] is [e2 x e3, e3 x e1, e1 x e2] / det (columns),
  // det = e1 . (e2 x e3) = 6 V.
  const Vec3 c23 = e2.cross(e3), c31 = e3.cross(e1), c12 = e1.cross(e2);
  const double det = e1.dot(c23);
  // The shape the mesh checks accept (classify_tet, tet_mesh.hpp): |6 V| > kDegenerateTetRatio l^3,
  // here squared (no square root) and with this det, so at the limit a cell may go either way by
  // rounding (both branches are measured there: tet_cell.hpp). Inside it the closed form; outside
  // (a caller that skipped the checks: a flat, degenerate or non-finite cell) Eigen's LU as before.
  const double l2 = std::max({e1.squaredNorm(), e2.squaredNorm(), e3.squaredNorm(), (x[2] - x[1]).squaredNorm(),
                              (x[3] - x[1]).squaredNorm(), (x[3] - x[2]).squaredNorm()});
  if (det * det > (kDegenerateTetRatio * kDegenerateTetRatio) * (l2 * l2 * l2) && std::isfinite(det)) {
    const double d1 = s[1] - s[0], d2 = s[2] - s[0], d3 = s[3] - s[0];
    f.gradient = (d1 * c23 + d2 * c31 + d3 * c12) / det;
    return f;
  }
  Eigen::Matrix3d edges;
  edges.row(0) = e1.transpose();
  edges.row(1) = e2.transpose();
  edges.row(2) = e3.transpose();
  f.gradient = edges.fullPivLu().solve(Eigen::Vector3d(s[1] - s[0], s[2] - s[0], s[3] - s[0]));
  return f;
}

}  // namespace rayint
