#include "rayint/report/check_summary.hpp"

#include "rayint/report/text_format.hpp"

namespace rayint {

// One status line for CI logs (stderr, so stdout stays the diff).
std::string check_summary_line(const CheckResult& r) {
  const char* channel_names[kChannels] = {"r", "g", "b"};
  const CheckSummary& s = r.summary;
  return "rayint check: " + std::string(r.pass ? "PASS" : "FAIL") + ": " + r.candidate_source +
         " vs " + r.case_source + ": " + std::to_string(s.failed_channels) + " of " +
         std::to_string(s.channels) + " channels in " + std::to_string(s.failed_rays) + " of " +
         std::to_string(s.rays) + " rays outside tolerance; max rel error " + g3(s.max_rel_error) +
         ", max abs error " + g3(s.max_abs_error) + " (worst: ray " + std::to_string(s.worst_ray) +
         " channel " + channel_names[s.worst_channel] + ")" +
         (s.expected_failed_rays > 0 ? "; " + std::to_string(s.expected_failed_rays) +
                                           " rays without an expected value (own interpolation did not converge)"
                                     : std::string());
}

}  // namespace rayint
