// rayint gate [--config cases/gates.json] -- every tolerance of every method, on the corpus and a
// stress sample (src/rayint/studies/gate.hpp, docs/gates.md). One line per check on stdout;
// exit 0 when all hold, 1 when any fails, 2 on a bad config.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "rayint/studies/gate.hpp"
#include "rayint/input/gate_config.hpp"
#include "rayint/report/stress_json.hpp"

namespace rayint::cli {
namespace {

std::string g3(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

// "PASS name: measured X (limit Y)"; a failure adds by how much.
std::string format_lines(const GateReport& r) {
  std::string out;
  for (const GateCheck& c : r.checks) {
    out += std::string(c.pass ? "PASS " : "FAIL ") + c.name + ": measured " + g3(c.measured) +
           " (limit " + g3(c.limit) + ")";
    if (!c.pass && c.limit > 0 && std::isfinite(c.measured))
      out += ", " + g3(c.measured / c.limit) + " times the limit";
    if (!c.note.empty()) out += " -- " + c.note;
    out += "\n";
  }
  out += "gate: " + std::to_string(r.checks.size()) + " checks, " + std::to_string(r.failures()) +
         " failed: " + (r.pass() ? "PASS" : "FAIL") + "\n";
  return out;
}

}  // namespace

void set_gate_command(CLI::App& app) {
  struct Options {
    std::string config = "cases/gates.json";
    int threads = 0;
    bool json = false;
    std::string output;
    bool quiet = false;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "gate", "Check every method's tolerances on the corpus and a stress sample (exit 1 on failure)");
  cmd->add_option("--config", opt->config,
                  "Gate config (docs/gates.md); its relative paths are resolved against the "
                  "directory that holds it")
      ->capture_default_str();
  cmd->add_option("--threads", opt->threads, "Worker threads (0: all cores)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_flag("--json", opt->json, "JSON instead of one line per check");
  cmd->add_option("-o,--output", opt->output, "Write the result to this file instead of stdout");
  cmd->add_flag("-q,--quiet", opt->quiet, "No progress on stderr");
  cmd->callback([opt] {
    GateConfig config = read_gate_config(opt->config);
    config.threads = opt->threads;
    std::function<void(const GateProgress&)> progress;
    if (!opt->quiet)
      progress = [](const GateProgress& p) {
        std::fprintf(stderr, "gate: %s %ld/%ld, %.0f s\n", p.phase.c_str(), p.done, p.total, p.seconds);
      };
    const GateReport report = run_gate(config, progress);
    emit(opt->json ? to_json(report).dump(2) : format_lines(report), opt->output);
    std::cout.flush();
    // The callback cannot return an exit code and main() maps exceptions to 2 (bad input), so a
    // failed gate ends here with 1, after its report is written and flushed.
    if (!report.pass()) throw ChecksFailed{};
  });
}

}  // namespace rayint::cli
