#include "rayint/report/evaluation_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rayint {

std::string evaluation_table(const std::vector<CaseEvaluation>& cases) {
  std::string out;
  char line[512];
  std::snprintf(line, sizeof line, "%-34s %-22s %5s %11s %11s %11s %12s  %s\n", "case", "method",
                "rays", "max rel", "max ulp", "ref rel est", "time/ray", "branches");
  out += line;
  out += std::string(130, '-') + "\n";
  for (const auto& c : cases) {
    if (c.rays.empty()) continue;
    for (std::size_t m = 0; m < c.rays.front().methods.size(); ++m) {
      double max_rel = 0, max_ulp = 0, ref_rel = 0, time = 0;
      bool finite = true;
      Diagnostics merged;
      for (const auto& ray : c.rays) {
        const auto& o = ray.methods[m];
        finite = finite && o.finite;
        for (int ch = 0; ch < kChannels; ++ch) {
          max_rel = std::max(max_rel, o.rel_error[ch]);
          max_ulp = std::max(max_ulp, o.ulp_error[ch]);
          const double mag = std::fabs(ray.reference.intensity[ch].hi);
          if (mag > 0) ref_rel = std::max(ref_rel, ray.reference.error_bound[ch] / mag);
        }
        time += o.seconds_per_ray;
        for (const auto& [k, v] : o.diagnostics.branches) merged.branches[k] += v;
      }
      std::string branches;
      for (const auto& [k, v] : merged.branches)
        branches += (branches.empty() ? "" : " ") + k + "=" + std::to_string(v);
      const auto& label = c.rays.front().methods[m].method;
      if (c.with_reference)
        std::snprintf(line, sizeof line, "%-34.34s %-22.22s %5zu %11.3g %11.3g %11.1e %9.3g us  %s%s\n",
                      c.name.c_str(), label.c_str(), c.rays.size(), max_rel, max_ulp, ref_rel,
                      time / static_cast<double>(c.rays.size()) * 1e6, finite ? "" : "NON-FINITE ",
                      branches.c_str());
      else  // --no-reference: no errors to show
        std::snprintf(line, sizeof line, "%-34.34s %-22.22s %5zu %11s %11s %11s %9.3g us  %s%s\n",
                      c.name.c_str(), label.c_str(), c.rays.size(), "-", "-", "skipped",
                      time / static_cast<double>(c.rays.size()) * 1e6, finite ? "" : "NON-FINITE ",
                      branches.c_str());
      out += line;
    }
  }
  return out;
}

}  // namespace rayint
