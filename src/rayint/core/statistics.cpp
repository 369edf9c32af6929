// The error statistics (definitions and reasons in statistics.hpp).
#include "rayint/core/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace rayint {
namespace {

// On a sorted, non-empty v.
double sorted_median(const std::vector<double>& v) {
  const std::size_t mid = v.size() / 2;
  if (v.size() % 2 == 1) return v[mid];
  return 0.5 * (v[mid - 1] + v[mid]);
}

double sorted_quantile(const std::vector<double>& v, double q) {
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
  return v[std::min(v.size(), std::max<std::size_t>(rank, 1)) - 1];
}

}  // namespace

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return sorted_median(v);
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return sorted_quantile(v, q);
}

ErrorStats error_stats(std::vector<double> v) {
  ErrorStats s;
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  s.max = v.back();
  s.p99 = sorted_quantile(v, kP99);
  s.median = sorted_median(v);
  return s;
}

}  // namespace rayint
