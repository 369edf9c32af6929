#pragma once
// How VTK splits a linear cell into tetrahedra (what ParaView renders after
// vtkDataSetTriangleFilter, the filter its unstructured volume mappers run first), for
// `--cells split` and for measuring what the split changes (issue 29).
//   Unstructured grids: vtkDataSetTriangleFilter hands each 3-D cell to vtkOrderedTriangulator
//     (TemplateTriangulate) in parametric coordinates, inserting the points in the order of their
//     global ids: the split depends only on that order. The tables (vtk_split_tables.cpp) were
//     recorded from VTK 9.1 for every order of the n ids (scripts/cells/vtk_split_tables.py) and
//     are checked against VTK's output on random distorted cells with random ids
//     (tests/fixtures/cells/vtk_split_check.json, tests [cells][isoparametric]). A tetra is
//     itself. Wedge: 3 tets; pyramid: 2; hexahedron and voxel: 5 or 6.
//   Structured grids (.vts hexahedra, .vtr/.vti voxels): StructuredExecute calls
//     TriangulateIds((i + j + k) % 2) on cell (i, j, k): 5 tets, alternating so that faces match.
// Tets are local node indices (VTK node order); their orientation is not normalised.
#include <array>
#include <cstdint>
#include <vector>

#include "rayint/cells/linear_cells.hpp"

namespace rayint {

inline constexpr int kMaxSplitTets = 6;

// VTK's split of an unstructured-grid cell whose node i has global id global_ids[i] (distinct).
std::vector<std::array<int, 4>> vtk_split(LinearCellType type, const std::int64_t* global_ids);

// VTK's split of the structured-grid cell with parity (i + j + k) % 2 (hexahedron or voxel).
std::vector<std::array<int, 4>> vtk_structured_split(LinearCellType type, int parity);

namespace vtk_split_tables {
extern const int kHexahedronSplitCount, kVoxelSplitCount, kWedgeSplitCount, kPyramidSplitCount;
extern const signed char kHexahedronSplits[][kMaxSplitTets][4];
extern const signed char kVoxelSplits[][kMaxSplitTets][4];
extern const signed char kWedgeSplits[][kMaxSplitTets][4];
extern const signed char kPyramidSplits[][kMaxSplitTets][4];
extern const unsigned char kHexahedronIndex[40320];
extern const unsigned char kVoxelIndex[40320];
extern const unsigned char kWedgeIndex[720];
extern const unsigned char kPyramidIndex[120];
extern const signed char kHexahedronStructured0[5][4], kHexahedronStructured1[5][4];
extern const signed char kVoxelStructured0[5][4], kVoxelStructured1[5][4];
}  // namespace vtk_split_tables

}  // namespace rayint
