// Reading the slab benchmark file and checking both slab solvers against it; see
// slab_benchmark.hpp.
#include "rayint/scattering/slab_benchmark.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "rayint/io/json_schema.hpp"
#include "rayint/io/json_source.hpp"

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

using json = nlohmann::json;
using json_source::index_path;
using json_source::member_path;

constexpr double kThinSlab = 0.1;

// "henyey_greenstein_g0.75" -> 0.75; isotropic -> nullopt-like NaN.
bool phase_of_group(const std::string& key, PhaseFunction& phase) {
  if (key == "isotropic") {
    phase = PhaseFunction::isotropic();
    return true;
  }
  const std::string prefix = "henyey_greenstein_g";
  if (key.rfind(prefix, 0) != 0) return false;
  const std::string number = key.substr(prefix.size());
  char* end = nullptr;
  const double g = std::strtod(number.c_str(), &end);
  if (number.empty() || end != number.c_str() + number.size() || !(std::fabs(g) < 1)) return false;
  phase = PhaseFunction::henyey_greenstein(g);
  return true;
}

BenchmarkProblem read_problem(const JsonSchema& s, const json& j, const std::string& path,
                              const PhaseFunction& phase) {
  s.require_object(j, path);
  s.check_fields(j, path, {"id", "tau", "albedo", "source", "mu0", "flux_up_top",
                           "diffuse_down_bottom", "direct_down_bottom", "intensity_up_top",
                           "intensity_down_bottom"});
  BenchmarkProblem bp;
  bp.id = s.non_empty_string(s.required(j, path, "id"), member_path(path, "id"));
  SlabProblem& p = bp.problem;
  p.phase = phase;
  p.tau = s.positive(s.required(j, path, "tau"), member_path(path, "tau"));
  p.albedo = s.in_range(s.required(j, path, "albedo"), member_path(path, "albedo"), 0, 1);
  const std::string src = s.string_value(s.required(j, path, "source"), member_path(path, "source"));
  if (src == "beam") {
    p.source = SlabSource::beam;
    p.mu0 = s.in_range(s.required(j, path, "mu0"), member_path(path, "mu0"), 0, 1);
    if (p.mu0 <= 0) s.fail(member_path(path, "mu0"), "must be in (0, 1], got 0");
  } else if (src == "fisot") {
    p.source = SlabSource::isotropic;
    if (s.optional(j, "mu0")) s.fail(member_path(path, "mu0"), "only a beam source has mu0");
    if (s.optional(j, "direct_down_bottom"))
      s.fail(member_path(path, "direct_down_bottom"), "isotropic incidence has no direct beam");
  } else {
    s.fail(member_path(path, "source"), "must be \"beam\" or \"fisot\", got " + json_source::quoted(src));
  }
  const bool thin = p.tau < kThinSlab;
  auto scalar = [&](const char* key, SlabQuantity q, bool is_flux) {
    if (const json* v = s.optional(j, key)) {
      BenchmarkValue bv;
      bv.quantity = q;
      bv.published = s.non_negative(*v, member_path(path, key));
      bv.tolerance_rel = (thin && is_flux) ? 1e-3 : 1e-4;
      bp.values.push_back(bv);
    }
  };
  scalar("flux_up_top", SlabQuantity::flux_up_top, true);
  scalar("diffuse_down_bottom", SlabQuantity::diffuse_down_bottom, true);
  scalar("direct_down_bottom", SlabQuantity::direct_down_bottom, false);
  auto intensities = [&](const char* key, SlabQuantity q, std::vector<double>& mus) {
    const json* v = s.optional(j, key);
    if (!v) return;
    const std::string vp = member_path(path, key);
    s.require_object(*v, vp);
    if (v->empty()) s.fail(vp, "must hold at least one \"mu\": intensity pair");
    for (const auto& [k, value] : v->items()) {
      const std::string kp = member_path(vp, k);
      char* end = nullptr;
      const double mu = std::strtod(k.c_str(), &end);
      if (k.empty() || end != k.c_str() + k.size() || !(mu > 0 && mu <= 1))
        s.fail(kp, "the key must be a cosine mu in (0, 1]");
      BenchmarkValue bv;
      bv.quantity = q;
      bv.mu = mu;
      bv.detector = mus.size();
      bv.published = s.non_negative(value, kp);
      bv.tolerance_rel = 1e-4;
      mus.push_back(mu);
      bp.values.push_back(bv);
    }
  };
  intensities("intensity_up_top", SlabQuantity::intensity_up_top, p.mu_up);
  intensities("intensity_down_bottom", SlabQuantity::intensity_down_bottom, p.mu_down);
  if (bp.values.empty()) s.fail(path, "has no published value");
  return bp;
}

