#pragma once
// The accuracy/cost sweep behind `rayint bench` and reports/: every method of the registry, swept
// along its accuracy knob (Riemann and RK4 steps per segment, ODE tolerance, table size), run on
// every ray of a case set, scored against the 50-digit reference of Williams & Max (1992) Eq. 4
// (reference/reference.hpp) and timed. Returns plain structs; report/sweep_json turns them into JSON.
//
// Definitions (reports/README.md quotes them):
//  - Error of one channel of one ray: the scored error
//        e = |I - I_ref| / max(|I_ref|, kUnderflowFloor)   (scored_error, metrics/error_metrics.hpp),
//    i.e. the relative error, except where the reference intensity is below 1e-290 (at and past
//    double underflow, e.g. thick-absorber-background), where the absolute error is measured in
//    units of 1e-290 -- the same threshold tests/test_exact.cpp uses to switch from its relative
//    to its absolute criterion. A non-finite I has e = +inf. |I - I_ref| uses the reference's
//    hi + lo (error_metrics.hpp), so errors far below one ulp are resolved.
//  - max_error / median_error of a setting: over all channels of all rays of the case set that the
//    method ran on (3 per ray). The median of an even count is the mean of the two middle values
//    (median, core/statistics.hpp).
//  - Time of one ray: time_per_ray (studies/evaluate.hpp): median over `timing_batches` batches,
//    each repeating integrate(ray, nullptr) for at least `timing_batch_seconds` -- single thread,
//    no diagnostics, no reference in the loop (references are computed once, before any timing).
//  - seconds_per_ray of a setting: the MEAN over rays of the per-ray times, i.e. the time to
//    integrate the whole case set once divided by its number of rays; median_seconds_per_ray is
//    the median over rays, for comparison. Cost multiples ("x exact") use the mean.
//  - A setting is complete when it ran on every ray (no failure, e.g. particle on a case with
//    colour varying) and every channel is finite; only complete settings can meet a target.
//  - The cheapest setting of a method for a target error is the complete setting of least
//    seconds_per_ray whose max_error (or median_error) is <= the target; settings within
//    kSweepTimeTieBand (10%) of that least time count as ties, and the earliest in table order
//    (the smallest knob) wins, so timing noise does not pick a needlessly large table.
//  - setup_seconds: constructing the integrator for every case (tables are built there); not
//    part of seconds_per_ray, reported beside it.
#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "rayint/core/shard.hpp"
#include "rayint/studies/evaluate.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/metrics/error_metrics.hpp"  // scored_error, the error of one channel
#include "rayint/model/ray.hpp"
#include "rayint/reference/reference.hpp"

namespace rayint {

// Relative time difference below which two settings' costs count as equal (timing noise on a
// shared machine: repeated runs of one setting differ by a few percent to ~10%).
inline constexpr double kSweepTimeTieBand = 0.10;

// The error targets the report answers "what does it take" for (issue: 1e-3, 1e-6, 1e-10).
inline const std::vector<double>& sweep_targets() {
  static const std::vector<double> targets = {1e-3, 1e-6, 1e-10};
  return targets;
}

// One row of the sweep table: a method and the values of its accuracy knob, cheapest first.
struct SweepAxis {
  std::string method;               // registry name
  std::string knob;                 // swept parameter; empty for a method without a knob
  std::vector<std::string> values;  // the knob's values, cheapest first; empty without a knob
  std::vector<MethodSpec> settings() const;  // one spec per value (one spec if no knob)
};

// THE sweep table: every method of the registry, in the order the sweep runs them (exact first:
// it is the unit of cost). Riemann and RK4: n = 1 .. 65536 steps per segment (powers of two);
// ODE: rtol = 1e-2 .. 1e-13 (atol at its default); tables: size = 32 .. 2048 (powers of two);
// the other methods have no knob and one setting.
const std::vector<SweepAxis>& sweep_table();
// Appends an axis (optional libraries, e.g. src/rayint/vtk/); call before any sweep runs.
void register_sweep_axis(const SweepAxis& axis);

// The rows of the table for these method names, in table order, with exact always included
// (the baseline of every cost multiple). Empty `methods` = the whole table. Throws
// std::invalid_argument for a name that is not in the table.
std::vector<SweepAxis> select_sweep_axes(const std::vector<std::string>& methods);

// Scores of one setting restricted to one case.
struct CaseScore {
  std::string name;
  std::size_t rays = 0, failed_rays = 0, nonfinite = 0;
  double max_error = 0.0, median_error = 0.0;
  double seconds_per_ray = 0.0;  // mean over the case's timed rays
};

struct SettingResult {
  std::string label;            // MethodSpec::label(), e.g. "riemann:n=64"
  std::string knob_value;       // "" for a method without a knob
  std::size_t rays = 0;         // rays of the case set
  std::size_t failed_rays = 0;  // the method threw (at construction or on the ray)
  std::size_t channels = 0;     // channels scored (3 per ray that ran)
  std::size_t nonfinite = 0;    // channels with a non-finite intensity
  double max_error = 0.0;       // over scored channels (+inf if any is non-finite)
  double median_error = 0.0;
  double seconds_per_ray = 0.0;         // mean over timed rays (0 when timing is off)
  double median_seconds_per_ray = 0.0;  // median over timed rays
  std::string worst_case;               // where max_error occurs
  std::size_t worst_ray = 0;
  int worst_channel = 0;
  std::string failure;  // first failure message, if any
  std::vector<CaseScore> per_case;
  double setup_seconds = 0.0;  // make_integrator over all cases (table construction)
  double wall_seconds = 0.0;   // how long set-up, scoring and timing this setting took

