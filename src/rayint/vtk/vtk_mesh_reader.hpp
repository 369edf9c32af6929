#pragma once
// Tetrahedral meshes read through VTK's own unstructured-grid readers (optional build,
// -DRAYINT_WITH_VTK=ON): .vtu (vtkXMLUnstructuredGridReader) and .pvtu
// (vtkXMLPUnstructuredGridReader). register_vtk_mesh_readers() adds them to the "mesh_file"
// readers of mesh cases; .vtk stays with rayint's own legacy reader.
#include <string>

#include "rayint/mesh/tet_mesh.hpp"

namespace rayint {

// Point scalars: the array named `scalar_name`, else the active scalars, else the first
// one-component point array. Non-tet cells, unreadable files, missing scalars: InputError
// "<file>: <field>: <what>".
TetMesh read_vtk_unstructured_grid(const std::string& path, const std::string& scalar_name);

void register_vtk_mesh_readers();  // idempotent

}  // namespace rayint
