#pragma once
// The sweep (studies/sweep.hpp) as JSON: the file `rayint bench` writes (reports/bench.json) and
// reports/make_report.py reads. Non-finite numbers are written as null, as in evaluation_json.
// Layout (all times in seconds; "definitions" spells out every statistic):
//   {"tool": "rayint", "report": "bench", "format_version": 1, "definitions": {...},
//    "run": {started_at, hardware_threads, load_average_start/end, timing, budgets,
//            reference_seconds, measure_seconds, truncated, truncation},
//    "cases": [{name, file, rays, pieces}], "rays": N, "pieces": N,
//    "exact_seconds_per_ray": t,
//    "methods": [{method, knob, truncated, truncation, skipped: [...],
//                 settings: [{label, knob_value, rays, failed_rays, channels, nonfinite,
//                             complete, max_error, median_error, seconds_per_ray,
//                             median_seconds_per_ray, cost_vs_exact, worst: {case, ray, channel},
//                             failure, setup_seconds, wall_seconds, per_case: [...]}]}],
//    "targets": [{target, statistic, method, reached, label, error, seconds_per_ray,
//                 cost_vs_exact, truncated}]}
#include <nlohmann/json.hpp>

#include "rayint/studies/sweep.hpp"

namespace rayint {

nlohmann::json to_json(const SettingResult& s, double exact_seconds_per_ray);
nlohmann::json to_json(const MethodSweep& m, double exact_seconds_per_ray);
nlohmann::json to_json(const TargetChoice& t);
nlohmann::json sweep_report_json(const SweepResult& r);

}  // namespace rayint
