// Exact gradients across transfer-function jumps (a node scalar stored twice: left value, right
// value): the analytic gradient (integrators/ray_gradient_chain.hpp, add_jump_crossing) against
// the 50-digit reference gradient (reference/reference_grad.cpp, whose jump position entry
// differences the 50-digit integral with both nodes of the jump moved), on rays crossing jumps in
// both directions, several times, thin and thick, with zero-density sides, starting and ending
// near a jump; the entries that do not exist (the ray touching a jump) are NaN in both, and the
// one-sided differences there really differ.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "rayint/integrators/exact.hpp"
#include "rayint/integrators/exact_grad.hpp"
#include "rayint/integrators/psi_table_grad.hpp"
#include "rayint/integrators/riemann_grad.hpp"
#include "rayint/reference/reference_grad.hpp"
#include "rayint/studies/grad_study.hpp"
#include "tolerances.hpp"
#include "transfer_builders.hpp"

using namespace rayint;

namespace {

// Max over the channel's entries of |got - want| / (largest |want| entry), where both exist; the
// NaN pattern (entries that do not exist) must be the same, else the error is +inf.
double jump_error(const RayGradient& got, const RayGradient& want, int c, std::string* where) {
  const double scale = want.channel_scale(c);
  std::vector<double> w;
  want.for_each(c, [&w](double v, const char*, std::size_t, const char*) { w.push_back(v); });
  std::size_t i = 0;
  double worst = 0.0;
  got.for_each(c, [&](double v, const char* block, std::size_t idx, const char* param) {
    const double ref = w[i++];
    double e = 0.0;
    if (std::isnan(v) || std::isnan(ref))
      e = std::isnan(v) && std::isnan(ref) ? 0.0 : HUGE_VAL;
    else
      e = std::fabs(v - ref) / (scale > 0.0 ? scale : 1.0);
    if (!(e <= worst)) {
      worst = e;
      if (where) *where = std::string(block) + "[" + std::to_string(idx) + "]" + (*param ? "." : "") + param;
    }
  });
  return worst;
}

struct Worst {
  double err = 0.0;
  std::string where;
  long samples = 0;
  void add(const RayGradient& got, const RayGradient& want, const std::string& label) {
    for (int c = 0; c < kChannels; ++c) {
      std::string w;
      const double e = jump_error(got, want, c, &w);
      ++samples;
      if (!(e <= err)) {
        err = e;
        where = label + " channel " + std::to_string(c) + " " + w;
      }
    }
  }
};

// A function on [0, 1] with 3..5 distinct node positions, one or two of them jumps (one of them,
// sometimes, at the first or last node); values in [0, vmax], some exactly 0 (zero-density sides).
PiecewiseLinear random_jump_function(std::mt19937_64& rng, double vmax) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int n = 3 + static_cast<int>(rng() % 3);
  std::vector<double> x(static_cast<std::size_t>(n));
  for (double& xi : x) xi = 0.05 + 0.9 * u(rng);
  std::sort(x.begin(), x.end());
  std::vector<bool> jump(x.size(), false);
  jump[rng() % x.size()] = true;
  if (rng() % 2 == 0) jump[rng() % x.size()] = true;
  if (rng() % 4 == 0) jump[rng() % 2 == 0 ? 0 : x.size() - 1] = true;
  const auto value = [&] { return rng() % 5 == 0 ? 0.0 : vmax * u(rng); };
  PiecewiseLinear f;
  for (std::size_t k = 0; k < x.size(); ++k) {
    f.scalar.push_back(x[k]);
    f.value.push_back(value());
    if (jump[k]) {
      f.scalar.push_back(x[k]);
      f.value.push_back(value());
    }
  }
  return f;
}

// All jump positions of the transfer functions.
std::vector<double> jump_positions(const TransferFunctions& tf) {
  std::vector<double> out;
  for (const auto* group : {&tf.density, &tf.color})
    for (const PiecewiseLinear& f : *group)
      for (std::size_t i = 0; i + 1 < f.scalar.size(); ++i)
        if (f.scalar[i] == f.scalar[i + 1]) out.push_back(f.scalar[i]);
  return out;
}

Rgb exact_intensity(const TransferFunctions& tf, const Ray& ray) {
  ExactIntegrator exact(tf, ExactIntegrator::Path::scalar);
  return exact.integrate(ray, nullptr).intensity;
}

}  // namespace

