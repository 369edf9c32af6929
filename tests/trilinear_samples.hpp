#pragma once
// The grids, transfer functions and rays of the trilinear tests (tests/test_trilinear.cpp, the
// sample described there; tests/test_trilinear_grad.cpp uses the same hard configurations).
#include <cmath>
#include <random>
#include <vector>

#include "rayint/grid/voxel_grid.hpp"
#include "rayint/model/ray.hpp"

namespace rayint::trilinear_samples {

constexpr int kRandomRays = 40;

inline VoxelGrid random_grid(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-0.1, 1.1);
  std::vector<double> v(6 * 5 * 7);
  for (double& x : v) x = u(rng);
  return VoxelGrid({6, 5, 7}, Vec3(-1.0, 0.5, 2.0), Vec3(0.7, 1.1, 0.9), v);
}

inline VoxelGrid smooth_grid() {
  const std::array<int, 3> d{9, 8, 10};
  const Vec3 o(0.2, -0.4, 0.1), h(0.5, 0.6, 0.45);
  std::vector<double> v;
  for (int k = 0; k < d[2]; ++k)
    for (int j = 0; j < d[1]; ++j)
      for (int i = 0; i < d[0]; ++i) {
        const Vec3 p = o + Vec3(i * h[0], j * h[1], k * h[2]);
        v.push_back(0.5 + 0.45 * std::sin(p[0]) * std::cos(1.3 * p[1]) * std::sin(0.7 * p[2] + 0.3));
      }
  return VoxelGrid(d, o, h, v);
}

inline TransferFunctions test_tf(double scale) {
  TransferFunctions tf;
  tf.density[0] = {{0.0, 0.3, 0.6, 1.0}, {0.0, 2.0 * scale, 0.5 * scale, 3.0 * scale}};
  tf.density[1] = {{0.1, 0.45, 0.9}, {0.2 * scale, 1.5 * scale, 0.1 * scale}};
  tf.density[2] = {{0.2, 0.5, 0.7, 0.95}, {1.0 * scale, 0.0, 2.5 * scale, 0.4 * scale}};
  tf.color[0] = {{0.0, 0.4, 0.8, 1.0}, {0.2, 1.0, 0.1, 0.7}};
  tf.color[1] = {{0.15, 0.35, 0.55, 0.75}, {0.9, 0.3, 0.8, 0.05}};
  tf.color[2] = {{0.05, 0.6, 0.85}, {0.0, 0.6, 1.0}};
  return tf;
}

inline std::vector<ViewRay> sample_rays(const VoxelGrid& g, std::mt19937& rng) {
  std::vector<ViewRay> rays;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Vec3 lo = g.lower(), hi = g.upper(), ext = hi - lo, h = g.spacing();
  auto inside = [&] { return Vec3(lo[0] + u(rng) * ext[0], lo[1] + u(rng) * ext[1], lo[2] + u(rng) * ext[2]); };
  for (int n = 0; n < kRandomRays; ++n) {
    const Vec3 target = inside();
    Vec3 dir(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
    dir.normalize();
    rays.push_back({target - 3.0 * ext.norm() * dir, dir});
  }
  const Vec3 far = lo - ext;  // behind the lower corner
  // In a grid plane x = lo + 2 h: oblique inside that plane.
  rays.push_back({Vec3(lo[0] + 2 * h[0], lo[1] - 1.0, lo[2] - 0.7), Vec3(0.0, 0.8, 0.6)});
  rays.push_back({Vec3(lo[0] + 1 * h[0], hi[1] + 1.0, lo[2] + 0.3), Vec3(0.0, -0.6, 0.3)});
  // Along grid edges (x and y on grid lines), and the box's own edges.
  rays.push_back({Vec3(lo[0] + 3 * h[0], lo[1] + 2 * h[1], lo[2] - 1.0), Vec3(0.0, 0.0, 1.0)});
  rays.push_back({Vec3(lo[0], lo[1], hi[2] + 1.0), Vec3(0.0, 0.0, -1.0)});
  rays.push_back({Vec3(hi[0] + 2.0, lo[1] + h[1], lo[2] + 4 * h[2]), Vec3(-1.0, 0.0, 0.0)});
  // Through vertices: the index-lattice diagonal (every cube corner to corner) and offsets.
  rays.push_back({lo - h, h});
  rays.push_back({lo + Vec3(h[0], 0.0, 0.0) - h, h});
  rays.push_back({far, (lo + Vec3(2 * h[0], 3 * h[1], 4 * h[2])) - far});
  rays.push_back({Vec3(hi[0] + 1.0, lo[1] - 1.0, lo[2] + 2 * h[2]), Vec3(-h[0], h[1], 0.0)});
  // Axis-parallel through cube interiors, and a ray from inside the box.
  rays.push_back({Vec3(lo[0] + 0.37 * h[0], lo[1] + 1.61 * h[1], lo[2] - 2.0), Vec3(0.0, 0.0, 1.0)});
  rays.push_back({Vec3(lo[0] - 1.0, lo[1] + 0.5 * h[1], lo[2] + 0.25 * h[2]), Vec3(2.0, 0.0, 0.0)});
  rays.push_back({0.5 * (lo + hi), Vec3(0.3, -0.2, 0.9)});
  return rays;
}

}  // namespace rayint::trilinear_samples
