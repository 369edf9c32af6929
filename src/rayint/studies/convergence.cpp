#include "rayint/studies/convergence.hpp"

#include <algorithm>
#include <cmath>

namespace rayint {

PixelErrorStats pixel_error_stats(std::vector<double> e) {
  PixelErrorStats s;
  if (e.empty()) return s;
  std::sort(e.begin(), e.end());
  const std::size_t n = e.size();
  s.ok = true;
  s.median = n % 2 == 1 ? e[n / 2] : 0.5 * (e[n / 2 - 1] + e[n / 2]);
  s.p95 = e[static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(n))) - 1];
  s.max = e.back();
  return s;
}

OrderFit observed_order(const std::vector<double>& h, const std::vector<double>& e, double floor,
                        double spread) {
  OrderFit f;
  const std::size_t n = std::min(h.size(), e.size());
  auto usable = [&](std::size_t i) { return std::isfinite(e[i]) && e[i] > floor && h[i] > 0.0; };
  for (std::size_t i = 0; i + 1 < n; ++i)
    f.local_orders.push_back(usable(i) && usable(i + 1) ? std::log(e[i] / e[i + 1]) / std::log(h[i] / h[i + 1])
                                                        : std::nan(""));
  // The finest usable point.
  std::size_t last = n;
  for (std::size_t i = n; i-- > 0;)
    if (usable(i)) {
      last = i;
      break;
    }
  if (last == n || last == 0 || !usable(last - 1)) {
    f.reason = "fewer than 2 consecutive steps with an error above the floor";
    return f;
  }
  const double finest_local = f.local_orders[last - 1];
  std::size_t first = last - 1;
  while (first > 0 && usable(first - 1) && std::abs(f.local_orders[first - 1] - finest_local) <= spread) --first;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double m = static_cast<double>(last - first + 1);
  for (std::size_t i = first; i <= last; ++i) {
    const double x = std::log(h[i]), y = std::log(e[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  f.ok = true;
  f.order = (m * sxy - sx * sy) / (m * sxx - sx * sx);
  f.first = first;
  f.last = last;
  return f;
}

}  // namespace rayint

namespace rayint {

void conclude(ConvergenceResult& r) {
  std::vector<double> steps, med, p95, mx;
  bool any_failed = false;
  double change = 0.0;
  for (const ConvergenceRow& row : r.rows) {
    steps.push_back(row.step);
    const double nan = std::nan("");
    med.push_back(row.failed ? nan : row.error.median);
    p95.push_back(row.failed ? nan : row.error.p95);
    mx.push_back(row.failed ? nan : row.error.max);
    any_failed = any_failed || row.failed;
    if (!row.failed) change = std::max(change, row.change_from_finest);
  }
  r.median_fit = observed_order(steps, med, r.floor);
  r.p95_fit = observed_order(steps, p95, r.floor);
  r.max_fit = observed_order(steps, mx, r.floor);
  r.invariant = !any_failed && change <= r.invariance_tolerance * r.peak;
  r.passed = !any_failed;
  if (r.has_expectation) {
    const OrderFit& f = r.gated_fit();
    r.passed = r.passed && f.ok && f.order >= r.expected_order - r.order_tolerance;
  }
}

}  // namespace rayint
