#pragma once
// The Kuhn (Freudenthal) interpolation weights of a voxel grid at a point: the four grid points of
// the Kuhn tetrahedron holding it and their barycentric weights, so that
// VoxelGrid::kuhn_value(p) = sum_k weight[k] * values[index[k]] (grid/voxel_grid.hpp: the axes
// ordered by decreasing local coordinate u, weights 1 - u1, u1 - u2, u2 - u3, u3; clamped to the
// box like kuhn_value). For the derivative of a voxel render with respect to its point values
// (scene/grid_gradient.hpp). tests/test_grid_gradient.cpp checks the sum against kuhn_value.
#include <array>
#include <cstddef>

#include "rayint/geometry/vec3.hpp"
#include "rayint/grid/voxel_grid.hpp"

namespace rayint {

struct KuhnWeights {
  std::array<std::size_t, 4> index{};  // x-fastest point indices (VoxelGrid::values order)
  std::array<double, 4> weight{};
};
KuhnWeights kuhn_weights(const VoxelGrid& grid, const Vec3& p);

}  // namespace rayint
