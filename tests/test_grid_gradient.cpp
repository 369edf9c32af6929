// Voxel-grid gradients (issue 28, images): scene/grid_gradient.* against fourth-order central
// differences of the 50-digit reference render of the perturbed grid (Kuhn interpolant), rays
// through grid points and along grid lines included; a wrong candidate (trilinear weights in
// place of the Kuhn ones) is caught by the same comparison.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "rayint/grid/kuhn_weights.hpp"
#include "rayint/integrators/exact_grad.hpp"
#include "rayint/reference/reference.hpp"
#include "rayint/scene/grid_gradient.hpp"
#include "transfer_builders.hpp"

using namespace rayint;

namespace {

// Same reasoning as tests/test_mesh_gradient.cpp: segment ends and their scalars are rounded to
// ~1e-16, divided by the step 1e-4.
constexpr double kGridTol = 1e-10;

VoxelGrid small_grid(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.6, 1.0);
  std::vector<double> v(4 * 3 * 3);
  for (double& x : v) x = u(rng);
  return VoxelGrid({4, 3, 3}, Vec3(-1.0, -0.5, -0.7), Vec3(0.6, 0.55, 0.7), v);
}

Rgb reference_pixel(const VoxelGrid& grid, const TransferFunctions& tf, const ViewRay& view, const Rgb& bg) {
  const ReferenceRay r = reference_ray(tf, ray_segments(grid, view, bg));
  return {r.intensity[0].hi + r.intensity[0].lo, r.intensity[1].hi + r.intensity[1].lo,
          r.intensity[2].hi + r.intensity[2].lo};
}

// Max over points and channels of |got - difference| / largest |got| entry of the channel.
double compare(const VoxelGrid& grid, const TransferFunctions& tf, const ViewRay& view, const Rgb& bg,
               const GridPixelJacobian& got) {
  double worst = 0.0;
  for (std::size_t i = 0; i < grid.point_count(); ++i) {
    const auto at = [&](double dv) {
      std::vector<double> v = grid.values();
      v[i] += dv;
      return reference_pixel(VoxelGrid(grid.dims(), grid.origin(), grid.spacing(), v), tf, view, bg);
    };
    const double h = 1e-4;
    const Rgb m2 = at(-2 * h), m1 = at(-h), p1 = at(h), p2 = at(2 * h);
    const auto it = std::lower_bound(got.index.begin(), got.index.end(), i);
    const bool has = it != got.index.end() && *it == i;
    for (int c = 0; c < kChannels; ++c) {
      const double want = (m2[c] - 8 * m1[c] + 8 * p1[c] - p2[c]) / (12 * h);
      const double d = has ? got.d_value[static_cast<std::size_t>(it - got.index.begin())][c] : 0.0;
      const double scale = got.channel_scale(c);
      worst = std::max(worst, std::fabs(d - want) / (scale > 0 ? scale : 1.0));
    }
  }
  return worst;
}

std::vector<ViewRay> rays(const VoxelGrid& grid) {
  const auto toward = [](const Vec3& from, const Vec3& to) { return ViewRay{from, (to - from).normalized()}; };
  const Vec3 lo = grid.lower(), hi = grid.upper();
  const Vec3 sp = grid.spacing();
  return {toward({-2.3, -1.7, -3.1}, {0.31, 0.22, 0.17}), toward({2.9, 0.4, -1.3}, {-0.27, 0.13, 0.41}),
          // along a grid line (in two grid planes) and through grid points
          toward(Vec3(lo.x() - 1.0, lo.y() + sp.y(), lo.z() + sp.z()), Vec3(hi.x(), lo.y() + sp.y(), lo.z() + sp.z())),
          // through grid points along a cube diagonal (a Kuhn edge)
          toward(lo - sp, lo + 2.0 * sp),
          // inside the grid: starts in the volume
          ViewRay{Vec3(0.1, 0.05, 0.0), Vec3(0.3, 0.5, 0.81).normalized()}};
}

}  // namespace

TEST_CASE("grid gradient: Kuhn weights reproduce kuhn_value", "[grad][grid]") {
  const VoxelGrid grid = small_grid(5);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst = 0.0;
  for (int n = 0; n < 2000; ++n) {
    const Vec3 p = grid.lower() + (grid.upper() - grid.lower()).cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
    const KuhnWeights w = kuhn_weights(grid, p);
    double f = 0.0, sum = 0.0;
    for (std::size_t k = 0; k < 4; ++k) {
      f += w.weight[k] * grid.values()[w.index[k]];
      sum += w.weight[k];
      CHECK(w.weight[k] >= 0.0);
    }
    CHECK(std::fabs(sum - 1.0) <= 1e-15);
    worst = std::max(worst, std::fabs(f - grid.kuhn_value(p)));
  }
  CHECK(worst <= 1e-15);
}

TEST_CASE("grid gradient: point values against differences of the 50-digit render", "[grad][grid]") {
  const VoxelGrid grid = small_grid(28);
  const TransferFunctions tf = test::kinked_tf();
  const Rgb bg{0.2, 0.1, 0.4};
  double worst = 0.0;
  for (const ViewRay& view : rays(grid)) {
    const GridPixelJacobian j = grid_pixel_jacobian(grid, tf, view, bg);
    REQUIRE(!j.index.empty());
    worst = std::max(worst, compare(grid, tf, view, bg, j));
  }
  WARN("voxel-grid Jacobian (Kuhn) vs 4th-order differences of the 50-digit render: worst " << worst
       << " (5 rays, 36 points, 3 channels)");
  CHECK(worst <= kGridTol);
}

