// special_reference.cpp -- erfcx(x) = exp(x^2) erfc(x) and Dawson's integral
// D(x) = exp(-x^2) int_0^x exp(t^2) dt for x >= 0 in cpp_bin_float_50 (eps 5.3e-51), by region:
//   - erfcx, x <= 25: exp(x^2) * erfc(x), Boost.Math's erfc at 50 digits (erfc(25) = 8e-274 is
//     far inside cpp_bin_float's exponent range, so there is no underflow or cancellation).
//   - D, x <= 25: the positive series D(x) = exp(-x^2) sum_n x^(2n+1) / (n! (2n+1))
//     (Abramowitz & Stegun 7.1.4 with erfi; every term positive, so only rounding, ~n eps).
//   - x > 25, both: the asymptotic series (A&S 7.1.23, and for D its companion)
//       erfcx(x) = 1/(sqrt(pi) x) sum_n (-1)^n (2n-1)!! / (2x^2)^n,
//       D(x)     = 1/(2x)         sum_n         (2n-1)!! / (2x^2)^n,
//     summed until a term is below 1e-55 of the sum; the terms fall until n ~ x^2 = 625, and the
//     error of the truncated series is below its smallest term, exp(-x^2) < 1e-271.
// Accuracy: ~1e-48 relative (tests/test_special_simd.cpp checks libcerf against it to 1e-15).
#include "rayint/reference/special_reference.hpp"

#include <boost/math/constants/constants.hpp>
#include <boost/math/special_functions/erf.hpp>
#include <cmath>
#include <stdexcept>

namespace rayint {
namespace reference_detail {
namespace {

constexpr double kAsymptoticFrom = 25.0;

// sum_n (sign)^n (2n-1)!! / (2x^2)^n
Real asymptotic_sum(const Real& x, int sign) {
  const Real w = 1 / (2 * x * x);
  Real term = 1, sum = 1;
  for (int n = 1; n < 2000; ++n) {
    term *= sign * (2 * n - 1) * w;
    sum += term;
    if (abs(term) < Real(1e-55) * abs(sum)) return sum;
  }
  throw std::runtime_error("special_reference: asymptotic series did not converge");
}

}  // namespace

Real erfcx_real(const Real& x) {
  if (x < 0) throw std::invalid_argument("erfcx_reference: x < 0");
  if (x <= kAsymptoticFrom) return exp(x * x) * boost::math::erfc(x);
  return asymptotic_sum(x, -1) / (boost::math::constants::root_pi<Real>() * x);
}

Real dawson_real(const Real& x) {
  if (x < 0) throw std::invalid_argument("dawson_reference: x < 0");
  if (x == 0) return 0;
  if (x > kAsymptoticFrom) return asymptotic_sum(x, +1) / (2 * x);
  const Real x2 = x * x;
  Real t = x, sum = x;  // t = x^(2n+1) / n!
  for (int n = 1; n < 10000; ++n) {
    t *= x2 / n;
    const Real term = t / (2 * n + 1);
    sum += term;
    if (n > x2 && term < Real(1e-55) * sum) return exp(-x2) * sum;
  }
  throw std::runtime_error("dawson_reference: series did not converge");
}

}  // namespace reference_detail

ExtendedValue erfcx_reference(double x) { return reference_detail::to_extended(reference_detail::erfcx_real(x)); }
ExtendedValue dawson_reference(double x) { return reference_detail::to_extended(reference_detail::dawson_real(x)); }

}  // namespace rayint