  bool complete() const { return failed_rays == 0 && nonfinite == 0 && channels > 0; }
};

struct MethodSweep {
  std::string method, knob;
  std::vector<SettingResult> settings;  // measured, in table order
  std::vector<std::string> skipped;     // labels not measured because a budget ran out
  bool truncated = false;
  std::string truncation;  // why, if truncated
};

enum class ErrorStatistic { max, median };
const char* statistic_name(ErrorStatistic s);

// The cheapest setting of one method meeting one target (see the file comment).
struct TargetChoice {
  double target = 0.0;
  ErrorStatistic statistic = ErrorStatistic::max;
  std::string method;
  bool reached = false;
  std::string label;   // of the chosen setting (empty if not reached)
  double error = 0.0;  // its max or median error
  double seconds_per_ray = 0.0;
  double cost_vs_exact = 0.0;  // seconds_per_ray / exact's seconds_per_ray (0 if unknown)
  bool truncated = false;      // the method's sweep was cut short: a setting not measured
                               // might have reached the target
};

struct SweepResult {
  std::vector<std::string> case_names, case_files;
  std::vector<std::size_t> case_rays, case_pieces;  // pieces: after splitting at breakpoints
  std::size_t rays = 0, pieces = 0;
  std::vector<MethodSweep> methods;
  EvalOptions timing;
  double max_seconds = 0.0, method_max_seconds = 0.0;  // budgets used (0 = none)
  double reference_seconds = 0.0;                      // computing the references (parallel)
  double measure_seconds = 0.0;                        // scoring + timing every setting
  bool truncated = false;  // some method or the whole sweep ran out of budget
  std::string truncation;  // the first reason
  unsigned hardware_threads = 0;
  std::array<double, 3> load_start{}, load_end{};  // 1/5/15-minute load averages (-1: unknown)
  std::string started_at;                          // UTC, ISO 8601
  double exact_seconds_per_ray = 0.0;              // 0 if exact was not measured
  std::vector<TargetChoice> targets;               // sweep_targets() x {max, median} x methods
};

struct SweepProgress {
  enum class Stage { reference, setting, skipped } stage = Stage::setting;
  std::string what;      // case name (reference) or setting label
  std::size_t done = 0;  // cases or settings finished so far
  std::size_t total = 0;
  double elapsed_seconds = 0.0;            // since the sweep started
  const SettingResult* setting = nullptr;  // the finished setting (Stage::setting)
  std::string reason;                      // Stage::skipped: which budget ran out
};

struct SweepOptions {
  EvalOptions timing;               // batches, batch length, measure_time, reference threads
  double max_seconds = 0.0;         // budget for measuring all settings (after the references);
                                    // 0 = none. Checked before each ray of each setting.
  double method_max_seconds = 0.0;  // the same budget per method; 0 = none
  // Called on the sweep's thread after each reference case and each setting; may be empty.
  std::function<void(const SweepProgress&)> progress;
};

// The 1/5/15-minute load averages (-1 each when unknown) and the time now, UTC ISO 8601: what
// every bench report records around its timing.
std::array<double, 3> load_average();
std::string utc_now();

// Runs `axes` on every ray of `cases`. The reference of each ray is computed once, up front, in
// parallel, and reused for every setting. When a budget runs out the setting being measured is
// dropped (never reported half-measured), the remaining settings are listed as skipped and the
// method (or the whole sweep) is marked truncated. `exact` is exempt from the budgets (it is
// the unit of cost, and cheap), though its time counts against --max-seconds. `cases` must
// outlive the call.
SweepResult run_sweep(const std::vector<Case>& cases, const std::vector<SweepAxis>& axes,
                      const SweepOptions& options);

// --- Shards (`rayint bench --shard I/N`, README "Shards and merge") ---------------------------
// Shard I of N measures every setting on the rays shard_range(R, I/N) of the case set's R rays
// (numbered case by case, in order) and keeps what each ray measured; the merge concatenates the
// shards' rays in order and summarises them with the code the single run uses, so every error
// figure, count and worst case is identical, and each time is the same statistic (mean, median)
// over the same per-ray times (each measured once, in whichever shard owns the ray).

// What one setting measured on one ray.
struct SweepRaySample {
  bool failed = false;                    // the method threw on the ray (no errors)
  std::string failure;                    // its message
  std::array<double, kChannels> error{};  // scored_error per channel
  unsigned nonfinite = 0;                 // bit c: channel c's intensity was not finite
  double seconds = 0.0;                   // time_per_ray (0 when timing is off)
};
// What one setting measured on the rays of one case that a part covers.
struct SweepCaseSamples {
  std::size_t first_ray = 0;  // the rays [first_ray, first_ray + covered) of the case
  std::size_t covered = 0;
  bool setup_failed = false;  // make_integrator threw (then `rays` is empty)
  std::string setup_failure;  // its message
  double setup_seconds = 0.0;
  std::vector<SweepRaySample> rays;
  // Joined parts of a partial merge (a shard missing): the ray number of each of `rays` (empty:
  // first_ray, first_ray + 1, ...).
  std::vector<std::size_t> ray_numbers;
};
struct SweepSettingSamples {
  std::vector<SweepCaseSamples> cases;  // one per case of the set (covered = 0 if none of its rays)
  double wall_seconds = 0.0;
};
struct SweepPart {
  std::vector<std::vector<SweepSettingSamples>> methods;  // per axis, per setting
  double reference_seconds = 0.0, measure_seconds = 0.0;
  unsigned hardware_threads = 0;
  std::array<double, 3> load_start{}, load_end{};
  std::string started_at;
};

// Shard `shard` of run_sweep. Budgets (max_seconds, method_max_seconds) depend on the clock, so
// a sharded sweep cannot have one: std::invalid_argument.
SweepPart run_sweep_part(const std::vector<Case>& cases, const std::vector<SweepAxis>& axes,
                         const SweepOptions& options, const ShardSpec& shard);
// The rays [begin, end) of each case that shard `shard` of the run measures (the cases' rays
// taken as one list, shard_range of it): what a part's first_ray and covered must be.
std::vector<IndexRange> sweep_shard_rays(const std::vector<Case>& cases, const ShardSpec& shard);
// The sweep's result from its parts in shard order (a missing shard: leave it out). The run's
// time fields: reference_seconds and measure_seconds are the sums over the parts, started_at
// and load_start the first part's, load_end the last part's, hardware_threads the largest.
SweepResult finish_sweep(const std::vector<Case>& cases, const std::vector<SweepAxis>& axes,
                         const SweepOptions& options, const std::vector<SweepPart>& parts);

// Index into m.settings of the cheapest complete setting whose error statistic is <= target.
std::optional<std::size_t> cheapest_setting(const MethodSweep& m, double target,
                                            ErrorStatistic statistic);

// The target table: for each target, each statistic (max then median) and each method.
std::vector<TargetChoice> target_table(const std::vector<MethodSweep>& methods,
                                       double exact_seconds_per_ray,
                                       const std::vector<double>& targets);

}  // namespace rayint
