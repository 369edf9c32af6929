#include "rayint/scene/grid_field.hpp"

#include <algorithm>
#include <stdexcept>

namespace rayint {

const char* interpolation_name(GridInterpolation i) {
  return i == GridInterpolation::trilinear ? "trilinear" : "kuhn";
}

GridField::GridField(VoxelGrid grid, GridInterpolation interpolation)
    : grid_(std::move(grid)), interpolation_(interpolation) {
  for (double v : grid_.values()) max_ = std::max(max_, v);
}

double GridField::density(const Vec3& p) const {
  if (!bounds().contains(p)) return 0.0;
  return interpolation_ == GridInterpolation::trilinear ? grid_.sample(p) : grid_.kuhn_value(p);
}

Ray GridField::linear_segments(const ViewRay& ray, const Rgb& background) const {
  if (interpolation_ != GridInterpolation::kuhn)
    throw std::logic_error("GridField::linear_segments: the trilinear grid is not piecewise linear");
  return ray_segments(grid_, ray, background);
}

bool exact_along_rays(const DensityField& field) {
  return field.piecewise_linear() || dynamic_cast<const GridField*>(&field) != nullptr;
}

VoxelGrid sample_to_grid(const DensityField& field, std::array<int, 3> dims) {
  const Bounds b = field.bounds();
  if (!b.finite()) throw std::invalid_argument("cannot sample an unbounded medium to a grid");
  const Vec3 spacing((b.upper.x() - b.lower.x()) / (dims[0] - 1), (b.upper.y() - b.lower.y()) / (dims[1] - 1),
                     (b.upper.z() - b.lower.z()) / (dims[2] - 1));
  std::vector<double> values(static_cast<std::size_t>(dims[0]) * dims[1] * dims[2]);
  std::size_t i = 0;
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int x = 0; x < dims[0]; ++x)
        values[i++] = field.density(b.lower + Vec3(x * spacing.x(), j * spacing.y(), k * spacing.z()));
  return VoxelGrid(dims, b.lower, spacing, std::move(values));
}

}  // namespace rayint
