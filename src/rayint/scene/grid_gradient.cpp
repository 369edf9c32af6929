#include "rayint/scene/grid_gradient.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "rayint/grid/kuhn_weights.hpp"
#include "rayint/integrators/exact_grad.hpp"

namespace rayint {

double GridPixelJacobian::channel_scale(int c) const {
  double s = 0.0;
  for (const Rgb& d : d_value) s = std::max(s, std::fabs(d[c]));
  return s;
}

namespace {

// gradient(ray, g): the ray's segment blocks into g (exact_ray_gradient or an ExactRayGradient).
template <class Gradient>
GridPixelJacobian pixel_jacobian(const VoxelGrid& grid, const Gradient& gradient, const ViewRay& view,
                                 const Rgb& background) {
  const Ray ray = ray_segments(grid, view, background);
  RayGradient g;  // the chain below reads the segment blocks only
  gradient(ray, g);
  GridPixelJacobian out;
  out.intensity = g.intensity;
  out.undefined = g.undefined;
  if (ray.segments.empty()) return out;
  // ray_segments' parameters: from max(0, t_enter), segments near -> far of length dt * speed.
  const RaySpan span = grid.clip(view);
  const double speed = view.direction.norm();
  std::map<std::size_t, Rgb> acc;
  const auto add = [&](double t, std::size_t j, bool far_end) {
    const KuhnWeights w = kuhn_weights(grid, view.origin + t * view.direction);
    for (std::size_t k = 0; k < 4; ++k) {
      Rgb& e = acc[w.index[k]];
      for (int c = 0; c < kChannels; ++c)
        e[c] += (far_end ? g.scalar_far[j][c] : g.scalar_exit[j][c]) * w.weight[k];
    }
  };
  double t = std::max(span.t_enter, 0.0);
  for (std::size_t m = ray.segments.size(); m-- > 0;) {  // near -> far
    add(t, m, false);
    t += ray.segments[m].length / speed;
    add(t, m, true);
  }
  for (const auto& [i, d] : acc) {
    out.index.push_back(i);
    out.d_value.push_back(d);
  }
  return out;
}

}  // namespace

GridPixelJacobian grid_pixel_jacobian(const VoxelGrid& grid, const TransferFunctions& tf, const ViewRay& view,
                                      const Rgb& background) {
  return pixel_jacobian(
      grid, [&tf](const Ray& ray, RayGradient& g) { exact_ray_gradient(tf, ray, g, GradientBlocks::segments); },
      view, background);
}

GridPixelJacobian grid_pixel_jacobian(const VoxelGrid& grid, const ExactRayGradient& gradient, const ViewRay& view,
                                      const Rgb& background) {
  return pixel_jacobian(
      grid, [&gradient](const Ray& ray, RayGradient& g) { gradient(ray, g, GradientBlocks::segments); }, view,
      background);
}

}  // namespace rayint
