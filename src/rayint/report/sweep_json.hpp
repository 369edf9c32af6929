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

#include "rayint/studies/own_split_bench.hpp"
#include "rayint/studies/sweep.hpp"

namespace rayint {

nlohmann::json to_json(const SettingResult& s, double exact_seconds_per_ray);
nlohmann::json to_json(const MethodSweep& m, double exact_seconds_per_ray);
nlohmann::json to_json(const TargetChoice& t);
nlohmann::json sweep_report_json(const SweepResult& r);

// Mesh cases of cells other than tetrahedra (studies/own_split_bench.hpp): the report's
// "own_vs_split" member --
//   {"definitions": {...}, "threads": 1, "repetitions": n, "started_at", "load_average_start/end",
//    "cases": [{name, file, mesh_file, cells: {type: count}, cell_total, rays, tets,
//               structured_split, split_ran, split_failure, own_failed_rays, own_failure,
//               split_failed_rays, complete, own_seconds, split_seconds, own_seconds_per_ray,
//               split_seconds_per_ray, own_over_split, own_setup_seconds, split_setup_seconds,
//               own_chords, split_segments, compared_rays, max_abs_difference,
//               max_rel_difference, worst: {ray, channel}}]}
// own_over_split is null unless the case is complete (no failed ray on either path); the
// differences are null when no ray ran on both paths; split_seconds null without a split.
nlohmann::json own_split_json(const OwnSplitRun& run);
// The whole bench report when every case is of that kind (no sweep): tool, report,
// format_version, "cases": [] and "methods": [] (nothing swept), and "own_vs_split".
nlohmann::json own_split_report_json(const OwnSplitRun& run);

}  // namespace rayint
