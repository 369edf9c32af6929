#pragma once
// Mathematical constants and the small numerical helpers every area shares, defined once here.
//
//   kPi                       pi to double precision.
//   step_weight(x)            (1 - e^{-x})/x for x >= 0 (1 at x = 0): the emission weight of a
//                             step of optical depth x with constant source (Williams & Max Eq. 6
//                             divided by x; Max 1995 Eq. 5).
//   attenuated_length(sigma, s)
//                             int_0^s e^{-sigma t} dt = s step_weight(sigma s) for sigma, s >= 0:
//                             the same weight carrying the length of the step.
//
// Methods, by region of x = sigma s (both helpers use the same regions):
//   x < 1e-8:  the Maclaurin series 1 - x/2 (times s). The truncation error is x^2/6 relative,
//              < 1.7e-17 (0.15 ulp of 1) below the threshold 1e-8, the largest power of ten at
//              which it stays below 2^-54 (half an ulp); the remaining error is the rounding of
//              1 - x/2. This also gives the limit 1 (resp. s) at x = 0 (sigma = 0) without 0/0.
//   x >= 1e-8: -expm1(-x)/x (resp. -expm1(-x)/sigma): expm1 has no cancellation, so the error is
//              that of expm1 plus the division. At x = inf the weight is 0.
// Error, relative, in units of epsilon = 2^-52, measured against the 50-digit value
// (cpp_bin_float_50) at 1e5 log-uniform x per region, x in [1e-300, 1e3], s in [1e-3, 1e3]
// (tests/test_math.cpp [math], with glibc's expm1):
//   step_weight        <= 0.31 (series region), <= 0.90 (expm1 region);
//   attenuated_length  <= 0.68 (series region), <= 1.31 (expm1 region: x = sigma s is rounded
//                      before expm1).
// Below 1e-8 the series is the more accurate form: -expm1(-x)/x there measured up to 1.5 ulp
// (0.65 ulp for the series). attenuated_length divides by sigma rather than multiplying s by
// step_weight(x): both are within 2.3 ulp, and this is the form its callers have always used.
#include <cmath>

namespace rayint {

inline constexpr double kPi = 3.14159265358979323846;

// Below this optical depth the step weight is the series 1 - x/2 (see the file comment).
inline constexpr double kStepWeightSeriesDepth = 1e-8;

// (1 - e^{-x})/x for x >= 0; 1 at x = 0, 0 at x = inf.
inline double step_weight(double x) {
  return x < kStepWeightSeriesDepth ? 1.0 - 0.5 * x : -std::expm1(-x) / x;
}

// int_0^s e^{-sigma t} dt = (1 - e^{-sigma s})/sigma for sigma, s >= 0; s at sigma = 0.
inline double attenuated_length(double sigma, double s) {
  const double x = sigma * s;
  return x < kStepWeightSeriesDepth ? s * (1.0 - 0.5 * x) : -std::expm1(-x) / sigma;
}

}  // namespace rayint
