#include "rayint/report/convergence_json.hpp"

#include <cmath>

#include "rayint/report/json_number.hpp"

namespace rayint {

namespace {

nlohmann::json fit_json(const OrderFit& f, const ConvergenceResult& r) {
  nlohmann::json j;
  j["order"] = f.ok ? number_or_null(f.order) : nlohmann::json(nullptr);
  if (!f.ok) j["reason"] = f.reason;
  if (f.ok) j["steps_used"] = {r.rows[f.first].step, r.rows[f.last].step};
  nlohmann::json local = nlohmann::json::array();
  for (double x : f.local_orders) local.push_back(number_or_null(x));
  j["local_orders"] = local;
  return j;
}

}  // namespace

nlohmann::json convergence_json(const ConvergenceResult& r) {
  nlohmann::json rows = nlohmann::json::array();
  for (const ConvergenceRow& row : r.rows) {
    nlohmann::json j{{"step", row.step}, {"candidate", row.candidate}, {"failed", row.failed}};
    if (row.failed) {
      j["failure"] = row.failure;
      j["median"] = j["p95"] = j["max"] = j["change_from_finest"] = nullptr;
    } else {
      j["median"] = number_or_null(row.error.median);
      j["p95"] = number_or_null(row.error.p95);
      j["max"] = number_or_null(row.error.max);
      j["change_from_finest"] = number_or_null(row.change_from_finest);
      if (!row.worst.empty()) {
        nlohmann::json w = nlohmann::json::array();
        for (const WorstPixel& p : row.worst)
          w.push_back({{"x", p.x}, {"y", p.y}, {"error", number_or_null(p.error)},
                       {"candidate", {number_or_null(p.candidate[0]), number_or_null(p.candidate[1]), number_or_null(p.candidate[2])}},
                       {"exact", {p.exact[0], p.exact[1], p.exact[2]}},
                       {"ray", {{"origin", p.origin}, {"direction", p.direction}}}});
        j["worst"] = w;
      }
      if (!row.error_map.empty()) j["error_map"] = row.error_map;
    }
    rows.push_back(j);
  }
  nlohmann::json out{{"rows", rows},
                     {"exact_peak", number_or_null(r.peak)},
                     {"error_floor", number_or_null(r.floor)},
                     {"fits", {{"median", fit_json(r.median_fit, r)}, {"p95", fit_json(r.p95_fit, r)},
                               {"max", fit_json(r.max_fit, r)}}},
                     {"metric", r.metric},
                     {"invariant_to_step", r.invariant},
                     {"invariance_tolerance", r.invariance_tolerance},
                     {"passed", r.passed}};
  if (r.has_expectation)
    out["expectation"] = {{"order", r.expected_order}, {"tolerance", r.order_tolerance}};
  return out;
}

}  // namespace rayint
