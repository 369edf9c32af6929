// The gradient of the trilinear ray integral (TrilinearIntegrator::gradient, grid/
// trilinear_integral.cpp, issue 28) against an independent reference: fourth-order central
// differences of the 50-digit polynomial reference (reference/poly_reference.hpp) on the
// perturbed cubics, with respect to grid point values and transfer-function nodes, on the rays
// of the trilinear tests (tests/trilinear_samples.hpp: rays in grid planes, along grid edges,
// through vertices, axis-parallel, from inside the box, random; scales 1 and 20).
//
// Difference step h = 1e-5: the integral is smooth in each input while every breakpoint
// crossing stays transversal (the cut point moves smoothly), so the truncation is O(h^4); the
// perturbed cubic coefficients are rounded to double (~1e-16), which the quotient turns into
// ~1e-11 of the intensity. h = 1e-4 was tried first and is too coarse on this sample: a cube of
// random-grid ray 12 has a near-tangency with a breakpoint within 4e-4 in the scalar, and the
// differences there moved by 3e-4 between h = 3e-4 and 1e-4 (the stencil straddles the
// tangency) and settled to 2e-12 of the gradient at h = 1e-5.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <sstream>
#include <vector>

#include "rayint/grid/trilinear_integral.hpp"
#include "rayint/grid/voxel_grid.hpp"
#include "rayint/reference/poly_reference.hpp"
#include "rayint/scene/grid_gradient.hpp"
#include "trilinear_samples.hpp"

using namespace rayint;
using namespace rayint::trilinear_samples;

namespace {

constexpr unsigned kSeed = 2026;
constexpr double kStep = 1e-5;

Rgb reference_intensity(const TransferFunctions& tf, const PolyRay& ray) {
  const ReferenceRay r = reference_poly_ray(tf, ray);
  Rgb out{};
  for (int c = 0; c < kChannels; ++c) out[c] = r.intensity[c].hi + r.intensity[c].lo;
  return out;
}

// Fourth-order central difference of f(x) (an Rgb) at step h.
template <class F>
Rgb difference(F&& f, double h) {
  const Rgb p2 = f(2 * h), p1 = f(h), m1 = f(-h), m2 = f(-2 * h);
  Rgb d{};
  for (int c = 0; c < kChannels; ++c) d[c] = (-p2[c] + 8 * p1[c] - 8 * m1[c] + m2[c]) / (12 * h);
  return d;
}

// The same one-sided (fourth order, forward), for a value that must stay >= 0.
template <class F>
Rgb forward_difference(F&& f, double h) {
  const Rgb f0 = f(0.0), f1 = f(h), f2 = f(2 * h), f3 = f(3 * h), f4 = f(4 * h);
  Rgb d{};
  for (int c = 0; c < kChannels; ++c)
    d[c] = (-25 * f0[c] + 48 * f1[c] - 36 * f2[c] + 16 * f3[c] - 3 * f4[c]) / (12 * h);
  return d;
}

// d/d value of grid point `index`: the ray's cubics with the point's corner cubics added h times
// (the walk is the same for every value; only the coefficients move).
Rgb voxel_difference(const TransferFunctions& tf, const VoxelGrid& g, const ViewRay& ray, const Rgb& background,
                     std::size_t index) {
  std::vector<TrilinearCubic> cubics;
  std::vector<double> scratch;
  trilinear_cubics(g, ray, cubics, scratch);
  std::vector<std::array<double, 4>> direction(cubics.size(), std::array<double, 4>{});
  for (std::size_t m = 0; m < cubics.size(); ++m) {
    const auto corners = trilinear_corner_cubics(g, ray, cubics[m]);
    for (int c = 0; c < 8; ++c)
      if (trilinear_corner_index(g, cubics[m].cube, c) == index)
        for (int k = 0; k < 4; ++k) direction[m][k] += corners[static_cast<std::size_t>(c)][k];
  }
  return difference([&](double h) {
    PolyRay pr;
    pr.background = background;
    for (std::size_t m = 0; m < cubics.size(); ++m) {
      PolySegment seg;
      seg.length = cubics[m].length;
      for (int k = 0; k < 4; ++k) seg.coeffs.push_back(cubics[m].coeffs[k] + h * direction[m][k]);
      pr.segments.push_back(seg);
    }
    return reference_intensity(tf, pr);
  }, kStep);
}

struct Worst {
  double err = 0.0;
  std::string where;
  long compared = 0;
  void add(double got, double want, double scale, const std::string& label) {
    const double e = std::fabs(got - want) / scale;
    ++compared;
    if (!(e <= err)) {
      err = e;
      where = label;
    }
  }
};

// The voxel entries of `grad` against voxel_difference: the `top` largest of channel 0 and every
// `every`-th of the rest (each costs four 50-digit renders). `where` labels the ray.
void compare_voxels(const TransferFunctions& tf, const VoxelGrid& g, const ViewRay& ray, const Rgb& background,
                    const TrilinearGradient& grad, std::size_t top, std::size_t every, const std::string& where,
                    Worst& voxels) {
  std::vector<std::size_t> order(grad.index.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::fabs(grad.d_value[a][0]) > std::fabs(grad.d_value[b][0]);
  });
  for (std::size_t n = 0; n < order.size(); ++n) {
    if (n >= top && n % every != 0) continue;
    const std::size_t i = order[n];
    const Rgb want = voxel_difference(tf, g, ray, background, grad.index[i]);
    for (int c = 0; c < kChannels; ++c) {
      std::ostringstream label;
      label << where << " voxel " << grad.index[i] << " channel " << c;
      voxels.add(grad.d_value[i][c], want[c], grad.channel_scale(c), label.str());
    }
  }
}

