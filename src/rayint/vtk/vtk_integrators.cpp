// vtk_integrators.cpp -- VTK 9's unstructured-grid ray integrators called through their public
// API on rayint's segments (docs/vtk.md). Nothing here re-implements VTK: each method builds a
// vtkVolume whose vtkVolumeProperty holds the case's transfer functions and calls
// vtkUnstructuredGridVolumeRayIntegrator::Initialize once and Integrate per ray.
//
// Translation (read from VTK 9.1's vtkUnstructuredGridLinearRayIntegrator.cxx):
//   attenuation(s) = ScalarOpacity(s) / ScalarOpacityUnitDistance; we set the unit distance to 1
//   and the scalar opacity to rho, so VTK's attenuation is our density rho.
//   VTK's RGB colour C(s) enters as emission C * attenuation (its per-piece update is
//   C_front (1 - Psi) + C_back (Psi - zeta), Moreland & Angel), i.e. our chromaticity kappa.
//   Integrate composites front to back (near first) into premultiplied RGBA starting at 0, so
//   intensity = rgb + (1 - a) * background and transmittance = 1 - a. Our segments run far ->
//   near, so they are handed to VTK reversed, with front = scalar_exit, back = scalar_far.
//   VTK builds its tables over the scalar range of the array given to Initialize; we pass the
//   transfer functions' breakpoint range and split every segment at its ends, then clamp: both
//   rayint and VTK hold the functions constant outside that range, so the split is exact.
//   The colour function gets a point at every breakpoint of any kappa channel (exact, since all
//   three are linear between consecutive ones).
// Not applicable (std::invalid_argument "<method>: not applicable: ..."): cases whose three
// density functions differ -- VTK has one attenuation for all channels.
// Precision: VTK composites in float; tests/vtk/test_vtk_methods.cpp checks agreement with
// `exact` to float precision where VTK's method is exact.
#include "rayint/vtk/vtk_integrators.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>

#include <vtkColorTransferFunction.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGridHomogeneousRayIntegrator.h>
#include <vtkUnstructuredGridLinearRayIntegrator.h>
#include <vtkUnstructuredGridPartialPreIntegration.h>
#include <vtkUnstructuredGridPreIntegration.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkObjectFactory.h>
#include <vtkUnstructuredGridVolumeMapper.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include "rayint/studies/sweep.hpp"
#include "rayint/integrators/integrator.hpp"

namespace rayint {
namespace {

// vtkUnstructuredGridPreIntegration reads the largest cell diagonal of its volume's mapper input
// (it sizes the table's length axis by it). VTK's concrete mappers need a rendering back end, so
// this mapper only carries the input and never renders.
class InputOnlyMapper : public vtkUnstructuredGridVolumeMapper {
 public:
  static InputOnlyMapper* New();
  vtkTypeMacro(InputOnlyMapper, vtkUnstructuredGridVolumeMapper)
  void Render(vtkRenderer*, vtkVolume*) override {}
};
vtkStandardNewMacro(InputOnlyMapper)

bool same_function(const PiecewiseLinear& a, const PiecewiseLinear& b) {
  return a.scalar == b.scalar && a.value == b.value;
}

class VtkIntegrator final : public RayIntegrator {
 public:
  VtkIntegrator(const std::string& name, vtkSmartPointer<vtkUnstructuredGridVolumeRayIntegrator> vtk,
                const TransferFunctions& tf, double max_length = 0.0)
      : integrator_(std::move(vtk)) {
    for (int c = 1; c < kChannels; ++c)
      if (!same_function(tf.density[0], tf.density[c]))
        throw std::invalid_argument(name +
                                    ": not applicable: per-channel density (VTK has one "
                                    "attenuation for all channels)");
    // AddPoint at a scalar already present replaces that node: a jump would silently become a
    // ramp to the next node.
    if (tf.has_jump())
      throw std::invalid_argument(name + ": not applicable: a transfer function with a jump (a scalar repeated)");
    std::set<double> points(tf.density[0].scalar.begin(), tf.density[0].scalar.end());
    for (int c = 0; c < kChannels; ++c)
      points.insert(tf.color[c].scalar.begin(), tf.color[c].scalar.end());
    s_min_ = *points.begin();
    s_max_ = *points.rbegin();
    if (s_max_ == s_min_) s_max_ = s_min_ + 1.0;  // VTK needs a non-empty range

    vtkNew<vtkPiecewiseFunction> opacity;
    for (std::size_t k = 0; k < tf.density[0].scalar.size(); ++k)
      opacity->AddPoint(tf.density[0].scalar[k], tf.density[0].value[k]);
    vtkNew<vtkColorTransferFunction> colour;
    colour->SetColorSpaceToRGB();
    for (const double s : points) colour->AddRGBPoint(s, tf.color[0](s), tf.color[1](s), tf.color[2](s));
    property_->SetColor(colour);
    property_->SetScalarOpacity(opacity);
    property_->SetScalarOpacityUnitDistance(1.0);
    property_->SetInterpolationTypeToLinear();
    property_->ShadeOff();
    volume_->SetProperty(property_);
    if (max_length > 0.0) {
      // vtkUnstructuredGridPreIntegration sizes its length axis by the largest cell diagonal of
      // the mapper's input: a one-line grid of that length sets it to `max_length`.
      vtkNew<vtkPoints> pts;
      pts->InsertNextPoint(0.0, 0.0, 0.0);
      pts->InsertNextPoint(max_length, 0.0, 0.0);
      vtkNew<vtkUnstructuredGrid> grid;
      grid->SetPoints(pts);
      const vtkIdType line[2] = {0, 1};
      grid->InsertNextCell(VTK_LINE, 2, line);
      mapper_->SetInputData(grid);
      volume_->SetMapper(mapper_);
    }
    vtkNew<vtkDoubleArray> range;
    range->SetNumberOfComponents(1);
    range->InsertNextValue(s_min_);
    range->InsertNextValue(s_max_);
    integrator_->Initialize(volume_, range);
  }

