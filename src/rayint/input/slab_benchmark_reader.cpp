// Reading a published slab benchmark file (format: ../shared/benchmarks/, docs/multiple-scattering.md)
// into the SlabBenchmark that scattering/slab_benchmark.hpp checks the solvers against.
#include "rayint/input/slab_benchmark_reader.hpp"

#include <cmath>
#include <cstdlib>

#include "rayint/input/json_schema.hpp"
#include "rayint/input/json_source.hpp"

namespace rayint {

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

}  // namespace rayint