// Every transfer-function node's value and position entry of `grad` against differences of the
// reference on `base` (the ray's cubics, which do not move with the nodes). A node value within
// 2h of 0 (densities and colours must stay >= 0) takes the one-sided difference. At a jump (two
// nodes at one scalar) the position entry is the first node's with both moved; the second's is 0
// (the tie), checked here.
void compare_nodes(TransferFunctions& tf, const PolyRay& base, const TrilinearGradient& grad, const std::string& where,
                   Worst& nodes) {
  for (int c = 0; c < kChannels; ++c) {
    const std::size_t ch = static_cast<std::size_t>(c);
    for (const bool density : {true, false}) {
      PiecewiseLinear& f = (density ? tf.density : tf.color)[ch];
      const auto& got = (density ? grad.density : grad.color)[ch];
      for (std::size_t k = 0; k < f.scalar.size(); ++k) {
        const bool jump_first = k + 1 < f.scalar.size() && f.scalar[k + 1] == f.scalar[k];
        const bool jump_second = k > 0 && f.scalar[k - 1] == f.scalar[k];
        for (const bool position : {false, true}) {
          if (position && jump_second) {
            CHECK(got[k].position == 0.0);  // the tie
            continue;
          }
          double& x = position ? f.scalar[k] : f.value[k];
          const double x0 = x;
          const auto at = [&](double h) {
            x = x0 + h;
            if (position && jump_first) f.scalar[k + 1] = x0 + h;
            const Rgb v = reference_intensity(tf, base);
            x = x0;
            if (position && jump_first) f.scalar[k + 1] = x0;
            return v;
          };
          const Rgb d = !position && x0 < 2 * kStep ? forward_difference(at, kStep) : difference(at, kStep);
          std::ostringstream label;
          label << where << (density ? " density" : " color") << "[" << c << "][" << k << "]."
                << (position ? "position" : "value");
          nodes.add(position ? got[k].position : got[k].value, d[c], grad.channel_scale(c), label.str());
        }
      }
    }
  }
}

}  // namespace