  RayResult integrate_segments(const Ray& ray, Diagnostics* diag) const override {
    // Per-thread arrays, reset per ray: allocating three vtkDoubleArrays per ray cost more than
    // some of VTK's integrators themselves.
    thread_local const vtkSmartPointer<vtkDoubleArray> lengths = vtkSmartPointer<vtkDoubleArray>::New();
    thread_local const vtkSmartPointer<vtkDoubleArray> near_s = vtkSmartPointer<vtkDoubleArray>::New();
    thread_local const vtkSmartPointer<vtkDoubleArray> far_s = vtkSmartPointer<vtkDoubleArray>::New();
    lengths->Reset();
    near_s->Reset();
    far_s->Reset();
    // near -> far: our segments reversed, each split at the range ends (see the file comment)
    for (auto it = ray.segments.rbegin(); it != ray.segments.rend(); ++it) {
      const double sn = it->scalar_exit, sf = it->scalar_far, length = it->length;
      std::vector<double> cuts{0.0, 1.0};  // fractions from near to far
      for (const double edge : {s_min_, s_max_})
        if ((sn - edge) * (sf - edge) < 0.0) cuts.push_back((edge - sn) / (sf - sn));
      std::sort(cuts.begin(), cuts.end());
      for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
        const double a = sn + (sf - sn) * cuts[k], b = sn + (sf - sn) * cuts[k + 1];
        lengths->InsertNextValue(length * (cuts[k + 1] - cuts[k]));
        near_s->InsertNextValue(std::clamp(k == 0 ? sn : a, s_min_, s_max_));
        far_s->InsertNextValue(std::clamp(k + 2 == cuts.size() ? sf : b, s_min_, s_max_));
      }
    }
    float rgba[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    if (lengths->GetNumberOfTuples() > 0) integrator_->Integrate(lengths, near_s, far_s, rgba);
    if (diag) diag->add_stat("vtk_pieces", static_cast<double>(lengths->GetNumberOfTuples()));
    RayResult r;
    const double a = rgba[3];
    for (int c = 0; c < kChannels; ++c) {
      r.intensity[c] = static_cast<double>(rgba[c]) + (1.0 - a) * ray.background[c];
      r.transmittance[c] = 1.0 - a;
    }
    return r;
  }

