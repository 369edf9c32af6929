#pragma once
// How VTK splits a linear cell into tetrahedra (what ParaView renders after
// vtkDataSetTriangleFilter, the filter its unstructured volume mappers run first), for
// `--cells split` and for measuring what the split changes (issue 29).
//   Unstructured grids: vtkDataSetTriangleFilter hands each 3-D cell to vtkOrderedTriangulator
//     (TemplateTriangulate), which inserts the cell's points with their parametric coordinates in
//     ascending global point id into a Delaunay triangulation. Those points are cospherical
//     (degenerate for Delaunay) and the result is the placing (beneath-beyond) triangulation in
//     that order: each new point is joined to the faces of the current hull it sees strictly. So
//     the split depends only on the order of the ids, not on the geometry. Checked against VTK
//     9.1's filter on one cell of each type for every order of its ids (pyramid 120, wedge 720,
//     hexahedron and voxel 40,320: tests/fixtures/readers/vtk_split_orders.py) and on 200 random
//     distorted cells with random ids (tests/fixtures/cells/vtk_split_check.json, written by VTK
//     through scripts/cells/vtk_split_check.py; tests [cells][isoparametric]). A tetra is itself.
//     Wedge: 3 tets; pyramid: 2; hexahedron and voxel: 5 or 6. A quad face is split along the
//     diagonal that avoids its largest id, so neighbours agree.
//   Structured grids (.vts hexahedra, .vtr/.vti voxels): StructuredExecute calls
//     TriangulateIds((i + j + k) % 2) on cell (i, j, k): 5 tets, alternating so that faces match.
// Tets are local node indices (VTK node order); their orientation is not normalised.
#include <array>
#include <cstdint>
#include <vector>

#include "rayint/cells/linear_cells.hpp"

namespace rayint {

// VTK's split of an unstructured-grid cell whose node i has global id global_ids[i]. The
// reference stays valid for the thread's lifetime (templates are cached per id order, as
// vtkOrderedTriangulator caches them).
const std::vector<std::array<int, 4>>& vtk_split(LinearCellType type, const std::int64_t* global_ids);

// VTK's split of the structured-grid cell with parity (i + j + k) % 2 (hexahedron or voxel).
std::vector<std::array<int, 4>> vtk_structured_split(LinearCellType type, int parity);


}  // namespace rayint
