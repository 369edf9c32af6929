// rayint eval CASE.json [...] -- every method against the 50-digit reference, per ray.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "commands.hpp"
#include "rayint/studies/evaluate.hpp"
#include "rayint/input/case_reader.hpp"
#include "rayint/report/evaluation_json.hpp"

namespace rayint::cli {
namespace {

std::string format_table(const std::vector<CaseEvaluation>& cases) {
  std::string out;
  char line[512];
  std::snprintf(line, sizeof line, "%-34s %-22s %5s %11s %11s %11s %12s  %s\n", "case", "method",
                "rays", "max rel", "max ulp", "ref rel est", "time/ray", "branches");
  out += line;
  out += std::string(130, '-') + "\n";
  for (const auto& c : cases) {
    if (c.rays.empty()) continue;
    for (std::size_t m = 0; m < c.rays.front().methods.size(); ++m) {
      double max_rel = 0, max_ulp = 0, ref_rel = 0, time = 0;
      bool finite = true;
      Diagnostics merged;
      for (const auto& ray : c.rays) {
        const auto& o = ray.methods[m];
        finite = finite && o.finite;
        for (int ch = 0; ch < kChannels; ++ch) {
          max_rel = std::max(max_rel, o.rel_error[ch]);
          max_ulp = std::max(max_ulp, o.ulp_error[ch]);
          const double mag = std::fabs(ray.reference.intensity[ch].hi);
          if (mag > 0) ref_rel = std::max(ref_rel, ray.reference.error_bound[ch] / mag);
        }
        time += o.seconds_per_ray;
        for (const auto& [k, v] : o.diagnostics.branches) merged.branches[k] += v;
      }
      std::string branches;
      for (const auto& [k, v] : merged.branches)
        branches += (branches.empty() ? "" : " ") + k + "=" + std::to_string(v);
      const auto& label = c.rays.front().methods[m].method;
      std::snprintf(line, sizeof line, "%-34.34s %-22.22s %5zu %11.3g %11.3g %11.1e %9.3g us  %s%s\n",
                    c.name.c_str(), label.c_str(), c.rays.size(), max_rel, max_ulp, ref_rel,
                    time / static_cast<double>(c.rays.size()) * 1e6, finite ? "" : "NON-FINITE ",
                    branches.c_str());
      out += line;
    }
  }
  return out;
}

}  // namespace

void set_eval_command(CLI::App& app) {
  struct Options {
    std::vector<std::string> files;
    std::string methods;
    std::string format = "json";
    std::string output;
    bool no_timing = false;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "eval", "Evaluate case files with each method against the 50-digit reference");
  cmd->add_option("cases", opt->files, "Case files (JSON) or folders of them")->required();
  cmd->add_option("--methods", opt->methods,
                  "Comma-separated methods, each name[:key=value...] (default: exact,paper)");
  cmd->add_option("--format", opt->format, "json or table")
      ->check(CLI::IsMember({"json", "table"}));
  cmd->add_option("-o,--output", opt->output, "Write to this file instead of stdout");
  cmd->add_flag("--no-timing", opt->no_timing, "Skip the timing runs (seconds_per_ray = 0)");
  cmd->callback([opt] {
    const std::vector<MethodSpec> methods =
        opt->methods.empty() ? default_methods() : parse_method_list(opt->methods);
    std::vector<Case> cases;
    for (const auto& f : opt->files) {  // a folder means every case file in it
      if (std::filesystem::is_directory(f)) {
        const std::vector<std::string> files = list_case_files(f);
        if (files.empty()) throw InputError(f + ": folder holds no case files (*.json)");
        for (const auto& file : files) cases.push_back(read_case_file(file));
      } else {
        cases.push_back(read_case_file(f));  // validate all before evaluating any
      }
    }
    EvalOptions eo;
    eo.measure_time = !opt->no_timing;
    std::vector<CaseEvaluation> results;
    for (const auto& c : cases) results.push_back(evaluate_case(c, methods, eo));
    emit(opt->format == "table" ? format_table(results) : eval_report_json(results).dump(2),
         opt->output);
  });
}

}  // namespace rayint::cli
