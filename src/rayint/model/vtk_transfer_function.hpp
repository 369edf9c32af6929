#pragma once
// VTK's transfer-function curves, evaluated as VTK 9.1 evaluates them, so that a renderer's
// transfer function (a ParaView preset) can be handed to rayint's piecewise-linear functions
// (model/transfer_function.hpp) with a stated, measured deviation.
//
//  - vtkPiecewiseFunction::GetValue (opacity): between nodes (x1, y1) and (x2, y2) the node's
//    midpoint m and sharpness h shape the curve. With s = (x - x1)/(x2 - x1) and m clamped to
//    [1e-5, 1 - 1e-5], s' = s/(2m) for s < m, else 1/2 + (s - m)/(2(1 - m)).
//      h < 0.01:  y = (1 - s')y1 + s'y2, i.e. two linear pieces meeting at x1 + m(x2 - x1) with
//                 value (y1 + y2)/2 -- exactly piecewise linear;
//      h > 0.99:  a step: y1 for s' < 1/2, y2 from there on;
//      else:      s'' = (2s')^(1+10h)/2 below 1/2 and 1 - (2(1 - s'))^(1+10h)/2 above, then the
//                 cubic Hermite curve h1 y1 + h2 y2 + (h3 + h4)(1 - h)(y2 - y1) in s''; the
//                 piecewise function clamps the result to [min(y1, y2), max(y1, y2)].
//  - vtkColorTransferFunction::GetColor: the same s' (and s'' for 0.01 <= h <= 0.99), applied in
//    the colour space of the function: RGB; HSV (vtkMath::RGBToHSV, with HSVWrap taking the
//    shorter way round the hue circle when the hues differ by more than 1/2); Lab (CIE L*a*b*
//    of sRGB, D65, vtkMath::RGBToLab/LabToRGB, the latter scaling a colour whose largest channel
//    exceeds 1 back into gamut and clipping negatives); Diverging (Moreland 2009, "Diverging
//    Color Maps for Scientific Visualization": linear in the polar Msh form of Lab, with white
//    M = max(M1, M2, 88) inserted between two saturated colours whose hues differ by more than
//    0.33 pi, and the hue of an unsaturated end "spun" towards the saturated one); Step (VTK_CTF_STEP:
//    no interpolation, the right node's colour on (x1, x2] unless sharpness > 0.99).
//  - Log scale (vtkColorTransferFunction::SetScale(VTK_CTF_LOG10), ParaView's UseLogScale): s is
//    (log10 x - log10 x1)/(log10 x2 - log10 x1), and the node search uses 10^(log10 x), as
//    GetColor(x) = GetTable(x, x, 1) computes it. VTK needs the first node > 0 (else it silently
//    uses the linear scale: the preset reader refuses that) and returns NaN for x < 0; here a
//    scalar <= 0 gets the first node's colour (the clamp below the range).
//  - Duplicate scalars (ParaView's AllowDuplicateScalars): nodes may repeat an x. VTK advances
//    past a node while x > node.x, so at a repeated x the colour is the left interval's end value
//    and just above it that of the interval after the last copy: a jump, left-continuous.
// The formulas were read from VTK's Common/DataModel/vtkPiecewiseFunction.cxx,
// Rendering/Core/vtkColorTransferFunction.cxx and Common/Core/vtkMath.cxx and written anew here;
// tests/test_tf_import.cpp checks them against VTK 9.1 itself (python3-vtk9, fixtures in
// tests/data/tf/) to 1e-12, and against ParaView 5.11 / VTK 9.2 on all 128 continuous built-in
// presets (tests/test_paraview_presets.cpp).
#include <cstddef>
#include <vector>

#include "rayint/model/transfer_function.hpp"

namespace rayint {

enum class VtkColorSpace { rgb, hsv, lab, diverging, step };

// The curve's shape on the interval after node k: a straight line (h < 0.01 and m = 1/2, or
// RGB/opacity with h < 0.01: two straight pieces; a Step colour space's constant), a step
// (h > 0.99), or curved.
enum class IntervalShape { linear, two_linear_pieces, step, curved };

struct VtkPiecewiseNode {
  double x = 0.0, y = 0.0, midpoint = 0.5, sharpness = 0.0;
};

struct VtkColorNode {
  double x = 0.0;
  Rgb rgb{};
  double midpoint = 0.5, sharpness = 0.0;
};

// StepLocation (below) of a sharpness > 0.99 interval.
struct StepLocation {
  double below = 0.0, above = 0.0;
};

// Nodes strictly increasing in x, at least one; midpoint and sharpness in [0, 1].
struct VtkPiecewiseFunction {
  std::vector<VtkPiecewiseNode> nodes;
  double operator()(double x) const;  // constant beyond the end nodes (VTK's Clamping on)
  // The curve of interval k (nodes k, k+1) at x in [x_k, x_k+1], ends included. At x = x_k+1
  // it is what VTK returns there; at x = x_k it is the limit from the right.
  double interval_value(std::size_t k, double x) const;
};

// Nodes non-decreasing in x (a repeated x is a jump), at least one; midpoint, sharpness in [0, 1].
struct VtkColorTransferFunction {
  VtkColorSpace space = VtkColorSpace::rgb;
  bool hsv_wrap = false;   // ParaView's default for its lookup tables (VTK's own default is on)
  bool log_scale = false;  // VTK_CTF_LOG10; requires nodes.front().x > 0
  std::vector<VtkColorNode> nodes;
  Rgb operator()(double x) const;
  // As VtkPiecewiseFunction::interval_value; interval k must have x_k < x_k+1.
  Rgb interval_value(std::size_t k, double x) const;
  // Interval k's parameter s in [0, 1] at x (before the midpoint's adjustment): linear or log10.
  double interval_parameter(std::size_t k, double x) const;
  IntervalShape interval_shape(std::size_t k) const;  // as a function of x, log scale included
  StepLocation step_location(std::size_t k) const;    // for a step interval
};

// vtkMath's colour conversions (RGB in [0, 1]; hue in [0, 1)).
Rgb rgb_to_hsv(const Rgb& rgb);
Rgb hsv_to_rgb(const Rgb& hsv);
Rgb rgb_to_lab(const Rgb& rgb);
Rgb lab_to_rgb(const Rgb& lab);

IntervalShape piecewise_interval_shape(const VtkPiecewiseNode& left);
// On the linear scale; VtkColorTransferFunction::interval_shape accounts for the log scale.
IntervalShape color_interval_shape(VtkColorSpace space, const VtkColorNode& left);

// The scalar at which interval k's curve passes its midpoint: x1 + m(x2 - x1), m clamped as VTK.
double midpoint_scalar(double x1, double x2, double midpoint);
// For a step interval: the largest double `below` with the left value and the smallest double
// `above` (= next double after below) with the right value, found by bisection on VTK's own
// comparison s' < 1/2, so the step sits where VTK puts it to the last bit.
StepLocation step_location(double x1, double x2, double midpoint);

}  // namespace rayint
