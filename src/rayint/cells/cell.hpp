#pragma once
// Undistorted higher-order cells (Williams & Max 1992, appendix): a 10-node quadratic
// tetrahedron with straight edges, 8-node trilinear and 20-node serendipity bricks shaped as
// parallelepipeds. Their geometry is affine, world = origin + axes * xi, so a straight ray is
// straight in reference coordinates and the scalar along it is a polynomial of degree
// ray_degree(type) (cells/shape_functions.hpp). Distorted (isoparametric) cells would need the
// inverse mapping the appendix leaves open; they are not handled.
//
// What a ray sees:
//   cell_chord     - the t range inside the cell and the scalar there as a polynomial in the
//                    distance s from the far end: the products of linear factors of the shape
//                    functions multiplied out exactly (no fitting), for the polynomial reference
//                    and the ODE method;
//   decomposed_ray - the same chord through the cell split into linear tetrahedra with `level`
//                    sub-cells per edge, the scalar sampled from the cell at their vertices, as
//                    an ordinary Ray for `exact`. Bricks: level^3 sub-cubes of 6 Kuhn
//                    tetrahedra each (grid/voxel_grid.hpp). Tetrahedra: in the coordinates
//                    (a, b, c) = (xi + eta + zeta, eta + zeta, zeta) the reference tet is the
//                    Kuhn simplex 1 >= a >= b >= c >= 0 of the unit cube, so the Kuhn split of
//                    the level^3 sub-cubes restricts to it: level^3 tetrahedra (Freudenthal's
//                    subdivision), whose segments come from the same plane crossings.
// Accuracy (tests [cells]): cell_chord's polynomial matches the shape-function evaluation at
// random points to <= 1e-13 (values O(1)); the decomposition at level 1 of a hex8 equals the
// voxel grid of its 8 nodes; chord lengths match the voxel and analytic chords.
#include <array>
#include <vector>

#include <Eigen/Core>

#include "rayint/cells/shape_functions.hpp"
#include "rayint/geometry/vec3.hpp"
#include "rayint/grid/voxel_grid.hpp"
#include "rayint/model/poly_ray.hpp"
#include "rayint/model/ray.hpp"

namespace rayint {

struct HigherOrderCell {
  CellType type = CellType::tet10;
  Vec3 origin = Vec3::Zero();                          // world position of xi = 0
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  // world = origin + axes * xi
  std::vector<double> values;                          // node scalars, VTK order
};

// A tet10 from its 4 corners (mid-edge nodes at the edge midpoints) and 10 node values; a brick
// (hex8 or hex20) from its centre, the 3 half-edge vectors as columns, and 8 or 20 values.
// Throw std::invalid_argument for a wrong value count, non-finite input or a degenerate cell
// (|det axes| <= 1e-12 times the product of the column lengths).
HigherOrderCell make_tet10(const std::array<Vec3, 4>& corners, std::vector<double> values);
HigherOrderCell make_brick(CellType type, const Vec3& centre, const Eigen::Matrix3d& half_axes,
                           std::vector<double> values);

Vec3 to_reference(const HigherOrderCell& cell, const Vec3& world);
Vec3 to_world(const HigherOrderCell& cell, const Vec3& xi);
// The scalar at a world point (shape functions at its reference coordinates; outside the cell
// the polynomial is extrapolated).
double cell_value(const HigherOrderCell& cell, const Vec3& world);

struct CellChord {
  RaySpan span;     // t range of the ray inside the closed cell (t >= 0)
  PolySegment segment;  // length = world length; scalar(s), s from the far end (t_exit)
};
CellChord cell_chord(const HigherOrderCell& cell, const ViewRay& ray);

// The chord as a one-segment PolyRay (no segments when the ray misses).
PolyRay cell_poly_ray(const HigherOrderCell& cell, const ViewRay& ray, const Rgb& background);

// The chord through the cell decomposed into linear tetrahedra, level >= 1 sub-cells per edge.
Ray decomposed_ray(const HigherOrderCell& cell, const ViewRay& ray, int level,
                   const Rgb& background);

}  // namespace rayint
