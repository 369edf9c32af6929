// gate.cpp -- runs the checks of a GateConfig (see gate.hpp). The corpus part evaluates each case
// with the methods that apply to it (evaluate_case, no timing), in parallel over cases; the
// stress part is one run_stress over the configured regimes with every stress method. A method
// named by several limit sets is run once and its figures checked against each set.
#include "rayint/studies/gate.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "rayint/core/parallel.hpp"
#include "rayint/studies/evaluate.hpp"

namespace rayint {
namespace {

bool applies(const GateMethod& m, const std::string& name) {
  return m.only.empty() || std::find(m.only.begin(), m.only.end(), name) != m.only.end();
}

// Index of the spec with the same setting as `spec` in `specs` (whatever the order its
// parameters were typed in), appended if absent.
std::size_t index_of(std::vector<MethodSpec>& specs, const MethodSpec& spec) {
  for (std::size_t i = 0; i < specs.size(); ++i)
    if (specs[i].canonical() == spec.canonical()) return i;
  specs.push_back(spec);
  return specs.size() - 1;
}

// The figures of one method over one case's rays, as run_stress would give them; the first
// ray's failure (or non-finite result) goes to worst.failure for the check's note.
MethodStress summarise(const CaseEvaluation& ev, std::size_t method) {
  MethodStress m;
  std::vector<double> rel, ulp;
  for (std::size_t r = 0; r < ev.rays.size(); ++r) {
    const RayEvaluation& ray = ev.rays[r];
    const MethodOutcome& o = ray.methods[method];
    m.method = o.method;
    for (const auto& [k, v] : o.diagnostics.branches) m.branches[k] += v;
    const SampleScore s = score_sample(o.result, ray.reference.intensity, !o.failure.empty());
    if (!s.finite) {
      ++m.non_finite;
      if (!o.failure.empty()) ++m.failures;
      if (m.worst.failure.empty())
        m.worst.failure = "ray " + std::to_string(r) + ": " +
                          (o.failure.empty() ? std::string("non-finite result") : o.failure);
      continue;
    }
    if (s.scored) {
      ++m.scored;
      rel.push_back(s.rel);
      ulp.push_back(s.ulp);
    }
    if (s.underflow) {
      ++m.underflow;
      m.max_abs_error_underflow = std::max(m.max_abs_error_underflow, s.abs_underflow);
    }
  }
  m.rel = error_stats(rel);
  m.ulp = error_stats(ulp);
  return m;
}

// One check per limit of `gm`. A failed check's note says what went wrong: the first failure
// (`m.worst.failure`), else where the worst value came from (`where`, may be empty).
// A method that failed (threw, or did not converge) on some ray or sample adds a check
// "<prefix>.<method>.failed" (the count, limit 0) whatever its limits: a failure fails the gate
// even where a limit allows some non-finite results.
void add_checks(GateReport& report, const std::string& prefix, const GateMethod& gm,
                const MethodStress& m, const std::string& where) {
  const std::string failed_name = prefix + "." + gm.spec.label() + ".failed";
  const bool listed = std::any_of(report.checks.begin(), report.checks.end(),
                                  [&](const GateCheck& c) { return c.name == failed_name; });
  if (m.failures > 0 && !listed) {  // once per method, not once per limit set
    GateCheck c;
    c.name = failed_name;
    c.measured = static_cast<double>(m.failures);
    c.limit = 0;
    c.pass = false;
    c.note = m.worst.failure;
    report.checks.push_back(std::move(c));
  }
  for (const std::string& metric : gate_metrics()) {
    const auto it = gm.limits.find(metric);
    if (it == gm.limits.end()) continue;
    GateCheck c;
    c.name = prefix + "." + gm.spec.label() + "." + metric;
    c.measured = gate_measure(m, metric);
    c.limit = it->second;
    c.pass = c.measured <= c.limit;
    if (!c.pass) c.note = m.non_finite > 0 && !m.worst.failure.empty() ? m.worst.failure : where;
    report.checks.push_back(std::move(c));
  }
}

void run_corpus(const GateConfig& cfg, GateReport& report,
                const std::function<void(const GateProgress&)>& progress,
                std::chrono::steady_clock::time_point start) {
  if (cfg.cases.empty() || cfg.corpus_methods.empty()) return;
  const std::vector<Case>& cases = cfg.cases;

  struct Outcome {
    std::vector<std::size_t> methods;  // indices into cfg.corpus_methods
    std::vector<std::size_t> spec;     // for each of those, its index in the evaluation
    CaseEvaluation evaluation;
    std::string failure;
  };
  std::vector<Outcome> outcomes(cases.size());
  std::vector<std::size_t> order;  // most rays first: they bound the run time
  for (std::size_t i = 0; i < cases.size(); ++i) order.push_back(i);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return cases[a].rays.size() > cases[b].rays.size();
  });

