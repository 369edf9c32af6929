#include "rayint/report/evaluation_table.hpp"

#include <algorithm>
#include <cmath>

#include "rayint/report/text_format.hpp"

namespace rayint {

// One line per case and method. The errors and time are over the rays on which the method did
// not fail; "failed" counts the others, and each method that failed somewhere gets a line after
// the table with its first failure. A method that failed on every ray shows "-" for its errors.
std::string evaluation_table(const std::vector<CaseEvaluation>& cases) {
  std::string out;
  std::string failures;
  appendf(out, "%-34s %-22s %5s %6s %11s %11s %11s %12s  %s\n", "case", "method", "rays", "failed",
          "max rel", "max ulp", "ref rel est", "time/ray", "branches");
  out += std::string(137, '-') + "\n";
  const auto number = [](double x, const char* format) {
    return std::isfinite(x) ? printf_number(format, x) : std::string("-");
  };
  for (const auto& c : cases) {
    if (c.rays.empty()) continue;
    const std::vector<MethodSummary> summaries = summarise_methods(c);
    double ref_rel = 0;
    for (const auto& ray : c.rays)
      for (int ch = 0; ch < kChannels; ++ch) {
        const double mag = std::fabs(ray.reference.intensity[ch].hi);
        if (mag > 0) ref_rel = std::max(ref_rel, ray.reference.error_bound[ch] / mag);
      }
    for (std::size_t m = 0; m < summaries.size(); ++m) {
      const MethodSummary& s = summaries[m];
      Diagnostics merged;
      for (const auto& ray : c.rays)
        for (const auto& [k, v] : ray.methods[m].diagnostics.branches) merged.branches[k] += v;
      std::string branches;
      for (const auto& [k, v] : merged.branches)
        branches += (branches.empty() ? "" : " ") + k + "=" + std::to_string(v);
      const std::string time = number(s.mean_seconds_per_ray * 1e6, "%9.3g") + " us";
      appendf(out, "%-34.34s %-22.22s %5zu %6zu %11s %11s %11s %12s  %s%s\n", c.name.c_str(),
              s.method.c_str(), s.rays, s.failed, number(s.max_rel_error, "%.3g").c_str(),
              number(s.max_ulp_error, "%.3g").c_str(),
              c.with_reference ? number(ref_rel, "%.1e").c_str() : "skipped", time.c_str(),
              s.failed > 0 ? (branches.empty() ? "FAILED" : "FAILED ") : "", branches.c_str());
      if (s.failed > 0)
        failures += "FAILED " + c.name + " " + s.method + " on " + std::to_string(s.failed) +
                    " of " + std::to_string(s.rays) + " rays; first: " + s.first_failure + "\n";
    }
  }
  return out + failures;
}

}  // namespace rayint
