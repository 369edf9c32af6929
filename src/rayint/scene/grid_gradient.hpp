#pragma once
// The exact gradient of a voxel-grid pixel with respect to every grid point value (issue 28,
// images): the sparse Jacobian a voxel renderer's adjoint produces, for the piecewise-linear Kuhn
// interpolant (grid/voxel_grid.hpp: 6 tetrahedra per cube; the path the exact method takes on
// grids). The trilinear interpolant is not differentiated here.
//
// Chain rule: exact_ray_gradient (integrators/exact_grad.hpp) on the ray's Kuhn segments
// (ray_segments) gives dI/ds at every segment end; each end is a point p on the ray, and
// s(p) = sum_k w_k(p) v_k over the four points of its Kuhn tetrahedron (grid/kuhn_weights.hpp), so
// dI/dv_k = sum over segment ends of dI/ds . w_k(p). A segment end on a Kuhn plane belongs to two
// tetrahedra whose weights agree on the shared face; the end points are recomputed from the
// segment lengths (rounding ~1e-16 of the box), which moves the weights by as much.
// Accuracy (tests/test_grid_gradient.cpp, [grad]): against fourth-order differences of the
// 50-digit reference render of the perturbed grid, rays through grid points and along grid lines
// included; see the test's WARN line for the measured worst.
// Jumps of the transfer functions: the crossing term is in exact_ray_gradient's dI/ds at the
// segment ends, so the chain carries it unchanged; where a segment end's scalar is exactly on a
// jump its dI/ds is NaN and `undefined` says why (model/ray_gradient.hpp).
#include <cstddef>
#include <string>
#include <vector>

#include "rayint/grid/voxel_grid.hpp"
#include "rayint/integrators/exact_grad.hpp"
#include "rayint/model/ray.hpp"

namespace rayint {

struct GridPixelJacobian {
  Rgb intensity{};
  std::vector<std::size_t> index;  // grid points with a derivative (ascending)
  std::vector<Rgb> d_value;        // [i][c] dI_c / d value of point index[i]
  std::string undefined;           // empty, or why some entries are NaN (a jump)
  double channel_scale(int c) const;
};

GridPixelJacobian grid_pixel_jacobian(const VoxelGrid& grid, const TransferFunctions& tf, const ViewRay& view,
                                      const Rgb& background);
// The same with the transfer functions prepared once (an image's pixels).
GridPixelJacobian grid_pixel_jacobian(const VoxelGrid& grid, const ExactRayGradient& gradient, const ViewRay& view,
                                      const Rgb& background);

}  // namespace rayint
