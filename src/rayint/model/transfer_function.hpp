#pragma once
// The six user transfer functions of Williams & Max (1992, Sec. 3.1): optical density rho and
// chromaticity kappa for r, g, b, each piecewise linear in the scalar and constant beyond its
// first and last point.
#include <array>
#include <cstddef>
#include <vector>

namespace rayint {

using Rgb = std::array<double, 3>;
inline constexpr int kChannels = 3;

struct PiecewiseLinear {
  std::vector<double> scalar;  // strictly increasing
  std::vector<double> value;   // finite, >= 0; same size as scalar, at least one point

  // Linear interpolation; the end value holds outside [scalar.front(), scalar.back()].
  // At a breakpoint it returns the stored value exactly.
  double operator()(double s) const;
  // operator() for scalar.front() < s < scalar.back() with k = the index upper_bound(scalar, s)
  // returns (scalar[k-1] <= s < scalar[k]), known to the caller: the same arithmetic, bit for bit.
  double interpolate(double s, std::size_t k) const;
};

struct TransferFunctions {
  std::array<PiecewiseLinear, kChannels> density;  // rho_r, rho_g, rho_b
  std::array<PiecewiseLinear, kChannels> color;    // kappa_r, kappa_g, kappa_b

  // Sorted, de-duplicated union of the breakpoints of all six functions.
  std::vector<double> breakpoints() const;
  // True when the three densities are the same function, point for point and bit for bit (a grey
  // medium, as from one opacity transfer function): every channel of a piece then has the same
  // optical depth, so its transmittance and emission weights need computing only once.
  bool grey() const;
};

}  // namespace rayint
