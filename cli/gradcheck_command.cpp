// rayint gradcheck CASE --candidate CAND.json [--rel-tol R] [--abs-tol A] [--junit J] [--reference]
// -- a renderer's gradients against the exact ones, or with --reference against the 50-digit
// reference gradient (issue 28; format: docs/gradients.md). Pass rule per ray, channel and entry:
// |got - want| <= max(A, R * largest |want| entry of that ray's channel). Exit 0 when all pass, 1
// when one fails (the worst entry is named on stderr), 2 on bad input.
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include "commands.hpp"
#include "options.hpp"
#include "rayint/core/atomic_file.hpp"
#include "rayint/input/case_reader.hpp"
#include "rayint/input/candidate_reader.hpp"
#include "rayint/report/grad_json.hpp"
#include "rayint/report/junit.hpp"
#include "rayint/studies/grad_study.hpp"

namespace rayint::cli {
namespace {


std::string entry_name(const GradCheckEntry& w) {
  static const char* kChannel[3] = {"r", "g", "b"};
  std::ostringstream s;
  s << "ray " << w.ray << " " << w.block;
  if (w.block == "density" || w.block == "color")
    s << " node " << w.index << " " << w.parameter;
  else if (w.block != "background")
    s << " segment " << w.index;
  s << " channel " << kChannel[w.channel];
  return s.str();
}

}  // namespace

void set_gradcheck_command(CLI::App& app) {
  struct Options {
    std::string case_file, candidate_file, output, junit;
    GradCheckOptions check;
    bool reference = false;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("gradcheck", "Compare a renderer's gradients with the exact ones");
  cmd->add_option("case", opt->case_file, "Case file (JSON, ray case)")->required();
  cmd->add_option("--candidate", opt->candidate_file, "The renderer's gradients (JSON, docs/gradients.md)")
      ->required();
  add_tolerance_options(cmd, opt->check.rel_tol, opt->check.abs_tol,
                        "Relative tolerance, of the largest |exact| entry of the ray's channel");
  cmd->add_flag("--reference", opt->reference,
                "Check against the 50-digit reference gradient instead of the analytic exact one (slow "
                "on long rays; the truth where an entry is ill-conditioned, docs/gradients.md)");
  add_threads_option(cmd, opt->check.threads, "Threads for the reference gradient (0: all cores)");
  cmd->add_option("--junit", opt->junit, "Also write the result as JUnit XML to this file");
  add_output_option(cmd, opt->output, "Write the JSON verdict to this file instead of stdout");
  cmd->callback([opt] {
    const Case c = read_case_file(opt->case_file);
    const GradCandidate cand = read_grad_candidate_file(opt->candidate_file, c);
    GradCheckOptions co = opt->check;
    co.against = opt->reference ? GradCheckAgainst::reference : GradCheckAgainst::exact;
    const GradCheckResult r = grad_check(c, cand, co);
    const char* want = opt->reference ? "reference" : "exact";
    emit(gradcheck_report_json(r).dump(2), opt->output);
    std::string line = "gradcheck " + c.name + ": " + (r.passed() ? "PASS" : "FAIL") + ", " +
                       std::to_string(r.failed) + " of " + std::to_string(r.entries) + " entries fail";
    if (r.null_in_candidate > 0)
      line += "; " + std::to_string(r.null_in_candidate) + " entries null in the candidate (not passed), first: " +
              entry_name(*r.first_null);
    if (r.undefined > 0)
      line += "; " + std::to_string(r.undefined) + " entries skipped, undefined (no derivative exists there: " +
              r.undefined_reason + ")";
    if (opt->reference) {  // how far the analytic exact gradient itself is from the truth here
      std::ostringstream s;
      s.precision(2);
      s << std::scientific << "; exact vs reference (largest per channel): r " << r.exact_vs_reference[0] << " g "
        << r.exact_vs_reference[1] << " b " << r.exact_vs_reference[2];
      line += s.str();
    }
    if (r.worst) {
      const GradCheckEntry& w = *r.worst;
      std::ostringstream s;
      s.precision(17);
      // Where only null entries fail, the worst numeric entry passes: say so rather than call it
      // the failure.
      const bool numeric_pass = !(w.excess > 1.0);
      s << (numeric_pass && !r.passed() ? "; every numeric entry passes, closest to its limit: " : "; worst: ")
        << entry_name(w) << ": got " << w.got << ", " << want << " " << w.exact << ", allowed "
        << w.allowed;
      line += s.str();
    }
    if (!opt->junit.empty()) {
      JUnitSuite suite{"rayint.gradcheck", {}};
      JUnitCase jc;
      jc.classname = "rayint.gradcheck." + c.name;
      jc.name = "gradient_within_tolerance";
      jc.pass = r.passed();
      if (!jc.pass && r.worst) jc.message = entry_name(*r.worst) + ": " + junit_measure(r.worst->excess, 1.0);
      if (r.null_in_candidate > 0)
        jc.message += (jc.message.empty() ? "" : "; ") + std::to_string(r.null_in_candidate) +
                      " entries null in the candidate, first: " + entry_name(*r.first_null);
      suite.cases.push_back(jc);
      write_file_atomically(opt->junit, junit_xml({suite}));
    }
    std::cout.flush();
    std::cerr << line << std::endl;
    if (!r.passed()) throw ChecksFailed{};
  });
}

}  // namespace rayint::cli
