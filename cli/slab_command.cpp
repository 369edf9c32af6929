// rayint slab -- the plane-parallel slab (src/rayint/scattering/slab.hpp): either one problem
// given by options, or every value of a published benchmark file (--benchmark), solved by the
// adding-doubling method, by Monte Carlo and (isotropic problems) by the integral equation for
// the source function. A table or JSON; exit 1 if a benchmark value is
// not reproduced under the acceptance rule of slab_benchmark.hpp.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "rayint/input/slab_benchmark_reader.hpp"
#include "rayint/scattering/slab_benchmark.hpp"
#include "rayint/input/slab_scene_reader.hpp"
#include "rayint/scattering/slab_single_scattering.hpp"

namespace rayint::cli {
namespace {

struct SlabOptions {
  std::string benchmark;
  std::string scene;
  std::vector<std::string> problems;
  std::string method = "both";
  long long photons = 1000000;
  unsigned long long seed = 1;
  int threads = 0;
  int streams = 64;
  double start_thickness = 1e-8;
  bool no_richardson = false;
  bool no_integral_equation = false;
  int ie_segments = 128;
  bool mc_analog = false;
  double mc_max_rel = 0.02;
  bool json = false;
  bool quiet = false;
  std::string output;
  // one problem
  double tau = 1, albedo = 1, mu0 = 1;
  std::string phase = "isotropic", source = "beam";
  std::vector<double> mu_up, mu_down;
  int max_order = 0;
};

PhaseFunction parse_phase(const std::string& text) {
  if (text == "isotropic") return PhaseFunction::isotropic();
  if (text == "lambert") return PhaseFunction::lambert_sphere();
  if (text.rfind("hg:", 0) == 0) {
    char* end = nullptr;
    const double g = std::strtod(text.c_str() + 3, &end);
    if (end != text.c_str() + text.size() || text.size() == 3 || !(std::fabs(g) < 1))
      throw std::invalid_argument("--phase: hg:G needs |G| < 1, got '" + text + "'");
    return PhaseFunction::henyey_greenstein(g);
  }
  throw std::invalid_argument("--phase: expected isotropic, lambert or hg:G, got '" + text + "'");
}

std::string fmt(const char* f, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, x);
  return buf;
}

nlohmann::json estimate_json(const Estimate& e) {
  return {{"mean", e.mean}, {"std_error", e.std_error}, {"lo95", e.lo95()}, {"hi95", e.hi95()}};
}

std::string benchmark_table(const BenchmarkReport& r, const BenchmarkRunOptions& o) {
  std::string out;
  char line[512];
  std::snprintf(line, sizeof line, "%-4s %-30s %12s %8s | %12s %10s %4s | %13s %8s %10s | %12s %10s %25s %10s %3s %4s  %s\n",
                "id", "value", "published", "tol", "doubling", "rel dev", "ok", "integral eq", "est err",
                "rel dev", "monte carlo",
                "rel dev", "95% interval", "4 SE/pub", "in", "ok", "verdict");
  out += line;
  for (const auto& row : r.rows) {
    std::string d = "", mc = "";
    std::snprintf(line, sizeof line, "%-4s %-30s %12.6g %8.0e | ", row.problem_id.c_str(),
                  row.value.label().c_str(), row.value.published, row.value.tolerance_rel);
    out += line;
    if (row.has_doubling)
      std::snprintf(line, sizeof line, "%12.7g %10.2e %4s | ", row.doubling, row.doubling_rel_dev,
                    row.doubling_pass ? "yes" : "NO");
    else
      std::snprintf(line, sizeof line, "%12s %10s %4s | ", "-", "-", "-");
    out += line;
    if (row.has_integral_equation)
      std::snprintf(line, sizeof line, "%13.10g %8.1e %10.2e | ", row.integral_equation, row.ie_error,
                    row.ie_rel_dev);
    else
      std::snprintf(line, sizeof line, "%13s %8s %10s | ", "-", "-", "-");
    out += line;
    if (row.has_monte_carlo) {
      const Estimate& e = row.monte_carlo;
      std::snprintf(line, sizeof line, "%12.7g %10.2e [%11.6g,%11.6g] %10.2e %3s %4s  %s\n", e.mean,
                    row.mc_rel_dev, e.lo95(), e.hi95(),
                    row.value.published != 0 ? 4 * e.std_error / row.value.published : 0.0,
                    row.mc_in_95 ? "yes" : "no", row.mc_pass ? "yes" : "NO", row.verdict_name());
    } else {
      std::snprintf(line, sizeof line, "%12s  %s\n", "-", row.verdict_name());
    }
    out += line;
  }
  long long photons = 0, collisions = 0;
  double mc_s = 0, d_s = 0, ie_s = 0;
  int ie_segments = 0;
  for (const auto& c : r.costs) {
    ie_s += c.ie_seconds;
    ie_segments = std::max(ie_segments, c.ie_segments);
    photons += c.mc_photons;
    collisions += c.mc_collisions;
    mc_s += c.mc_seconds;
    d_s += c.doubling_seconds;
  }
  if (o.doubling)
    out += "doubling: " + std::to_string(o.doubling_options.streams) + " streams per hemisphere, " +
           fmt("%.3f", d_s) + " s in total\n";
  if (ie_segments > 0)
    out += "integral equation (isotropic problems): product integration, meshes " +
           std::to_string(o.ie_options.segments) + "-" + std::to_string(ie_segments) +
           " segments, Richardson; est err = change of the extrapolation with the last mesh; " +
           fmt("%.3f", ie_s) + " s in total\n";
  if (o.monte_carlo)
    out += std::string(o.mc_split ? "monte carlo (exact orders 0-1 + MC orders >= 2)"
                                  : "monte carlo (analog)") + ": seed " + std::to_string(o.mc_options.seed) + ", " +
           std::to_string(photons) + " photons, " + std::to_string(collisions) + " collisions, " +
           fmt("%.2f", mc_s) + " s wall, " + fmt("%.3g", static_cast<double>(photons) / mc_s) +
           " photons/s\n";
  out += std::string("acceptance: doubling |dev| <= tol*|published|; monte carlo |dev| <= "
                     "max(tol*|published|, 4 SE) and 4 SE <= ") +
         fmt("%g", o.mc_max_rel) + "*|published|\n";
  int reproduced = 0, disputed = 0, failed = 0;
  for (const auto& row : r.rows) {
    if (row.verdict == BenchmarkRow::Verdict::reproduced) ++reproduced;
    if (row.verdict == BenchmarkRow::Verdict::disputed) ++disputed;
    if (row.verdict == BenchmarkRow::Verdict::failed) ++failed;
  }
  out += "disputed: the published value misses its tolerance, doubling and Monte Carlo agree within 4 SE, "
         "and the Monte Carlo excludes the published value by more than 4 SE or the integral equation "
         "(est err <= 1e-6 rel) agrees with the doubling and so excludes it too\n";
  out += std::to_string(reproduced) + " reproduced, " + std::to_string(disputed) + " disputed, " +
         std::to_string(failed) + " failed of " + std::to_string(r.rows.size()) + " values\n";
  return out;
}

nlohmann::json benchmark_json(const SlabBenchmark& b, const BenchmarkReport& r,
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
      j["monte_carlo"] = estimate_json(row.monte_carlo);
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

void run_problem(const SlabOptions& s, const SlabProblem& p, nlohmann::json j, bool doubling, bool mc);

void run_one(const SlabOptions& s, bool doubling, bool mc) {
  SlabProblem p;
  p.tau = s.tau;
  p.albedo = s.albedo;
  p.phase = parse_phase(s.phase);
  if (s.source == "beam")
    p.source = SlabSource::beam;
  else if (s.source == "isotropic")
    p.source = SlabSource::isotropic;
  else
    throw std::invalid_argument("--source: expected beam or isotropic, got '" + s.source + "'");
  p.mu0 = s.mu0;
  p.mu_up = s.mu_up;
  p.mu_down = s.mu_down;
  validate(p);
  nlohmann::json j = {{"tau", p.tau}, {"albedo", p.albedo}, {"phase", s.phase},
                      {"source", s.source}, {"mu0", p.mu0}, {"mu_up", p.mu_up},
                      {"mu_down", p.mu_down}};
  run_problem(s, p, j, doubling, mc);
}

void run_scene(const SlabOptions& s, bool doubling, bool mc) {
  const SlabScene scene = read_slab_scene(s.scene);
  const SlabProblem& p = scene.problem;
  const bool beam = p.source == SlabSource::beam;
  nlohmann::json j = {{"scene", s.scene}, {"name", scene.name}, {"tau", p.tau}, {"albedo", p.albedo},
                      {"phase", p.phase.name()}, {"source", beam ? "beam" : "isotropic"},
                      {"mu_up", p.mu_up}, {"mu_down", p.mu_down}};
  if (beam) j["mu0"] = p.mu0;
  run_problem(s, p, j, doubling, mc);
}

void run_problem(const SlabOptions& s, const SlabProblem& p, nlohmann::json j, bool doubling, bool mc) {
  auto values_json = [&](const SlabValues& v) {
    return nlohmann::json{{"flux_up_top", v.flux_up_top},
                          {"diffuse_down_bottom", v.diffuse_down_bottom},
                          {"direct_down_bottom", v.direct_down_bottom},
                          {"intensity_up_top", v.intensity_up_top},
                          {"intensity_down_bottom", v.intensity_down_bottom}};
  };
  if (doubling && s.max_order == 0) {
    DoublingOptions d;
    d.streams = s.streams;
    d.start_thickness = s.start_thickness;
    d.richardson = !s.no_richardson;
    j["doubling"] = values_json(solve_slab_doubling(p, d));
  }
  if (doubling && s.max_order == 0 && !s.no_integral_equation &&
      p.phase.kind() == PhaseFunction::Kind::isotropic) {
    SlabIntegralEquationOptions ie;
    ie.segments = s.ie_segments;
    const SlabIntegralEquationResult r = solve_slab_integral_equation(p, ie);
    j["integral_equation"] = values_json(r.values);
    j["integral_equation"]["error_estimate"] = values_json(r.error_estimate);
    j["integral_equation"]["finest_segments"] = r.finest_segments;
  }
  if (s.max_order == 1)
    j["single_scattering_closed_form"] = values_json(single_scattering(p));
  if (mc) {
    SlabMonteCarloOptions m;
    m.photons = s.photons;
    m.seed = s.seed;
    m.threads = s.threads;
    m.max_order = s.max_order;
    const bool split = !s.mc_analog && s.max_order != 1;
    const SlabEstimates e = split ? solve_slab_monte_carlo_split(p, m) : solve_slab_monte_carlo(p, m);
    nlohmann::json up = nlohmann::json::array(), down = nlohmann::json::array();
    for (const auto& x : e.intensity_up_top) up.push_back(estimate_json(x));
    for (const auto& x : e.intensity_down_bottom) down.push_back(estimate_json(x));
    j["monte_carlo"] = {{"estimator", split ? "exact orders 0-1 + MC orders >= 2" : "analog, every order"},
                        {"seed", s.seed},
                        {"max_order", s.max_order},
                        {"photons", e.photons},
                        {"collisions", e.collisions},
                        {"seconds", e.seconds},
                        {"photons_per_second", static_cast<double>(e.photons) / e.seconds},
                        {"flux_up_top", estimate_json(e.flux_up_top)},
                        {"diffuse_down_bottom", estimate_json(e.diffuse_down_bottom)},
                        {"direct_down_bottom", estimate_json(e.direct_down_bottom)},
                        {"intensity_up_top", up},
                        {"intensity_down_bottom", down}};
  }
  emit(j.dump(2), s.output);
}

}  // namespace

void set_slab_command(CLI::App& app) {
  auto s = std::make_shared<SlabOptions>();
  CLI::App* cmd = app.add_subcommand(
      "slab", "Plane-parallel slab multiple scattering: one problem, or a published benchmark file");
  cmd->add_option("--benchmark", s->benchmark,
                  "benchmark file (cases/scattering/disort_slab.json): check every value");
  cmd->add_option("--scene", s->scene,
                  "slab scene file (medium type \"slab\", beam or isotropic light, detectors; "
                  "docs/multiple-scattering.md): solve it");
  cmd->add_option("--problems", s->problems, "benchmark: only these problem ids (e.g. 1a,3b)")
      ->delimiter(',');
  cmd->add_option("--method", s->method, "doubling, monte_carlo or both (default)");
  cmd->add_option("--photons", s->photons, "Monte Carlo photons per problem (default 1e6)");
  cmd->add_option("--seed", s->seed, "Monte Carlo seed (default 1)");
  cmd->add_option("--threads", s->threads, "threads (default: all cores); results do not depend on it")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--streams", s->streams, "doubling: Gauss cosines per hemisphere (default 64)");
  cmd->add_option("--start-thickness", s->start_thickness,
                  "doubling: largest optical thickness of the single-scattering start layer (1e-8)");
  cmd->add_flag("--no-richardson", s->no_richardson,
                "doubling: no extrapolation in the start thickness (for convergence studies)");
  cmd->add_flag("--no-integral-equation", s->no_integral_equation,
                "no integral-equation solver (isotropic problems; it runs with the doubling)");
  cmd->add_option("--ie-segments", s->ie_segments,
                  "integral equation: coarsest mesh segments (default 128; meshes x1, x2, x4, x8)");
  cmd->add_option("--mc-max-rel", s->mc_max_rel,
                  "benchmark: largest 4 SE / published a Monte Carlo check may have (default 0.02)");
  cmd->add_flag("--mc-analog", s->mc_analog,
                "Monte Carlo of every order (default: exact orders 0-1 plus Monte Carlo of orders >= 2)");
  cmd->add_flag("--json", s->json, "benchmark: JSON instead of a table");
  cmd->add_flag("--quiet", s->quiet, "no progress on stderr");
  cmd->add_option("-o,--output", s->output, "write the result here (atomically) instead of stdout");
  cmd->add_option("--tau", s->tau, "one problem: optical thickness");
  cmd->add_option("--albedo", s->albedo, "one problem: single-scattering albedo");
  cmd->add_option("--phase", s->phase, "one problem: isotropic, lambert or hg:G");
  cmd->add_option("--source", s->source, "one problem: beam or isotropic");
  cmd->add_option("--mu0", s->mu0, "one problem: beam cosine");
  cmd->add_option("--mu-up", s->mu_up, "one problem: reflected-intensity cosines")->delimiter(',');
  cmd->add_option("--mu-down", s->mu_down, "one problem: transmitted-intensity cosines")->delimiter(',');
  cmd->add_option("--max-order", s->max_order,
                  "one problem: Monte Carlo scattering orders (1: single scattering, compared "
                  "with the closed form)");
  cmd->callback([s]() {
    const bool doubling = s->method == "doubling" || s->method == "both";
    const bool mc = s->method == "monte_carlo" || s->method == "both";
    if (!doubling && !mc)
      throw std::invalid_argument("--method: expected doubling, monte_carlo or both, got '" +
                                  s->method + "'");
    if (s->photons < 1) throw std::invalid_argument("--photons: must be >= 1");
    if (s->streams < 2 || s->streams > 1024) throw std::invalid_argument("--streams: must be in [2, 1024]");
    if (!(s->start_thickness > 0 && s->start_thickness <= 1e-3))
      throw std::invalid_argument("--start-thickness: must be in (0, 1e-3]");
    if (s->ie_segments < 4 || s->ie_segments > 512)
      throw std::invalid_argument("--ie-segments: must be in [4, 512]");
    if (!(s->mc_max_rel > 0)) throw std::invalid_argument("--mc-max-rel: must be > 0");
    if (s->max_order < 0) throw std::invalid_argument("--max-order: must be >= 0");
    if (!s->scene.empty() && !s->benchmark.empty())
      throw std::invalid_argument("--scene and --benchmark: give one of them");
    if (!s->scene.empty()) {
      run_scene(*s, doubling, mc);
      return;
    }
    if (s->benchmark.empty()) {
      run_one(*s, doubling, mc);
      return;
    }
    SlabBenchmark b = read_slab_benchmark(s->benchmark);
    if (!s->problems.empty()) {
      std::vector<BenchmarkProblem> kept;
      for (const auto& id : s->problems) {
        bool found = false;
        for (const auto& p : b.problems)
          if (p.id == id) {
            kept.push_back(p);
            found = true;
          }
        if (!found) throw std::invalid_argument("--problems: no problem '" + id + "' in " + s->benchmark);
      }
      b.problems = kept;
    }
    BenchmarkRunOptions o;
    o.doubling = doubling;
    o.monte_carlo = mc;
    o.doubling_options.streams = s->streams;
    o.doubling_options.start_thickness = s->start_thickness;
    o.doubling_options.richardson = !s->no_richardson;
    o.integral_equation = doubling && !s->no_integral_equation;
    o.ie_options.segments = s->ie_segments;
    o.mc_options.photons = s->photons;
    o.mc_options.seed = s->seed;
    o.mc_options.threads = s->threads;
    o.mc_max_rel = s->mc_max_rel;
    o.mc_split = !s->mc_analog;
    const bool quiet = s->quiet;
    const BenchmarkReport r = run_slab_benchmark(b, o, [quiet](const std::string& id) {
      if (!quiet) std::cerr << "rayint slab: problem " << id << "\n";
    });
    emit(s->json ? benchmark_json(b, r, o).dump(2) : benchmark_table(r, o), s->output);
    if (!r.all_pass()) throw ChecksFailed{};
  });
}

}  // namespace rayint::cli