TEST_CASE("trilinear gradient: forward intensity is integrate()'s and the background derivative its transmittance",
          "[trilinear_grad]") {
  std::mt19937 rng(kSeed);
  const VoxelGrid g = random_grid(rng);
  const TransferFunctions tf = test_tf(1.0);
  const TrilinearIntegrator integrator(tf);
  const Rgb background{0.1, 0.2, 0.3};
  for (const ViewRay& ray : sample_rays(g, rng)) {
    const TrilinearGradient grad = integrator.gradient(g, ray, background);
    const TrilinearRayResult fwd = integrator.integrate(g, ray, background);
    for (int c = 0; c < kChannels; ++c) {
      CHECK(grad.intensity[c] == fwd.intensity[c]);
      CHECK(grad.background[c] == Approx(fwd.transmittance[c]).epsilon(1e-14));
    }
  }
}

TEST_CASE("trilinear gradient against differences of the 50-digit reference", "[trilinear_grad]") {
  std::mt19937 rng(kSeed);
  const VoxelGrid grids[] = {random_grid(rng), smooth_grid()};
  const Rgb background{0.1, 0.2, 0.3};
  Worst voxels, nodes;
  long rays = 0;
  for (double scale : {1.0, 20.0}) {
    TransferFunctions tf = test_tf(scale);
    const TrilinearIntegrator integrator(tf);
    for (const VoxelGrid& g : grids) {
      std::vector<ViewRay> all = sample_rays(g, rng);
      // The 12 special rays and 2 of the random ones.
      std::vector<ViewRay> chosen(all.end() - 12, all.end());
      chosen.insert(chosen.end(), all.begin(), all.begin() + 2);
      for (std::size_t r = 0; r < chosen.size(); ++r) {
        const ViewRay& ray = chosen[r];
        const TrilinearGradient grad = integrator.gradient(g, ray, background);
        REQUIRE(!grad.index.empty());
        ++rays;
        std::ostringstream where;
        where << "scale " << scale << " ray " << r;
        compare_voxels(tf, g, ray, background, grad, 3, 12, where.str(), voxels);
        // Transfer-function nodes on one ray per grid and scale (the last random one): every
        // node's value and position.
        if (r != chosen.size() - 1) continue;
        compare_nodes(tf, trilinear_ray(g, ray, background), grad, where.str(), nodes);
      }
    }
  }
  std::ostringstream msg;
  msg << "trilinear gradient vs 4th-order differences (h = 1e-5) of the 50-digit reference: " << rays
      << " rays; voxel entries " << voxels.compared << ", worst " << voxels.err << " of the channel's largest entry ("
      << voxels.where << "); node entries " << nodes.compared << ", worst " << nodes.err << " (" << nodes.where << ")";
  WARN(msg.str());
  CHECK(voxels.err <= 1e-8);
  CHECK(nodes.err <= 1e-8);
  CHECK(rays == 2 * 2 * 14);
}

TEST_CASE("trilinear gradient: the Kuhn split's gradient fails as a candidate for it", "[trilinear_grad]") {
  // The Kuhn-split gradient (scene/grid_gradient.hpp) differentiates another interpolant: the
  // same reference must reject it as the trilinear render's gradient, or the comparison above
  // could not tell a wrong gradient from a right one.
  std::mt19937 rng(kSeed);
  const VoxelGrid g = random_grid(rng);
  const TransferFunctions tf = test_tf(1.0);
  const TrilinearIntegrator integrator(tf);
  const Rgb background{0.1, 0.2, 0.3};
  const ViewRay ray = sample_rays(g, rng).front();
  const TrilinearGradient grad = integrator.gradient(g, ray, background);
  const GridPixelJacobian kuhn = grid_pixel_jacobian(g, tf, ray, background);
  double worst_right = 0.0, worst_kuhn = 0.0;
  for (std::size_t i = 0; i < grad.index.size(); i += 3) {
    const Rgb want = voxel_difference(tf, g, ray, background, grad.index[i]);
    const auto it = std::find(kuhn.index.begin(), kuhn.index.end(), grad.index[i]);
    const double k = it == kuhn.index.end() ? 0.0 : kuhn.d_value[static_cast<std::size_t>(it - kuhn.index.begin())][0];
    worst_right = std::max(worst_right, std::fabs(grad.d_value[i][0] - want[0]) / grad.channel_scale(0));
    worst_kuhn = std::max(worst_kuhn, std::fabs(k - want[0]) / grad.channel_scale(0));
  }
  WARN("Kuhn-split gradient as a trilinear candidate: error " << worst_kuhn << " (trilinear gradient "
                                                             << worst_right << ")");
  CHECK(worst_right <= 1e-8);
  CHECK(worst_kuhn > 1e-2);
}

