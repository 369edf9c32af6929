// The gradient of the pre-integrated renderer (integrators/preintegrated_grad.cpp, issue 28):
// against central differences of the renderer itself (its table rebuilt for every node
// perturbation) and, as the table grows, against the exact gradient.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "rayint/integrators/exact_grad.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/integrators/preintegrated.hpp"
#include "rayint/studies/grad_study.hpp"

using namespace rayint;

namespace {

// Kinks inside segments; no lookup coordinate within a difference step of a grid line and no
// segment length near a whole number of steps (checked by hand for the sizes used below).
TransferFunctions test_functions() {
  TransferFunctions tf;
  tf.density = {PiecewiseLinear{{0.0, 0.43, 1.0}, {0.3, 2.1, 0.7}}, PiecewiseLinear{{0.0, 1.0}, {0.5, 1.5}},
                PiecewiseLinear{{0.1, 0.61, 0.9}, {1.0, 0.2, 2.5}}};
  tf.color = {PiecewiseLinear{{0.0, 1.0}, {0.9, 0.3}}, PiecewiseLinear{{0.0, 0.57, 1.0}, {0.4, 0.8, 0.5}},
              PiecewiseLinear{{0.0, 1.0}, {0.2, 0.7}}};
  return tf;
}

Ray test_ray() {
  Ray ray;
  ray.background = {0.3, 0.1, 0.6};
  ray.segments = {{0.7, 0.0123, 0.8871}, {0.45, 0.8871, 0.3317}, {0.3, 0.3317, 0.9533}};
  return ray;
}

// Central differences of the renderer's intensity (step 1e-6 relative). Node positions at the
// table's range ends (0 and 1 here) are left 0: moving them moves the range, which the gradient
// holds fixed (preintegrated_grad.cpp), and the difference straddles the min/max over functions.
RayGradient finite_difference(const std::string& spec_text, TransferFunctions tf, Ray ray, bool* range_node = nullptr) {
  RayGradient g = RayGradient::zeros(tf, ray);
  const MethodSpec spec = parse_method_spec(spec_text);
  const auto I = [&]() { return make_integrator(spec, tf)->integrate(ray, nullptr); };
  const auto diff = [&](double& x, auto&& store) {
    const double x0 = x, h = 1e-6 * std::max(1.0, std::fabs(x0));
    x = x0 + h;
    const Rgb up = I().intensity;
    x = x0 - h;
    const Rgb down = I().intensity;
    x = x0;
    for (int c = 0; c < kChannels; ++c) store(c, (up[c] - down[c]) / (2 * h));
  };
  for (std::size_t j = 0; j < ray.segments.size(); ++j) {
    diff(ray.segments[j].length, [&](int c, double d) { g.length[j][c] = d; });
    diff(ray.segments[j].scalar_far, [&](int c, double d) { g.scalar_far[j][c] = d; });
    diff(ray.segments[j].scalar_exit, [&](int c, double d) { g.scalar_exit[j][c] = d; });
  }
  const std::vector<double> bp = tf.breakpoints();
  for (int c = 0; c < kChannels; ++c) {
    g.background[c] = I().transmittance[c];
    for (const bool density : {true, false}) {
      PiecewiseLinear& f = (density ? tf.density : tf.color)[c];
      auto& out = (density ? g.density : g.color)[c];
      for (std::size_t k = 0; k < f.scalar.size(); ++k) {
        if (f.scalar[k] == bp.front() || f.scalar[k] == bp.back()) {
          if (range_node) *range_node = true;
        } else {
          diff(f.scalar[k], [&](int ch, double d) { if (ch == c) out[k].position = d; });
        }
        diff(f.value[k], [&](int ch, double d) { if (ch == c) out[k].value = d; });
      }
    }
  }
  return g;
}

// Max over channel c's entries of |got - want| / largest |want|, skipping node positions at the
// range ends (zeroed in `want`), the worst entry named in `where`.
double error_without_range_nodes(const RayGradient& got, const RayGradient& want, const TransferFunctions& tf, int c,
                                 std::string& where) {
  const std::vector<double> bp = tf.breakpoints();
  const double scale = want.channel_scale(c);
  std::vector<double> w;
  want.for_each(c, [&w](double v, const char*, std::size_t, const char*) { w.push_back(v); });
  std::size_t i = 0;
  double worst = 0.0;
  got.for_each(c, [&](double v, const char* block, std::size_t idx, const char* param) {
    const double want_v = w[i++];
    const std::string b = block, p = param;
    if (p == "position") {
      const double s = (b == "density" ? tf.density : tf.color)[c].scalar[idx];
      if (s == bp.front() || s == bp.back()) return;
    }
    const double e = std::fabs(v - want_v) / scale;
    if (!(e <= worst)) {
      worst = e;
      where = b + "[" + std::to_string(idx) + "]" + (p.empty() ? "" : "." + p);
    }
  });
  return worst;
}

}  // namespace

