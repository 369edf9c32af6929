#pragma once
// Gradients of the scalar field for shading (Williams & Max 1992, Sec. 3.2), three ways:
//  - cell:             the gradient of the cell's Eq. 9 function, constant over the cell (not
//                      continuous across faces: shading shows the mesh, which the paper notes is
//                      useful feedback on mesh quality);
//  - vertex_average:   at each vertex the plain average of the gradients at the centroids of all
//                      cells sharing it; inside a cell, the barycentric interpolation of its four
//                      vertex gradients (continuous, "smooth shading");
//  - inverse_distance: as vertex_average, but each centroid gradient is weighted by
//                      1 / |centroid - vertex| (the paper's "more accurate" average).
// On a field linear over the whole mesh all three return that field's gradient exactly up to
// rounding (tests/test_mesh_traversal.cpp, "Gradients (Sec. 3.2): ...", [mesh]: <= 1e-12).
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "rayint/geometry/vec3.hpp"
#include "rayint/mesh/tet_traversal.hpp"

namespace rayint {

enum class GradientMode { cell, vertex_average, inverse_distance };

std::string gradient_mode_name(GradientMode mode);
// "cell", "vertex_average", "inverse_distance"; throws std::invalid_argument otherwise.
GradientMode parse_gradient_mode(const std::string& name);

class GradientField {
 public:
  GradientField(const TetTraversal& mesh, GradientMode mode);
  GradientMode mode() const { return mode_; }
  // The gradient at point p of `cell` (p is expected inside or on the cell).
  Vec3 at(std::size_t cell, const Vec3& p) const;
  // Vertex gradients (empty in cell mode).
  const std::vector<Vec3>& vertex_gradients() const { return vertex_; }

 private:
  const TetTraversal* mesh_;
  GradientMode mode_;
  std::vector<Vec3> vertex_;
};

// Whether the 3 x 3 system with columns a, b, c (determinant det) is solved by Cramer's rule /
// the cofactor inverse, or by a full-pivoting LU: |det| / (|a| |b| |c|), the sine-like volume
// ratio, above kSolveVolumeRatio. Below it (an axis-aligned ray lying in a face plane of a
// structured mesh makes the face system exactly singular) the LU decides the numerical rank and
// returns a finite solution where a cofactor inverse gives ~1e17. Above it the condition number
// is below ~1e6 (so Cramer's relative error <~ 1e6 eps ~ 1e-10 at worst) and the two agree to
// rounding in practice: the mesh loss gradient of cases/mesh-ball-radial.json (384^2, tilted
// camera) with and without Cramer: 2.9e-16 (scalars) and 6.6e-16 (positions) of the largest entry.
inline constexpr double kSolveVolumeRatio = 1e-6;

// The decision is the one of |det| > kSolveVolumeRatio * a.norm() * b.norm() * c.norm() (in that
// order of rounding), taken without the three square roots (9% of the mesh loss gradient with
// positions, perf, reports/gradients/): det^2 against kSolveVolumeRatio^2 |a|^2 |b|^2 |c|^2 where
// the two sides differ by more than kSquaresMargin (relative), the norms' form otherwise.
// Margin: the norms' form has relative rounding error <= 10.5 u (three dot products 3 u each,
// halved by sqrt, + 1 u each; 3 products), the squares' form <= 16 u (3 dot products, 3 products,
// the squared constant, det^2, the margin product), u = 2^-53; a decision by squares outside
// 1e-12 (~ 9000 u) of the threshold is therefore the norms' decision exactly. Squares are used
// only while every |.|^2 is in [1e-60, 1e60], where no product leaves the normal range.
// tests/test_mesh_gradient.cpp ([grad][mesh]) compares both forms ulp by ulp through the threshold.
inline constexpr double kSquaresMargin = 1e-12;
bool well_conditioned_by_norms(double det, const Vec3& a, const Vec3& b, const Vec3& c);
inline bool well_conditioned(double det, const Vec3& a, const Vec3& b, const Vec3& c) {
  const double a2 = a.squaredNorm(), b2 = b.squaredNorm(), c2 = c.squaredNorm();
  const auto in_range = [](double v) { return v >= 1e-60 && v <= 1e60; };
  if (std::isfinite(det) && in_range(a2) && in_range(b2) && in_range(c2)) {
    const double p = kSolveVolumeRatio * kSolveVolumeRatio * a2 * b2 * c2, q = det * det;
    if (q > p * (1.0 + kSquaresMargin)) return true;
    if (q < p * (1.0 - kSquaresMargin)) return false;
  }
  return well_conditioned_by_norms(det, a, b, c);
}

// A cell's frame for barycentric coordinates: vertex 0, the edges e_k = x_k - x_0, e2 x e3, the
// determinant e1 . (e2 x e3) and whether Cramer's rule solves it (well_conditioned). Both ends of
// a crossing lie in one cell: the mesh gradient forms the frame once per crossing.
struct TetFrame {
  Vec3 x0, e1, e2, e3, c23;
  double det = 0.0;
  bool cramer = false;
};
TetFrame tet_frame(const TetMesh& mesh, std::size_t cell);

// Barycentric coordinates of p in tet `cell` (sum to 1): Cramer's rule (three triple products),
// a full-pivoting LU for a (nearly) degenerate cell (well_conditioned above). The LU alone, run
// at every segment end, was a quarter of the mesh loss gradient's time (perf, reports/gradients/).
std::array<double, 4> barycentric(const TetFrame& frame, const Vec3& p);
inline std::array<double, 4> barycentric(const TetMesh& mesh, std::size_t cell, const Vec3& p) {
  return barycentric(tet_frame(mesh, cell), p);
}

}  // namespace rayint
