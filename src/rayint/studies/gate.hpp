#pragma once
// `rayint gate`: the accuracy tolerances of every method, on the case corpus and on a stress
// sample, kept in one config file (cases/gates.json; format in docs/gates.md) and checked in one
// run. Each limit becomes a named check with its measured value; the gate holds when all pass.
// The figures are the ones `rayint stress` and `rayint eval` report (score_sample, error_stats),
// so a gate and a report never disagree about a number.
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "rayint/studies/drift.hpp"
#include "rayint/studies/stress.hpp"

namespace rayint {

// The metrics a limit can bound (each an upper limit, measured per case or per regime):
//   max_rel_error, p99_rel_error, median_rel_error   relative error of the intensity
//   max_ulp_error, p99_ulp_error, median_ulp_error   the same in ulps
//   max_abs_error_underflow   absolute error where |reference| < kUnderflowFloor
//   max_non_finite            count of non-finite results (or failures)
// A non-finite result makes every error metric +inf, so an error limit alone also catches it.
const std::vector<std::string>& gate_metrics();
double gate_measure(const MethodStress& m, const std::string& metric);  // throws invalid_argument

// One limit set of one method. A method may have several (different limits on different cases
// or regimes); it is run once and each set checked.
struct GateMethod {
  MethodSpec spec;
  std::map<std::string, double> limits;  // metric -> upper limit
  std::vector<std::string> only;         // case names (corpus) or regime names (stress); empty: all
};

struct GateConfig {
  std::string source;                   // the config file, for messages
  std::vector<std::string> case_files;  // the corpus, resolved paths
  std::vector<Case> cases;              // the corpus as read (input/gate_config.hpp reads them)
  std::vector<GateMethod> corpus_methods;
  bool stress = false;                  // run the stress part
  long stress_count = 0;
  std::uint64_t stress_seed = 1;
  std::vector<Regime> stress_regimes;   // empty: all
  std::vector<GateMethod> stress_methods;
  unsigned threads = 0;                 // 0: all cores
};

struct GateCheck {
  std::string name;  // "corpus.<case>.<method>.<metric>", "corpus.<case>.<method>.failed", "stress.<regime>.<method>.<metric>",
                     // "stress.<regime>.reference_failures", "corpus.<case>.evaluation"
  double measured = 0.0;
  double limit = 0.0;
  bool pass = false;
  std::string note;  // why a check without a number failed (e.g. an exception's message)
};

struct GateReport {
  std::vector<GateCheck> checks;
  // Per corpus method (MethodSpec::canonical(), so a baseline matches however the spec was
  // typed): its per-ray intensities on every case it ran on, for the
  // drift baselines (studies/drift.hpp); NaN where the method threw.
  std::map<std::string, RayResults> corpus_results;
  bool pass() const;
  long failures() const;
};

struct GateProgress {
  std::string phase;  // "corpus" (done/total cases) or "stress" (done/total pieces)
  long done = 0, total = 0;
  double seconds = 0.0;
};

// Runs the corpus part (config.cases, read by input/gate_config.hpp) then the stress part.
GateReport run_gate(const GateConfig& config,
                    const std::function<void(const GateProgress&)>& progress = {});

}  // namespace rayint
