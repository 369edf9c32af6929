// The accuracy/cost sweep behind `rayint bench` and reports/ (studies/sweep.hpp): its table
// covers the registry, its errors fall along every knob on a smooth case, its "cheapest setting"
// is the least-time setting meeting a target, and a budget that runs out is recorded.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <string>

#include "test_paths.hpp"
#include "rayint/report/sweep_table.hpp"
#include "rayint/studies/sweep.hpp"
#include "rayint/input/case_reader.hpp"
#include "rayint/report/sweep_json.hpp"

using namespace rayint;

namespace {

Case smooth_case() {
  return read_case_file(std::string(RAYINT_SOURCE_DIR) + "/cases/smooth-convergence.json");
}

const SweepAxis& axis_of(const std::string& method) {
  for (const auto& a : sweep_table())
    if (a.method == method) return a;
  FAIL("no sweep axis for " << method);
  throw;  // unreachable
}

SettingResult fake_setting(const std::string& label, double max_error, double median_error,
                           double seconds) {
  SettingResult s;
  s.label = label;
  s.rays = 4;
  s.channels = 12;
  s.max_error = max_error;
  s.median_error = median_error;
  s.seconds_per_ray = seconds;
  return s;
}

// Below this the errors of a double-precision method sit on rounding noise (~1e4 ulps of
// accumulated round-off over 10^5 steps), where "decreasing" means nothing.
constexpr double kRoundoffFloor = 1e-12;

}  // namespace

TEST_CASE("the sweep table covers every registered method, each setting a valid spec", "[sweep]") {
  const auto& table = sweep_table();
  for (const auto& name : method_names()) {
    INFO("method " << name);
    CHECK(std::count_if(table.begin(), table.end(),
                        [&](const SweepAxis& a) { return a.method == name; }) == 1);
  }
  CHECK(table.size() == method_names().size());
  CHECK(table.front().method == "exact");  // the unit of cost runs first
  for (const auto& a : table) {
    INFO("method " << a.method);
    const auto specs = a.settings();  // parse_method_spec rejects a knob the method lacks
    CHECK(specs.size() == (a.knob.empty() ? 1u : a.values.size()));
    if (!a.knob.empty()) CHECK(a.values.size() >= 7);
  }
  // The ranges the issue asks for.
  CHECK(axis_of("riemann").values.front() == "1");
  CHECK(axis_of("riemann").values.back() == "65536");
  CHECK(axis_of("rk4").values.size() == 17);
  CHECK(axis_of("ode").values.front() == "1e-2");
  CHECK(axis_of("ode").values.back() == "1e-13");
  CHECK(axis_of("preintegrated").values.front() == "32");
  CHECK(axis_of("psi_table").values.back() == "2048");
}

TEST_CASE("select_sweep_axes keeps table order, always includes exact, rejects unknown names",
          "[sweep]") {
  const auto axes = select_sweep_axes({"riemann", "ode"});
  REQUIRE(axes.size() == 3);
  CHECK(axes[0].method == "exact");
  CHECK(axes[1].method == "riemann");
  CHECK(axes[2].method == "ode");
  CHECK(select_sweep_axes({}).size() == sweep_table().size());
  CHECK_THROWS_AS(select_sweep_axes({"simpson"}), std::invalid_argument);
}

TEST_CASE("scored error: relative, absolute in units of 1e-290 below it, inf if non-finite",
          "[sweep]") {
  CHECK(scored_error(1.0, ExtendedValue{1.0, 0.0}) == 0.0);
  CHECK(scored_error(1.5, ExtendedValue{1.0, 0.0}) == Approx(0.5));
  CHECK(scored_error(2.0, ExtendedValue{4.0, 0.0}) == Approx(0.5));
  // reference 0 (nothing emitted, black background): absolute error / 1e-290
  CHECK(scored_error(1e-300, ExtendedValue{0.0, 0.0}) == Approx(1e-10));
  CHECK(scored_error(0.0, ExtendedValue{0.0, 0.0}) == 0.0);
  // a reference past underflow
  CHECK(scored_error(0.0, ExtendedValue{1e-320, 0.0}) <= 1e-29);
  CHECK(std::isinf(scored_error(std::nan(""), ExtendedValue{1.0, 0.0})));
  CHECK(std::isinf(scored_error(INFINITY, ExtendedValue{1.0, 0.0})));
}

