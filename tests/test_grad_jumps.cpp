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
#include <utility>
#include <vector>

#include "rayint/integrators/exact.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/integrators/exact_grad.hpp"
#include "rayint/integrators/psi_table_grad.hpp"
#include "rayint/integrators/riemann_grad.hpp"
#include "rayint/reference/reference_grad.hpp"
#include "rayint/studies/grad_study.hpp"
#include "grad_checks.hpp"
#include "tolerances.hpp"
#include "transfer_builders.hpp"

using namespace rayint;

using test::gradient_error;
using Worst = test::WorstGradientError;

namespace {

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
      CHECK(gradient_error(got, ref.gradient, c, &where) <= test::GradTolerances::jump_vs_reference_rel);
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
  for (int c = 0; c < kChannels; ++c) CHECK(gradient_error(got, ref.gradient, c, nullptr) <= test::GradTolerances::jump_vs_reference_rel);
}

TEST_CASE("every ray gradient accepts a transfer function with a jump", "[grad][grad_jump]") {
  const TransferFunctions tf =
      test::uniform_tf(PiecewiseLinear{{0.2, 0.5, 0.5, 0.9}, {0.4, 0.6, 2.5, 1.0}}, test::constant(0.5));
  const Ray ray{{0, 0, 0}, {{1.0, 0.1, 0.9}}};
  // (preintegrated:size=64 would put grid scalar 35 of [0, 0.9] on the jump at 0.5: undefined there.)
  for (const char* spec : {"exact", "riemann:n=8", "nerf:n=8", "pl_nerf:n=8", "psi_table:size=64", "preintegrated:size=60"}) {
    INFO(spec);
    const RayGradient g = method_gradient(parse_method_spec(spec), tf, ray);
    CHECK(g.undefined.empty());
    CHECK(g.density[0][1].position != 0.0);  // the jump (or the linear piece beside it) moves I
    CHECK(g.density[0][2].position == 0.0);  // the tie
  }
}

namespace {

// Transfer functions with jumps of every kind for the sampled renderers: density r jumps between
// two linear pieces at 0.45; density b jumps at its first node 0.3 (0.05 below); colour r is a pure
// step at 0.55 (constant on both sides); colour g jumps between linear pieces at 0.62. (Not a
// value exactly 0: psi_table skips a transparent piece and central differences of a 0 value
// cross into negative densities, so neither is differentiable there.)
TransferFunctions sampled_jump_tf() {
  TransferFunctions tf;
  tf.density = {PiecewiseLinear{{0.2, 0.45, 0.45, 0.9}, {0.4, 0.6, 2.5, 1.0}}, PiecewiseLinear{{0.0, 1.0}, {0.5, 1.5}},
                PiecewiseLinear{{0.3, 0.3, 0.8}, {0.05, 1.2, 0.5}}};
  tf.color = {PiecewiseLinear{{0.55, 0.55}, {0.2, 0.9}}, PiecewiseLinear{{0.0, 0.62, 0.62, 1.0}, {0.2, 0.3, 0.8, 0.9}},
              PiecewiseLinear{{0.0, 1.0}, {0.2, 0.7}}};
  return tf;
}

// The scalars of every sample the renderer takes on the ray: fractions (k + 1/2)/n of each
// segment for midpoint samples (riemann, nerf at=mid), k/n (k = 0..n) for nerf at=near and pl_nerf.
std::vector<double> sample_scalars(const Ray& ray, int n, bool midpoints) {
  std::vector<double> out;
  for (const Segment& seg : ray.segments)
    for (int j = midpoints ? 1 : 0; j <= 2 * n; j += 2)
      out.push_back(seg.scalar_far + (j / (2.0 * n)) * (seg.scalar_exit - seg.scalar_far));
  return out;
}

}  // namespace

