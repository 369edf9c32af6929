#include "rayint/metrics/error_metrics.hpp"

#include <algorithm>

namespace rayint {

double ulp_of(double x) {
  const double a = std::fabs(x);
  if (!std::isfinite(a)) return std::numeric_limits<double>::infinity();
  if (a < std::numeric_limits<double>::min()) return std::numeric_limits<double>::denorm_min();
  return std::nextafter(a, std::numeric_limits<double>::infinity()) - a;
}

double absolute_error(double x, const ExtendedValue& ref) {
  if (!std::isfinite(x)) return std::numeric_limits<double>::infinity();
  // x - hi is exact when x is within a factor 2 of hi (Sterbenz); otherwise the error is large
  // and its rounding does not matter.
  return std::fabs((x - ref.hi) - ref.lo);
}

double relative_error(double x, const ExtendedValue& ref) {
  const double err = absolute_error(x, ref);
  if (err == 0.0) return 0.0;
  const double mag = std::fabs(ref.hi);
  if (mag == 0.0) return std::numeric_limits<double>::infinity();
  return err / mag;
}

double ulp_error(double x, const ExtendedValue& ref) {
  const double err = absolute_error(x, ref);
  if (err == 0.0) return 0.0;
  return err / ulp_of(ref.hi);
}

double relative_error(double x, double ref) { return relative_error(x, ExtendedValue{ref, 0.0}); }

bool underflowed(const ExtendedValue& ref) { return std::fabs(ref.hi) < kUnderflowFloor; }

double scored_error(double x, const ExtendedValue& ref) {
  if (!std::isfinite(x)) return std::numeric_limits<double>::infinity();
  const double err = absolute_error(x, ref);
  if (err == 0.0) return 0.0;
  return err / std::max(std::fabs(ref.hi), kUnderflowFloor);
}

}  // namespace rayint
