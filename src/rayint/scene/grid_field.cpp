#include "rayint/scene/grid_field.hpp"

#include <algorithm>
#include <stdexcept>

namespace rayint {

GridField::GridField(VoxelGrid grid) : grid_(std::move(grid)) {
  for (double v : grid_.values()) max_ = std::max(max_, v);
}

double GridField::density(const Vec3& p) const {
  return bounds().contains(p) ? grid_.kuhn_value(p) : 0.0;
}

Ray GridField::linear_segments(const ViewRay& ray, const Rgb& background) const {
  return ray_segments(grid_, ray, background);
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