TEST_CASE("riemann, nerf, pl_nerf gradients across jumps: the derivative of each renderer's own sum",
          "[grad][grad_jump]") {
  const TransferFunctions tf = sampled_jump_tf();
  const Ray ray = test::three_segment_ray();  // crosses every jump, no end within 1e-3 of a node
  const std::vector<double> bp = tf.breakpoints();
  const std::vector<double> jumps = jump_positions(tf);
  REQUIRE(jumps.size() == 4);
  // Central differences, step 1e-6 (relative to max(1, |x|): scalars and positions move <= 1e-6).
  const double step = 1e-6;
  struct Spec {
    const char* spec;
    int n;
    bool midpoints;
  };
  Worst worst;
  for (const Spec& sp : {Spec{"riemann:n=16", 16, true}, Spec{"riemann:n=64", 64, true}, Spec{"nerf:n=16", 16, true},
                         Spec{"nerf:n=16:at=near", 16, false}, Spec{"pl_nerf:n=16", 16, false},
                         Spec{"pl_nerf:n=16:color=near", 16, false}}) {
    INFO(sp.spec);
    // The precondition of comparing with differences: no sample within a few steps of a node (no
    // sample changes side of a jump, or interval of a kink, under any perturbation), checked on a
    // superset of the sample scalars (both grids: the renderers compute them in their own order).
    const std::vector<double> all = sample_scalars(ray, sp.n, true), grid = sample_scalars(ray, sp.n, false);
    double nearest = HUGE_VAL;
    for (const auto* samples : {&all, &grid})
      for (const double s : *samples)
        for (const double x : bp) nearest = std::min(nearest, std::fabs(s - x));
    INFO("nearest sample to a node " << nearest);
    REQUIRE(nearest > 8 * step);
    // ... and not vacuous: samples on both sides of every jump.
    const std::vector<double> taken = sample_scalars(ray, sp.n, sp.midpoints);
    for (const double x : jumps) {
      const auto below = std::count_if(taken.begin(), taken.end(), [x](double s) { return s < x; });
      CHECK(below > 0);
      CHECK(below < static_cast<long>(taken.size()));
    }
    const RayGradient got = method_gradient(parse_method_spec(sp.spec), tf, ray);
    const RayGradient fd = test::method_finite_difference(sp.spec, tf, ray, step);
    CHECK(got.undefined.empty());
    worst.add(got, fd, sp.spec);
    for (int c = 0; c < kChannels; ++c) {
      std::string where;
      const double err = gradient_error(got, fd, c, &where);
      INFO("channel " << c << " worst at " << where << ": " << err);
      CHECK(err <= 1e-8);
      const double I = make_integrator(parse_method_spec(sp.spec), tf)->integrate(ray, nullptr).intensity[c];
      CHECK(std::fabs(got.intensity[c] - I) <= 1e-14 * std::fabs(I));
    }
    // The tie: second nodes 0; the jumps between linear pieces move those pieces (non-zero);
    // the pure step (colour r) has nothing beside it to move: exactly 0, where exact's is not.
    CHECK(got.density[0][2].position == 0.0);
    CHECK(got.density[0][1].position != 0.0);
    CHECK(fd.density[0][1].position != 0.0);
    CHECK(got.color[1][2].position == 0.0);
    CHECK(got.color[1][1].position != 0.0);
    CHECK(got.color[0][0].position == 0.0);
    CHECK(got.color[0][1].position == 0.0);
    CHECK(std::fabs(exact_ray_gradient(tf, ray).color[0][0].position) > 0.01 * got.channel_scale(0));
  }
  WARN("sampled renderers across jumps vs central differences of their own sums: worst " << worst.err << " at "
       << worst.where << " (" << worst.samples << " ray-channels)");
}