TEST_CASE("errors fall along every knob on a smooth case", "[sweep]") {
  const std::vector<Case> cases = {smooth_case()};
  std::vector<SweepAxis> axes;
  for (const auto& a : sweep_table())
    if (!a.knob.empty()) axes.push_back(a);
  SweepOptions opt;
  opt.timing.measure_time = false;  // errors only; the timing loop is not under test here
  const SweepResult r = run_sweep(cases, axes, opt);
  REQUIRE(r.methods.size() == axes.size());
  CHECK(!r.truncated);
  for (const auto& m : r.methods) {
    INFO("method " << m.method);
    REQUIRE(m.settings.size() == axis_of(m.method).values.size());
    for (const auto& s : m.settings) {
      INFO(s.label << ": " << s.failure);
      CHECK(s.complete());
      CHECK(s.channels == 3 * cases.front().rays.size());
    }
    // Monotone (max error) until the round-off floor, and a real overall drop.
    for (std::size_t k = 1; k < m.settings.size(); ++k) {
      const double prev = m.settings[k - 1].max_error, next = m.settings[k].max_error;
      if (prev <= kRoundoffFloor) break;
      INFO(m.settings[k - 1].label << " " << prev << " -> " << m.settings[k].label << " " << next);
      CHECK(next <= prev);
    }
    CHECK(m.settings.back().max_error < m.settings.front().max_error / 100);
  }
}

TEST_CASE("cheapest setting: least time among complete settings meeting the target", "[sweep]") {
  MethodSweep m;
  m.method = "riemann";
  m.knob = "n";
  m.settings = {fake_setting("riemann:n=1", 1e-2, 1e-3, 1e-7),
                fake_setting("riemann:n=2", 1e-4, 1e-5, 2e-7),
                fake_setting("riemann:n=4", 1e-7, 1e-8, 5e-7),  // meets 1e-6 ...
                fake_setting("riemann:n=8", 5e-7, 1e-9, 3e-7),  // ... so does this, cheaper
                fake_setting("riemann:n=16", 1e-12, 1e-13, 4e-6)};
  CHECK(cheapest_setting(m, 1e-3, ErrorStatistic::max) == std::optional<std::size_t>(1));
  CHECK(cheapest_setting(m, 1e-6, ErrorStatistic::max) == std::optional<std::size_t>(3));
  CHECK(cheapest_setting(m, 1e-10, ErrorStatistic::max) == std::optional<std::size_t>(4));
  CHECK(!cheapest_setting(m, 1e-13, ErrorStatistic::max));
  CHECK(cheapest_setting(m, 1e-3, ErrorStatistic::median) == std::optional<std::size_t>(0));
  CHECK(cheapest_setting(m, 1e-1, ErrorStatistic::max) == std::optional<std::size_t>(0));

  SECTION("incomplete settings never qualify") {
    m.settings[3].nonfinite = 1;  // its max error would be +inf in a real sweep; not needed here
    CHECK(cheapest_setting(m, 1e-6, ErrorStatistic::max) == std::optional<std::size_t>(2));
    m.settings[2].failed_rays = 1;
    CHECK(cheapest_setting(m, 1e-6, ErrorStatistic::max) == std::optional<std::size_t>(4));
  }
  SECTION("times within the tie band go to the smallest knob") {
    m.settings[2].seconds_per_ray = 3e-7 * (1.0 + kSweepTimeTieBand / 2);
    CHECK(cheapest_setting(m, 1e-6, ErrorStatistic::max) == std::optional<std::size_t>(2));
    m.settings[2].seconds_per_ray = 3e-7 * (1.0 + 2 * kSweepTimeTieBand);
    CHECK(cheapest_setting(m, 1e-6, ErrorStatistic::max) == std::optional<std::size_t>(3));
  }
  SECTION("target table: one row per target x statistic x method, cost in units of exact") {
    const auto rows = target_table({m}, 1e-7, {1e-3, 1e-14});
    REQUIRE(rows.size() == 4);
    CHECK(rows[0].statistic == ErrorStatistic::max);
    CHECK(rows[0].reached);
    CHECK(rows[0].label == "riemann:n=2");
    CHECK(rows[0].cost_vs_exact == Approx(2.0));
    CHECK(rows[1].statistic == ErrorStatistic::median);
    CHECK(rows[1].label == "riemann:n=1");
    CHECK(!rows[2].reached);
    CHECK(!rows[3].reached);
  }
}