TEST_CASE("trilinear gradient across jumps against differences of the 50-digit reference", "[trilinear_grad][grad_jump]") {
  // Density r and colour g jump inside the grid's value range, density b at its first node; the
  // jump position entry is the difference with both nodes moved (the tie: the second node's
  // entry is 0). The crossings move with the grid values too (du*/dv = -B_v(u*)/G'(u*)).
  std::mt19937 rng(kSeed);
  const VoxelGrid grids[] = {random_grid(rng), smooth_grid()};
  const Rgb background{0.1, 0.2, 0.3};
  Worst voxels, nodes;
  long rays = 0, undefined = 0;
  for (const double scale : {1.0, 20.0})
    for (const VoxelGrid& g : grids) {
      TransferFunctions tf = test_tf(scale);
      const auto [lo_it, hi_it] = std::minmax_element(g.values().begin(), g.values().end());
      const double lo = *lo_it, hi = *hi_it;
      const double x1 = lo + 0.37 * (hi - lo), x2 = lo + 0.61 * (hi - lo);
      tf.density[0] = {{lo, x1, x1, hi}, {0.5 * scale, 1.0 * scale, 3.0 * scale, 2.0 * scale}};
      tf.color[1] = {{lo, x2, x2, hi}, {0.2, 0.9, 0.3, 0.6}};
      tf.density[2] = {{x1, x1, hi}, {0.0, 1.5 * scale, 0.5 * scale}};  // transparent below x1
      REQUIRE(tf.has_jump());
      const TrilinearIntegrator integrator(tf);
      std::vector<ViewRay> all = sample_rays(g, rng);
      std::vector<ViewRay> chosen(all.end() - 12, all.end());
      chosen.insert(chosen.end(), all.begin(), all.begin() + 2);
      // Special rays 0, 3, 6, 9 and the last random one (13). Not 12: a cube of that ray has a
      // near-tangency with a breakpoint (file header), where the h = 1e-5 differences of a node
      // position straddle it (9.9e-6 measured on density g's node 2, a function without a jump).
      for (const std::size_t r : {std::size_t{0}, std::size_t{3}, std::size_t{6}, std::size_t{9}, std::size_t{13}}) {
        const ViewRay& ray = chosen[r];
        const TrilinearGradient grad = integrator.gradient(g, ray, background);
        if (!grad.undefined.empty()) {  // a ray touching a jump exactly: not compared
          ++undefined;
          continue;
        }
        ++rays;
        std::ostringstream where;
        where << "scale " << scale << " ray " << r;
        compare_voxels(tf, g, ray, background, grad, 4, 8, where.str(), voxels);
        compare_nodes(tf, trilinear_ray(g, ray, background), grad, where.str(), nodes);
      }
    }
  std::ostringstream msg;
  msg << "trilinear gradient across jumps vs 4th-order differences (h = 1e-5) of the 50-digit reference: " << rays
      << " rays (" << undefined << " touching a jump, skipped); voxel entries " << voxels.compared << ", worst "
      << voxels.err << " (" << voxels.where << "); node entries " << nodes.compared << ", worst " << nodes.err << " ("
      << nodes.where << ")";
  WARN(msg.str());
  CHECK(rays >= 16);
  CHECK(voxels.err <= 1e-8);
  CHECK(nodes.err <= 1e-8);
}
