// rayint stress -- adversarial pieces and rays, regime by regime, each method against the 50-digit
// reference (src/rayint/studies/stress.hpp); a table or JSON on stdout, progress on stderr, the
// worst sample of each regime and method written as a replayable case file.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "subcommand.hpp"
#include "options.hpp"
#include "shard.hpp"
#include "rayint/core/limits.hpp"
#include "rayint/core/output_dir.hpp"
#include "rayint/input/shard_reader.hpp"
#include "rayint/report/shard_json.hpp"
#include "rayint/studies/stress.hpp"
#include "rayint/report/stress_json.hpp"
#include "rayint/report/stress_table.hpp"

namespace rayint::cli {

void set_stress_command(CLI::App& app) {
  struct Options {
    long count = 10000;
    std::uint64_t seed = 1;
    std::vector<std::string> regimes;
    std::string methods = "exact";
    int threads = 0;
    bool json = false;
    std::string output;
    std::string worst_dir;  // empty: the worst samples are not written
    bool no_worst = false;
    bool quiet = false;
    std::string shard;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = add_command(
      app, "stress", "Adversarial pieces and rays, regime by regime, against the 50-digit reference",
      "0 no method and no reference failed; 1 a method threw or returned a "
      "non-finite result, or the reference failed, on some sample (report written, counted in "
      "the nonfin and failed columns); 2 bad input.");
  cmd->add_option("--count", opt->count,
                  "Pieces in total, split evenly over the regimes (ray-level regimes draw whole "
                  "rays until their pieces reach their share)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--seed", opt->seed, "Seed; the same seed gives the same report")
      ->check(CLI::NonNegativeNumber)  // else CLI11 wraps -1 to 2^64 - 1
      ->capture_default_str();
  std::string regime_help = "Regimes to run (repeat or comma-separate; default all):";
  for (const Regime r : stress_regimes()) regime_help += " " + regime_name(r);
  regime_help += "; opt-in, by name only:";
  for (const Regime r : extra_regimes()) regime_help += " " + regime_name(r);
  cmd->add_option("--regime", opt->regimes, regime_help)->delimiter(',');
  cmd->add_option("--methods", opt->methods,
                  "Comma-separated methods, each name[:key=value...]")
      ->capture_default_str();
  add_threads_option(cmd, opt->threads)->capture_default_str();
  cmd->add_flag("--json", opt->json, "JSON report instead of the table");
  add_output_option(cmd, opt->output, "Write the report to this file instead of stdout");
  cmd->add_option("--worst-dir", opt->worst_dir,
                  "Folder (created when missing) for the worst sample of each regime and method, as "
                  "case files; without it they are not written");
  cmd->add_flag("--no-worst", opt->no_worst, "Do not write the worst samples (the default without --worst-dir)");
  add_quiet_flag(cmd, opt->quiet);
  add_shard_option(cmd, opt->shard);
  cmd->callback([opt] {
    StressOptions so;
    so.count = opt->count;
    limits::check(limits::kStressSamples, static_cast<double>(so.count), "--count");
    so.seed = opt->seed;
    so.methods = parse_methods_option(opt->methods);
    so.threads = opt->threads;
    for (const auto& name : opt->regimes) {
      if (name == "all") {
        so.regimes.clear();
        break;
      }
      Regime r;
      if (!parse_regime(name, r)) throw std::invalid_argument("--regime: unknown regime '" + name + "'");
      so.regimes.push_back(r);
    }
    if (!opt->quiet)
      so.progress = [](const StressProgress& p) { std::fputs(stress_progress_line(p).c_str(), stderr); };
    const bool in_shard = !opt->shard.empty();
    if (!in_shard && !opt->no_worst && !opt->worst_dir.empty()) ensure_output_directory(opt->worst_dir, "--worst-dir");
    so.shard = begin_shard(opt->shard, opt->output);
    if (in_shard) {  // this shard's part of the run, for `rayint merge`
      write_shard(opt->output, "stress", so.shard, {}, to_json(run_stress_part(so)));
      return;
    }
    StressReport report;
    if (merging()) {
      // every regime's samples exactly once: each part holds what its shard evaluates
      const auto check = [&so](std::size_t i, const StressPartial& part) {
        const std::vector<long> want = stress_shard_samples(so, merged_shard(i));
        check_shard_count(i, want.size(), part.regimes.size(), "data.regimes (regimes)");
        for (std::size_t r = 0; r < want.size(); ++r)
          check_shard_count(i, static_cast<std::size_t>(want[r]), static_cast<std::size_t>(part.regimes[r].samples),
                            "data.regimes[" + std::to_string(r) + "].samples");
      };
      report = finish_stress(so, merged_parts("stress", {}, stress_partial_from_json, check));
    } else {
      report = run_stress(so);
    }
    if (!opt->no_worst && !opt->worst_dir.empty()) write_worst_cases(report, opt->worst_dir);
    emit(opt->json ? to_json(report).dump(2) : stress_table(report), opt->output);
    // A method that failed (threw or returned a non-finite result) or a reference that failed on
    // some sample: written and counted, exit 1.
    long failed = 0;
    for (const auto& m : report.overall) failed += m.non_finite;
    for (const auto& reg : report.regimes) failed += reg.reference_failures;
    if (failed > 0) throw ChecksFailed{};
  });
}

}  // namespace rayint::cli
