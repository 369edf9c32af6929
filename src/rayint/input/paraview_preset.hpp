#pragma once
// ParaView colour-map presets (what "Export" in ParaView's colour map editor writes, and what
// ParaView ships in Remoting/Views/ColorMaps.json): a JSON list of presets, or one preset, each
//   {"Name": "...", "ColorSpace": "RGB" | "HSV" | "Lab" | "Diverging" | "Step" | "CIELAB",
//    "RGBPoints": [x, r, g, b, ...] (x non-decreasing: a repeated x is a colour jump),
//    "Points": [x, opacity, midpoint, sharpness, ...] (optional; without it the opacity is
//    ParaView's default for a new colour map, a ramp 0 -> 1 over the RGBPoints' range),
//    "HSVWrap": bool (optional), "UseLogScale": bool (optional),
//    ... other fields (NanColor, Creator, ...) are ignored}
// Categorical presets ("IndexedColors") are refused. "CIELAB" (one of ParaView 5.11's built-ins)
// is no colour space of ParaView's: applied to a lookup table it leaves RGB, as measured with
// pvpython, so it is read as RGB with a note.
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
  std::vector<std::string> notes;               // how a field was read, when not as written
};

// Which preset of a file: by Name, by index in the list, or (both empty) the file's only one.
// A name that several presets carry is refused with their indices, unless `index` picks one.
struct PresetSelection {
  std::string name;
  std::optional<std::size_t> index;
  std::string request_source;  // where the index came from ("rayint tf import", a case file); "" = the file
  std::string index_field = "--index";
};

// The selected preset. Throws InputError.
ParaViewPreset parse_paraview_preset(std::string_view text, const std::string& source,
                                     const PresetSelection& which);
ParaViewPreset parse_paraview_preset(std::string_view text, const std::string& source,
                                     const std::string& name);
ParaViewPreset read_paraview_preset_file(const std::string& path, const std::string& name);

struct PresetImportRequest {
  std::string file;
  std::string name;
  std::optional<std::size_t> index;           // the preset's index in the file's list
  TfImportOptions options;
  std::optional<double> constant_opacity;     // replaces the preset's "Points" (or the default ramp)
  std::optional<std::array<double, 2>> range; // rescale the scalars from the colour range to this
  // How the request's own fields are named in messages ("--sample-distance" on the command line,
  // "transfer_function.sample_distance" in a case file) and where they come from.
  std::string request_source;
  std::string distance_field;
  std::string opacity_field;
  std::string range_field = "range";
  std::string tolerance_field = "tolerance";
  std::string index_field = "index";
};

struct PresetImport {
  ParaViewPreset preset;  // after rescaling
  TfImport result;
  // The preset had no "Points" and no constant was given: the opacity is ParaView's default for a
  // new colour map, a linear ramp from 0 at the first RGBPoints scalar to 1 at the last.
  bool default_opacity = false;
};

// Reads, selects, rescales and imports. Throws InputError.
PresetImport import_paraview_preset(const PresetImportRequest& request);
PresetImport import_paraview_preset_text(std::string_view text, const PresetImportRequest& request);

// "density", "unit_distance", "sample_distance", "nerf_sigma" (also with '-' for '_'); nullopt else.
std::optional<OpacityConvention> parse_convention(const std::string& name);

}  // namespace rayint