double doubling_value(const SlabValues& v, const BenchmarkValue& b) {
  switch (b.quantity) {
    case SlabQuantity::flux_up_top: return v.flux_up_top;
    case SlabQuantity::diffuse_down_bottom: return v.diffuse_down_bottom;
    case SlabQuantity::direct_down_bottom: return v.direct_down_bottom;
    case SlabQuantity::intensity_up_top: return v.intensity_up_top[b.detector];
    case SlabQuantity::intensity_down_bottom: return v.intensity_down_bottom[b.detector];
  }
  return 0;
}

Estimate mc_value(const SlabEstimates& e, const BenchmarkValue& b) {
  switch (b.quantity) {
    case SlabQuantity::flux_up_top: return e.flux_up_top;
    case SlabQuantity::diffuse_down_bottom: return e.diffuse_down_bottom;
    case SlabQuantity::direct_down_bottom: return e.direct_down_bottom;
    case SlabQuantity::intensity_up_top: return e.intensity_up_top[b.detector];
    case SlabQuantity::intensity_down_bottom: return e.intensity_down_bottom[b.detector];
  }
  return {};
}

}  // namespace

SlabBenchmark parse_slab_benchmark(const std::string& text, const std::string& source) {
  const json root = json_source::parse(text, source);
  const JsonSchema s(source);
  s.require_object(root, "");
  SlabBenchmark b;
  for (const auto& [key, value] : root.items()) {
    if (key == "about" || key == "conventions") continue;  // prose, not read
    if (key == "source") {
      b.source = s.string_value(value, key);
      continue;
    }
    PhaseFunction phase = PhaseFunction::isotropic();
    if (!phase_of_group(key, phase))
      s.fail(key, "unknown field (expected about, source, conventions, isotropic or "
                  "henyey_greenstein_g<g>)");
    s.non_empty_array(value, key, "problems");
    for (std::size_t i = 0; i < value.size(); ++i)
      b.problems.push_back(read_problem(s, value[i], index_path(key, i), phase));
  }
  if (b.problems.empty()) s.fail("", "no problem groups (isotropic, henyey_greenstein_g<g>)");
  return b;
}

SlabBenchmark read_slab_benchmark(const std::string& path) {
  return parse_slab_benchmark(json_source::read_text_file(path), path);
}

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
    SlabValues dv;
    SlabEstimates me;
    if (o.doubling) {
      const auto t0 = std::chrono::steady_clock::now();
      dv = solve_slab_doubling(bp.problem, o.doubling_options);
      cost.doubling_seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    SlabIntegralEquationResult ie;
    const bool run_ie = o.integral_equation && bp.problem.phase.kind() == PhaseFunction::Kind::isotropic;
    if (run_ie) {
      ie = solve_slab_integral_equation(bp.problem, o.ie_options);
      cost.ie_seconds = ie.seconds;
      cost.ie_segments = ie.finest_segments;
    }
    if (o.monte_carlo) {
      me = o.mc_split ? solve_slab_monte_carlo_split(bp.problem, o.mc_options)
                      : solve_slab_monte_carlo(bp.problem, o.mc_options);
      cost.mc_seconds = me.seconds;
      cost.mc_photons = me.photons;
      cost.mc_collisions = me.collisions;
    }
    report.costs.push_back(cost);
    for (const auto& v : bp.values) {
      BenchmarkRow row;
      row.problem_id = bp.id;
      row.value = v;
      const double allowed = v.tolerance_rel * std::fabs(v.published);
      if (o.doubling) {
        row.has_doubling = true;
        row.doubling = doubling_value(dv, v);
        row.doubling_rel_dev = (row.doubling - v.published) / v.published;
        row.doubling_pass = std::fabs(row.doubling - v.published) <= allowed;
      }
      if (run_ie) {
        row.has_integral_equation = true;
        row.integral_equation = doubling_value(ie.values, v);
        row.ie_error = doubling_value(ie.error_estimate, v);
        row.ie_order = doubling_value(ie.observed_order, v);
        row.ie_rel_dev = (row.integral_equation - v.published) / v.published;
        row.ie_pass = std::fabs(row.integral_equation - v.published) <= allowed;
      }
      if (o.monte_carlo) {
        row.has_monte_carlo = true;
        row.monte_carlo = mc_value(me, v);
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
