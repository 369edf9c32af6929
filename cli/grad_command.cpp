// rayint grad CASE... [--methods exact,riemann:n=64] [-o OUT.json] -- gradients of every ray's
// intensity with respect to every input of the ray (issue 28), per method, against the 50-digit
// reference gradient; format: docs/gradients.md. Exit 0, or 2 on bad input.
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "options.hpp"
#include "rayint/input/case_reader.hpp"
#include "rayint/input/json_schema.hpp"
#include "rayint/input/json_source.hpp"
#include "rayint/input/preset_curves.hpp"
#include "rayint/report/grad_json.hpp"
#include "rayint/studies/grad_study.hpp"

namespace rayint::cli {

void set_grad_command(CLI::App& app) {
  struct Options {
    std::vector<std::string> cases;
    std::string methods = "exact";
    std::string output;
    bool no_reference = false;
    unsigned threads = 1;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "grad", "Gradients of each ray's intensity w.r.t. every input, per method, against the 50-digit reference");
  cmd->add_option("cases", opt->cases, "Case files (JSON, ray cases)")->required();
  cmd->add_option("--methods", opt->methods,
                  "Comma-separated methods with a gradient: exact, riemann:n=N, nerf, pl_nerf (the derivative "
                  "of their discrete sums), psi_table, preintegrated (of their table lookups); others are "
                  "reported as failed")
      ->capture_default_str();
  cmd->add_flag("--no-reference", opt->no_reference, "Skip the 50-digit reference gradient (slow on long rays)");
  add_threads_option(cmd, opt->threads, "Threads for the reference gradient (0: all cores)");
  add_output_option(cmd, opt->output, "Write the JSON to this file instead of stdout");
  cmd->callback([opt] {
    GradStudyOptions so;
    so.methods = parse_method_list(opt->methods);
    so.reference = !opt->no_reference;
    so.threads = opt->threads;
    std::vector<Case> cases;
    for (const std::string& f : opt->cases) cases.push_back(read_case_file(f));  // all read first
    std::vector<GradCaseResult> results;
    for (const Case& c : cases) results.push_back(grad_case(c, so));
    // A transfer function imported from a ParaView preset (already validated by read_case_file):
    // the node blocks are with respect to the imported nodes; the report names the preset, and
    // each gradient is also mapped onto the preset's own points (model/preset_point_gradient.hpp).
    for (std::size_t i = 0; i < cases.size(); ++i) {
      const nlohmann::json root = json_source::parse(json_source::read_text_file(opt->cases[i]), opt->cases[i]);
      const auto tf = root.find("transfer_function");
      if (tf == root.end() || !tf->is_object() || !tf->contains("paraview_preset")) continue;
      std::string origin = "ParaView preset";
      if (tf->contains("name")) origin += " \"" + (*tf)["name"].get<std::string>() + "\"";
      if (tf->contains("index")) origin += " #" + std::to_string((*tf)["index"].get<long long>());
      results[i].transfer_origin = origin + " of " + (*tf)["paraview_preset"].get<std::string>();
      const PresetCurvesImport preset =
          import_preset_curves(JsonSchema(opt->cases[i]).preset_import_request(*tf, "transfer_function"));
      for (GradRayResult& r : results[i].rays) {
        if (r.reference)
          r.reference_preset = preset_point_gradient(preset.curves, preset.import.result, r.reference->gradient);
        for (GradMethodResult& m : r.methods)
          if (m.ok) m.preset = preset_point_gradient(preset.curves, preset.import.result, m.gradient);
      }
    }
    emit(grad_report_json(results).dump(2), opt->output);
  });
}

}  // namespace rayint::cli
