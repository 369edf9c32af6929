// rayint eval CASE.json [...] -- every method against the 50-digit reference, per ray.
// Progress on stderr (at most one line a second, none with --quiet); --no-reference skips the
// reference and the error fields.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "commands.hpp"
#include "progress.hpp"
#include "subcommand.hpp"
#include "options.hpp"
#include "rayint/studies/evaluate.hpp"
#include "rayint/input/case_reader.hpp"
#include "rayint/report/evaluation_json.hpp"
#include "rayint/report/evaluation_table.hpp"
#include "rayint/report/cell_render_json.hpp"
#include "rayint/studies/own_cells_eval.hpp"

namespace rayint::cli {

// From this many rays on (a 32 x 32 camera), eval warns before it computes the reference.
constexpr std::size_t kManyRays = 1024;

void set_eval_command(CLI::App& app) {
  struct Options {
    std::vector<std::string> files;
    std::string methods;
    std::string format = "json";
    std::string output;
    bool no_timing = false;
    bool no_reference = false;
    bool quiet = false;
    double progress_every = 1.0;
    MeshReadOptions mesh;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = add_command(
      app, "eval", "Evaluate case files with each method against the 50-digit reference",
      "0 every method ran on every ray; 1 some method failed on some ray (output "
      "written, the failed rays with null errors and their failure text, a failed count per "
      "method); 2 bad input (nothing written).");
  cmd->add_option("cases", opt->files, "Case files (JSON) or folders of them")->required();
  cmd->add_option("--methods", opt->methods,
                  "Comma-separated methods, each name[:key=value...] (default: exact,paper)");
  cmd->add_option("--format", opt->format, "json or table")
      ->check(CLI::IsMember({"json", "table"}));
  add_output_option(cmd, opt->output);
  cmd->add_flag("--no-timing", opt->no_timing, "Skip the timing runs (seconds_per_ray = 0)");
  cmd->add_flag("--no-reference", opt->no_reference,
                "Skip the 50-digit reference and the error fields (costs time on big cases)");
  add_quiet_flag(cmd, opt->quiet);
  cmd->add_option("--progress-every", opt->progress_every,
                  "Seconds between progress lines on stderr (0: every step)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  add_strict_mesh_flag(cmd, opt->mesh.strict);
  add_cells_option(cmd, opt->mesh.split_cells);
  cmd->callback([opt] {
    const std::vector<MethodSpec> methods =
        opt->methods.empty() ? default_methods() : parse_methods_option(opt->methods);
    using clock = std::chrono::steady_clock;
    const auto start = clock::now();
    auto last = start;
    // True (and the clock reset) when --progress-every seconds have passed since the last line.
    const auto line_due = [&]() {
      const auto now = clock::now();
      if (opt->quiet || std::chrono::duration<double>(now - last).count() < opt->progress_every)
        return false;
      last = now;
      return true;
    };
    const auto seconds = [&]() { return std::chrono::duration<double>(clock::now() - start).count(); };
    std::vector<Case> cases;
    std::vector<std::optional<TetRepairs>> repairs;  // mesh cases: reoriented / dropped tets
    std::vector<MeshCase> own;  // mesh cases of cells other than tetrahedra ("mode": "own")
    // Every file is read (and so validated) before any is evaluated: a bad one must give one line
    // and nothing before it (issue 30). While reading, progress is a terminal line rewritten in
    // place (main ends it before an error); in a log, one line once all files are read.
    ProgressLine read_progress;
    bool read_was_slow = false;
    const auto read = [&](const std::string& file) {
      repairs.emplace_back();
      std::optional<MeshCase> own_case;
      Case c = read_case_file(file, opt->mesh, &repairs.back(), &own_case);
      if (own_case) {
        repairs.pop_back();
        own.push_back(std::move(*own_case));
      } else {
        cases.push_back(std::move(c));
      }
      if (!line_due()) return;
      read_was_slow = true;
      if (stderr_is_terminal()) read_progress.update("eval: read " + file, 0.0);
    };
    for (const auto& f : opt->files) {  // a folder means every case file in it
      if (std::filesystem::is_directory(f)) {
        const std::vector<std::string> files = list_case_files(f);
        if (files.empty()) throw InputError(f + ": folder holds no case files (*.json)");
        for (const auto& file : files) read(file);
      } else {
        read(f);  // validate all before evaluating any
      }
    }
    read_progress.finish();
    if (read_was_slow) {
      const std::size_t n = cases.size() + own.size();
      std::fprintf(stderr, "eval: read %zu case file%s, %.0f s\n", n, n == 1 ? "" : "s", seconds());
    }
    if (!own.empty()) {
      // Cells other than tetrahedra in their own interpolation (mesh/cell_traversal.hpp): the
      // methods take linear segments, so these cases are evaluated alone.
      require_own_cases_alone(own, cases.empty() ? std::string() : cases.front().source, !opt->methods.empty(),
                              "--methods", "--cells split");
      std::vector<OwnCaseEvaluation> own_results;
      long failed = 0;
      for (const MeshCase& mc : own) {
        if (!opt->quiet)
          std::fprintf(stderr, "eval: %s: mode own: cells other than tetrahedra integrated in their own (isoparametric) "
                       "interpolation (--cells split: VTK's tetrahedralisation)\n", mc.name.c_str());
        own_results.push_back(evaluate_own_cells(mc, !opt->no_reference));
        failed += own_results.back().failed;
      }
      emit(opt->format == "table" ? own_eval_table(own_results, !opt->no_reference)
                                  : own_eval_json(own_results, !opt->no_reference).dump(2),
           opt->output);
      if (failed > 0) throw ChecksFailed{};  // written, failures marked: exit 1
      return;
    }
    EvalOptions eo;
    eo.measure_time = !opt->no_timing;
    eo.with_reference = !opt->no_reference;
    std::string name;  // the case being evaluated
    eo.progress_seconds = std::max(opt->progress_every, 0.05);
    if (!opt->quiet)
      eo.progress = [&](const EvalProgress& p) {
        if (line_due()) std::fputs(eval_progress_line(name, p, seconds()).c_str(), stderr);
      };
    // A camera case is one ray per pixel: say what the 50-digit reference is about to cost.
    if (!opt->quiet && eo.with_reference)
      for (const Case& c : cases)
        if (c.rays.size() >= kManyRays) {
          std::size_t segments = 0;
          for (const Ray& r : c.rays) segments += r.segments.size();
          std::fprintf(stderr,
                       "eval: %s: %zu rays, %zu segments: the 50-digit reference traces every one "
                       "(minutes or more); --no-reference skips it, `rayint render` draws the image\n",
                       c.name.c_str(), c.rays.size(), segments);
        }
    std::vector<CaseEvaluation> results;
    for (std::size_t i = 0; i < cases.size(); ++i) {
      name = cases[i].name;
      results.push_back(evaluate_case(cases[i], methods, eo));
      results.back().mesh_repairs = repairs[i];
    }
    emit(opt->format == "table" ? evaluation_table(results) : eval_report_json(results).dump(2),
         opt->output);
    if (failed_outcomes(results) > 0) throw ChecksFailed{};  // written, failures marked: exit 1
  });
}

}  // namespace rayint::cli