  std::atomic<long> done{0};
  EvalOptions eo;
  eo.measure_time = false;
  eo.threads = 1;
  auto run_case = [&](long long k) {
    const std::size_t i = order[static_cast<std::size_t>(k)];
    Outcome& out = outcomes[i];
    std::vector<MethodSpec> specs;
    for (std::size_t m = 0; m < cfg.corpus_methods.size(); ++m)
      if (applies(cfg.corpus_methods[m], cases[i].name)) {
        out.methods.push_back(m);
        out.spec.push_back(index_of(specs, cfg.corpus_methods[m].spec));
      }
    try {
      if (!specs.empty()) out.evaluation = evaluate_case(cases[i], specs, eo);
    } catch (const std::exception& e) {
      out.failure = e.what();
    }
    ++done;
  };
  auto report_progress = [&] {
    if (progress)
      progress({"corpus", done.load(), static_cast<long>(cases.size()),
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()});
  };
  // Progress every 2 s from this thread, while the workers run.
  parallel_for(static_cast<long long>(order.size()), cfg.threads, run_case, 2.0, report_progress);
  report_progress();

  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Outcome& out = outcomes[i];
    const std::string prefix = "corpus." + cases[i].name;
    if (!out.failure.empty()) {
      GateCheck c;
      c.name = prefix + ".evaluation";
      c.measured = 1;
      c.limit = 0;
      c.pass = false;
      c.note = out.failure;
      report.checks.push_back(std::move(c));
      continue;
    }
    for (std::size_t k = 0; k < out.methods.size(); ++k) {
      add_checks(report, prefix, cfg.corpus_methods[out.methods[k]],
                 summarise(out.evaluation, out.spec[k]), "");
      std::vector<Rgb>& rays = report.corpus_results[cfg.corpus_methods[out.methods[k]].spec.canonical()][cases[i].name];
      if (!rays.empty()) continue;  // the same method under another limit set
      for (const RayEvaluation& ray : out.evaluation.rays) {
        const MethodOutcome& o = ray.methods[out.spec[k]];
        const double nan = std::numeric_limits<double>::quiet_NaN();
        rays.push_back(o.failure.empty() ? o.result.intensity : Rgb{nan, nan, nan});
      }
    }
  }
}

void run_stress_part(const GateConfig& cfg, GateReport& report,
                     const std::function<void(const GateProgress&)>& progress) {
  if (!cfg.stress || cfg.stress_methods.empty()) return;
  StressOptions so;
  so.count = cfg.stress_count;
  so.seed = cfg.stress_seed;
  so.regimes = cfg.stress_regimes;
  so.threads = cfg.threads;
  std::vector<std::size_t> spec;  // for each stress method, its index in so.methods
  for (const auto& m : cfg.stress_methods) spec.push_back(index_of(so.methods, m.spec));
  if (progress)
    so.progress = [&progress](const StressProgress& p) {
      progress({"stress", p.pieces_done, p.pieces_total, p.seconds});
    };
  const StressReport sr = run_stress(so);
  for (const RegimeStress& rs : sr.regimes) {
    const std::string prefix = "stress." + rs.regime;
    GateCheck ref;
    ref.name = prefix + ".reference_failures";
    ref.measured = static_cast<double>(rs.reference_failures);
    ref.limit = 0;
    ref.pass = rs.reference_failures == 0;
    ref.note = rs.reference_failure;
    report.checks.push_back(std::move(ref));
    for (std::size_t m = 0; m < cfg.stress_methods.size(); ++m) {
      if (!applies(cfg.stress_methods[m], rs.regime)) continue;
      const MethodStress& ms = rs.methods[spec[m]];
      std::string where;
      if (ms.worst.present)
        where = "worst: sample " + std::to_string(ms.worst.index) + " of regime " + rs.regime +
                " with seed " + std::to_string(sr.seed) +
                " (rayint stress writes it as a case file when its run includes that sample)";
      add_checks(report, prefix, cfg.stress_methods[m], ms, where);
    }
  }
}

}  // namespace

const std::vector<std::string>& gate_metrics() {
  static const std::vector<std::string> names = {
      "max_rel_error", "p99_rel_error", "median_rel_error", "max_ulp_error", "p99_ulp_error",
      "median_ulp_error", "max_abs_error_underflow", "max_non_finite"};
  return names;
}

double gate_measure(const MethodStress& m, const std::string& metric) {
  if (metric == "max_non_finite") return static_cast<double>(m.non_finite);
  const double inf = std::numeric_limits<double>::infinity();
  const bool bad = m.non_finite > 0;
  if (metric == "max_rel_error") return bad ? inf : m.rel.max;
  if (metric == "p99_rel_error") return bad ? inf : m.rel.p99;
  if (metric == "median_rel_error") return bad ? inf : m.rel.median;
  if (metric == "max_ulp_error") return bad ? inf : m.ulp.max;
  if (metric == "p99_ulp_error") return bad ? inf : m.ulp.p99;
  if (metric == "median_ulp_error") return bad ? inf : m.ulp.median;
  if (metric == "max_abs_error_underflow") return bad ? inf : m.max_abs_error_underflow;
  throw std::invalid_argument("unknown gate metric '" + metric + "'");
}

bool GateReport::pass() const { return failures() == 0; }

long GateReport::failures() const {
  return static_cast<long>(std::count_if(checks.begin(), checks.end(),
                                         [](const GateCheck& c) { return !c.pass; }));
}

GateReport run_gate(const GateConfig& config,
                    const std::function<void(const GateProgress&)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  GateReport report;
  run_corpus(config, report, progress, start);
  run_stress_part(config, report, progress);
  return report;
}

}  // namespace rayint