TEST_CASE("a budget that runs out stops the sweep cleanly and is recorded", "[sweep]") {
  const std::vector<Case> cases = {smooth_case()};
  SECTION("the whole-sweep budget: everything after it is skipped") {
    SweepOptions opt;
    opt.timing.measure_time = false;
    opt.max_seconds = 1e-9;
    const SweepResult r = run_sweep(cases, select_sweep_axes({"riemann"}), opt);
    CHECK(r.truncated);
    CHECK(r.truncation.find("--max-seconds") != std::string::npos);
    REQUIRE(r.methods.size() == 2);
    CHECK(!r.methods[0].truncated);  // exact, the unit of cost, is exempt
    CHECK(r.methods[0].settings.size() == 1);
    const MethodSweep& riemann = r.methods[1];
    CHECK(riemann.truncated);
    CHECK(riemann.settings.empty());
    CHECK(riemann.skipped.size() == axis_of("riemann").settings().size());
    const auto j = sweep_report_json(r);
    CHECK(j["run"]["truncated"] == true);
    CHECK(j["methods"][1]["skipped"].size() == 17);
  }
  SECTION("the per-method budget: the expensive tail is skipped, other methods run") {
    SweepOptions opt;
    opt.timing.timing_batches = 3;
    opt.timing.timing_batch_seconds = 1e-3;
    opt.method_max_seconds = 0.05;  // riemann needs > 0.1 s for n = 1 .. 65536 when timed
    std::vector<std::string> progress;
    opt.progress = [&](const SweepProgress& p) {
      if (p.stage == SweepProgress::Stage::skipped) progress.push_back(p.what);
    };
    const SweepResult r = run_sweep(cases, select_sweep_axes({"riemann"}), opt);
    REQUIRE(r.methods.size() == 2);
    const MethodSweep& exact = r.methods[0];
    const MethodSweep& riemann = r.methods[1];
    CHECK(!exact.truncated);
    CHECK(exact.settings.size() == 1);
    CHECK(r.exact_seconds_per_ray > 0);
    CHECK(riemann.truncated);
    CHECK(r.truncated);
    CHECK(riemann.truncation.find("--method-seconds") != std::string::npos);
    CHECK(!riemann.skipped.empty());
    CHECK(riemann.settings.size() + riemann.skipped.size() == 17);
    CHECK(riemann.skipped.back() == "riemann:n=65536");  // the tail, in order
    CHECK(progress == riemann.skipped);
    for (const auto& s : riemann.settings) CHECK(s.complete());  // nothing half-measured
    // A target only the skipped tail could reach is "not reached", flagged as truncated.
    const auto rows = target_table(r.methods, r.exact_seconds_per_ray, {1e-30});
    CHECK(!rows[1].reached);
    CHECK(rows[1].truncated);
  }
}

TEST_CASE("A bench progress line shows a setting that failed on every ray without numbers", "[sweep][failure]") {
  rayint::SettingResult failed;
  failed.label = "particle";
  failed.rays = 3;
  failed.failed_rays = 3;  // no channel scored
  rayint::SweepProgress p;
  p.stage = rayint::SweepProgress::Stage::setting;
  p.what = failed.label;
  p.done = 1;
  p.total = 1;
  p.setting = &failed;
  const std::string line = rayint::sweep_progress_line(p);
  INFO(line);
  CHECK(line.find("max -") != std::string::npos);
  CHECK(line.find("median -") != std::string::npos);
  CHECK(line.find("failed on 3 rays") != std::string::npos);
  CHECK(line.find("0.00e+00") == std::string::npos);
  failed.channels = 3;  // one ray ran: its numbers are shown
  failed.failed_rays = 2;
  failed.max_error = 1.5e-3;
  CHECK(rayint::sweep_progress_line(p).find("max 1.50e-03") != std::string::npos);
}

TEST_CASE("bench own vs split: failed rays give no ratio, no compared ray no difference", "[sweep][bench][failure]") {
  using namespace rayint;
  OwnSplitRun run;
  run.repetitions = 3;
  run.load_start = run.load_end = {-1.0, -1.0, -1.0};
  OwnSplitCase c;
  c.name = "hexes";
  c.cells = {{"hexahedron", 8}};
  c.cell_total = 8;
  c.split_ran = true;
  c.tets = 40;
  c.rays = 10;
  c.own_seconds = 4e-3;
  c.split_seconds = 1e-3;
  c.compared_rays = 7;
  c.max_abs_difference = 0.25;
  c.max_rel_difference = 0.5;
  c.own_failed_rays = 3;
  c.own_failure = "a cell's chord could not be located";
  run.cases.push_back(c);
  c.name = "none";
  c.own_failed_rays = 10;
  c.compared_rays = 0;
  run.cases.push_back(c);
  c.name = "whole";
  c.own_failed_rays = 0;
  c.own_failure.clear();
  c.compared_rays = 10;
  run.cases.push_back(c);
  const nlohmann::json j = own_split_report_json(run);
  const auto& cases = j["own_vs_split"]["cases"];
  REQUIRE(cases.size() == 3);
  CHECK(cases[0]["complete"] == false);
  CHECK(cases[0]["own_over_split"].is_null());  // the failed rays' time is not the mesh's
  CHECK(cases[0]["own_failed_rays"] == 3);
  CHECK(cases[0]["max_abs_difference"] == 0.25);  // over the 7 rays both paths integrated
  CHECK(cases[1]["max_abs_difference"].is_null());
  CHECK(cases[1]["max_rel_difference"].is_null());
  CHECK(cases[1]["worst"].is_null());
  CHECK(cases[2]["complete"] == true);
  CHECK(cases[2]["own_over_split"] == 4.0);
  CHECK(j["own_vs_split"]["load_average_start"].is_null());
  const std::string table = own_split_table(run);
  CHECK(table.find("failed: hexes: own on 3 of 10 rays (first: a cell's chord could not be located)") != std::string::npos);
  CHECK(table.find("failed: none: own on 10 of 10 rays") != std::string::npos);
  CHECK(table.find("failed: whole") == std::string::npos);
}