TEST_CASE("exact gradient across jumps against the 50-digit reference: random rays", "[grad][grad_jump]") {
  std::mt19937_64 rng(2027);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  // Density scales: thin (optical depths ~0.05), moderate, thick (~50 per unit length).
  const double scales[] = {0.1, 1.0, 8.0, 50.0};
  Worst worst;
  int crossings = 0, rays = 0;
  for (int i = 0; i < 48; ++i) {
    const double rho_max = scales[i % 4];
    TransferFunctions tf;
    for (int c = 0; c < kChannels; ++c) {
      tf.density[c] = random_jump_function(rng, rho_max);
      tf.color[c] = random_jump_function(rng, 1.0);
    }
    // 1..4 segments whose scalars wander over [-0.1, 1.1] (crossing jumps both ways, several
    // times); every fourth ray starts or ends 1e-9 from a jump (near, not on it).
    Ray ray;
    ray.background = {u(rng), u(rng), u(rng)};
    const int m = 1 + static_cast<int>(rng() % 4);
    double s = -0.1 + 1.2 * u(rng);
    for (int j = 0; j < m; ++j) {
      const double next = -0.1 + 1.2 * u(rng);
      ray.segments.push_back({0.05 + 1.5 * u(rng), s, next});
      s = next;
    }
    if (i % 4 == 3) {
      const std::vector<double> jumps = jump_positions(tf);
      const double x = jumps[rng() % jumps.size()];
      (i % 8 == 3 ? ray.segments.front().scalar_far : ray.segments.back().scalar_exit) = x + (i % 16 < 8 ? 1e-9 : -1e-9);
    }
    for (const Segment& seg : ray.segments)
      for (const double x : jump_positions(tf))
        if ((seg.scalar_far - x) * (seg.scalar_exit - x) < 0.0) ++crossings;
    const RayGradient got = exact_ray_gradient(tf, ray);
    const ReferenceGradient ref = reference_gradient(tf, ray);
    CHECK(got.undefined.empty());  // generic rays: every derivative exists
    worst.add(got, ref.gradient, "ray " + std::to_string(i));
    ++rays;
  }
  WARN("jumps, random rays: worst " << worst.err << " at " << worst.where << " (" << rays << " rays, "
                                    << worst.samples << " ray-channels, " << crossings << " jump crossings)");
  CHECK(crossings > 100);
  CHECK(worst.err <= test::GradTolerances::jump_vs_reference_rel);
}

TEST_CASE("exact gradient across a jump: several crossings both ways, zero-density sides", "[grad][grad_jump]") {
  // Density r jumps 0 -> 2 at 0.5 (transparent below), density g 1.5 -> 0 (transparent above),
  // colour b jumps at 0.5 too (with density b continuous); the ray zig-zags across 0.5 four times.
  TransferFunctions tf = test::uniform_tf(PiecewiseLinear{{0.2, 0.9}, {0.7, 1.1}}, PiecewiseLinear{{0.0, 1.0}, {0.3, 0.9}});
  tf.density[0] = {{0.1, 0.5, 0.5, 0.8}, {0.0, 0.0, 2.0, 1.0}};
  tf.density[1] = {{0.3, 0.5, 0.5}, {1.0, 1.5, 0.0}};
  tf.color[2] = {{0.0, 0.5, 0.5, 1.0}, {0.2, 0.4, 1.3, 0.6}};
  for (const double L : {0.05, 1.0, 10.0}) {  // thin to thick
    const Ray ray{{0.3, 0.2, 0.1}, {{L, 0.2, 0.8}, {L, 0.8, 0.3}, {0.5 * L, 0.3, 0.6}, {L, 0.6, 0.45}}};
    const RayGradient got = exact_ray_gradient(tf, ray);
    const ReferenceGradient ref = reference_gradient(tf, ray);
    Worst w;
    w.add(got, ref.gradient, "L=" + std::to_string(L));
    WARN("zig-zag across jumps, L = " << L << ": worst " << w.err << " at " << w.where << " (reference noise "
                                       << std::max({ref.noise[0], ref.noise[1], ref.noise[2]}) << ")");
    // L = 10 saturates (optical depth ~8 per crossing stretch: the light at a crossing equals the
    // colour to rounding, and kappa - I* in the jump term keeps that rounding): the compositing
    // form's conditioning limit, as for the saturated regime.
    CHECK(w.err <= (L < 10.0 ? test::GradTolerances::jump_vs_reference_rel : test::GradTolerances::saturated_rel));
    CHECK(got.undefined.empty());
    // The tie: the second node of each jump carries 0, the first the jump's derivative (non-zero).
    CHECK(got.density[0][2].position == 0.0);
    CHECK(got.density[0][1].position != 0.0);
    CHECK(got.color[2][2].position == 0.0);
    CHECK(got.color[2][1].position != 0.0);
  }
}

