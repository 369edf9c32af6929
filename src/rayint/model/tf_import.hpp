#pragma once
// A renderer's transfer function (VTK curves, model/vtk_transfer_function.hpp) restated as
// rayint's six piecewise-linear functions (Williams & Max 1992, Sec. 3.1), with the opacity
// convention of the renderer and a measured bound on what linearisation changed.
// The conventions, their formulas, the renderers that use them and worked examples are in
// docs/transfer-function-conventions.md.
//
// What is exact and what is linearised:
//  - opacity intervals with sharpness < 0.01 (VTK's linear branch) are two straight pieces,
//    reproduced node for node (a node at x1 + m(x2 - x1) when m != 1/2); steps (sharpness > 0.99)
//    become a jump (a repeated scalar: model/transfer_function.hpp) at the place VTK switches. Under the density, unit-distance and
//    NeRF conventions rho is linear in opacity, so these stay exact (to rounding).
//  - everything else -- sharpness in [0.01, 0.99], colour spaces other than RGB, and every
//    interval under the per-sample convention (rho = -ln(1 - alpha)/d is not linear in alpha) --
//    is linearised adaptively: an interval is bisected until the chord is within `tolerance` of
//    the curve, measured as the maximum of the error curve (16 probes, each sampled local maximum
//    refined by Brent's method: tf_import.cpp), and the largest deviation found is reported.
//    tests/test_tf_import.cpp checks the reported deviation against VTK 9.1's own values, and
//    tests/test_paraview_presets.cpp against ParaView 5.11's on all its continuous presets.
//  - colour steps: a Step colour space, sharpness > 0.99 and repeated scalars become a jump of
//    rayint's function (the scalar repeated: left value, right value) at the last double where
//    VTK has the left value: exact at every double, and exact in the integral (no ramp).
#include <cstddef>
#include <string>

#include "rayint/model/transfer_function.hpp"
#include "rayint/model/vtk_transfer_function.hpp"

namespace rayint {

// How the renderer's opacity y(s) (a vtkPiecewiseFunction value) becomes rayint's density rho.
enum class OpacityConvention {
  density,          // rho = y                      (rayint's own; y is an extinction coefficient)
  unit_distance,    // rho = y / D                  (VTK unstructured-grid integrators, ParaView
                    //                               ScalarOpacityUnitDistance as attenuation)
  sample_distance,  // rho = -ln(1 - y) / d         (opacity per sample at spacing d, Engel et al.'s
                    //                               opacity correction, VTK image-data mappers)
  nerf_sigma,       // rho = sigma = y              (NeRF's volume density, Mildenhall et al. 2020)
};

const char* convention_name(OpacityConvention c);  // "density", "unit_distance", ...

// rho from one opacity value: y / D, -ln(1 - y)/d = -log1p(-y)/d, or y. Requires y < 1 under
// sample_distance (the caller reports y >= 1 as bad input before calling).
double density_from_opacity(double y, OpacityConvention convention, double distance);

struct TfImportOptions {
  OpacityConvention convention = OpacityConvention::density;
  double distance = 1.0;    // D or d; > 0
  double tolerance = 1e-6;  // colour: absolute (RGB in [0, 1]); density: relative to max rho
};

// What linearising one function did.
struct LinearisationReport {
  std::size_t nodes = 0;                // points of the rayint function
  std::size_t exact_intervals = 0;      // intervals reproduced node for node
  std::size_t adaptive_intervals = 0;   // intervals linearised adaptively
  double max_deviation = 0.0;           // largest |rayint - curve| seen (absolute)
  double tolerance = 0.0;               // the absolute tolerance used
  bool converged = true;                // false if a bisection hit its depth budget
  bool exact() const { return adaptive_intervals == 0; }
};

struct TfImport {
  TransferFunctions transfer;
  LinearisationReport density;
  LinearisationReport color;  // over the three channels together
};

// Throws std::invalid_argument for an empty function or a sample_distance opacity >= 1, and
// std::length_error when a function would need more nodes than core/limits.hpp kTransferNodes
// allows (10^6 unless RAYINT_MAX_TF_NODES says otherwise; a tolerance too small).
TfImport import_vtk_transfer_function(const VtkColorTransferFunction& color,
                                      const VtkPiecewiseFunction& opacity,
                                      const TfImportOptions& options);

}  // namespace rayint
