#include "rayint/report/sweep_json.hpp"

#include "rayint/report/evaluation_json.hpp"

namespace rayint {
namespace {

nlohmann::json load_json(const std::array<double, 3>& l) {
  if (l[0] < 0) return nullptr;
  return {{"1min", l[0]}, {"5min", l[1]}, {"15min", l[2]}};
}

double cost_ratio(double seconds, double exact_seconds) {
  return exact_seconds > 0 && seconds > 0 ? seconds / exact_seconds : 0.0;
}

}  // namespace

nlohmann::json to_json(const SettingResult& s, double exact_seconds_per_ray) {
  nlohmann::json per_case = nlohmann::json::array();
  for (const auto& c : s.per_case)
    per_case.push_back({{"case", c.name},
                        {"rays", c.rays},
                        {"failed_rays", c.failed_rays},
                        {"nonfinite", c.nonfinite},
                        // null where no ray of the case ran (all failed): never an error of 0
                        {"max_error", c.rays > c.failed_rays ? number_or_null(c.max_error) : nullptr},
                        {"median_error", c.rays > c.failed_rays ? number_or_null(c.median_error) : nullptr},
                        {"seconds_per_ray", c.seconds_per_ray}});
  nlohmann::json j = {
      {"label", s.label},
      {"knob_value", s.knob_value},
      {"rays", s.rays},
      {"failed_rays", s.failed_rays},
      {"channels", s.channels},
      {"nonfinite", s.nonfinite},
      {"complete", s.complete()},
      {"max_error", s.channels > 0 ? number_or_null(s.max_error) : nullptr},  // over the rays that ran
      {"median_error", s.channels > 0 ? number_or_null(s.median_error) : nullptr},
      {"seconds_per_ray", s.seconds_per_ray},
      {"median_seconds_per_ray", s.median_seconds_per_ray},
      {"cost_vs_exact", cost_ratio(s.seconds_per_ray, exact_seconds_per_ray)},
      {"worst", {{"case", s.worst_case}, {"ray", s.worst_ray}, {"channel", s.worst_channel}}},
      {"setup_seconds", s.setup_seconds},
      {"wall_seconds", s.wall_seconds},
      {"per_case", per_case}};
  if (!s.failure.empty()) j["failure"] = s.failure;
  return j;
}

nlohmann::json to_json(const MethodSweep& m, double exact_seconds_per_ray) {
  nlohmann::json settings = nlohmann::json::array();
  for (const auto& s : m.settings) settings.push_back(to_json(s, exact_seconds_per_ray));
  return {{"method", m.method},         {"knob", m.knob},       {"truncated", m.truncated},
          {"truncation", m.truncation}, {"skipped", m.skipped}, {"settings", settings}};
}

nlohmann::json to_json(const TargetChoice& t) {
  nlohmann::json j = {{"target", t.target},
                      {"statistic", statistic_name(t.statistic)},
                      {"method", t.method},
                      {"reached", t.reached},
                      {"truncated", t.truncated}};
  if (t.reached) {
    j["label"] = t.label;
    j["error"] = number_or_null(t.error);
    j["seconds_per_ray"] = t.seconds_per_ray;
    j["cost_vs_exact"] = t.cost_vs_exact;
  }
  return j;
}

nlohmann::json sweep_report_json(const SweepResult& r) {
  nlohmann::json cases = nlohmann::json::array();
  for (std::size_t i = 0; i < r.case_names.size(); ++i)
    cases.push_back({{"name", r.case_names[i]},
                     {"file", r.case_files[i]},
                     {"rays", r.case_rays[i]},
                     {"pieces", r.case_pieces[i]}});
  nlohmann::json methods = nlohmann::json::array();
  for (const auto& m : r.methods) methods.push_back(to_json(m, r.exact_seconds_per_ray));
  nlohmann::json targets = nlohmann::json::array();
  for (const auto& t : r.targets) targets.push_back(to_json(t));
  const nlohmann::json definitions = {
      {"error",
       "per channel of each ray: |I - I_ref| / max(|I_ref|, underflow_floor) against the "
       "50-digit reference (relative error; absolute error in units of underflow_floor where the "
       "reference is below it); +inf (null) for a non-finite intensity"},
      {"underflow_floor", kUnderflowFloor},
      {"max_error", "maximum over all channels (3 per ray) of all rays the method ran on"},
      {"median_error", "median over the same channels (mean of the two middle values)"},
      {"time_per_ray",
       "per ray: median over timing.batches batches, each repeating integrate(ray) without "
       "diagnostics for at least timing.batch_seconds, single thread, reference not in the loop"},
      {"seconds_per_ray", "mean over rays of the per-ray time (= case-set time / rays)"},
      {"median_seconds_per_ray", "median over rays of the per-ray time"},
      {"cost_vs_exact", "seconds_per_ray / exact's seconds_per_ray, same run"},
      {"complete", "ran on every ray (no failure) and every channel finite"},
      {"setup_seconds",
       "constructing the integrator for every case (tables); not in seconds_per_ray"},
      {"time_tie_band", kSweepTimeTieBand},
      {"target_choice",
       "the complete setting of least seconds_per_ray whose max (or median) error <= target; "
       "settings within time_tie_band of that time are ties, won by the earliest (smallest knob)"}};
  return {{"tool", "rayint"},
          {"report", "bench"},
          {"format_version", 1},
          {"definitions", definitions},
          {"run",
           {{"started_at", r.started_at},
            {"hardware_threads", r.hardware_threads},
            {"load_average_start", load_json(r.load_start)},
            {"load_average_end", load_json(r.load_end)},
            {"timing",
             {{"batches", r.timing.timing_batches},
              {"batch_seconds", r.timing.timing_batch_seconds},
              {"measured", r.timing.measure_time}}},
            {"max_seconds", r.max_seconds},
            {"method_max_seconds", r.method_max_seconds},
            {"reference_seconds", r.reference_seconds},
            {"measure_seconds", r.measure_seconds},
            {"truncated", r.truncated},
            {"truncation", r.truncation}}},
          {"cases", cases},
          {"rays", r.rays},
          {"pieces", r.pieces},
          {"exact_seconds_per_ray", r.exact_seconds_per_ray},
          {"methods", methods},
          {"targets", targets}};
}

nlohmann::json own_split_json(const OwnSplitRun& run) {
  nlohmann::json cases = nlohmann::json::array();
  for (const OwnSplitCase& c : run.cases) {
    nlohmann::json cells = nlohmann::json::object();
    for (const auto& [type, n] : c.cells) cells[type] = n;
    const double rays = static_cast<double>(c.rays);
    const bool compared = c.compared_rays > 0;
    nlohmann::json j = {
        {"name", c.name},
        {"file", c.source},
        {"mesh_file", c.mesh_source},
        {"cells", cells},
        {"cell_total", c.cell_total},
        {"rays", c.rays},
        {"tets", c.split_ran ? nlohmann::json(c.tets) : nlohmann::json(nullptr)},
        {"structured_split", c.structured_split},
        {"split_ran", c.split_ran},
        {"own_failed_rays", c.own_failed_rays},
        {"split_failed_rays", c.split_failed_rays},
        {"complete", c.complete()},
        {"own_seconds", number_or_null(c.own_seconds)},
        {"split_seconds", c.split_ran ? number_or_null(c.split_seconds) : nlohmann::json(nullptr)},
        {"own_seconds_per_ray", c.rays > 0 ? number_or_null(c.own_seconds / rays) : nlohmann::json(nullptr)},
        {"split_seconds_per_ray",
         c.split_ran && c.rays > 0 ? number_or_null(c.split_seconds / rays) : nlohmann::json(nullptr)},
        {"own_over_split", number_or_null(c.ratio())},
        {"own_setup_seconds", c.own_setup_seconds},
        {"split_setup_seconds", c.split_ran ? nlohmann::json(c.split_setup_seconds) : nlohmann::json(nullptr)},
        {"own_chords", c.own_chords},
        {"split_segments", c.split_segments},
        {"compared_rays", c.compared_rays},
        {"max_abs_difference", compared ? number_or_null(c.max_abs_difference) : nlohmann::json(nullptr)},
        {"max_rel_difference", compared ? number_or_null(c.max_rel_difference) : nlohmann::json(nullptr)},
        {"worst", compared ? nlohmann::json{{"ray", c.worst_ray}, {"channel", c.worst_channel}} : nlohmann::json(nullptr)}};
    if (!c.own_failure.empty()) j["own_failure"] = c.own_failure;
    if (!c.split_failure.empty()) j["split_failure"] = c.split_failure;
    cases.push_back(j);
  }
  const nlohmann::json definitions = {
      {"own", "CellTraversal trace + integrate: the cells in their own (isoparametric) interpolation"},
      {"split", "split_cells (VTK's vtkDataSetTriangleFilter rule) + TetTraversal + exact: --cells split"},
      {"own_seconds", "median over repetitions of the thread CPU time to integrate every ray of the case once, "
                      "single thread, own and split passes interleaved, each timed pass after an untimed one of the same path "
                      "(warm caches); setting up not included (*_setup_seconds)"},
      {"own_over_split", "own_seconds / split_seconds; null unless no ray failed on either path"},
      {"max_abs_difference", "max over rays integrated by both paths and channels of |I_split - I_own|"},
      {"max_rel_difference", "the same of |I_split - I_own| / |I_own| (absolute where I_own = 0)"},
      {"failed_rays", "own: not converged or non-finite; split: threw or non-finite; such rays have no value"}};
  return {{"definitions", definitions},
          {"threads", 1},
          {"clock", "thread CPU time"},
          {"repetitions", run.repetitions},
          {"started_at", run.started_at},
          {"load_average_start", load_json(run.load_start)},
          {"load_average_end", load_json(run.load_end)},
          {"cases", cases}};
}

nlohmann::json own_split_report_json(const OwnSplitRun& run) {
  return {{"tool", "rayint"},
          {"report", "bench"},
          {"format_version", 1},
          {"cases", nlohmann::json::array()},
          {"methods", nlohmann::json::array()},
          {"own_vs_split", own_split_json(run)}};
}

}  // namespace rayint
