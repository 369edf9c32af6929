#pragma once
// A voxel-grid medium: density = an interpolant of the grid's point values (grid/voxel_grid.hpp),
// 0 outside the grid's box. Two interpolants, and every method of a scene reads the same one:
//  * trilinear (the default; what VTK's image mappers and every image renderer mean): sample();
//    a cubic per cube along a ray, integrated exactly by grid/trilinear_integral.hpp (method
//    exact) against reference_poly_ray (the 50-digit reference);
//  * kuhn (scene "interpolation": "kuhn"): piecewise linear on 6 tetrahedra per cube
//    (kuhn_value), so linear along rays between plane crossings: ray_segments, the closed form
//    of Sec. 3.3 and reference_ray. A different field: docs/images.md measures how far apart.
// A grid with a placement (VoxelGrid::placement(): a VTK image's rotated Direction) is read in
// its own frame: points and rays are taken there by the inverse placement, q = pivot + D^T
// (p - pivot), D orthonormal, so a ray keeps its parameter t and its lengths, and every method
// integrates the rotated image as the axis-aligned one along the rotated ray.
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
  // The world box around the placed grid (its own box when not rotated).
  Bounds bounds() const override { return bounds_; }
  double density(const Vec3& p) const override;
  double max_density() const override { return max_; }
  double gradient_step() const override { return 0.25 * grid_.spacing().minCoeff(); }
  // A cubic per cube (kinks only at cube faces), or linear per Kuhn tetrahedron: a cell's
  // smallest spacing holds at most a few kinks.
  double feature_length() const override { return grid_.spacing().minCoeff(); }
  bool piecewise_linear() const override { return interpolation_ == GridInterpolation::kuhn; }
  Ray linear_segments(const ViewRay& ray, const Rgb& background) const override;
  // The grid, in its own frame: read it only through to_grid()'s points and rays.
  const VoxelGrid& grid() const { return grid_; }
  GridInterpolation interpolation() const { return interpolation_; }
  // A world point / ray in the grid's own frame (unchanged when the grid is not rotated).
  Vec3 to_grid(const Vec3& p) const;
  ViewRay to_grid(const ViewRay& ray) const;

 private:
  VoxelGrid grid_;
  GridInterpolation interpolation_;
  double max_ = 0.0;
  bool placed_ = false;                   // a placement other than the identity
  Eigen::Matrix3d to_grid_ = Eigen::Matrix3d::Identity();  // D^T
  Bounds bounds_;
};

// True when a scene's exact method integrates `field` along rays: piecewise linear fields
// (homogeneous, Kuhn grids) through the closed form, and trilinear grids through
// grid/trilinear_integral.hpp.
bool exact_along_rays(const DensityField& field);

// The field sampled at the points of a dims[0] x dims[1] x dims[2] grid spanning its bounds
// (e.g. Max's cloud as a voxel volume). Needs finite bounds.
VoxelGrid sample_to_grid(const DensityField& field, std::array<int, 3> dims);

}  // namespace rayint