 private:
  vtkSmartPointer<vtkUnstructuredGridVolumeRayIntegrator> integrator_;
  vtkNew<vtkVolume> volume_;
  vtkNew<vtkVolumeProperty> property_;
  vtkNew<InputOnlyMapper> mapper_;
  double s_min_ = 0.0, s_max_ = 1.0;
};

// VTK's table holds scalar_res^2 x length_res entries of 4 floats (16 B) per component; kept
// under 1 GiB like rayint's own tables (preintegrated, psi_table).
void check_vtk_preint(const MethodSpec& spec) {
  const double bytes = 16.0 * spec.integer("scalar_res") * spec.integer("scalar_res") *
                       spec.integer("length_res");
  if (bytes > 1024.0 * 1024.0 * 1024.0)
    throw std::invalid_argument("a table of " + std::to_string(static_cast<long long>(bytes / (1 << 20))) +
                                " MiB (16 B x scalar_res^2 x length_res) exceeds the 1 GiB limit");
}

std::unique_ptr<RayIntegrator> make_vtk_linear(const MethodSpec& spec, const TransferFunctions& tf) {
  return std::make_unique<VtkIntegrator>(
      spec.name, vtkSmartPointer<vtkUnstructuredGridLinearRayIntegrator>::New(), tf);
}

std::unique_ptr<RayIntegrator> make_vtk_partial(const MethodSpec& spec, const TransferFunctions& tf) {
  return std::make_unique<VtkIntegrator>(
      spec.name, vtkSmartPointer<vtkUnstructuredGridPartialPreIntegration>::New(), tf);
}

std::unique_ptr<RayIntegrator> make_vtk_homogeneous(const MethodSpec& spec,
                                                    const TransferFunctions& tf) {
  auto h = vtkSmartPointer<vtkUnstructuredGridHomogeneousRayIntegrator>::New();
  h->SetTransferFunctionTableSize(spec.integer("table_size"));  // range: register_vtk_methods
  return std::make_unique<VtkIntegrator>(spec.name, h, tf);
}

std::unique_ptr<RayIntegrator> make_vtk_preint(const MethodSpec& spec, const TransferFunctions& tf) {
  auto p = vtkSmartPointer<vtkUnstructuredGridPreIntegration>::New();
  p->SetIncrementalPreIntegration(spec.integer("incremental"));  // ranges: register_vtk_methods
  p->SetIntegrationTableScalarResolution(spec.integer("scalar_res"));
  p->SetIntegrationTableLengthResolution(spec.integer("length_res"));
  const double max_length = spec.number("max_length");
  return std::make_unique<VtkIntegrator>(spec.name, p, tf, max_length);
}

}  // namespace

void register_vtk_methods() {
  static std::once_flag once;
  std::call_once(once, [] {
    register_method({"vtk_linear", "VTK's vtkUnstructuredGridLinearRayIntegrator", {},
                     make_vtk_linear, nullptr});
    register_method({"vtk_partial_preint", "VTK's vtkUnstructuredGridPartialPreIntegration", {},
                     make_vtk_partial, nullptr});
    register_method(
        {"vtk_preint",
         "VTK's vtkUnstructuredGridPreIntegration (a scalar x scalar x length table)",
         {integer_param("incremental", "1", 0, 1, "1: incremental pre-integration"),
          integer_param("scalar_res", "128", 2, 4096, "table points per scalar axis"),
          integer_param("length_res", "256", 2, 4096, "table points on the length axis"),
          number_param("max_length", "1", 0.0, true, std::numeric_limits<double>::infinity(), false,
                       "longest segment length in the table")},
         make_vtk_preint, check_vtk_preint});
    register_method({"vtk_homogeneous", "VTK's vtkUnstructuredGridHomogeneousRayIntegrator",
                     {integer_param("table_size", "1024", 2, 1 << 20,
                                    "transfer-function table entries")},
                     make_vtk_homogeneous, nullptr});
    register_sweep_axis({"vtk_linear", "", {}});  // `rayint bench`: VTK's knob-free methods
    register_sweep_axis({"vtk_partial_preint", "", {}});
    register_sweep_axis({"vtk_homogeneous", "table_size", {"64", "256", "1024", "4096"}});
    register_sweep_axis({"vtk_preint", "scalar_res", {"32", "64", "128"}});
  });
}

}  // namespace rayint
