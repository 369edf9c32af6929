#pragma once
// The gradient of a ray with respect to a ParaView preset's own points (issue 28): the chain rule
// from the imported nodes (model/tf_import.hpp) back to the preset's RGBPoints (x, r, g, b) and
// Points (x, opacity), where the import is a differentiable function of them.
//
// Where it is: an interval the import reproduces node for node (LinearisationReport::exact():
// RGB colour space with sharpness < 0.01, opacity under the density, unit_distance and nerf_sigma
// conventions, steps). Then every imported node is one of
//   - a preset point k itself: position X_k, value V_k (colour channel c, or rho = y, y / D);
//   - the kink of a two-piece interval (midpoint m != 1/2): position X_k + m (X_k+1 - X_k), value
//     (V_k + V_k+1)/2 (m clamped to [1e-5, 1 - 1e-5] as VTK does);
//   - the two nodes of a step (sharpness > 0.99), a jump at the same place: values V_k and V_k+1
//     (its position entry, the jump's, on the first node: model/ray_gradient.hpp's tie);
// and the chain rule is linear in those forms. With a range (the preset rescaled to [b0, b1]),
// X' = b0 + (X - X_0)(b1 - b0)/(X_n - X_0) is differentiated too, so the x entries are with
// respect to the preset file's own scalars.
// Where it is not, the block is marked unavailable with the reason, never filled with numbers:
//   - an interval linearised adaptively (HSV, Lab, Diverging colour spaces, log scale, sharpness
//     in [0.01, 0.99], the sample_distance convention's -ln(1 - y)/d): the imported node count
//     and positions come from a bisection on a tolerance, a piecewise-constant function of the
//     points; the node values are samples of the curve, but their positions are not;
//   - repeated x in the preset's own points (a colour jump written as two points at one x): the
//     chain to two points that share one x is not written;
//   - the midpoint and sharpness of a point are not differentiated: on a linear interval
//     (sharpness < 0.01, m = 1/2) the derivative in m moves a node the import does not have,
//     and sharpness has derivative 0 inside the linear (< 0.01) and step (> 0.99) branches.
// "Points" is present only when the preset's own Points were imported (not the default ramp or a
// constant opacity; the ramp's ends are RGBPoints' first and last x, and count there).
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "rayint/model/ray_gradient.hpp"
#include "rayint/model/tf_import.hpp"
#include "rayint/model/vtk_transfer_function.hpp"

namespace rayint {

enum class PresetOpacitySource { points, default_ramp, constant };

// The curves as imported (after any rescaling) and how.
struct PresetCurves {
  VtkColorTransferFunction color;
  VtkPiecewiseFunction opacity;  // the one imported (preset Points, default ramp or constant)
  PresetOpacitySource opacity_source = PresetOpacitySource::points;
  TfImportOptions options;
  // The rescaling applied: the preset's first and last RGBPoints x before it (a0, a1) and the
  // range (b0, b1). nullopt: none.
  std::optional<std::array<double, 4>> rescale;
};

struct PresetPointGradient {
  bool color_ok = false;
  std::string color_unavailable;  // why, when !color_ok
  // [c][k] = dI_c / d (x, r, g, b) of RGBPoints point k.
  std::array<std::vector<std::array<double, 4>>, kChannels> rgb_points;
  bool opacity_ok = false;
  std::string opacity_unavailable;
  // [c][k] = dI_c / d (x, opacity) of Points point k (opacity_source == points only).
  std::array<std::vector<std::array<double, 2>>, kChannels> points;
};

// `imported` must be import_vtk_transfer_function(curves.color, curves.opacity, curves.options)
// and `g` a gradient with respect to imported.transfer's nodes.
PresetPointGradient preset_point_gradient(const PresetCurves& curves, const TfImport& imported, const RayGradient& g);

}  // namespace rayint