TEST_CASE("riemann gradient: a sample exactly on a jump takes the left value's side", "[grad][grad_jump]") {
  // riemann:n=4 on a segment 0 -> 1 samples at 0.125, 0.375, 0.625, 0.875 exactly; the density
  // jumps 1 -> 3 at 0.375, so one sample sits on the jump, where operator() returns the left
  // value. The sum is left-continuous there: its derivatives are the one-sided ones for moving
  // that sample down (scalar_far and scalar_exit decreased, as ds/ds_far = 5/8, ds/ds_exit = 3/8
  // are positive) or the jump up, measured by second-order one-sided differences.
  const TransferFunctions tf = test::uniform_tf(PiecewiseLinear{{0.1, 0.375, 0.375, 0.9}, {0.5, 1.0, 3.0, 0.8}},
                                                PiecewiseLinear{{0.0, 1.0}, {0.2, 0.9}});
  const Ray ray{{0.2, 0.2, 0.2}, {{1.0, 0.0, 1.0}}};
  const std::string spec = "riemann:n=4";
  REQUIRE(0.0 + (1.5 / 4.0) * (1.0 - 0.0) == 0.375);
  const RayGradient got = method_gradient(parse_method_spec(spec), tf, ray);
  const auto I = [&](const TransferFunctions& t, const Ray& r) {
    return make_integrator(parse_method_spec(spec), t)->integrate(r, nullptr).intensity[0];
  };
  const double h = 1e-7;
  // d/dx by a one-sided stencil in direction dir (+1 forward, -1 backward): second order.
  const auto one_sided = [&](auto&& f, double dir) { return dir * (-3.0 * f(0.0) + 4.0 * f(dir * h) - f(2.0 * dir * h)) / (2.0 * h); };
  const auto far = [&](double d) { Ray r = ray; r.segments[0].scalar_far += d; return I(tf, r); };
  const auto exit = [&](double d) { Ray r = ray; r.segments[0].scalar_exit += d; return I(tf, r); };
  const auto jump = [&](double d) {
    TransferFunctions t = tf;
    t.density[0].scalar[1] = t.density[0].scalar[2] = 0.375 + d;
    return I(t, ray);
  };
  const double scale = got.channel_scale(0);
  INFO("scale " << scale);
  CHECK(std::fabs(got.scalar_far[0][0] - one_sided(far, -1.0)) <= 1e-7 * scale);
  CHECK(std::fabs(got.scalar_exit[0][0] - one_sided(exit, -1.0)) <= 1e-7 * scale);
  CHECK(std::fabs(got.density[0][1].position - one_sided(jump, +1.0)) <= 1e-7 * scale);
  CHECK(got.density[0][2].position == 0.0);
  // Not a convention the other side would also satisfy: the other one-sided differences see the
  // jump (O(1/h)).
  CHECK(std::fabs(one_sided(far, +1.0) - got.scalar_far[0][0]) > 1e3 * scale);
  CHECK(std::fabs(one_sided(jump, -1.0) - got.density[0][1].position) > 1e3 * scale);
  // The value: the sample reads the left value (node 1), the right value (node 2) only through
  // the samples above the jump (0.625, 0.875); central differences of the values agree.
  const RayGradient fd = test::method_finite_difference(spec, tf, ray, 1e-6, [](double) { return true; });
  for (const std::size_t k : {std::size_t{1}, std::size_t{2}})
    CHECK(std::fabs(got.density[0][k].value - fd.density[0][k].value) <= 1e-8 * scale);
}

