// Eq. 9 of Williams & Max (1992) per linear tetrahedron (see tet_cell.hpp).
#include "rayint/mesh/tet_cell.hpp"

#include <cmath>
#include <limits>
#include <utility>

namespace rayint {

Vec3 full_pivot_lu_solve(const Eigen::Matrix3d& a, const Eigen::Vector3d& b) {
  // Eigen 3.4's FullPivLU<Matrix3d>::computeInPlace, then _solve_impl, step by step.
  Eigen::Matrix3d lu = a;
  std::array<int, 3> row_t{}, col_t{};  // the transpositions of step k
  int nonzero_pivots = 3;
  double max_pivot = 0.0;
  for (int k = 0; k < 3; ++k) {
    // The biggest |coefficient| of the corner, the first in column-major order (maxCoeff).
    int row = k, col = k;
    double biggest = std::abs(lu(k, k));
    for (int j = k; j < 3; ++j)
      for (int i = k; i < 3; ++i) {
        if (i == k && j == k) continue;
        const double score = std::abs(lu(i, j));
        if (score > biggest) {
          biggest = score;
          row = i;
          col = j;
        }
      }
    if (biggest == 0.0) {
      nonzero_pivots = k;
      for (int i = k; i < 3; ++i) row_t[static_cast<std::size_t>(i)] = col_t[static_cast<std::size_t>(i)] = i;
      break;
    }
    if (biggest > max_pivot) max_pivot = biggest;
    row_t[static_cast<std::size_t>(k)] = row;
    col_t[static_cast<std::size_t>(k)] = col;
    if (k != row) lu.row(k).swap(lu.row(row));
    if (k != col) lu.col(k).swap(lu.col(col));
    for (int i = k + 1; i < 3; ++i) lu(i, k) /= lu(k, k);
    for (int j = k + 1; j < 3; ++j)
      for (int i = k + 1; i < 3; ++i) lu(i, j) -= lu(i, k) * lu(k, j);
  }
  // rank(): pivots above epsilon x 3 x the largest pivot.
  const double threshold = max_pivot * (std::numeric_limits<double>::epsilon() * 3.0);
  int rank = 0;
  for (int i = 0; i < nonzero_pivots; ++i) rank += std::abs(lu(i, i)) > threshold ? 1 : 0;
  if (rank == 0) return Vec3::Zero();
  // c = P b: the row swaps in the order they were made.
  std::array<double, 3> c{b[0], b[1], b[2]};
  for (std::size_t k = 0; k < 3; ++k) std::swap(c[k], c[static_cast<std::size_t>(row_t[k])]);
  // L (unit lower) then U (upper, its top-left rank x rank corner), column by column as
  // triangular_solve_vector (ColMajor) does, skipping a zero entry.
  for (int i = 0; i < 3; ++i)
    if (c[static_cast<std::size_t>(i)] != 0.0)
      for (int j = i + 1; j < 3; ++j) c[static_cast<std::size_t>(j)] -= c[static_cast<std::size_t>(i)] * lu(j, i);
  for (int i = rank - 1; i >= 0; --i)
    if (c[static_cast<std::size_t>(i)] != 0.0) {
      c[static_cast<std::size_t>(i)] /= lu(i, i);
      for (int j = 0; j < i; ++j) c[static_cast<std::size_t>(j)] -= c[static_cast<std::size_t>(i)] * lu(j, i);
    }
  for (int i = rank; i < 3; ++i) c[static_cast<std::size_t>(i)] = 0.0;
  // x = Q c: the column swaps undone, last first.
  for (int k = 2; k >= 0; --k) std::swap(c[static_cast<std::size_t>(k)], c[static_cast<std::size_t>(col_t[static_cast<std::size_t>(k)])]);
  return Vec3(c[0], c[1], c[2]);
}

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
  f.gradient = full_pivot_lu_solve(edges, rhs);
  return f;
}

}  // namespace rayint
