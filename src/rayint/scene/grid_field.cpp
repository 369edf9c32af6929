#include "rayint/scene/grid_field.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace rayint {

const char* interpolation_name(GridInterpolation i) {
  return i == GridInterpolation::trilinear ? "trilinear" : "kuhn";
}

GridField::GridField(VoxelGrid grid, GridInterpolation interpolation)
    : grid_(std::move(grid)), interpolation_(interpolation), bounds_(grid_.bounds()) {
  for (double v : grid_.values()) max_ = std::max(max_, v);
  const GridPlacement& p = grid_.placement();
  placed_ = !p.identity();
  if (placed_) {
    // D is orthonormal to 1e-12 (VoxelGrid::set_placement): its transpose is its inverse.
    to_grid_ = p.direction.transpose();
    const Bounds own = grid_.bounds();
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (int c = 0; c < 8; ++c) {
      const Vec3 corner((c & 1) ? own.upper.x() : own.lower.x(), (c & 2) ? own.upper.y() : own.lower.y(),
                        (c & 4) ? own.upper.z() : own.lower.z());
      const Vec3 w = p.pivot + p.direction * (corner - p.pivot);
      lo = lo.cwiseMin(w);
      hi = hi.cwiseMax(w);
    }
    // Widened by a few ulps of the extent: the rotated corners carry rounding.
    const Vec3 pad = 1e-14 * (hi - lo).cwiseAbs().cwiseMax(lo.cwiseAbs()).cwiseMax(hi.cwiseAbs());
    bounds_ = Bounds{lo - pad, hi + pad};
  }
}

Vec3 GridField::to_grid(const Vec3& p) const {
  if (!placed_) return p;
  const Vec3& pivot = grid_.placement().pivot;
  return pivot + to_grid_ * (p - pivot);
}

ViewRay GridField::to_grid(const ViewRay& ray) const {
  if (!placed_) return ray;
  return {to_grid(ray.origin), to_grid_ * ray.direction};
}

double GridField::density(const Vec3& p) const {
  const Vec3 q = to_grid(p);
  if (!grid_.bounds().contains(q)) return 0.0;
  return interpolation_ == GridInterpolation::trilinear ? grid_.sample(q) : grid_.kuhn_value(q);
}

Ray GridField::linear_segments(const ViewRay& ray, const Rgb& background) const {
  if (interpolation_ != GridInterpolation::kuhn)
    throw std::logic_error("GridField::linear_segments: the trilinear grid is not piecewise linear");
  return ray_segments(grid_, to_grid(ray), background);
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