TEST_CASE("psi_table and preintegrated gradients across jumps: the derivative of each renderer's own forward",
          "[grad][grad_jump]") {
  const TransferFunctions tf = sampled_jump_tf();
  const double step = 1e-6;  // central differences, relative to max(1, |x|)
  const Ray ray = test::three_segment_ray();  // crosses every jump, no end within 1e-3 of a node
  const std::vector<double> bp = tf.breakpoints();
  const std::vector<double> jumps = jump_positions(tf);
  // Preconditions of comparing with differences: no segment end within a few steps of a node (the
  // split of a segment changes only continuously), ...
  for (const Segment& seg : ray.segments)
    for (const double x : bp) {
      REQUIRE(std::fabs(seg.scalar_far - x) > 8 * step);
      REQUIRE(std::fabs(seg.scalar_exit - x) > 8 * step);
    }
  // ... and every jump crossed (not vacuous).
  for (const double x : jumps) {
    int crossings = 0;
    for (const Segment& seg : ray.segments) crossings += (seg.scalar_far - x) * (seg.scalar_exit - x) < 0.0;
    CHECK(crossings > 0);
  }
  struct Spec {
    const char* spec;
    int table_size;  // preintegrated's grid (0: psi_table, whose table is in optical depths)
  };
  Worst worst;
  for (const Spec& sp : {Spec{"psi_table:size=64", 0}, Spec{"psi_table:size=512", 0}, Spec{"preintegrated:size=64", 64},
                         Spec{"preintegrated:size=48:step=0.031", 48}, Spec{"preintegrated:size=40:dims=3:lengths=12", 40}}) {
    INFO(sp.spec);
    // preintegrated: no grid scalar (s_lo + i (s_hi - s_lo)/(size - 1), range [0, 1] here) within
    // a few steps of a jump (a table entry is smooth in x only while x is strictly inside its step).
    // The lookup coordinates are those of tests/test_preintegrated_grad.cpp (same ray, same range).
    REQUIRE(bp.front() == 0.0);
    REQUIRE(bp.back() == 1.0);
    for (int i = 0; i < sp.table_size; ++i)
      for (const double x : jumps) REQUIRE(std::fabs(i / (sp.table_size - 1.0) - x) > 8 * step);
    const RayGradient got = method_gradient(parse_method_spec(sp.spec), tf, ray);
    CHECK(got.undefined.empty());
    // preintegrated holds its scalar range fixed: the positions of nodes at 0 and 1 are not compared.
    const auto range_node = [&](double s) { return sp.table_size > 0 && (s == bp.front() || s == bp.back()); };
    const RayGradient fd = test::method_finite_difference(sp.spec, tf, ray, step, range_node);
    for (int c = 0; c < kChannels; ++c) {
      std::string where;
      const double err = gradient_error(got, fd, c, &where, [&](const char* block, std::size_t idx, const char* param) {
        return std::string(param) == "position" &&
               range_node((std::string(block) == "density" ? tf.density : tf.color)[c].scalar[idx]);
      });
      INFO("channel " << c << " worst at " << where << ": " << err);
      CHECK(err <= 1e-8);
      if (!(err <= worst.err)) {
        worst.err = err;
        worst.where = std::string(sp.spec) + " channel " + std::to_string(c) + " " + where;
      }
      ++worst.samples;
    }
    // The jumps' position entries (ties: second 0) carry the moving switch point: non-zero, also
    // for the pure step of colour r (nothing linear beside it), unlike the sampled renderers.
    CHECK(got.density[0][2].position == 0.0);
    CHECK(got.color[0][1].position == 0.0);
    CHECK(std::fabs(got.color[0][0].position) > 1e-3 * got.channel_scale(0));
    CHECK(std::fabs(got.color[0][0].position - fd.color[0][0].position) <= 1e-8 * got.channel_scale(0));
    CHECK(std::fabs(got.density[0][1].position) > 1e-3 * got.channel_scale(0));
  }
  WARN("psi_table and preintegrated across jumps vs central differences of their own forward: worst " << worst.err
       << " at " << worst.where << " (" << worst.samples << " ray-channels)");
}

TEST_CASE("preintegrated gradient: a grid scalar on a jump leaves its position undefined", "[grad][grad_jump]") {
  // Range [0, 1], size 65: grid scalar 32/64 = 0.5 is exactly the jump; the ray's scalars pass
  // through the cells beside it, so the entries of that row and column are read.
  const TransferFunctions tf = test::uniform_tf(PiecewiseLinear{{0.0, 0.5, 0.5, 1.0}, {0.4, 0.6, 2.5, 1.0}},
                                                PiecewiseLinear{{0.0, 1.0}, {0.2, 0.9}});
  const Ray ray{{0.2, 0.2, 0.2}, {{1.0, 0.13, 0.91}}};
  const RayGradient got = method_gradient(parse_method_spec("preintegrated:size=65"), tf, ray);
  CHECK_FALSE(got.undefined.empty());
  for (int c = 0; c < kChannels; ++c) {
    CHECK(std::isnan(got.density[c][1].position));
    CHECK(got.density[c][2].position == 0.0);
    CHECK(std::isfinite(got.density[c][1].value));
    CHECK(std::isfinite(got.scalar_far[0][c]));
  }
  // size 64 (no grid scalar on 0.5): defined.
  CHECK(method_gradient(parse_method_spec("preintegrated:size=64"), tf, ray).undefined.empty());
}

