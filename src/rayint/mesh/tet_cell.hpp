#pragma once
// One linear tetrahedron's scalar field: Williams & Max (1992) Eq. 9, S_c(x,y,z) = c1 + c2 x +
// c3 y + c4 z, fitted to the scalars at the four vertices, and its restriction to a ray, Eq. 13,
// S_c(t) = v + w t.
//
// Method: Eq. 9's four equations are solved in the equivalent form centred on vertex 0,
// S_c(x) = s0 + g . (x - x0) with the gradient g = (c2, c3, c4) from the 3x3 system
// A g = [s1-s0; s2-s0; s3-s0], A = [x1-x0; x2-x0; x3-x0], and c1 = s0 - g . x0. Centring keeps the
// solve's conditioning that of the cell's shape, not of its distance from the origin (the 4x4
// form with a column of ones loses digits in proportion to |x0| / cell size). The 3x3 solve is
// the closed form A^-1 = [e2 x e3, e3 x e1, e1 x e2] / det (columns; e_k = x_k - x0,
// det = e1 . (e2 x e3) = 6 V) for every cell of the shape the mesh checks accept
// (|6 V| > kDegenerateTetRatio l^3, tet_mesh.hpp), Eigen's LU with full pivoting otherwise (the
// method before issue 33 for every cell: ~90 ns a cell against ~7 ns, ~8% of the 105k load).
// Accuracy (tests/test_mesh_traversal.cpp, [mesh], against the gradient of the same doubles in
// cpp_bin_float_50): relative error |g - g*| / |g*| <= 0.67 eps kappa_F(A) on every sample, LU
// <= 0.59 eps kappa_F beside it; max 2.7e-14 on the 105k-tet ball (rayint generate-mesh ball
// --n 13; LU 6.5e-14), 1.3e-15 on the 63 fixture meshes (LU 1.2e-15), 4.4e-5 on 99,868 slivers,
// needles and caps down to the checks' limit, kappa_F up to 1.1e12 (LU 4.2e-5). A linear field is
// reproduced at the vertices to <= 1e-14 relative to max |s| on the unit right tet and a sliver
// with edge ratio 1e3.
#include <array>

#include "rayint/geometry/vec3.hpp"

namespace rayint {

struct LinearTetField {
  Vec3 anchor = Vec3::Zero();    // x0, vertex 0 of the cell
  double anchor_scalar = 0.0;    // s0
  Vec3 gradient = Vec3::Zero();  // (c2, c3, c4): constant over the cell (Sec. 3.2)

  double c1() const { return anchor_scalar - gradient.dot(anchor); }
  double at(const Vec3& p) const { return anchor_scalar + gradient.dot(p - anchor); }
};

// Eq. 9 for the cell with vertices x[0..3] and scalars s[0..3]. The cell must not be degenerate
// (validate_tet_mesh rejects those).
LinearTetField fit_linear_tet(const std::array<Vec3, 4>& x, const std::array<double, 4>& s);

// Eq. 13 for a ray entering the cell at `entry` along the unit vector `direction`:
// v = S_c(entry), w = gradient . direction, so S_c(entry + t direction) = v + w t.
struct Eq13 {
  double v = 0.0;
  double w = 0.0;
};
inline Eq13 ray_parameters(const LinearTetField& f, const Vec3& entry, const Vec3& direction) {
  return Eq13{f.at(entry), f.gradient.dot(direction)};
}

}  // namespace rayint
