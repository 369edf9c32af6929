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

// Barycentric coordinates of p in tet `cell` (sum to 1).
std::array<double, 4> barycentric(const TetMesh& mesh, std::size_t cell, const Vec3& p);

}  // namespace rayint
