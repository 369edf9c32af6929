// Checking the slab solvers against a published benchmark; see slab_benchmark.hpp (the file is
// read by input/slab_benchmark_reader.hpp).
#include "rayint/scattering/slab_benchmark.hpp"

#include "rayint/scattering/slab_run.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <type_traits>


namespace rayint {

const char* quantity_name(SlabQuantity q) {
  switch (q) {
    case SlabQuantity::flux_up_top: return "flux_up_top";
    case SlabQuantity::diffuse_down_bottom: return "diffuse_down_bottom";
    case SlabQuantity::direct_down_bottom: return "direct_down_bottom";
    case SlabQuantity::intensity_up_top: return "intensity_up_top";
    case SlabQuantity::intensity_down_bottom: return "intensity_down_bottom";
  }
  return "?";
}

std::string BenchmarkValue::label() const {
  if (quantity != SlabQuantity::intensity_up_top && quantity != SlabQuantity::intensity_down_bottom)
    return quantity_name(quantity);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s(mu=%g)", quantity_name(quantity), mu);
  return buf;
}

namespace {

// The value a benchmark names, from the doubling values (SlabValues) or the Monte Carlo estimates
// (SlabEstimates): the same members, double or Estimate.
template <class Values>
auto benchmark_value(const Values& v, const BenchmarkValue& b)
    -> std::decay_t<decltype(v.flux_up_top)> {
  switch (b.quantity) {
    case SlabQuantity::flux_up_top: return v.flux_up_top;
    case SlabQuantity::diffuse_down_bottom: return v.diffuse_down_bottom;
    case SlabQuantity::direct_down_bottom: return v.direct_down_bottom;
    case SlabQuantity::intensity_up_top: return v.intensity_up_top[b.detector];
    case SlabQuantity::intensity_down_bottom: return v.intensity_down_bottom[b.detector];
  }
  return {};
}

}  // namespace

const char* BenchmarkRow::verdict_name() const {
  switch (verdict) {
    case Verdict::reproduced: return "reproduced";
    case Verdict::disputed: return "disputed";
    case Verdict::failed: return "FAILED";
  }
  return "?";
}

bool BenchmarkReport::all_pass() const {
  for (const auto& r : rows)
    if (r.verdict == BenchmarkRow::Verdict::failed) return false;
  return !rows.empty();
}

namespace {
// The integral equation, accurate to 1e-6 |published| by its own estimate, agrees with the
// doubling and so also excludes the published value (the doubling already misses it).
bool ie_confirms_doubling(const BenchmarkRow& row) {
  if (!row.has_integral_equation || !row.has_doubling) return false;
  const double scale = 1e-6 * std::fabs(row.value.published);
  return !row.ie_pass && row.ie_error <= scale &&
         std::fabs(row.integral_equation - row.doubling) <= std::max(4 * row.ie_error, scale);
}
}  // namespace

BenchmarkReport run_slab_benchmark(const SlabBenchmark& benchmark, const BenchmarkRunOptions& o,
                                   const std::function<void(const std::string&)>& progress) {
  BenchmarkReport report;
  for (const auto& bp : benchmark.problems) {
    if (progress) progress(bp.id);
    BenchmarkProblemCost cost;
    cost.problem_id = bp.id;
    // The one solver dispatch (slab_run.hpp); a benchmark has no max_order.
    const SlabRun run = run_slab_problem(bp.problem, o);
    cost.doubling_seconds = run.doubling_seconds;
    if (run.integral_equation) {
      cost.ie_seconds = run.integral_equation->seconds;
      cost.ie_segments = run.integral_equation->finest_segments;
    }
    if (run.monte_carlo) {
      cost.mc_seconds = run.monte_carlo->seconds;
      cost.mc_photons = run.monte_carlo->photons;
      cost.mc_collisions = run.monte_carlo->collisions;
    }
    report.costs.push_back(cost);
    for (const auto& v : bp.values) {
      BenchmarkRow row;
      row.problem_id = bp.id;
      row.value = v;
      const double allowed = v.tolerance_rel * std::fabs(v.published);
      if (run.doubling) {
        row.has_doubling = true;
        row.doubling = benchmark_value(*run.doubling, v);
        row.doubling_rel_dev = (row.doubling - v.published) / v.published;
        row.doubling_pass = std::fabs(row.doubling - v.published) <= allowed;
      }
      if (const auto& ie = run.integral_equation) {
        row.has_integral_equation = true;
        row.integral_equation = benchmark_value(ie->values, v);
        row.ie_error = benchmark_value(ie->error_estimate, v);
        row.ie_order = benchmark_value(ie->observed_order, v);
        row.ie_rel_dev = (row.integral_equation - v.published) / v.published;
        row.ie_pass = std::fabs(row.integral_equation - v.published) <= allowed;
      }
      if (run.monte_carlo) {
        row.has_monte_carlo = true;
        row.monte_carlo = benchmark_value(*run.monte_carlo, v);
        row.mc_rel_dev = (row.monte_carlo.mean - v.published) / v.published;
        row.mc_allowed = std::max(allowed, 4 * row.monte_carlo.std_error);
        row.mc_in_95 = row.monte_carlo.covers(v.published);
        row.mc_pass = std::fabs(row.monte_carlo.mean - v.published) <= row.mc_allowed &&
                      4 * row.monte_carlo.std_error <= o.mc_max_rel * std::fabs(v.published);
      }
      using V = BenchmarkRow::Verdict;
      if (row.has_doubling && row.has_monte_carlo) {
        const double four_se = 4 * row.monte_carlo.std_error;
        const bool precise = four_se <= o.mc_max_rel * std::fabs(v.published);
        if (row.doubling_pass && row.mc_pass)
          row.verdict = V::reproduced;
        else if (!row.doubling_pass && precise &&
                 std::fabs(row.doubling - row.monte_carlo.mean) <= four_se &&
                 (std::fabs(v.published - row.monte_carlo.mean) > four_se || ie_confirms_doubling(row)))
          row.verdict = V::disputed;
        else
          row.verdict = V::failed;
      } else if (row.has_doubling && row.has_integral_equation && !row.doubling_pass &&
                 ie_confirms_doubling(row)) {
        row.verdict = V::disputed;
      } else {
        row.verdict = (row.has_doubling ? row.doubling_pass : row.mc_pass) ? V::reproduced : V::failed;
      }
      report.rows.push_back(row);
    }
  }
  return report;
}

}  // namespace rayint
