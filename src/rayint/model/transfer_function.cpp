#include "rayint/model/transfer_function.hpp"

#include <algorithm>

namespace rayint {

double PiecewiseLinear::operator()(double s) const {
  if (s <= scalar.front()) return value.front();
  if (s >= scalar.back()) return value.back();
  const auto it = std::upper_bound(scalar.begin(), scalar.end(), s);
  const auto k = static_cast<std::size_t>(it - scalar.begin());  // scalar[k-1] <= s < scalar[k]
  const double s0 = scalar[k - 1], s1 = scalar[k];
  if (s == s0) return value[k - 1];
  // Interpolate from the nearer end so that values at breakpoints are reproduced exactly and
  // the result stays between the two end values.
  const double f = (s - s0) / (s1 - s0);
  return f <= 0.5 ? value[k - 1] + f * (value[k] - value[k - 1])
                  : value[k] + (1.0 - f) * (value[k - 1] - value[k]);
}

std::vector<double> TransferFunctions::breakpoints() const {
  std::vector<double> all;
  for (const auto* group : {&density, &color})
    for (const auto& f : *group) all.insert(all.end(), f.scalar.begin(), f.scalar.end());
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  return all;
}

}  // namespace rayint
