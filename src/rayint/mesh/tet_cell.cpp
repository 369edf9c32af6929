// Eq. 9 of Williams & Max (1992) per linear tetrahedron (see tet_cell.hpp).
#include "rayint/mesh/tet_cell.hpp"

#include <cmath>
#include <limits>
#include <utility>

#include <Eigen/LU>

namespace rayint {

namespace {

// Eigen 3.4's FullPivLU<Matrix3d>::compute followed by solve(), written out for the 3 x 3 case:
// the same IEEE operations on the same operands in the same order, so the same doubles bit for
// bit (tests/test_mesh_traversal.cpp compares both on random, tied, zero and signed-zero entries).
// Eigen's general code went through dynamic-size blocks, a visitor and two triangular-solve
// kernels: ~6% of the 105k-tet load (issue 33). Returns false, leaving Eigen to do it, where
// Eigen would find the matrix rank-deficient (a pivot of 0, or one at most 3 eps times the largest
// pivot, Eigen's default threshold, FullPivLU::rank()), which includes every NaN pivot: there
// Eigen's solve takes its rank-deficient branch.
//   a: the matrix, a[i][j] row i column j (overwritten by L and U); b: the right-hand side.
bool full_pivot_solve3(double a[3][3], const double b[3], double x[3]) {
  int row_swap[3], col_swap[3];
  double max_pivot = 0.0;
  for (int k = 0; k < 3; ++k) {
    // The biggest |a_ij| of the corner i, j >= k, scanned column by column from (k, k), the first
    // one kept on a tie (Eigen's maxCoeff visitor: `value > res`).
    double biggest = std::fabs(a[k][k]);
    int br = k, bc = k;
    for (int j = k; j < 3; ++j)
      for (int i = (j == k ? k + 1 : k); i < 3; ++i)
        if (std::fabs(a[i][j]) > biggest) {
          biggest = std::fabs(a[i][j]);
          br = i;
          bc = j;
        }
    if (biggest == 0.0) return false;
    if (biggest > max_pivot) max_pivot = biggest;
    row_swap[k] = br;
    col_swap[k] = bc;
    if (br != k)
      for (int j = 0; j < 3; ++j) std::swap(a[k][j], a[br][j]);
    if (bc != k)
      for (int i = 0; i < 3; ++i) std::swap(a[i][k], a[i][bc]);
    for (int i = k + 1; i < 3; ++i) a[i][k] /= a[k][k];
    // The rank-one update, Eigen's outer product: a_ij -= u_kj * l_ik.
    for (int j = k + 1; j < 3; ++j)
      for (int i = k + 1; i < 3; ++i) a[i][j] -= a[k][j] * a[i][k];
  }
  // FullPivLU::rank() with the default threshold, 3 eps (diagonal size times epsilon).
  const double threshold = std::fabs(max_pivot) * (std::numeric_limits<double>::epsilon() * 3.0);
  for (int k = 0; k < 3; ++k)
    if (!(std::fabs(a[k][k]) > threshold)) return false;
  // c = P b: P's indices are the identity with the row transpositions applied last to first.
  int p[3] = {0, 1, 2};
  for (int k = 2; k >= 0; --k) std::swap(p[k], p[row_swap[k]]);
  double c[3];
  for (int i = 0; i < 3; ++i) c[p[i]] = b[i];
  // L c' = c, unit lower (Eigen's triangular_solve_vector: a zero entry skips its column).
  for (int i = 0; i < 3; ++i)
    if (c[i] != 0.0)
      for (int s = i + 1; s < 3; ++s) c[s] -= c[i] * a[s][i];
  // U c'' = c', upper, from the last row up (the same kernel).
  for (int i = 2; i >= 0; --i)
    if (c[i] != 0.0) {
      c[i] /= a[i][i];
      for (int s = 0; s < i; ++s) c[s] -= c[i] * a[s][i];
    }
  // x = Q c'': Q's indices are the identity with the column transpositions applied first to last.
  int q[3] = {0, 1, 2};
  for (int k = 0; k < 3; ++k) std::swap(q[k], q[col_swap[k]]);
  for (int i = 0; i < 3; ++i) x[q[i]] = c[i];
  return true;
}

}  // namespace

LinearTetField fit_linear_tet(const std::array<Vec3, 4>& x, const std::array<double, 4>& s) {
  double a[3][3], b[3];
  for (std::size_t k = 0; k < 3; ++k) {
    for (int j = 0; j < 3; ++j) a[k][j] = x[k + 1][j] - x[0][j];
    b[k] = s[k + 1] - s[0];
  }
  LinearTetField f;
  f.anchor = x[0];
  f.anchor_scalar = s[0];
  double g[3];
  if (full_pivot_solve3(a, b, g)) {
    f.gradient = Vec3(g[0], g[1], g[2]);
  } else {
    Eigen::Matrix3d edges;
    Eigen::Vector3d rhs;
    for (int k = 0; k < 3; ++k) {
      edges.row(k) = (x[static_cast<std::size_t>(k + 1)] - x[0]).transpose();
      rhs[k] = s[static_cast<std::size_t>(k + 1)] - s[0];
    }
    f.gradient = edges.fullPivLu().solve(rhs);
  }
  return f;
}

}  // namespace rayint
