#pragma once
// Writing a TetMesh as a VTK legacy unstructured grid (version 3.0 layout, readable by every VTK
// and ParaView release): POINTS double, CELLS, CELL_TYPES 10, POINT_DATA SCALARS double.
#include <string>

#include "rayint/mesh/tet_mesh.hpp"

namespace rayint {

enum class VtkEncoding { ascii, binary };

struct VtkWriteOptions {
  VtkEncoding encoding = VtkEncoding::binary;
  std::string title = "rayint tetrahedral mesh";  // one line, at most 255 characters
  std::string scalar_name = "scalar";
};

// The file's bytes. ASCII numbers are written with 17 significant digits (round trip exact).
std::string encode_vtk_legacy(const TetMesh& mesh, const VtkWriteOptions& options = {});
// Atomically (no partial file on failure).
void write_vtk_legacy(const std::string& path, const TetMesh& mesh, const VtkWriteOptions& options = {});

}  // namespace rayint
