// rayint bench [CASES...] -- the accuracy/cost sweep (studies/sweep.hpp): every method along its
// knob, error against the 50-digit reference and time per ray, written as JSON
// (reports/bench.json by default; reports/make_report.py turns it into plots and a README).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "rayint/studies/sweep.hpp"
#include "rayint/input/case_reader.hpp"
#include "rayint/report/sweep_json.hpp"

namespace rayint::cli {
namespace {

// The case files named on the command line (a folder means every case file in it), or every
// case of ./cases when none is named.
std::vector<std::string> case_files(const std::vector<std::string>& args) {
  if (args.empty() && !std::filesystem::is_directory("cases"))
    throw InputError("bench: no case files given and no cases/ folder in " +
                     std::filesystem::current_path().string());
  std::vector<std::string> files;
  for (const auto& a : args.empty() ? std::vector<std::string>{"cases"} : args) {
    if (std::filesystem::is_directory(a)) {
      for (const auto& f : list_case_files(a)) files.push_back(f);
    } else {
      files.push_back(a);
    }
  }
  if (files.empty()) throw InputError("bench: no case files found");
  return files;
}

std::vector<std::string> split_names(const std::string& csv) {
  std::vector<std::string> out;
  std::stringstream in(csv);
  for (std::string item; std::getline(in, item, ',');) {
    if (item.empty()) continue;
    if (item.find(':') != std::string::npos)
      throw std::invalid_argument(
          "bench: --methods takes method names (the sweep chooses the "
          "settings), got '" +
          item + "'");
    out.push_back(item);
  }
  return out;
}

std::string format_error(double e) {
  char buf[32];
  if (!std::isfinite(e)) return "non-finite";
  std::snprintf(buf, sizeof buf, "%.2e", e);
  return buf;
}

std::string format_seconds(double s) {
  char buf[32];
  if (s >= 1e-3)
    std::snprintf(buf, sizeof buf, "%.3g ms", s * 1e3);
  else if (s >= 1e-6)
    std::snprintf(buf, sizeof buf, "%.3g us", s * 1e6);
  else
    std::snprintf(buf, sizeof buf, "%.3g ns", s * 1e9);
  return buf;
}

void print_progress(const SweepProgress& p) {
  char line[320];
  switch (p.stage) {
    case SweepProgress::Stage::reference:
      std::snprintf(line, sizeof line, "[reference %2zu/%zu] %-34s %7.1f s\n", p.done, p.total,
                    p.what.c_str(), p.elapsed_seconds);
      break;
    case SweepProgress::Stage::setting: {
      const SettingResult& s = *p.setting;
      std::string note;
      if (s.failed_rays > 0) note += "  failed on " + std::to_string(s.failed_rays) + " rays";
      if (s.nonfinite > 0) note += "  " + std::to_string(s.nonfinite) + " non-finite";
      if (s.setup_seconds >= 0.05) {
        char setup[48];
        std::snprintf(setup, sizeof setup, "  set-up %.1f s", s.setup_seconds);
        note += setup;
      }
      std::snprintf(line, sizeof line,
                    "[%3zu/%zu] %-26s max %-10s median %-10s %11s/ray %7.1f s%s\n", p.done, p.total,
                    p.what.c_str(), format_error(s.max_error).c_str(),
                    format_error(s.median_error).c_str(), format_seconds(s.seconds_per_ray).c_str(),
                    p.elapsed_seconds, note.c_str());
      break;
    }
    case SweepProgress::Stage::skipped:
      std::snprintf(line, sizeof line, "[%3zu/%zu] %-26s skipped: %s\n", p.done, p.total,
                    p.what.c_str(), p.reason.c_str());
      break;
  }
  std::cerr << line << std::flush;
}

std::string format_targets(const SweepResult& r) {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof line, "exact: %s per ray (mean over %zu rays)\n",
                format_seconds(r.exact_seconds_per_ray).c_str(), r.rays);
  out += line;
  std::snprintf(line, sizeof line, "%-8s %-14s %-28s %12s %10s\n", "max err", "method",
                "cheapest setting", "time/ray", "x exact");
  out += line;
  for (const auto& t : r.targets) {
    if (t.statistic != ErrorStatistic::max) continue;
    char target[16];
    std::snprintf(target, sizeof target, "%.0e", t.target);
    if (t.reached)
      std::snprintf(line, sizeof line, "%-8s %-14s %-28s %12s %10.3g\n", target, t.method.c_str(),
                    t.label.c_str(), format_seconds(t.seconds_per_ray).c_str(), t.cost_vs_exact);
    else
      std::snprintf(line, sizeof line, "%-8s %-14s %-28s\n", target, t.method.c_str(),
                    t.truncated ? "not reached (sweep truncated)" : "not reached");
    out += line;
  }
  if (r.truncated) out += "truncated: " + r.truncation + "\n";
  return out;
}

}  // namespace

void set_bench_command(CLI::App& app) {
  struct Options {
    std::vector<std::string> files;
    std::string methods;
    double max_seconds = 0.0;
    double method_seconds = 0.0;
    std::string output = "reports/bench.json";
    int batches = 5;
    double batch_seconds = 1e-3;
    int threads = 0;
    bool quiet = false;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "bench", "Accuracy/cost sweep: every method along its knob, error and time per ray");
  cmd->add_option("cases", opt->files,
                  "Case files (JSON) or folders of them; default: the folder cases/");
  cmd->add_option("--methods", opt->methods,
                  "Comma-separated method names to sweep (default: all; exact always runs)");
  cmd->add_option(
         "--max-seconds", opt->max_seconds,
         "Budget in seconds for measuring all settings, after the references; exact always "
         "runs in full (0 = none)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--method-seconds", opt->method_seconds, "The same budget per method (0 = none)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("-o,--output", opt->output, "JSON output file ('-' = stdout)")
      ->capture_default_str();
  cmd->add_option("--batches", opt->batches, "Timing batches per ray (median taken)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--batch-seconds", opt->batch_seconds, "Minimum length of one timing batch")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--threads", opt->threads, "Threads for the reference (0 = all cores)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("-q,--quiet", opt->quiet, "No progress on stderr");
  cmd->callback([opt] {
    const std::vector<SweepAxis> axes = select_sweep_axes(split_names(opt->methods));
    const std::vector<std::string> files = case_files(opt->files);
    std::vector<Case> cases;
    for (const auto& f : files) cases.push_back(read_case_file(f));  // validate all first
    if (opt->output != "-") {
      const auto parent = std::filesystem::path(opt->output).parent_path();
      if (!parent.empty()) std::filesystem::create_directories(parent);
    }
    SweepOptions so;
    so.timing.timing_batches = opt->batches;
    so.timing.timing_batch_seconds = opt->batch_seconds;
    so.timing.threads = opt->threads;
    so.max_seconds = opt->max_seconds;
    so.method_max_seconds = opt->method_seconds;
    if (!opt->quiet) so.progress = print_progress;
    const SweepResult result = run_sweep(cases, axes, so);
    emit(sweep_report_json(result).dump(1), opt->output);
    if (opt->output != "-") {
      std::cout << format_targets(result);
      std::cout << "wrote " << opt->output << "\n";
    }
  });
}

}  // namespace rayint::cli
