// rayint check CASE.json --candidate THEIRS.json -- another renderer's per-ray intensities
// against the exact values; writes a JSON diff (docs/candidate-format.md). Exit 0 when every
// channel of every ray is within tolerance, 1 when one is not, 2 on bad input.
#include <cmath>
#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "options.hpp"
#include "rayint/studies/check.hpp"
#include "rayint/input/candidate_reader.hpp"
#include "rayint/report/check_json.hpp"
#include "rayint/report/check_summary.hpp"
#include "rayint/input/case_reader.hpp"

namespace rayint::cli {
namespace {

// A tolerance: a finite number >= 0 (CLI11's NonNegativeNumber lets "nan" through).
const CLI::Validator kTolerance(
    [](std::string& text) -> std::string {
      double x = 0.0;
      if (!CLI::detail::lexical_cast(text, x) || !std::isfinite(x) || x < 0.0)
        return "must be a finite number >= 0, got " + text;
      return {};
    },
    "TOL>=0");

}  // namespace

void set_check_command(CLI::App& app) {
  struct Options {
    std::string case_file;
    std::string candidate_file;
    std::string output;
    CheckOptions check;
    bool no_reference = false;
    MeshReadOptions mesh;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "check", "Compare another renderer's per-ray intensities with the exact values");
  cmd->add_option("case", opt->case_file, "Case file (JSON)")->required();
  cmd->add_option("--candidate", opt->candidate_file,
                  "The renderer's intensities (JSON, docs/candidate-format.md)")
      ->required();
  cmd->add_option("--rel-tol", opt->check.rel_tol,
                  "Relative tolerance: a channel passes if "
                  "|got - expected| <= max(abs-tol, rel-tol * |expected|)")
      ->check(kTolerance)
      ->capture_default_str();
  cmd->add_option("--abs-tol", opt->check.abs_tol, "Absolute tolerance (see --rel-tol)")
      ->check(kTolerance)
      ->capture_default_str();
  cmd->add_flag("--no-reference", opt->no_reference,
                "Skip the 50-digit reference (reported for context only; costs time on big cases)");
  cmd->add_option("-o,--output", opt->output, "Write the diff to this file instead of stdout");
  add_strict_mesh_flag(cmd, opt->mesh.strict);
  cmd->callback([opt] {
    const Case c = read_case_file(opt->case_file, opt->mesh);
    const Candidate candidate = read_candidate_file(opt->candidate_file, c);
    CheckOptions co = opt->check;
    co.with_reference = !opt->no_reference;
    const CheckResult result = check_candidate(c, candidate, co);
    emit(check_report_json(result).dump(2), opt->output);
    std::cout.flush();
    std::cerr << check_summary_line(result) << std::endl;
    // The callback cannot return an exit code and main() maps exceptions to 2 (bad input), so a
    // failed check ends here with 1, after its diff is written and flushed.
    if (!result.pass) throw ChecksFailed{};
  });
}

}  // namespace rayint::cli