TEST_CASE("exact gradient across jumps: the segment blocks alone are the full gradient's, bit for bit",
          "[grad][grad_jump]") {
  // GradientBlocks::segments (what the mesh and grid image losses call) on rays that cross and
  // touch jumps, and on density and color jumping at one scalar: the segment entries are the
  // full gradient's (NaN where it has NaN), the intensity is exact:path=scalar's. Only the
  // node blocks' mark differs: where density[c] and color[c] both jump at a crossed scalar the
  // full gradient's node positions are undefined, which the segment blocks do not contain.
  std::mt19937_64 rng(2829);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto same = [](double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); };
  int rays = 0, nan_entries = 0;
  for (int i = 0; i < 64; ++i) {
    TransferFunctions tf;
    for (int c = 0; c < kChannels; ++c) {
      tf.density[c] = random_jump_function(rng, i % 2 == 0 ? 1.0 : 8.0);
      tf.color[c] = i % 4 == 1 ? tf.density[c] : random_jump_function(rng, 1.0);  // both jump at one scalar
    }
    if (i % 4 == 2)
      for (int c = 1; c < kChannels; ++c) tf.density[c] = tf.density[0];  // grey
    Ray ray;
    ray.background = {u(rng), u(rng), u(rng)};
    const int m = 1 + static_cast<int>(rng() % 4);
    double s = -0.1 + 1.2 * u(rng);
    for (int j = 0; j < m; ++j) {
      const double next = rng() % 6 == 0 ? s : -0.1 + 1.2 * u(rng);  // some constant segments
      ray.segments.push_back({0.05 + 1.5 * u(rng), s, next});
      s = next;
    }
    if (i % 3 == 0) {  // an end (or a constant segment) exactly on a jump: NaN entries
      const std::vector<double> jumps = jump_positions(tf);
      ray.segments.back().scalar_exit = jumps[rng() % jumps.size()];
    }
    const RayGradient all = exact_ray_gradient(tf, ray);
    RayGradient seg;
    exact_ray_gradient(tf, ray, seg, GradientBlocks::segments);
    const Rgb fwd = exact_intensity(tf, ray);
    INFO("ray " << i);
    int ray_nans = 0;
    for (int c = 0; c < kChannels; ++c) {
      CHECK(std::fabs(all.intensity[c] - fwd[c]) <= test::GradTolerances::forward_rel * std::fabs(fwd[c]));
      CHECK(seg.intensity[c] == all.intensity[c]);
      CHECK(seg.background[c] == all.background[c]);
      CHECK(seg.density[c].empty());
      CHECK(seg.color[c].empty());
      for (std::size_t j = 0; j < ray.segments.size(); ++j) {
        CHECK(same(seg.length[j][c], all.length[j][c]));
        CHECK(same(seg.scalar_far[j][c], all.scalar_far[j][c]));
        CHECK(same(seg.scalar_exit[j][c], all.scalar_exit[j][c]));
        ray_nans += std::isnan(seg.scalar_far[j][c]) + std::isnan(seg.scalar_exit[j][c]);
      }
    }
    // The scalar entries' NaNs are explained in both; the full one may add the node positions'.
    CHECK(seg.undefined.empty() == (ray_nans == 0));
    CHECK(all.undefined.find(seg.undefined) != std::string::npos);
    nan_entries += ray_nans;
    ++rays;
  }
  CHECK(nan_entries > 0);
}

