#pragma once
// ParaView colour-map presets (what "Export" in ParaView's colour map editor writes, and what
// ParaView ships in Remoting/Views/ColorMaps.json): a JSON list of presets, or one preset, each
//   {"Name": "...", "ColorSpace": "RGB" | "HSV" | "Lab" | "Diverging",
//    "RGBPoints": [x, r, g, b, ...], "Points": [x, opacity, midpoint, sharpness, ...] (optional),
//    "HSVWrap": bool (optional), ... other fields (NanColor, Creator, ...) are ignored}
// read into VTK's curves (model/vtk_transfer_function.hpp) and imported as rayint transfer
// functions (model/tf_import.hpp). Every problem is one InputError line naming the file and the
// field, e.g. `p.json: [2].Points[5]: opacity 1 ...`.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rayint/core/error.hpp"
#include "rayint/model/tf_import.hpp"
#include "rayint/model/vtk_transfer_function.hpp"

namespace rayint {

struct ParaViewPreset {
  std::string source;      // the file
  std::string field;       // "" for a file holding one preset, "[i]" for the i-th of a list
  std::string name;
  std::string color_space; // as written
  VtkColorTransferFunction color;
  std::optional<VtkPiecewiseFunction> opacity;  // the preset's "Points"
  std::vector<std::string> ignored_fields;      // fields present that do not shape the curves
};

// The preset called `name` (empty: the file's only preset). Throws InputError.
ParaViewPreset parse_paraview_preset(std::string_view text, const std::string& source,
                                     const std::string& name);
ParaViewPreset read_paraview_preset_file(const std::string& path, const std::string& name);

struct PresetImportRequest {
  std::string file;
  std::string name;
  TfImportOptions options;
  std::optional<double> constant_opacity;     // when the preset has no "Points"
  std::optional<std::array<double, 2>> range; // rescale the scalars from the colour range to this
  // How the request's own fields are named in messages ("--sample-distance" on the command line,
  // "transfer_function.sample_distance" in a case file) and where they come from.
  std::string request_source;
  std::string distance_field;
  std::string opacity_field;
  std::string range_field = "range";
  std::string tolerance_field = "tolerance";
};

struct PresetImport {
  ParaViewPreset preset;  // after rescaling
  TfImport result;
};

// Reads, selects, rescales and imports. Throws InputError.
PresetImport import_paraview_preset(const PresetImportRequest& request);
PresetImport import_paraview_preset_text(std::string_view text, const PresetImportRequest& request);

// "density", "unit_distance", "sample_distance", "nerf_sigma" (also with '-' for '_'); nullopt else.
std::optional<OpacityConvention> parse_convention(const std::string& name);

}  // namespace rayint
