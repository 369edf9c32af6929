// rayint gate [--config cases/gates.json] -- every tolerance of every method, on the corpus and a
// stress sample (src/rayint/studies/gate.hpp, docs/gates.md). One line per check on stdout;
// exit 0 when all hold, 1 when any fails, 2 on a bad config.
#include <cstdio>
#include <functional>
#include <iostream>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "data_dir.hpp"
#include "subcommand.hpp"
#include "options.hpp"
#include "rayint/studies/gate.hpp"
#include "rayint/core/output_dir.hpp"
#include "rayint/input/gate_config.hpp"
#include "rayint/core/atomic_file.hpp"
#include "rayint/input/baseline_reader.hpp"
#include "rayint/input/candidate_reader.hpp"
#include "rayint/input/json_source.hpp"
#include "rayint/report/baseline_json.hpp"
#include "rayint/report/gate_lines.hpp"
#include "rayint/report/junit.hpp"
#include "rayint/report/stress_json.hpp"

namespace rayint::cli {
namespace {

// The drift allowance: 4 ulps. On one machine and compiler a deterministic method reproduces its
// numbers exactly (0 ulps, measured: README "Drift baselines"); the allowance leaves room for a
// different libm or libcerf (erfcx, exp, log1p are not correctly rounded: 1-2 ulps each) and a
// compiler that contracts a*b+c into an FMA, which move a result by a few ulps, while a change of
// the algorithm moves it by many orders more.
constexpr double kDefaultDriftUlps = 4.0;

std::string join(const std::string& dir, const std::string& name) {
  return (std::filesystem::path(dir) / name).string();
}

// The renderer's numbers from its candidate files (docs/candidate-format.md), by case name.
RayResults candidate_results(const std::vector<std::string>& files) {
  RayResults out;
  for (const std::string& f : files) {
    const Candidate c = parse_candidate_text(json_source::read_text_file(f), f);
    if (out.count(c.case_name)) throw InputError(f + ": case: a second candidate for case " + c.case_name);
    out[c.case_name] = c.intensity;
  }
  return out;
}

// One drift check per method (or for the candidates): against DIR/<method>.json.
void add_drift_checks(GateReport& report, const std::map<std::string, RayResults>& now,
                      const std::map<std::string, Baseline>& baselines, const std::string& dir,
                      double allowance) {
  for (const auto& [method, results] : now) {
    GateCheck c;
    c.name = "drift." + method + ".max_ulp_drift";
    c.limit = allowance;
    const auto it = baselines.find(method);
    if (it == baselines.end()) {
      c.measured = std::numeric_limits<double>::infinity();
      c.pass = false;
      c.note = "no baseline " + join(dir, baseline_file_name(method)) +
               " (write it with rayint gate --write-baseline " + dir + ")";
    } else {
      const DriftResult d = compare_to_baseline(it->second, results, allowance);
      c.measured = d.mismatch.empty() ? d.max_ulps : std::numeric_limits<double>::infinity();
      c.pass = d.mismatch.empty() && d.max_ulps <= allowance;
      c.note = !d.mismatch.empty() ? d.mismatch
               : d.max_ulps > 0   ? std::to_string(d.drifted) + " of " + std::to_string(d.values) +
                                      " values beyond the allowance; largest at " + d.where
                                  : "";
    }
    report.checks.push_back(std::move(c));
  }
}

}  // namespace

void set_gate_command(CLI::App& app) {
  struct Options {
    std::string config = "cases/gates.json";
    int threads = 0;
    bool json = false;
    std::string output;
    bool quiet = false;
    std::string junit;
    std::string baseline;        // --baseline DIR: drift checks against DIR's baselines
    std::string write_baseline;  // --write-baseline DIR
    double drift_ulps = kDefaultDriftUlps;
    std::vector<std::string> candidates;  // --candidate FILE...: a renderer's own numbers
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = add_command(
      app, "gate", "Check every method's tolerances on the corpus and a stress sample (exit 1 on failure)",
      "0 every check passed; 1 some check failed (a method that failed on some ray "
      "fails the check <part>.<case>.<method>.failed whatever its limits); 2 bad configuration, "
      "including an invalid method spec in it.");
  cmd->add_option("--config", opt->config,
                  "Gate config (docs/gates.md); its relative paths are resolved against the "
                  "directory that holds it. Outside a source tree the default is the installed "
                  "<prefix>/share/rayint/cases/gates.json")
      ->capture_default_str();
  add_threads_option(cmd, opt->threads)->capture_default_str();
  cmd->add_flag("--json", opt->json, "JSON instead of one line per check");
  add_output_option(cmd, opt->output, "Write the result to this file instead of stdout");
  add_quiet_flag(cmd, opt->quiet);
  cmd->add_option("--junit", opt->junit, "Also write the checks as JUnit XML to this file");
  auto* baseline = cmd->add_option(
      "--baseline", opt->baseline,
      "Drift: compare every corpus method's per-ray numbers (or the --candidate files') with the "
      "baselines in this directory; fail beyond --drift-ulps");
  auto* write = cmd->add_option("--write-baseline", opt->write_baseline,
                                "Drift: (re)write the baselines into this directory");
  baseline->excludes(write);
  cmd->add_option("--drift-ulps", opt->drift_ulps, "Drift allowance in ulps")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--candidate", opt->candidates,
                  "Drift of your renderer: its candidate files (docs/candidate-format.md) instead "
                  "of the config's methods; needs --baseline or --write-baseline")
      ->check(CLI::ExistingFile);
  cmd->callback([opt] {
    const bool drift = !opt->baseline.empty() || !opt->write_baseline.empty();
    if (!opt->candidates.empty() && !drift)
      throw InputError("--candidate: needs --baseline DIR or --write-baseline DIR");
    std::map<std::string, Baseline> baselines;  // read before the run: bad input fails early
    if (!opt->baseline.empty()) {
      require_input_directory(opt->baseline, "--baseline");
      for (const auto& e : std::filesystem::directory_iterator(opt->baseline))
        if (e.path().extension() == ".json") {
          Baseline b = read_baseline_file(e.path().string());
          baselines[b.method] = std::move(b);
        }
    }
    if (!opt->write_baseline.empty()) ensure_output_directory(opt->write_baseline, "--write-baseline");
    GateReport report;
    std::map<std::string, RayResults> now;
    if (!opt->candidates.empty()) {
      now["candidates"] = candidate_results(opt->candidates);
    } else {
      GateConfig config = read_gate_config(bundled_path(opt->config));
      config.threads = opt->threads;
      std::function<void(const GateProgress&)> progress;
      if (!opt->quiet)
        progress = [](const GateProgress& p) { std::fputs(gate_progress_line(p).c_str(), stderr); };
      report = run_gate(config, progress);
      now = report.corpus_results;
    }
    if (!opt->baseline.empty()) add_drift_checks(report, now, baselines, opt->baseline, opt->drift_ulps);
    if (!opt->write_baseline.empty()) {
      std::string command = "rayint gate";
      if (opt->candidates.empty()) command += " --config " + opt->config;
      for (const std::string& c : opt->candidates) command += " --candidate " + c;
      command += " --write-baseline " + opt->write_baseline;
      for (const auto& [method, results] : now)
        write_file_atomically(join(opt->write_baseline, baseline_file_name(method)),
                              baseline_text(Baseline{method, command, results}));
    }

    emit(opt->json ? to_json(report).dump(2) : gate_lines(report), opt->output);
    if (!opt->junit.empty()) write_file_atomically(opt->junit, junit_xml({gate_junit(report)}));
    std::cout.flush();
    // The callback cannot return an exit code and main() maps exceptions to 2 (bad input), so a
    // failed gate ends here with 1, after its report is written and flushed.
    if (!report.pass()) throw ChecksFailed{};
  });
}

}  // namespace rayint::cli
