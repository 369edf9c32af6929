#pragma once
// A voxel-grid medium: density = the piecewise-linear (Kuhn, 6 tetrahedra per cube) interpolant
// of the grid's point values (grid/voxel_grid.hpp), 0 outside the grid's box. Piecewise linear
// along every ray, so the exact method applies (ray_segments), and every sampling method reads
// the same function (kuhn_value) as exact does.
#include <memory>

#include "rayint/grid/voxel_grid.hpp"
#include "rayint/media/medium.hpp"

namespace rayint {

class GridField final : public DensityField {
 public:
  explicit GridField(VoxelGrid grid);
  std::string kind() const override { return "voxel grid"; }
  Bounds bounds() const override { return grid_.bounds(); }
  double density(const Vec3& p) const override;
  double max_density() const override { return max_; }
  double gradient_step() const override { return 0.25 * grid_.spacing().minCoeff(); }
  // Linear on each Kuhn tetrahedron: a cell's smallest spacing holds at most a few kinks.
  double feature_length() const override { return grid_.spacing().minCoeff(); }
  bool piecewise_linear() const override { return true; }
  Ray linear_segments(const ViewRay& ray, const Rgb& background) const override;
  const VoxelGrid& grid() const { return grid_; }

 private:
  VoxelGrid grid_;
  double max_ = 0.0;
};

// The field sampled at the points of a dims[0] x dims[1] x dims[2] grid spanning its bounds
// (e.g. Max's cloud as a voxel volume). Needs finite bounds.
VoxelGrid sample_to_grid(const DensityField& field, std::array<int, 3> dims);

}  // namespace rayint
