// rayint gate [--config cases/gates.json] -- every tolerance of every method, on the corpus and a
// stress sample (src/rayint/studies/gate.hpp, docs/gates.md). One line per check on stdout;
// exit 0 when all hold, 1 when any fails, 2 on a bad config.
#include <cstdio>
#include <functional>
#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "options.hpp"
#include "rayint/studies/gate.hpp"
#include "rayint/input/gate_config.hpp"
#include "rayint/report/gate_lines.hpp"
#include "rayint/report/stress_json.hpp"

namespace rayint::cli {

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
  add_threads_option(cmd, opt->threads)->capture_default_str();
  cmd->add_flag("--json", opt->json, "JSON instead of one line per check");
  cmd->add_option("-o,--output", opt->output, "Write the result to this file instead of stdout");
  add_quiet_flag(cmd, opt->quiet);
  cmd->callback([opt] {
    GateConfig config = read_gate_config(opt->config);
    config.threads = opt->threads;
    std::function<void(const GateProgress&)> progress;
    if (!opt->quiet)
      progress = [](const GateProgress& p) { std::fputs(gate_progress_line(p).c_str(), stderr); };
    const GateReport report = run_gate(config, progress);
    emit(opt->json ? to_json(report).dump(2) : gate_lines(report), opt->output);
    std::cout.flush();
    // The callback cannot return an exit code and main() maps exceptions to 2 (bad input), so a
    // failed gate ends here with 1, after its report is written and flushed.
    if (!report.pass()) throw ChecksFailed{};
  });
}

}  // namespace rayint::cli
