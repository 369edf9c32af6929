#pragma once
// `rayint tf import`'s output: the transfer_function object exactly as a case file holds it
// (cases/README.md), and the report of what the import linearised and how far it moved.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rayint/model/tf_import.hpp"

namespace rayint {

// Where an import came from and what it was asked to do (for the report).
struct TfImportDescription {
  std::string preset_file;
  std::string preset_name;
  std::string color_space;
  bool hsv_wrap = false;
  TfImportOptions options;
  std::vector<std::string> ignored_fields;
  std::vector<std::string> notes;  // how fields were read when not as written (ParaViewPreset::notes)
  bool constant_opacity = false;
  bool default_opacity = false;    // no Points: ParaView's default ramp 0 -> 1 over the colour range
  bool log_scale = false;
};

// {"density": [[s, rho], ...], "color": [[s, kappa], ...] or {"r": ..., "g": ..., "b": ...}}:
// the shared form when the three channels are equal. Numbers round-trip bit for bit.
nlohmann::ordered_json transfer_function_json(const TransferFunctions& tf);
// The transfer_function object laid out one function (or channel) per line, with a final newline.
std::string transfer_function_text(const TransferFunctions& tf);

// {"preset", "name", "color_space", "convention", "distance", "tolerance", "density": {...},
//  "color": {...}, "ignored_fields": [...]}: per function the node count, exact and linearised
// intervals, the measured max deviation (absolute) and whether every bisection converged.
nlohmann::ordered_json tf_import_report_json(const TfImport& import, const TfImportDescription& d);
// The same as a few lines of text for stderr.
std::string tf_import_summary(const TfImport& import, const TfImportDescription& d);

}  // namespace rayint
