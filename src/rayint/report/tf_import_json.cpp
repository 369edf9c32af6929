// The transfer_function object and the import report of `rayint tf import` (header).
#include "rayint/report/tf_import_json.hpp"

#include "rayint/core/format.hpp"

namespace rayint {
namespace {

using json = nlohmann::ordered_json;

json points(const PiecewiseLinear& f) {
  json out = json::array();
  for (std::size_t k = 0; k < f.scalar.size(); ++k) out.push_back(json::array({f.scalar[k], f.value[k]}));
  return out;
}

bool same(const PiecewiseLinear& a, const PiecewiseLinear& b) {
  return a.scalar == b.scalar && a.value == b.value;
}

json channels(const std::array<PiecewiseLinear, kChannels>& f) {
  if (same(f[0], f[1]) && same(f[0], f[2])) return points(f[0]);
  return json{{"r", points(f[0])}, {"g", points(f[1])}, {"b", points(f[2])}};
}

std::string channels_text(const std::string& key, const json& j) {
  std::string out = "  " + json(key).dump() + ": ";
  if (j.is_array()) return out + j.dump();
  out += "{\n";
  bool first = true;
  for (const auto& item : j.items()) {
    out += std::string(first ? "" : ",\n") + "    " + json(item.key()).dump() + ": " + item.value().dump();
    first = false;
  }
  return out + "\n  }";
}

json linearisation_json(const LinearisationReport& r) {
  return json{{"nodes", r.nodes},
              {"exact_intervals", r.exact_intervals},
              {"linearised_intervals", r.adaptive_intervals},
              {"exact", r.exact()},
              {"tolerance", r.tolerance},
              {"max_deviation", r.max_deviation},
              {"converged", r.converged}};
}

std::string linearisation_line(const char* what, const LinearisationReport& r) {
  std::string s = std::string(what) + ": " + std::to_string(r.nodes) + " nodes; ";
  if (r.exact()) return s + "exact (" + std::to_string(r.exact_intervals) + " intervals reproduced node for node)\n";
  return s + std::to_string(r.exact_intervals) + " intervals exact, " + std::to_string(r.adaptive_intervals) +
         " linearised; measured max deviation " + format_number(r.max_deviation) + " (tolerance " +
         format_number(r.tolerance) + (r.converged ? ")" : ", NOT reached everywhere: a jump)") + "\n";
}

}  // namespace

nlohmann::ordered_json transfer_function_json(const TransferFunctions& tf) {
  return json{{"density", channels(tf.density)}, {"color", channels(tf.color)}};
}

std::string transfer_function_text(const TransferFunctions& tf) {
  return "{\n" + channels_text("density", channels(tf.density)) + ",\n" +
         channels_text("color", channels(tf.color)) + "\n}\n";
}

nlohmann::ordered_json tf_import_report_json(const TfImport& import, const TfImportDescription& d) {
  json j{{"preset", d.preset_file},
         {"name", d.preset_name},
         {"color_space", d.color_space},
         {"hsv_wrap", d.hsv_wrap},
         {"convention", convention_name(d.options.convention)},
         {"distance", d.options.distance},
         {"tolerance", d.options.tolerance},
         {"log_scale", d.log_scale},
         {"constant_opacity", d.constant_opacity},
         {"opacity", d.constant_opacity ? "constant" : d.default_opacity ? "default ramp 0 to 1" : "preset Points"},
         {"density", linearisation_json(import.density)},
         {"color", linearisation_json(import.color)},
         {"ignored_fields", d.ignored_fields},
         {"notes", d.notes}};
  return j;
}

std::string tf_import_summary(const TfImport& import, const TfImportDescription& d) {
  std::string s = "preset " + json(d.preset_name).dump() + " (" + d.color_space + ") from " + d.preset_file +
                  "; opacity convention " + convention_name(d.options.convention);
  if (d.options.convention == OpacityConvention::unit_distance ||
      d.options.convention == OpacityConvention::sample_distance)
    s += " (distance " + format_number(d.options.distance) + ")";
  if (d.log_scale) s += "; colour on a log10 scale (UseLogScale)";
  s += "\n";
  if (d.default_opacity)
    s += "note: the preset has no opacity Points: the opacity is ParaView's default for a new colour map, a ramp "
         "0 -> 1 over the colour range; add Points to the preset or give --opacity A for a constant\n";
  for (const std::string& n : d.notes) s += "note: " + n + "\n";
  s += linearisation_line("density", import.density) + linearisation_line("color", import.color);
  return s;
}

}  // namespace rayint
