#pragma once
// A voxel-grid medium: density = an interpolant of the grid's point values (grid/voxel_grid.hpp),
// 0 outside the grid's box. Two interpolants, and every method of a scene reads the same one:
//  * trilinear (the default; what VTK's image mappers and every image renderer mean): sample();
//    a cubic per cube along a ray, integrated exactly by grid/trilinear_integral.hpp (method
//    exact) against reference_poly_ray (the 50-digit reference);
//  * kuhn (scene "interpolation": "kuhn"): piecewise linear on 6 tetrahedra per cube
//    (kuhn_value), so linear along rays between plane crossings: ray_segments, the closed form
//    of Sec. 3.3 and reference_ray. A different field: docs/images.md measures how far apart.
#include <memory>

#include "rayint/grid/voxel_grid.hpp"
#include "rayint/media/medium.hpp"

namespace rayint {

enum class GridInterpolation { trilinear, kuhn };
const char* interpolation_name(GridInterpolation i);

class GridField final : public DensityField {
 public:
  explicit GridField(VoxelGrid grid, GridInterpolation interpolation = GridInterpolation::trilinear);
  std::string kind() const override {
    return interpolation_ == GridInterpolation::trilinear ? "voxel grid (trilinear)" : "voxel grid (kuhn)";
  }
  Bounds bounds() const override { return grid_.bounds(); }
  double density(const Vec3& p) const override;
  double max_density() const override { return max_; }
  double gradient_step() const override { return 0.25 * grid_.spacing().minCoeff(); }
  // A cubic per cube (kinks only at cube faces), or linear per Kuhn tetrahedron: a cell's
  // smallest spacing holds at most a few kinks.
  double feature_length() const override { return grid_.spacing().minCoeff(); }
  bool piecewise_linear() const override { return interpolation_ == GridInterpolation::kuhn; }
  Ray linear_segments(const ViewRay& ray, const Rgb& background) const override;
  const VoxelGrid& grid() const { return grid_; }
  GridInterpolation interpolation() const { return interpolation_; }

 private:
  VoxelGrid grid_;
  GridInterpolation interpolation_;
  double max_ = 0.0;
};

// True when a scene's exact method integrates `field` along rays: piecewise linear fields
// (homogeneous, Kuhn grids) through the closed form, and trilinear grids through
// grid/trilinear_integral.hpp.
bool exact_along_rays(const DensityField& field);

// The field sampled at the points of a dims[0] x dims[1] x dims[2] grid spanning its bounds
// (e.g. Max's cloud as a voxel volume). Needs finite bounds.
VoxelGrid sample_to_grid(const DensityField& field, std::array<int, 3> dims);

}  // namespace rayint
