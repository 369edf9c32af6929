// rayint tf import PRESET -- a ParaView colour-map preset (with its opacity Points) as a rayint
// transfer_function object, under one of the opacity conventions of
// docs/transfer-function-conventions.md, with a report of what was linearised and the measured
// max deviation (stderr; --report FILE for JSON). Exit 2 on bad input, with no output written.
#include <array>
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "options.hpp"
#include "rayint/input/paraview_preset.hpp"
#include "rayint/report/tf_import_json.hpp"

namespace rayint::cli {

void set_tf_command(CLI::App& app) {
  struct Options {
    std::string preset;
    std::string name;
    std::string convention;
    std::optional<double> unit_distance, sample_distance, opacity;
    std::optional<std::size_t> index;
    std::vector<double> range;
    double tolerance = 1e-6;
    std::string output, report;
    bool quiet = false;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* tf = app.add_subcommand("tf", "Transfer functions as renderers store them");
  tf->require_subcommand(1);
  CLI::App* cmd = tf->add_subcommand(
      "import", "A ParaView preset as a rayint transfer_function (docs/transfer-function-conventions.md)");
  cmd->add_option("preset", opt->preset, "ParaView preset file (JSON: one preset or a list)")->required();
  cmd->add_option("--name", opt->name, "The preset's Name (required when the file holds several)");
  cmd->add_option("--index", opt->index,
                  "The preset's index in the file's list (from 0; for names that several presets share)");
  auto* unit = cmd->add_option("--unit-distance", opt->unit_distance,
                               "Opacity per unit distance D: rho = opacity / D (VTK unstructured-grid "
                               "integrators, ParaView ScalarOpacityUnitDistance)");
  auto* sample = cmd->add_option("--sample-distance", opt->sample_distance,
                                 "Opacity per sample at spacing d: rho = -ln(1 - opacity) / d (opacity "
                                 "correction, VTK image-data mappers)");
  unit->excludes(sample);
  cmd->add_option("--convention", opt->convention,
                  "density (default: the opacity is rho), nerf_sigma (the same: sigma is rho), "
                  "unit_distance or sample_distance (implied by the two options above)");
  cmd->add_option("--tolerance", opt->tolerance,
                  "Linearisation tolerance: colour absolute (RGB in [0, 1]), density relative to its max")
      ->capture_default_str();
  cmd->add_option("--opacity", opt->opacity,
                  "Constant opacity instead of the preset's Points (without Points and without this option: "
                  "ParaView's default, a ramp 0 -> 1 over the colour range)");
  cmd->add_option("--range", opt->range, "LO HI: rescale the preset's scalars to [LO, HI] (as ParaView does)")
      ->expected(2);
  add_output_option(cmd, opt->output, "Write the transfer_function object here instead of stdout");
  cmd->add_option("--report", opt->report, "Write the import report (JSON) here");
  cmd->add_flag("-q,--quiet", opt->quiet, "No report on stderr");
  cmd->callback([opt] {
    PresetImportRequest r;
    r.file = opt->preset;
    r.name = opt->name;
    r.index = opt->index;
    r.index_field = "--index";
    r.request_source = "rayint tf import";
    r.opacity_field = "--opacity";
    r.distance_field = "--unit-distance";
    r.range_field = "--range";
    r.tolerance_field = "--tolerance";
    r.options.tolerance = opt->tolerance;
    if (!opt->convention.empty()) {
      const auto c = parse_convention(opt->convention);
      if (!c) field::fail(r.request_source, "--convention",
                          "must be density, unit_distance, sample_distance or nerf_sigma, got " +
                              field::quoted(opt->convention));
      r.options.convention = *c;
    }
    auto distance = [&](const std::optional<double>& d, OpacityConvention c, const char* flag) {
      if (!d) return;
      if (!opt->convention.empty() && r.options.convention != c)
        field::fail(r.request_source, flag, std::string("contradicts --convention ") + opt->convention);
      r.options.convention = c;
      r.options.distance = *d;
      r.distance_field = flag;
    };
    distance(opt->unit_distance, OpacityConvention::unit_distance, "--unit-distance");
    distance(opt->sample_distance, OpacityConvention::sample_distance, "--sample-distance");
    if ((r.options.convention == OpacityConvention::unit_distance ||
         r.options.convention == OpacityConvention::sample_distance) &&
        !opt->unit_distance && !opt->sample_distance)
      field::fail(r.request_source, "--convention",
                  std::string(convention_name(r.options.convention)) + " needs its distance (--unit-distance D or --sample-distance d)");
    r.constant_opacity = opt->opacity;
    if (!opt->range.empty()) r.range = std::array<double, 2>{opt->range[0], opt->range[1]};
    const PresetImport imp = import_paraview_preset(r);
    TfImportDescription d;
    d.preset_file = imp.preset.source;
    d.preset_name = imp.preset.name;
    d.color_space = imp.preset.color_space;
    d.hsv_wrap = imp.preset.color.hsv_wrap;
    d.options = r.options;
    d.ignored_fields = imp.preset.ignored_fields;
    d.constant_opacity = r.constant_opacity.has_value();
    d.default_opacity = imp.default_opacity;
    d.log_scale = imp.preset.color.log_scale;
    d.notes = imp.preset.notes;
    // Both outputs are formed before either is written, so bad input leaves neither behind.
    const std::string tf_text = transfer_function_text(imp.result.transfer);
    const std::string report_text = tf_import_report_json(imp.result, d).dump(2);
    emit(tf_text, opt->output);
    if (!opt->report.empty()) emit(report_text, opt->report);
    if (!opt->quiet) std::cerr << tf_import_summary(imp.result, d);
  });
}

}  // namespace rayint::cli
