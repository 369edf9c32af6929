#include "rayint/report/stress_json.hpp"

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "rayint/report/case_writer.hpp"
#include "rayint/report/json_number.hpp"

namespace rayint {
namespace {

using json = nlohmann::ordered_json;

json counts(const std::map<std::string, long>& m) {
  json j = json::object();
  for (const auto& [k, v] : m) j[k] = v;
  return j;
}

json worst_json(const WorstSample& w) {
  if (!w.present) return nullptr;
  json j;
  j["sample"] = w.index;
  j["sample_seed"] = w.sample_seed;
  j["non_finite"] = w.non_finite;
  if (!w.failure.empty()) j["failure"] = w.failure;
  j["rel_error"] = number_or_null<json>(w.rel_error);
  j["ulp_error"] = number_or_null<json>(w.ulp_error);
  j["abs_error"] = number_or_null<json>(w.abs_error);
  j["intensity"] = rgb_json<json>(w.value);
  j["reference"] = rgb_json<json>(w.reference);
  j["branches"] = counts(w.diagnostics.branches);
  j["case"] = w.replay.name;
  if (!w.file.empty()) j["file"] = w.file;
  return j;
}

}  // namespace

nlohmann::ordered_json to_json(const ErrorStats& s) {
  return json{{"max", number_or_null<json>(s.max)}, {"p99", number_or_null<json>(s.p99)}, {"median", number_or_null<json>(s.median)}};
}

nlohmann::ordered_json to_json(const MethodStress& m) {
  json j;
  j["method"] = m.method;
  j["scored"] = m.scored;
  j["non_finite"] = m.non_finite;
  j["negative"] = m.negative;
  j["failures"] = m.failures;
  j["underflow"] = m.underflow;
  j["rel_error"] = to_json(m.rel);
  j["ulp_error"] = to_json(m.ulp);
  j["max_abs_error_underflow"] = number_or_null<json>(m.max_abs_error_underflow);
  j["branches"] = counts(m.branches);
  if (m.worst.present) j["worst"] = worst_json(m.worst);
  if (m.worst_finite.present) j["worst_finite"] = worst_json(m.worst_finite);
  return j;
}

nlohmann::ordered_json to_json(const RegimeStress& r) {
  json j;
  j["regime"] = r.regime;
  j["level"] = r.ray_level ? "ray" : "piece";
  j["samples"] = r.samples;
  j["pieces"] = r.pieces;
  j["reference_max_rel_bound"] = number_or_null<json>(r.max_reference_rel_bound);
  j["reference_failures"] = r.reference_failures;
  if (!r.reference_failure.empty()) j["reference_failure"] = r.reference_failure;
  json methods = json::array();
  for (const auto& m : r.methods) methods.push_back(to_json(m));
  j["methods"] = std::move(methods);
  return j;
}

nlohmann::ordered_json to_json(const StressReport& r) {
  json j;
  j["seed"] = r.seed;
  j["count"] = r.count;
  j["methods"] = r.methods;
  j["underflow_threshold"] = kUnderflowFloor;
  json regimes = json::array();
  for (const auto& reg : r.regimes) regimes.push_back(to_json(reg));
  j["regimes"] = std::move(regimes);
  json overall = json::array();
  for (const auto& m : r.overall) overall.push_back(to_json(m));
  j["overall"] = std::move(overall);
  return j;
}

nlohmann::ordered_json to_json(const GateReport& r) {
  json checks = json::array();
  for (const auto& c : r.checks) {
    json j;
    j["name"] = c.name;
    j["pass"] = c.pass;
    j["measured"] = number_or_null<json>(c.measured);
    j["limit"] = number_or_null<json>(c.limit);
    if (!c.note.empty()) j["note"] = c.note;
    checks.push_back(std::move(j));
  }
  json j;
  j["pass"] = r.pass();
  j["failures"] = r.failures();
  j["checks"] = std::move(checks);
  return j;
}

void write_worst_cases(StressReport& report, const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error(dir + ": cannot create directory (" + ec.message() + ")");
  for (auto& regime : report.regimes)
    for (auto& m : regime.methods)
      for (WorstSample* w : {&m.worst, &m.worst_finite}) {
        if (!w->present) continue;
        const std::string path = (std::filesystem::path(dir) / (w->replay.name + ".json")).string();
        write_case_file(path, w->replay);
        w->file = path;
      }
}

}  // namespace rayint
