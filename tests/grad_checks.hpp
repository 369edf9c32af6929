#pragma once
// Shared by the gradient tests (issue 28): the error of one ray gradient against another, and
// central differences of a renderer's own intensity (the forward, not the gradient code).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "rayint/integrators/integrator.hpp"
#include "rayint/model/ray_gradient.hpp"
#include "rayint/studies/grad_study.hpp"

namespace rayint::test {

// The gradient tests' ray: three segments far -> near with scalars that wander up, down and up
// over [0.0123, 0.9533] (no end on a round number), background (0.3, 0.1, 0.6).
inline Ray three_segment_ray() {
  Ray ray;
  ray.background = {0.3, 0.1, 0.6};
  ray.segments = {{0.7, 0.0123, 0.8871}, {0.45, 0.8871, 0.3317}, {0.3, 0.3317, 0.9533}};
  return ray;
}

// Channel c's entries of g in RayGradient::for_each's order.
inline std::vector<double> channel_entries(const RayGradient& g, int c) {
  std::vector<double> out;
  g.for_each(c, [&out](double v, const char*, std::size_t, const char*) { out.push_back(v); });
  return out;
}

// Max over channel c's entries of |got - want| / (largest |want| entry; 1 if that is 0), skipping
// the entries skip(block, index, parameter) names. Where an entry does not exist (NaN) it must be
// NaN in both, else the error is +inf. The worst entry is named in `where`.
template <class Skip>
double gradient_error(const RayGradient& got, const RayGradient& want, int c, std::string* where, Skip&& skip) {
  const double scale = want.channel_scale(c);
  const std::vector<double> w = channel_entries(want, c);
  std::size_t i = 0;
  double worst = 0.0;
  got.for_each(c, [&](double v, const char* block, std::size_t idx, const char* param) {
    const double ref = w[i++];
    if (skip(block, idx, param)) return;
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
inline double gradient_error(const RayGradient& got, const RayGradient& want, int c, std::string* where) {
  return gradient_error(got, want, c, where, [](const char*, std::size_t, const char*) { return false; });
}

// The worst gradient_error over every channel of the rays added, with its place.
struct WorstGradientError {
  double err = 0.0;
  std::string where;
  long samples = 0;  // ray-channels
  void add(const RayGradient& got, const RayGradient& want, const std::string& label) {
    for (int c = 0; c < kChannels; ++c) {
      std::string w;
      const double e = gradient_error(got, want, c, &w);
      ++samples;
      if (!(e <= err)) {
        err = e;
        where = label + " channel " + std::to_string(c) + " " + w;
      }
    }
  }
};

// Central difference of eval() (an Rgb) in x: x moved by +-h, h = rel_step * max(1, |x|), x
// restored; store(c, derivative) per channel.
template <class Eval, class Store>
void central_difference(double& x, double rel_step, Eval&& eval, Store&& store) {
  const double x0 = x, h = rel_step * std::max(1.0, std::fabs(x0));
  x = x0 + h;
  const Rgb up = eval();
  x = x0 - h;
  const Rgb down = eval();
  x = x0;
  for (int c = 0; c < kChannels; ++c) store(c, (up[c] - down[c]) / (2 * h));
}

// Central differences (step rel_step, relative as above) of the renderer `spec_text`'s own
// intensity (registry, integrate()) with respect to every input of the ray: segment lengths and
// end scalars, background (the transmittance, exactly linear), node values and positions. A node
// position for which skip_position(scalar) is true is left 0. For a jump, both nodes are moved
// together and the derivative goes to the first node's entry, the second's is 0 (the tie of
// model/ray_gradient.hpp).
template <class SkipPosition>
RayGradient method_finite_difference(const std::string& spec_text, TransferFunctions tf, Ray ray, double rel_step,
                                     SkipPosition&& skip_position) {
  RayGradient g = RayGradient::zeros(tf, ray);
  const MethodSpec spec = parse_method_spec(spec_text);
  const auto result = [&]() { return make_integrator(spec, tf)->integrate(ray, nullptr); };
  const auto I = [&]() { return result().intensity; };
  for (std::size_t j = 0; j < ray.segments.size(); ++j) {
    central_difference(ray.segments[j].length, rel_step, I, [&](int c, double d) { g.length[j][c] = d; });
    central_difference(ray.segments[j].scalar_far, rel_step, I, [&](int c, double d) { g.scalar_far[j][c] = d; });
    central_difference(ray.segments[j].scalar_exit, rel_step, I, [&](int c, double d) { g.scalar_exit[j][c] = d; });
  }
  for (int c = 0; c < kChannels; ++c) {
    g.background[c] = result().transmittance[c];
    for (const bool density : {true, false}) {
      PiecewiseLinear& f = (density ? tf.density : tf.color)[c];
      auto& out = (density ? g.density : g.color)[c];
      for (std::size_t k = 0; k < f.scalar.size(); ++k) {
        const bool jump_second = k > 0 && f.scalar[k - 1] == f.scalar[k];
        const bool jump_first = k + 1 < f.scalar.size() && f.scalar[k + 1] == f.scalar[k];
        if (!jump_second && !skip_position(f.scalar[k])) {
          if (jump_first) {  // both nodes of the jump: a proxy moved, copied to the pair
            double x = f.scalar[k];
            const auto moved = [&]() {
              f.scalar[k] = f.scalar[k + 1] = x;
              return I();
            };
            const double x0 = x;
            central_difference(x, rel_step, moved, [&](int ch, double d) { if (ch == c) out[k].position = d; });
            f.scalar[k] = f.scalar[k + 1] = x0;
          } else {
            central_difference(f.scalar[k], rel_step, I, [&](int ch, double d) { if (ch == c) out[k].position = d; });
          }
        }
        central_difference(f.value[k], rel_step, I, [&](int ch, double d) { if (ch == c) out[k].value = d; });
      }
    }
  }
  return g;
}
inline RayGradient method_finite_difference(const std::string& spec_text, const TransferFunctions& tf, const Ray& ray,
                                            double rel_step) {
  return method_finite_difference(spec_text, tf, ray, rel_step, [](double) { return false; });
}

}  // namespace rayint::test