TEST_CASE("exact gradient where the ray touches a jump: null, and the one-sided differences differ", "[grad][grad_jump]") {
  const TransferFunctions tf =
      test::uniform_tf(PiecewiseLinear{{0.2, 0.5, 0.5, 0.9}, {0.4, 0.6, 2.5, 1.0}}, PiecewiseLinear{{0.0, 1.0}, {0.2, 0.9}});
  struct Touch {
    const char* what;
    Ray ray;
    bool far;  // which end of segment `segment` is on the jump
    std::size_t segment;
  };
  const Touch touches[] = {
      {"ray ends on the jump", Ray{{0.1, 0.1, 0.1}, {{1.0, 0.1, 0.3}, {1.0, 0.3, 0.5}}}, false, 1},
      {"ray starts on the jump", Ray{{0.1, 0.1, 0.1}, {{1.0, 0.5, 0.8}}}, true, 0},
      {"segment end on the jump, turning back", Ray{{0.1, 0.1, 0.1}, {{1.0, 0.8, 0.5}, {1.0, 0.5, 0.9}}}, false, 0},
      // (ds/dt 0.2 before, 0.8 after: with equal slopes it would be differentiable)
      {"segment end on the jump, crossing it", Ray{{0.1, 0.1, 0.1}, {{1.0, 0.3, 0.5}, {0.5, 0.5, 0.9}}}, false, 0},
      {"constant segment on the jump", Ray{{0.1, 0.1, 0.1}, {{1.0, 0.3, 0.5}, {1.0, 0.5, 0.5}}}, true, 1},
  };
  for (const Touch& t : touches) {
    INFO(t.what);
    const RayGradient got = exact_ray_gradient(tf, t.ray);
    const ReferenceGradient ref = reference_gradient(tf, t.ray);
    CHECK_FALSE(got.undefined.empty());
    CHECK_FALSE(ref.gradient.undefined.empty());
    for (int c = 0; c < kChannels; ++c) {
      CHECK(std::isnan(got.density[c][1].position));
      CHECK(std::isnan((t.far ? got.scalar_far : got.scalar_exit)[t.segment][c]));
      std::string where;
      CHECK(jump_error(got, ref.gradient, c, &where) <= test::GradTolerances::jump_vs_reference_rel);
    }
    // Not a convention: moving the jump (both nodes) one way and the other gives different
    // slopes, in double, step 1e-6 (their difference is O(1) of the channel's scale here).
    const double h = 1e-6;
    const auto moved = [&](double d) {
      TransferFunctions m = tf;
      for (int c = 0; c < kChannels; ++c) m.density[c].scalar[1] = m.density[c].scalar[2] = 0.5 + d;
      return exact_intensity(m, t.ray)[0];
    };
    const double I0 = exact_intensity(tf, t.ray)[0];
    const double forward = (moved(h) - I0) / h, backward = (I0 - moved(-h)) / h;
    INFO("forward " << forward << " backward " << backward << " scale " << got.channel_scale(0));
    CHECK(std::fabs(forward - backward) > 1e-3 * got.channel_scale(0));
  }
}

TEST_CASE("exact gradient: density and color jumping at one scalar", "[grad][grad_jump]") {
  // Moving the density jump alone is not differentiable (null); the segment scalars, which move
  // both crossings together, are, and agree with the reference.
  TransferFunctions tf = test::uniform_tf(PiecewiseLinear{{0.2, 0.5, 0.5, 0.9}, {0.4, 0.6, 2.5, 1.0}},
                                          PiecewiseLinear{{0.0, 0.5, 0.5, 1.0}, {0.2, 0.3, 0.8, 0.9}});
  const Ray ray{{0.2, 0.2, 0.2}, {{1.0, 0.2, 0.7}, {0.5, 0.7, 0.6}}};
  const RayGradient got = exact_ray_gradient(tf, ray);
  const ReferenceGradient ref = reference_gradient(tf, ray);
  CHECK(std::isnan(got.density[0][1].position));
  CHECK(std::isnan(got.color[0][1].position));
  CHECK(std::isfinite(got.scalar_far[0][0]));
  for (int c = 0; c < kChannels; ++c) CHECK(jump_error(got, ref.gradient, c, nullptr) <= test::GradTolerances::jump_vs_reference_rel);
}

TEST_CASE("gradients that do not differentiate a jump refuse it with one line", "[grad][grad_jump]") {
  const TransferFunctions tf =
      test::uniform_tf(PiecewiseLinear{{0.2, 0.5, 0.5, 0.9}, {0.4, 0.6, 2.5, 1.0}}, test::constant(0.5));
  const Ray ray{{0, 0, 0}, {{1.0, 0.1, 0.9}}};
  CHECK_THROWS_WITH(riemann_ray_gradient(tf, ray, RiemannOptions{}), Catch::Contains("jump"));
  CHECK_THROWS_WITH(psi_table_ray_gradient(tf, ray, 64, table::Lookup::linear), Catch::Contains("jump"));
  CHECK_THROWS_WITH(method_gradient(parse_method_spec("preintegrated:size=64"), tf, ray), Catch::Contains("jump"));
  CHECK_NOTHROW(exact_ray_gradient(tf, ray));
}
