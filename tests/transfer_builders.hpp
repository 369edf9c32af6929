#pragma once
// Small builders for the transfer functions tests write by hand.
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

}  // namespace rayint::test
