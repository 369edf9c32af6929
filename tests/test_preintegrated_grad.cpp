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
#include "grad_checks.hpp"

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

Ray test_ray() { return test::three_segment_ray(); }

// Central differences of the renderer's intensity (step 1e-6 relative). Node positions at the
// table's range ends (0 and 1 here) are left 0: moving them moves the range, which the gradient
// holds fixed (preintegrated_grad.cpp), and the difference straddles the min/max over functions.
RayGradient finite_difference(const std::string& spec_text, const TransferFunctions& tf, const Ray& ray,
                              bool* range_node = nullptr) {
  const std::vector<double> bp = tf.breakpoints();
  return test::method_finite_difference(spec_text, tf, ray, 1e-6, [&](double s) {
    const bool at_end = s == bp.front() || s == bp.back();
    if (at_end && range_node) *range_node = true;
    return at_end;
  });
}

// Max over channel c's entries of |got - want| / largest |want|, skipping node positions at the
// range ends (zeroed in `want`), the worst entry named in `where`.
double error_without_range_nodes(const RayGradient& got, const RayGradient& want, const TransferFunctions& tf, int c,
                                 std::string& where) {
  const std::vector<double> bp = tf.breakpoints();
  return test::gradient_error(got, want, c, &where, [&](const char* block, std::size_t idx, const char* param) {
    if (std::string(param) != "position") return false;
    const double s = (std::string(block) == "density" ? tf.density : tf.color)[c].scalar[idx];
    return s == bp.front() || s == bp.back();
  });
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
