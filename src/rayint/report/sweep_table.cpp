#include "rayint/report/sweep_table.hpp"

#include <cmath>
#include <cstdio>

#include "rayint/report/text_format.hpp"

namespace rayint {
namespace {

std::string format_error(double e) {
  return std::isfinite(e) ? printf_number("%.2e", e) : "non-finite";
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

}  // namespace

std::string sweep_progress_line(const SweepProgress& p) {
  std::string line;
  switch (p.stage) {
    case SweepProgress::Stage::reference:
      appendf(line, "[reference %2zu/%zu] %-34s %7.1f s\n", p.done, p.total, p.what.c_str(),
              p.elapsed_seconds);
      break;
    case SweepProgress::Stage::setting: {
      const SettingResult& s = *p.setting;
      // A setting that ran on no ray has no error and no time: "-", never "max 0".
      const bool scored = s.channels > 0;
      std::string note;
      if (s.failed_rays > 0) note += "  failed on " + std::to_string(s.failed_rays) + " rays";
      if (s.nonfinite > 0) note += "  " + std::to_string(s.nonfinite) + " non-finite";
      if (s.setup_seconds >= 0.05) {
        char setup[48];
        std::snprintf(setup, sizeof setup, "  set-up %.1f s", s.setup_seconds);
        note += setup;
      }
      appendf(line, "[%3zu/%zu] %-26s max %-10s median %-10s %11s/ray %7.1f s%s\n", p.done, p.total,
              p.what.c_str(), scored ? format_error(s.max_error).c_str() : "-",
              scored ? format_error(s.median_error).c_str() : "-",
              scored ? format_seconds(s.seconds_per_ray).c_str() : "-", p.elapsed_seconds,
              note.c_str());
      break;
    }
    case SweepProgress::Stage::skipped:
      appendf(line, "[%3zu/%zu] %-26s skipped: %s\n", p.done, p.total, p.what.c_str(),
              p.reason.c_str());
      break;
  }
  return line;
}

std::string sweep_targets_table(const SweepResult& r) {
  std::string out;
  appendf(out, "exact: %s per ray (mean over %zu rays)\n",
          format_seconds(r.exact_seconds_per_ray).c_str(), r.rays);
  appendf(out, "%-8s %-14s %-28s %12s %10s\n", "max err", "method", "cheapest setting", "time/ray",
          "x exact");
  for (const auto& t : r.targets) {
    if (t.statistic != ErrorStatistic::max) continue;
    char target[16];
    std::snprintf(target, sizeof target, "%.0e", t.target);
    if (t.reached)
      appendf(out, "%-8s %-14s %-28s %12s %10.3g\n", target, t.method.c_str(), t.label.c_str(),
              format_seconds(t.seconds_per_ray).c_str(), t.cost_vs_exact);
    else
      appendf(out, "%-8s %-14s %-28s\n", target, t.method.c_str(),
              t.truncated ? "not reached (sweep truncated)" : "not reached");
  }
  if (r.truncated) out += "truncated: " + r.truncation + "\n";
  // Settings that failed on some rays (threw, e.g. particle on a case with several transfer
  // functions): their errors are over the other rays only, and they never meet a target.
  for (const auto& m : r.methods) {
    std::size_t failed_settings = 0;
    const SettingResult* first = nullptr;
    for (const auto& s : m.settings)
      if (s.failed_rays > 0) {
        ++failed_settings;
        if (!first) first = &s;
      }
    if (failed_settings == 0) continue;
    out += "failed: " + m.method + ": " + std::to_string(failed_settings) + " of " +
           std::to_string(m.settings.size()) + " settings failed on some rays (" + first->label +
           " on " + std::to_string(first->failed_rays) + " of " + std::to_string(first->rays) +
           " rays; first: " + first->failure + ")\n";
  }
  return out;
}

std::string own_split_table(const OwnSplitRun& run) {
  std::string out;
  appendf(out, "%-24s %8s %8s %12s %12s %9s %11s\n", "own vs split", "cells", "tets", "own",
          "split", "own/split", "max |diff|");
  for (const OwnSplitCase& c : run.cases) {
    const std::string tets = c.split_ran ? std::to_string(c.tets) : "-";
    const std::string split = c.split_ran ? format_seconds(c.split_seconds) : "-";
    char ratio[32] = "-";
    if (std::isfinite(c.ratio())) std::snprintf(ratio, sizeof ratio, "%.2f", c.ratio());
    const std::string diff = c.compared_rays > 0 ? format_error(c.max_abs_difference) : "-";
    appendf(out, "%-24s %8ld %8s %12s %12s %9s %11s\n", c.name.c_str(), c.cell_total, tets.c_str(),
            format_seconds(c.own_seconds).c_str(), split.c_str(), ratio, diff.c_str());
  }
  out += "(" + std::to_string(run.repetitions) + " repetitions, median CPU time of every ray once, single thread)\n";
  for (const OwnSplitCase& c : run.cases) {
    if (!c.split_ran) out += "failed: " + c.name + ": no split: " + c.split_failure + "\n";
    if (c.own_failed_rays > 0)
      out += "failed: " + c.name + ": own on " + std::to_string(c.own_failed_rays) + " of " + std::to_string(c.rays) +
             " rays (first: " + c.own_failure + ")\n";
    if (c.split_ran && c.split_failed_rays > 0)
      out += "failed: " + c.name + ": split on " + std::to_string(c.split_failed_rays) + " of " + std::to_string(c.rays) +
             " rays (first: " + c.split_failure + ")\n";
  }
  return out;
}

}  // namespace rayint
