#include "rayint/studies/drift.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "rayint/core/format.hpp"

namespace rayint {
namespace {

// Position of a finite double in the ordered sequence of doubles (-0 and +0 both at 0).
long double ordinal(double x) {
  std::int64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  if (bits < 0) bits = std::numeric_limits<std::int64_t>::min() - bits;  // negatives mirrored below 0
  return static_cast<long double>(bits);
}

const char* kNames[3] = {"r", "g", "b"};

}  // namespace

double ulp_distance(double a, double b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b) ? 0.0 : INFINITY;
  if (std::isinf(a) || std::isinf(b)) return a == b ? 0.0 : INFINITY;
  return static_cast<double>(std::fabs(ordinal(a) - ordinal(b)));
}

DriftResult compare_to_baseline(const Baseline& baseline, const RayResults& now, double allowance) {
  DriftResult r;
  for (const auto& [name, rays] : now)
    if (!baseline.cases.count(name)) r.mismatch += (r.mismatch.empty() ? "" : "; ") + std::string("case ") + name + " is not in the baseline";
  for (const auto& [name, base] : baseline.cases) {
    const auto it = now.find(name);
    if (it == now.end()) {
      r.mismatch += (r.mismatch.empty() ? "" : "; ") + std::string("baseline case ") + name + " was not evaluated";
      continue;
    }
    if (it->second.size() != base.size()) {
      r.mismatch += (r.mismatch.empty() ? "" : "; ") + std::string("case ") + name + ": " +
                    std::to_string(it->second.size()) + " rays, the baseline has " + std::to_string(base.size());
      continue;
    }
    for (std::size_t i = 0; i < base.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        const double d = ulp_distance(base[i][c], it->second[i][c]);
        ++r.values;
        if (d > allowance) ++r.drifted;
        if (d > r.max_ulps) {
          r.max_ulps = d;
          r.where = "case " + name + " ray " + std::to_string(i) + " channel " + kNames[c] + ": baseline " +
                    format_number(base[i][c]) + ", now " + format_number(it->second[i][c]);
        }
      }
  }
  return r;
}

}  // namespace rayint
