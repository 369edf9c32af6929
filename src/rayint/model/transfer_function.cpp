#include "rayint/model/transfer_function.hpp"

#include <algorithm>
#include <cstring>
#include <cmath>

namespace rayint {

double PiecewiseLinear::operator()(double s) const { return limit(s, false); }

double PiecewiseLinear::limit(double s, bool from_above) const {
  // A NaN scalar gives NaN (it fails both end tests, and upper_bound would return the end, an
  // index one past the arrays).
  if (std::isnan(s)) return s;
  // At a scalar stored twice the first point is the left value, the second the right value; a
  // jump at an end point counts too (below the first point the function is the first value).
  if (s < scalar.front() || (s == scalar.front() && !from_above)) return value.front();
  if (s > scalar.back() || (s == scalar.back() && from_above)) return value.back();
  const auto k = from_above ? std::upper_bound(scalar.begin(), scalar.end(), s)
                            : std::lower_bound(scalar.begin(), scalar.end(), s);
  return limit(s, from_above, static_cast<std::size_t>(k - scalar.begin()));
}

double PiecewiseLinear::limit(double s, bool from_above, std::size_t k) const {
  if (std::isnan(s)) return s;
  if (s < scalar.front() || (s == scalar.front() && !from_above)) return value.front();
  if (s > scalar.back() || (s == scalar.back() && from_above)) return value.back();
  // From above: scalar[k-1] <= s < scalar[k], k-1 the last point at s, if any.
  if (from_above) return interpolate(s, k);
  // From below: k is the first point >= s; at s itself that point's (left) value, else the line
  // of scalar[k-1] < s < scalar[k] (the same k as upper_bound's: bit for bit as without jumps).
  if (scalar[k] == s) return value[k];
  return interpolate(s, k);
}

bool PiecewiseLinear::has_jump() const {
  return std::adjacent_find(scalar.begin(), scalar.end()) != scalar.end();
}

std::string check_points(const PiecewiseLinear& f) {
  if (f.scalar.empty() || f.scalar.size() != f.value.size())
    return "needs matching, non-empty point lists";
  for (std::size_t i = 0; i < f.scalar.size(); ++i) {
    if (!std::isfinite(f.scalar[i])) return "scalars must be finite";
    if (!(std::isfinite(f.value[i]) && f.value[i] >= 0.0)) return "values must be finite and >= 0";
    if (i > 0 && !(f.scalar[i - 1] <= f.scalar[i])) return "scalars must be non-decreasing";
    if (i > 1 && f.scalar[i - 2] == f.scalar[i])
      return "a scalar may appear at most twice in a row (a jump: left, then right value)";
  }
  return {};
}

double PiecewiseLinear::interpolate(double s, std::size_t k) const {
  const double s0 = scalar[k - 1], s1 = scalar[k];
  if (s == s0) return value[k - 1];
  // Interpolate from the nearer end, with that end's distance computed directly: near a
  // breakpoint s1 - s is exact (Sterbenz) where 1 - (s - s0)/(s1 - s0) would cancel. (`rayint
  // stress` found kappa = 5.7e-12 at 4.3e-14 from a zero of kappa off by 5e-4 with 1 - f.)
  // Values at breakpoints are reproduced exactly; the result lies between the end values and,
  // the weight being <= 1/2, keeps at least half the nearer value: relative error a few ulps.
  const double d0 = s - s0, d1 = s1 - s, span = s1 - s0;
  return d0 <= d1 ? value[k - 1] + (d0 / span) * (value[k] - value[k - 1])
                  : value[k] + (d1 / span) * (value[k - 1] - value[k]);
}

std::vector<double> TransferFunctions::breakpoints() const {
  std::vector<double> all;
  breakpoints_into(all);
  return all;
}

void TransferFunctions::breakpoints_into(std::vector<double>& all) const {
  all.clear();
  for (const auto* group : {&density, &color})
    for (const auto& f : *group) all.insert(all.end(), f.scalar.begin(), f.scalar.end());
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
}

bool TransferFunctions::has_jump() const {
  for (const auto* group : {&density, &color})
    for (const auto& f : *group)
      if (f.has_jump()) return true;
  return false;
}

bool TransferFunctions::grey() const {
  // Bits, not ==: a -0.0 beside a 0.0 would make the channels' results differ in a zero's sign.
  const auto same_bits = [](const std::vector<double>& x, const std::vector<double>& y) {
    return x.size() == y.size() && (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(double)) == 0);
  };
  for (int c = 1; c < kChannels; ++c)
    if (!same_bits(density[0].scalar, density[c].scalar) || !same_bits(density[0].value, density[c].value))
      return false;
  return true;
}

}  // namespace rayint
