#pragma once
// `--cells split`: a CellMesh tetrahedralised the way VTK's vtkDataSetTriangleFilter does it
// (Filters/General/vtkDataSetTriangleFilter.cxx, VTK 9.1) before its unstructured-grid mappers,
// so that rayint integrates exactly what a ParaView user's renderer integrates. This is an
// APPROXIMATION of the file's field: a hexahedron, wedge, pyramid or voxel interpolates its nodes
// trilinearly (isoparametrically), the tetrahedra linearly; the difference is what the issue-29
// report measures (reports/cells/).
//
// The decompositions are the cells area's (cells/vtk_split.hpp, where they are documented and
// checked against VTK 9.1): structured grids by VTK's fixed 5-tetrahedra tables alternating with
// the parity of i + j + k; unstructured cells by the placing triangulation in global point id
// order that vtkOrderedTriangulator produces. Tetrahedra pass unchanged.
// Cell data: every tetrahedron takes its cell's value. Point data and points are kept as they are.
#include <map>
#include <string>

#include "rayint/mesh/cell_mesh.hpp"
#include "rayint/mesh/tet_mesh.hpp"

namespace rayint {

struct CellSplitCounts {
  std::map<std::string, long> cells;  // cells split, by type name (tetrahedra counted as passed)
  std::map<std::string, long> tets;   // tetrahedra they gave
  bool structured = false;            // the structured rule (5 per cell, alternating)
};

// The tetrahedra of `mesh`, as vtkDataSetTriangleFilter makes them. info.cell_ids of the result
// gives, per tetrahedron, the file index of the cell it came from.
TetMesh split_cells(const CellMesh& mesh, CellSplitCounts* counts = nullptr);

}  // namespace rayint
