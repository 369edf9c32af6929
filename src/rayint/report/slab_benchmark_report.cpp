#include "rayint/report/slab_benchmark_report.hpp"

#include <cstdio>

#include "rayint/report/slab_run_json.hpp"
#include "rayint/report/text_format.hpp"

namespace rayint {

std::string slab_benchmark_table(const BenchmarkReport& r, const BenchmarkRunOptions& o) {
  std::string out;
  appendf(out,
          "%-4s %-30s %12s %8s | %12s %10s %4s | %13s %8s %10s | %12s %10s %25s %10s %3s %4s  %s\n",
          "id", "value", "published", "tol", "doubling", "rel dev", "ok", "integral eq", "est err",
          "rel dev", "monte carlo", "rel dev", "95% interval", "4 SE/pub", "in", "ok", "verdict");
  for (const auto& row : r.rows) {
    appendf(out, "%-4s %-30s %12.6g %8.0e | ", row.problem_id.c_str(), row.value.label().c_str(),
            row.value.published, row.value.tolerance_rel);
    if (row.has_doubling)
      appendf(out, "%12.7g %10.2e %4s | ", row.doubling, row.doubling_rel_dev,
              row.doubling_pass ? "yes" : "NO");
    else
      appendf(out, "%12s %10s %4s | ", "-", "-", "-");
    if (row.has_integral_equation)
      appendf(out, "%13.10g %8.1e %10.2e | ", row.integral_equation, row.ie_error, row.ie_rel_dev);
    else
      appendf(out, "%13s %8s %10s | ", "-", "-", "-");
    if (row.has_monte_carlo) {
      const Estimate& e = row.monte_carlo;
      appendf(out, "%12.7g %10.2e [%11.6g,%11.6g] %10.2e %3s %4s  %s\n", e.mean, row.mc_rel_dev,
              e.lo95(), e.hi95(),
              row.value.published != 0 ? 4 * e.std_error / row.value.published : 0.0,
              row.mc_in_95 ? "yes" : "no", row.mc_pass ? "yes" : "NO", row.verdict_name());
    } else {
      appendf(out, "%12s  %s\n", "-", row.verdict_name());
    }
  }
  const BenchmarkTotals t = benchmark_totals(r);
  if (o.doubling)
    out += "doubling: " + std::to_string(o.doubling_options.streams) + " streams per hemisphere, " +
           printf_number("%.3f", t.doubling_seconds) + " s in total\n";
  if (t.ie_finest_segments > 0)
    out += "integral equation (isotropic problems): product integration, meshes " +
           std::to_string(o.ie_options.segments) + "-" + std::to_string(t.ie_finest_segments) +
           " segments, Richardson; est err = change of the extrapolation with the last mesh; " +
           printf_number("%.3f", t.ie_seconds) + " s in total\n";
  if (o.monte_carlo)
    out += std::string(o.mc_split ? "monte carlo (exact orders 0-1 + MC orders >= 2)"
                                  : "monte carlo (analog)") + ": seed " + std::to_string(o.mc_options.seed) + ", " +
           std::to_string(t.mc_photons) + " photons, " + std::to_string(t.mc_collisions) + " collisions, " +
           printf_number("%.2f", t.mc_seconds) + " s wall, " +
           printf_number("%.3g", static_cast<double>(t.mc_photons) / t.mc_seconds) + " photons/s\n";
  out += std::string("acceptance: doubling |dev| <= tol*|published|; monte carlo |dev| <= "
                     "max(tol*|published|, 4 SE) and 4 SE <= ") +
         printf_number("%g", o.mc_max_rel) + "*|published|\n";
  out += "disputed: the published value misses its tolerance, doubling and Monte Carlo agree within 4 SE, "
         "and the Monte Carlo excludes the published value by more than 4 SE or the integral equation "
         "(est err <= 1e-6 rel) agrees with the doubling and so excludes it too\n";
  out += std::to_string(t.reproduced) + " reproduced, " + std::to_string(t.disputed) + " disputed, " +
         std::to_string(t.failed) + " failed of " + std::to_string(r.rows.size()) + " values\n";
  return out;
}

nlohmann::json slab_benchmark_json(const SlabBenchmark& b, const BenchmarkReport& r,
                                   const BenchmarkRunOptions& o) {
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& row : r.rows) {
    nlohmann::json j = {{"id", row.problem_id},
                        {"value", row.value.label()},
                        {"published", row.value.published},
                        {"tolerance_rel", row.value.tolerance_rel},
                        {"verdict", row.verdict_name()}};
    if (row.has_doubling)
      j["doubling"] = {{"value", row.doubling}, {"rel_dev", row.doubling_rel_dev},
                       {"pass", row.doubling_pass}};
    if (row.has_integral_equation)
      j["integral_equation"] = {{"value", row.integral_equation}, {"error_estimate", row.ie_error},
                                {"observed_order", row.ie_order}, {"rel_dev", row.ie_rel_dev},
                                {"pass", row.ie_pass}};
    if (row.has_monte_carlo) {
      j["monte_carlo"] = to_json(row.monte_carlo);
      j["monte_carlo"]["rel_dev"] = row.mc_rel_dev;
      j["monte_carlo"]["allowed_abs"] = row.mc_allowed;
      j["monte_carlo"]["in_95"] = row.mc_in_95;
      j["monte_carlo"]["pass"] = row.mc_pass;
    }
    rows.push_back(j);
  }
  nlohmann::json costs = nlohmann::json::array();
  for (const auto& c : r.costs)
    costs.push_back({{"id", c.problem_id}, {"doubling_seconds", c.doubling_seconds},
                     {"ie_seconds", c.ie_seconds}, {"ie_finest_segments", c.ie_segments},
                     {"mc_seconds", c.mc_seconds}, {"mc_photons", c.mc_photons},
                     {"mc_collisions", c.mc_collisions}});
  return {{"benchmark_source", b.source},
          {"doubling_streams", o.doubling_options.streams},
          {"ie_segments", o.integral_equation ? o.ie_options.segments : 0},
          {"ie_levels", o.ie_options.levels},
          {"mc_seed", o.mc_options.seed},
          {"mc_photons_per_problem", o.mc_options.photons},
          {"mc_threads", o.mc_options.threads},
          {"mc_estimator", o.mc_split ? "exact orders 0-1 + MC orders >= 2" : "analog"},
          {"mc_max_rel", o.mc_max_rel},
          {"rows", rows},
          {"costs", costs},
          {"all_pass", r.all_pass()}};
}

}  // namespace rayint
