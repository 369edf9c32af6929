#include "rayint/report/evaluation_json.hpp"

#include <cmath>

#include "rayint/report/text_format.hpp"

namespace rayint {

nlohmann::json to_json(const Diagnostics& d) {
  nlohmann::json j = nlohmann::json::object();
  j["branches"] = d.branches;
  nlohmann::json stats = nlohmann::json::object();
  for (const auto& [k, v] : d.stats) stats[k] = number_or_null(v);
  j["stats"] = stats;
  return j;
}

nlohmann::json to_json(const ReferenceRay& ref) {
  Rgb intensity{}, transmittance{}, rel{};
  for (int c = 0; c < kChannels; ++c) {
    intensity[c] = ref.intensity[c].hi;
    transmittance[c] = ref.transmittance[c].hi;
    const double mag = std::fabs(ref.intensity[c].hi);
    rel[c] = mag > 0 ? ref.error_bound[c] / mag : (ref.error_bound[c] > 0 ? INFINITY : 0.0);
  }
  return {{"intensity", rgb_json(intensity)},
          {"transmittance", rgb_json(transmittance)},
          {"error_estimate", {{"abs", rgb_json(ref.error_bound)}, {"rel", rgb_json(rel)}}},
          {"precision_digits", 50},
          {"pieces", ref.pieces},
          {"quadrature_subintervals", ref.subintervals}};
}

// A failed outcome has no numbers: intensity, errors and time are null, "failed" is true and
// "failure" says why.
nlohmann::json to_json(const MethodOutcome& o, bool with_reference) {
  const bool ok = !o.failed();
  const auto rgb = [ok](const Rgb& v) { return ok ? rgb_json(v) : nlohmann::json(nullptr); };
  nlohmann::json j = {{"intensity", rgb(o.result.intensity)},
                      {"transmittance", rgb(o.result.transmittance)},
                      {"seconds_per_ray", ok ? number_or_null(o.seconds_per_ray) : nlohmann::json(nullptr)},
                      {"finite", o.finite},
                      {"failed", !ok}};
  if (with_reference) {
    j["abs_error"] = rgb(o.abs_error);
    j["rel_error"] = rgb(o.rel_error);
    j["ulp_error"] = rgb(o.ulp_error);
    j["transmittance_rel_error"] = rgb(o.transmittance_rel_error);
  }
  const nlohmann::json d = to_json(o.diagnostics);
  j["branches"] = d["branches"];
  j["stats"] = d["stats"];
  if (!o.failure.empty()) j["failure"] = o.failure;
  return j;
}

nlohmann::json to_json(const TetRepairs& r) {
  nlohmann::json skipped = nlohmann::json::object();
  for (const auto& [type, n] : r.skipped_by_type) skipped[type] = n;
  nlohmann::json j = {{"tets_read", r.tets_read},
                      {"reoriented", r.reoriented},
                      {"dropped_zero_volume", r.zero_volume},
                      {"dropped_slivers", r.slivers},
                      {"skipped_cells", r.skipped_cells},  // dimension 0-2 cells of the file (not volume)
                      {"skipped_by_type", skipped},
                      {"ghost_cells_dropped", r.ghost_cells}};
  if (!r.split_cells.empty()) {
    nlohmann::json split = nlohmann::json::object();
    for (const auto& [type, n] : r.split_cells) split[type] = n;
    j["cells"] = {{"mode", "split"},
                  {"approximation", "--cells split: the file's cells tetrahedralised as VTK's vtkDataSetTriangleFilter "
                                    "does; the field is linear per tetrahedron, not the cells' own interpolation"},
                  {"cells_split_by_type", split}};
  }
  return j;
}

nlohmann::json to_json(const CaseEvaluation& c) {
  nlohmann::json rays = nlohmann::json::array();
  for (std::size_t i = 0; i < c.rays.size(); ++i) {
    nlohmann::json methods = nlohmann::json::object();
    for (const auto& m : c.rays[i].methods) methods[m.method] = to_json(m, c.with_reference);
    nlohmann::json ray = {{"index", i}, {"methods", methods}};
    if (c.with_reference) ray["reference"] = to_json(c.rays[i].reference);
    rays.push_back(std::move(ray));
  }
  // Per method over the rays: the failed count and the largest errors over the rays that did not
  // fail (null when none was scored).
  nlohmann::json summary = nlohmann::json::array();
  for (const MethodSummary& s : summarise_methods(c)) {
    nlohmann::json m = {{"method", s.method}, {"rays", s.rays}, {"failed", s.failed}};
    if (c.with_reference) {
      m["max_rel_error"] = number_or_null(s.max_rel_error);
      m["max_ulp_error"] = number_or_null(s.max_ulp_error);
    }
    m["mean_seconds_per_ray"] = number_or_null(s.mean_seconds_per_ray);
    if (s.failed > 0) m["first_failure"] = s.first_failure;
    summary.push_back(std::move(m));
  }
  nlohmann::json j = {{"name", c.name}, {"file", c.source}, {"description", c.description},
                      {"summary", summary}, {"rays", rays}};
  if (!c.with_reference) j["reference"] = "skipped";
  if (c.mesh_repairs) j["mesh_repairs"] = to_json(*c.mesh_repairs);
  return j;
}

nlohmann::json eval_report_json(const std::vector<CaseEvaluation>& cases) {
  nlohmann::json arr = nlohmann::json::array();
  for (const auto& c : cases) arr.push_back(to_json(c));
  // "failed": method-ray outcomes that failed, over all cases (0: every method ran on every ray).
  return {{"tool", "rayint"}, {"report", "eval"}, {"failed", failed_outcomes(cases)}, {"cases", arr}};
}

std::string eval_progress_line(const std::string& case_name, const EvalProgress& p, double seconds) {
  std::string line;
  if (p.stage == EvalProgress::Stage::reference) {
    const double percent = p.total > 0 ? 100.0 * static_cast<double>(p.done) / static_cast<double>(p.total) : 100.0;
    appendf(line, "eval %s: reference %zu/%zu segments (%.0f%%), %.0f s\n", case_name.c_str(),
            p.done, p.total, percent, seconds);
  } else {
    appendf(line, "eval %s: method %s, ray %zu/%zu, %.0f s\n", case_name.c_str(), p.method.c_str(),
            p.done + 1, p.total, seconds);
  }
  return line;
}

}  // namespace rayint
