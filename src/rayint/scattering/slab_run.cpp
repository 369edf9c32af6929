#include "rayint/scattering/slab_run.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "rayint/scattering/slab_single_scattering.hpp"

namespace rayint {

SlabRun run_slab_problem(const SlabProblem& p, const BenchmarkRunOptions& o) {
  SlabRun run;
  run.options = o;
  const int max_order = o.mc_options.max_order;
  const bool ground = p.ground_albedo > 0;
  if (ground && max_order != 0)
    throw std::invalid_argument("--max-order: truncated orders need a black ground (ground albedo 0)");
  if (o.doubling && max_order == 0) {
    const auto t0 = std::chrono::steady_clock::now();
    run.doubling = solve_slab_doubling(p, o.doubling_options);
    run.doubling_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  if (o.integral_equation && max_order == 0 && !ground && p.phase.kind() == PhaseFunction::Kind::isotropic)
    run.integral_equation = solve_slab_integral_equation(p, o.ie_options);
  if (o.pn && max_order == 0) {
    const auto t0 = std::chrono::steady_clock::now();
    run.pn = solve_slab_pn(p, o.pn_options);
    run.pn_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  if (max_order == 1) run.single_scattering_closed_form = single_scattering(p);
  if (o.monte_carlo) {
    run.mc_split = o.mc_split && max_order != 1 && !ground;
    run.monte_carlo = run.mc_split ? solve_slab_monte_carlo_split(p, o.mc_options)
                                   : solve_slab_monte_carlo(p, o.mc_options);
  }
  return run;
}

void select_benchmark_problems(SlabBenchmark& b, const std::vector<std::string>& ids,
                               const std::string& source_name) {
  if (ids.empty()) return;
  std::vector<BenchmarkProblem> kept;
  for (const auto& id : ids) {
    bool found = false;
    for (const auto& p : b.problems)
      if (p.id == id) {
        kept.push_back(p);
        found = true;
      }
    if (!found) throw std::invalid_argument("no problem '" + id + "' in " + source_name);
  }
  b.problems = kept;
}

BenchmarkTotals benchmark_totals(const BenchmarkReport& r) {
  BenchmarkTotals t;
  for (const auto& c : r.costs) {
    t.ie_seconds += c.ie_seconds;
    t.ie_finest_segments = std::max(t.ie_finest_segments, c.ie_segments);
    t.mc_photons += c.mc_photons;
    t.mc_collisions += c.mc_collisions;
    t.mc_seconds += c.mc_seconds;
    t.doubling_seconds += c.doubling_seconds;
  }
  for (const auto& row : r.rows) {
    if (row.verdict == BenchmarkRow::Verdict::reproduced) ++t.reproduced;
    if (row.verdict == BenchmarkRow::Verdict::disputed) ++t.disputed;
    if (row.verdict == BenchmarkRow::Verdict::failed) ++t.failed;
  }
  return t;
}

}  // namespace rayint
