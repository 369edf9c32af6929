#pragma once
// VTK 9's own unstructured-grid ray integrators as rayint methods (optional build,
// -DRAYINT_WITH_VTK=ON; docs/vtk.md). register_vtk_methods() adds to the method registry:
//   vtk_linear          vtkUnstructuredGridLinearRayIntegrator
//   vtk_partial_preint  vtkUnstructuredGridPartialPreIntegration
//   vtk_preint          vtkUnstructuredGridPreIntegration   knobs incremental=0|1, scalar_res, length_res
//   vtk_homogeneous     vtkUnstructuredGridHomogeneousRayIntegrator   knob table_size
// Cases whose three density functions differ are refused (std::invalid_argument
// "<method>: not applicable: ..."): VTK has one attenuation for all channels.
namespace rayint {

void register_vtk_methods();  // idempotent

}  // namespace rayint
