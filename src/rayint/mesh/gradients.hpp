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
// rounding (tests/test_mesh_gradients.cpp, [mesh]: <= 1e-12 relative).
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
bool well_conditioned(double det, const Vec3& a, const Vec3& b, const Vec3& c);

// Barycentric coordinates of p in tet `cell` (sum to 1): Cramer's rule (three triple products),
// a full-pivoting LU for a (nearly) degenerate cell (well_conditioned above). The LU alone, run
// at every segment end, was a quarter of the mesh loss gradient's time (perf, reports/gradients/).
std::array<double, 4> barycentric(const TetMesh& mesh, std::size_t cell, const Vec3& p);

}  // namespace rayint
