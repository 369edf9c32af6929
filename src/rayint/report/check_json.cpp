// The JSON diff `rayint check` writes (format: docs/candidate-format.md).
#include "rayint/report/check_json.hpp"

#include <cmath>

#include "rayint/report/json_number.hpp"

namespace rayint {

namespace {

constexpr const char* kChannelNames[kChannels] = {"r", "g", "b"};

using ojson = nlohmann::ordered_json;

ojson channel_json(const ChannelCheck& ch, int k, bool with_reference) {
  ojson j = {{"channel", kChannelNames[k]},
             {"pass", ch.pass},
             {"expected", number_or_null<ojson>(ch.expected)},
             {"got", number_or_null<ojson>(ch.got)},
             {"abs_error", number_or_null<ojson>(ch.abs_error)},
             {"rel_error", number_or_null<ojson>(ch.rel_error)},
             {"allowed", number_or_null<ojson>(ch.allowed)}};
  if (with_reference) {
    j["reference"] = number_or_null<ojson>(ch.reference);
    j["expected_error"] = number_or_null<ojson>(ch.expected_error);
  }
  return j;
}

}  // namespace

nlohmann::ordered_json check_report_json(const CheckResult& r) {
  const CheckSummary& s = r.summary;
  const bool with_ref = r.options.with_reference;
  ojson summary = {{"rays", s.rays},
                   {"failed_rays", s.failed_rays},
                   {"channels", s.channels},
                   {"failed_channels", s.failed_channels},
                   {"max_abs_error", number_or_null<ojson>(s.max_abs_error)},
                   {"max_rel_error", number_or_null<ojson>(s.max_rel_error)},
                   {"worst", {{"ray", s.worst_ray}, {"channel", kChannelNames[s.worst_channel]}}}};
  if (with_ref)
    summary["expected_max_rel_uncertainty"] = number_or_null<ojson>(s.expected_max_rel_uncertainty);
  const bool own = r.expected_method != "exact";  // own interpolation: its failures are counted
  if (own) {
    summary["expected_failed_rays"] = s.expected_failed_rays;
    if (with_ref) summary["reference_failed_rays"] = s.reference_failed_rays;
  }
  ojson rays = ojson::array();
  for (std::size_t i = 0; i < r.rays.size(); ++i) {
    ojson channels = ojson::array();
    for (int k = 0; k < kChannels; ++k)
      channels.push_back(channel_json(r.rays[i].channel[static_cast<std::size_t>(k)], k, with_ref));
    ojson ray = {{"index", i}, {"pass", r.rays[i].pass}};
    if (!r.rays[i].expected_failure.empty()) ray["expected_failure"] = r.rays[i].expected_failure;
    if (!r.rays[i].reference_failure.empty()) ray["reference_failure"] = r.rays[i].reference_failure;
    ray["channels"] = channels;
    rays.push_back(ray);
  }
  return {{"tool", "rayint"},
          {"report", "check"},
          {"pass", r.pass},
          {"case", {{"name", r.case_name}, {"file", r.case_source}}},
          {"candidate", {{"file", r.candidate_source}, {"renderer", r.renderer}}},
          {"expected", r.expected_method},
          {"rule",
           "pass if |got - expected| <= max(abs_tol, rel_tol * |expected|) "
           "for every channel of every ray"},
          {"tolerance", {{"rel", r.options.rel_tol}, {"abs", r.options.abs_tol}}},
          {"summary", summary},
          {"rays", rays}};
}

}  // namespace rayint