TEST_CASE("grid gradient: trilinear weights in place of Kuhn's are caught", "[grad][grid]") {
  // A plausible mistake: a voxel adjoint that spreads dI/ds with the trilinear weights of the cube
  // while the forward render interpolates on Kuhn tetrahedra.
  const VoxelGrid grid = small_grid(28);
  const TransferFunctions tf = test::kinked_tf();
  const Rgb bg{0.2, 0.1, 0.4};
  const ViewRay view = rays(grid)[0];
  const Ray ray = ray_segments(grid, view, bg);
  const RayGradient g = exact_ray_gradient(tf, ray);
  GridPixelJacobian wrong = grid_pixel_jacobian(grid, tf, view, bg);
  std::vector<Rgb> dense(grid.point_count(), Rgb{});
  double t = std::max(grid.clip(view).t_enter, 0.0);
  const auto spread = [&](double tt, const Rgb& gs) {
    const Vec3 x = (view.origin + tt * view.direction - grid.origin()).cwiseQuotient(grid.spacing());
    std::array<int, 3> c{};
    std::array<double, 3> u{};
    for (int i = 0; i < 3; ++i) {
      const double xi = std::clamp(x[i], 0.0, static_cast<double>(grid.dims()[i] - 1));
      c[i] = std::min(static_cast<int>(std::floor(xi)), grid.dims()[i] - 2);
      u[i] = xi - c[i];
    }
    for (int k = 0; k < 8; ++k) {
      const int a = k & 1, b = (k >> 1) & 1, d = (k >> 2) & 1;
      const double w = (a ? u[0] : 1 - u[0]) * (b ? u[1] : 1 - u[1]) * (d ? u[2] : 1 - u[2]);
      const auto idx = static_cast<std::size_t>(c[0] + a + grid.dims()[0] * (c[1] + b + grid.dims()[1] * (c[2] + d)));
      for (int ch = 0; ch < kChannels; ++ch) dense[idx][ch] += w * gs[ch];
    }
  };
  for (std::size_t m = ray.segments.size(); m-- > 0;) {
    spread(t, g.scalar_exit[m]);
    t += ray.segments[m].length / view.direction.norm();
    spread(t, g.scalar_far[m]);
  }
  wrong.index.clear();
  wrong.d_value.clear();
  for (std::size_t i = 0; i < dense.size(); ++i) {
    wrong.index.push_back(i);
    wrong.d_value.push_back(dense[i]);
  }
  const double right_err = compare(grid, tf, view, bg, grid_pixel_jacobian(grid, tf, view, bg));
  const double wrong_err = compare(grid, tf, view, bg, wrong);
  WARN("grid: right " << right_err << ", trilinear weights " << wrong_err);
  CHECK(right_err <= kGridTol);
  CHECK(wrong_err > 1e-2);
}

TEST_CASE("grid gradient across transfer-function jumps: point values against the 50-digit render",
          "[grad][grid][grad_jump]") {
  const VoxelGrid grid = small_grid(28);
  // Jumps of every kind on the grid's value range [-0.6, 1]: density r between linear pieces at
  // 0.1, density b a pure step at 0.35, colour g at 0.45.
  TransferFunctions tf = test::kinked_tf();
  tf.density[0] = {{-0.4, 0.1, 0.1, 0.8}, {0.5, 0.4, 2.2, 1.5}};
  tf.density[2] = {{0.35, 0.35}, {0.3, 1.6}};
  tf.color[1] = {{-0.4, 0.45, 0.45, 0.8}, {0.3, 0.2, 0.9, 0.6}};
  const std::vector<double> jumps = {0.1, 0.35, 0.45};
  const Rgb bg{0.2, 0.1, 0.4};
  double worst = 0.0;
  int crossed = 0, used = 0;
  for (const ViewRay& view : rays(grid)) {
    const Ray ray = ray_segments(grid, view, bg);
    // The differences (step 1e-4, up to 2e-4) must not move a segment end across a jump: skip a
    // ray with an end within 5e-3 of one (counted; most rays qualify).
    double nearest = HUGE_VAL;
    int crossings = 0;
    for (const Segment& seg : ray.segments)
      for (const double x : jumps) {
        crossings += (seg.scalar_far - x) * (seg.scalar_exit - x) < 0.0;
        nearest = std::min({nearest, std::fabs(seg.scalar_far - x), std::fabs(seg.scalar_exit - x)});
      }
    if (!(nearest > 5e-3)) continue;
    ++used;
    crossed += crossings;
    const GridPixelJacobian j = grid_pixel_jacobian(grid, tf, view, bg);
    CHECK(j.undefined.empty());
    REQUIRE(!j.index.empty());
    worst = std::max(worst, compare(grid, tf, view, bg, j));
  }
  WARN("voxel-grid Jacobian (Kuhn) across jumps vs 4th-order differences of the 50-digit render: worst "
       << worst << " (" << used << " rays of 5, " << crossed << " jump crossings)");
  CHECK(used >= 3);
  CHECK(crossed >= 4);
  CHECK(worst <= kGridTol);
}
