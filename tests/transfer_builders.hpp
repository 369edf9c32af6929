#pragma once
// Small builders for the transfer functions tests write by hand.
#include <vector>

#include "rayint/model/transfer_function.hpp"

namespace rayint::test {

inline PiecewiseLinear line(double s0, double v0, double s1, double v1) {
  return {{s0, s1}, {v0, v1}};
}
inline PiecewiseLinear constant(double v) { return {{0.0}, {v}}; }

// The same density and the same colour for all three channels.
inline TransferFunctions uniform_tf(const PiecewiseLinear& rho, const PiecewiseLinear& kappa) {
  TransferFunctions tf;
  for (int c = 0; c < kChannels; ++c) {
    tf.density[c] = rho;
    tf.color[c] = kappa;
  }
  return tf;
}

// Constant density and colour, one value per channel.
inline TransferFunctions constant_tf(const Rgb& rho, const Rgb& kappa) {
  TransferFunctions tf;
  for (int c = 0; c < kChannels; ++c) {
    tf.density[c] = constant(rho[static_cast<std::size_t>(c)]);
    tf.color[c] = constant(kappa[static_cast<std::size_t>(c)]);
  }
  return tf;
}

// Per-channel densities and colours with kinks inside the scalar range [-0.4, 0.8] (the gradient
// tests: derivatives across breakpoints).
inline TransferFunctions kinked_tf() {
  TransferFunctions tf;
  const std::vector<double> s = {-0.4, 0.0, 0.3, 0.8};
  tf.density[0] = {s, {0.5, 2.0, 0.7, 1.5}};
  tf.density[1] = {s, {1.0, 0.2, 2.5, 0.1}};
  tf.density[2] = {{-0.2, 0.5}, {0.3, 3.0}};
  tf.color[0] = {s, {0.1, 0.9, 0.4, 1.0}};
  tf.color[1] = {{0.1, 0.6}, {1.0, 0.2}};
  tf.color[2] = {s, {0.6, 0.3, 1.2, 0.5}};
  return tf;
}

}  // namespace rayint::test