TEST_CASE("preintegrated gradient: the derivative of the renderer's own lookups and table build",
          "[grad][preintegrated_grad]") {
  const TransferFunctions tf = test_functions();
  const Ray ray = test_ray();
  for (const char* spec : {"preintegrated:size=64", "preintegrated:size=48:step=0.031",
                           "preintegrated:size=40:dims=3:lengths=12", "preintegrated:size=40:dims=3:lengths=9:max_length=0.5"}) {
    const RayGradient got = method_gradient(parse_method_spec(spec), tf, ray);
    bool range_node = false;
    const RayGradient fd = finite_difference(spec, tf, ray, &range_node);
    CHECK(range_node);  // the skip above is exercised, not vacuous
    const RayResult fwd = make_integrator(parse_method_spec(spec), tf)->integrate(ray, nullptr);
    for (int c = 0; c < kChannels; ++c) {
      std::string where;
      const double err = error_without_range_nodes(got, fd, tf, c, where);
      INFO(spec << " channel " << c << " worst at " << where);
      CHECK(err <= 1e-8);
      CHECK(got.intensity[c] == fwd.intensity[c]);  // integrate()'s, bit for bit
    }
  }
}

TEST_CASE("preintegrated gradient: nearest lookup has no derivative through the coordinates",
          "[grad][preintegrated_grad]") {
  const TransferFunctions tf = test_functions();
  const Ray ray = test_ray();
  const RayGradient got = method_gradient(parse_method_spec("preintegrated:size=64:lookup=nearest"), tf, ray);
  // Piecewise constant in the end scalars (steps are 2^-6 long, scalars move the read entry only):
  // dims = 2's dI/d scalar is 0 exactly; the node values still act through the table entries.
  for (std::size_t j = 0; j < ray.segments.size(); ++j)
    for (int c = 0; c < kChannels; ++c) {
      CHECK(got.scalar_far[j][c] == 0.0);
      CHECK(got.scalar_exit[j][c] == 0.0);
    }
  const RayGradient fd = finite_difference("preintegrated:size=64:lookup=nearest", tf, ray);
  for (int c = 0; c < kChannels; ++c)
    for (std::size_t k = 0; k < got.density[c].size(); ++k)
      CHECK(std::fabs(got.density[c][k].value - fd.density[c][k].value) <= 1e-8 * got.channel_scale(c));
}

TEST_CASE("preintegrated gradient converges to the exact gradient as the table grows",
          "[grad][preintegrated_grad]") {
  const TransferFunctions tf = test_functions();
  const Ray ray = test_ray();
  const RayGradient exact = exact_ray_gradient(tf, ray);
  double previous = HUGE_VAL;
  // Measured (worst channel, every entry, range nodes included): size 32 ... 512 below.
  for (int size : {32, 128, 512}) {
    const RayGradient got =
        method_gradient(parse_method_spec("preintegrated:size=" + std::to_string(size)), tf, ray);
    double worst = 0.0;
    for (int c = 0; c < kChannels; ++c) worst = std::max(worst, gradient_relative_error(got, exact, c));
    WARN("preintegrated size " << size << ": gradient error vs exact " << worst);
    CHECK(worst < previous);
    previous = worst;
  }
}
