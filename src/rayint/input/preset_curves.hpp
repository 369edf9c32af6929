#pragma once
// A ParaView preset imported for gradients: the curves exactly as imported (after rescaling, with
// the opacity that was used: the preset's Points, ParaView's default ramp or a constant) and the
// import, for the chain rule to the preset's own points (model/preset_point_gradient.hpp). Kept
// apart from paraview_preset.cpp, which it calls unchanged.
#include "rayint/input/paraview_preset.hpp"
#include "rayint/model/preset_point_gradient.hpp"

namespace rayint {

struct PresetCurvesImport {
  PresetCurves curves;
  PresetImport import;
};

// import_paraview_preset(request) plus the curves it imported. Throws InputError like it.
PresetCurvesImport import_preset_curves(const PresetImportRequest& request);

}  // namespace rayint
