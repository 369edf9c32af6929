#pragma once
// `--cells split`: a CellMesh tetrahedralised the way VTK's vtkDataSetTriangleFilter does it
// (Filters/General/vtkDataSetTriangleFilter.cxx, VTK 9.1) before its unstructured-grid mappers,
// so that rayint integrates exactly what a ParaView user's renderer integrates. This is an
// APPROXIMATION of the file's field: a hexahedron, wedge, pyramid or voxel interpolates its nodes
// trilinearly (isoparametrically), the tetrahedra linearly; the difference is what the issue-29
// report measures (reports/cells/).
//
// The decompositions:
//   - structured grids (.vts hexahedra, .vtr voxels; StructuredExecute): every cell into 5
//     tetrahedra by a fixed table, alternating with the parity of i + j + k (vtkHexahedron /
//     vtkVoxel::Triangulate(index): index 0 when i + j + k is even). Neighbours agree on their
//     shared faces because the parities alternate.
//   - unstructured cells (UnstructuredExecute): tetrahedra pass unchanged; every other linear
//     cell goes through vtkOrderedTriangulator::TemplateTriangulate, which inserts the cell's
//     points in ascending global point id into a Delaunay triangulation of the cell's parametric
//     coordinates. Those points are cospherical (degenerate for Delaunay), and the result is the
//     placing (beneath-beyond) triangulation in that order: each new point is joined to the faces
//     of the current hull it sees strictly. Measured with VTK 9.1's filter on one cell of each
//     type for every order of its point ids (pyramid 120, wedge 720, hexahedron and voxel 40,320
//     orders): the placing triangulation gave VTK's tetrahedra in every case (tests/fixtures/
//     readers/vtk_split_orders.py). A quad face is split along the diagonal that avoids its largest
//     point id, so neighbours agree. Hexahedra and voxels give 5 or 6 tetrahedra, wedges 3,
//     pyramids 2.
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