TEST_CASE("psi_table gradient on pieces between two jumps, density and color jumping at one of them",
          "[grad][grad_jump]") {
  // Channel r: density jumps at 0.3, 0.5 and 0.7, colour at 0.5 too, and no other function has a
  // node in [0.2, 0.8]: the ray's pieces between 0.3 and 0.5 and between 0.5 and 0.7 have both
  // ends on r's jumps, so in psi_table's gradient (PieceEnds::moving) each piece's length moves
  // with the two jumps' positions. Where density and colour both jump (0.5) moving one of them
  // alone is not differentiable: both position entries are null (NaN) and `undefined` says why;
  // every other entry is the derivative of psi_table's own forward (central differences, step
  // 1e-6, as in the test above). (The other channels' nodes lie outside [0.2, 0.8]: a breakpoint
  // shared with another channel splits r's pieces where moving r's node alone does not, a
  // derivative psi_table_grad.hpp leaves out; so no two functions share a node.)
  TransferFunctions tf;
  tf.density = {PiecewiseLinear{{0.1, 0.3, 0.3, 0.5, 0.5, 0.7, 0.7, 0.9}, {0.4, 0.9, 2.2, 1.6, 0.3, 0.8, 1.9, 1.1}},
                PiecewiseLinear{{0.14, 0.86}, {0.5, 1.5}}, PiecewiseLinear{{0.15, 0.85}, {1.2, 0.4}}};
  tf.color = {PiecewiseLinear{{0.0, 0.5, 0.5, 1.0}, {0.2, 0.5, 1.1, 0.7}}, PiecewiseLinear{{0.03, 0.97}, {0.3, 0.9}},
              PiecewiseLinear{{0.05, 0.92}, {0.8, 0.2}}};
  const Ray ray = test::three_segment_ray();  // no end within 1e-2 of a node
  const std::vector<double> bp = tf.breakpoints();
  for (const Segment& seg : ray.segments)
    for (const double x : bp) {
      REQUIRE(std::fabs(seg.scalar_far - x) > 1e-2);
      REQUIRE(std::fabs(seg.scalar_exit - x) > 1e-2);
    }
  // Pieces with both ends on jumps: [0.3, 0.5] and [0.5, 0.7] inside a segment's scalar range
  // (the first segment holds both, the other two the second).
  int between = 0;
  for (const Segment& seg : ray.segments)
    for (const auto& [x0, x1] : {std::pair{0.3, 0.5}, std::pair{0.5, 0.7}})
      between += std::min(seg.scalar_far, seg.scalar_exit) < x0 && std::max(seg.scalar_far, seg.scalar_exit) > x1;
  REQUIRE(between == 4);
  const double step = 1e-6;
  for (const char* spec : {"psi_table:size=64", "psi_table:size=512"}) {
    INFO(spec);
    const RayGradient got = method_gradient(parse_method_spec(spec), tf, ray);
    CHECK_FALSE(got.undefined.empty());
    CHECK(std::isnan(got.density[0][3].position));  // first node of the density jump at 0.5
    CHECK(std::isnan(got.color[0][1].position));    // first node of the colour jump at 0.5
    // The jumps at 0.3 and 0.7 (density only) carry the moving ends of the pieces beside them.
    for (const std::size_t k : {std::size_t{1}, std::size_t{5}}) {
      CHECK(std::fabs(got.density[0][k].position) > 1e-3 * got.channel_scale(0));
      CHECK(got.density[0][k + 1].position == 0.0);  // the tie
    }
    const auto at_both = [](int c, double s) { return c == 0 && s == 0.5; };
    for (int c = 0; c < kChannels; ++c) {
      const RayGradient fd =
          test::method_finite_difference(spec, tf, ray, step, [&](double s) { return at_both(c, s); });
      std::string where;
      const double err = gradient_error(got, fd, c, &where, [&](const char* block, std::size_t idx, const char* param) {
        return std::string(param) == "position" &&
               at_both(c, (std::string(block) == "density" ? tf.density : tf.color)[c].scalar[idx]);
      });
      INFO("channel " << c << " worst at " << where << ": " << err);
      CHECK(err <= 1e-8);
    }
  }
}
