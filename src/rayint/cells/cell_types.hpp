#pragma once
// The one table of cell types every mesh reader maps its format onto (VTK legacy .vtk, VTK XML
// .vtu/.pvtu, gmsh .msh, TetGen .ele) and `rayint mesh info` reports: VTK's type id
// (vtkCellType.h), the node count, the dimension, gmsh's element type id (gmsh reference manual,
// "MSH file format", elm-type) with the permutation from gmsh's node order to VTK's, and what
// rayint does with the type:
//   Traversed   a volume cell the tetrahedral traversal integrates: the linear tetrahedron;
//   Quadratic   the quadratic tetrahedron (10 nodes): its corners are traversed as a tetrahedron
//               and its six mid-edge nodes kept beside it (TetMesh::edge_nodes); with straight
//               edges its scalar is quadratic along a chord and integrated as such
//               (mesh/quadratic_tets.hpp); a mesh with curved edges is read as a CellMesh
//               instead and integrated in its isoparametric interpolation like Isoparametric
//               cells. `--cells split` (the CellMesh path) refuses it: VTK's split is defined
//               for linear cells;
//   Isoparametric  a quadratic volume cell other than the tetrahedron (quadratic hexahedron,
//               quadratic wedge, quadratic pyramid, triquadratic hexahedron, biquadratic-quadratic
//               wedge): read into a CellMesh and integrated in its own isoparametric
//               interpolation, curved or not (cells/quadratic_isoparametric.hpp); the
//               tetrahedral paths and `--cells split` refuse it (unsupported_cell_message);
//   Skipped     a cell of dimension 0-2 (vertex, line, triangle, quad, ...): boundary and
//               annotation cells gmsh writes beside the volume; they hold no volume, so a ray
//               integral never sees them. Readers drop them and count them by type;
//   CellPath    a linear volume cell other than the tetrahedron (voxel, hexahedron, wedge,
//               pyramid): read into a CellMesh (mesh/cell_mesh.hpp) and integrated after
//               `--cells split` (mesh/cell_split.hpp, VTK's tetrahedralisation: an approximation);
//               the tetrahedral path refuses it with unsupported_cell_message(), which says so;
//   NotYet      a volume cell rayint does not integrate yet (pentagonal/hexagonal prisms, polyhedra):
//               refused with unsupported_cell_message().
// Node order is always VTK's once read: a reader permutes gmsh's order with gmsh_to_vtk
// (vtk node i = gmsh node gmsh_to_vtk[i]). The permutations are gmsh's documented node numbering
// ("Node ordering") against VTK's cell documentation (vtkQuadraticTetra.h: edge nodes on
// (0,1), (1,2), (2,0), (0,3), (1,3), (2,3); gmsh's 10-node tetrahedron has node 8 on edge (2,3)
// and node 9 on edge (1,3): the last two are swapped), checked on files gmsh 4.8 writes
// (tests/test_tet10.cpp, "[tet10]": every edge node at its edge's midpoint, and rayint's quadratic
// field equal to vtkQuadraticTetra's interpolation at random points of every cell).
// TetGen 1.6 (-o2) lists the mid-edge nodes of a tetrahedron (corners 0-3) on the edges (2,3),
// (0,3), (0,1), (1,2), (1,3), (0,2) (found on the file tetgen writes, tests/fixtures/readers/
// cube-o2.1.ele: each node at exactly one edge midpoint); kTetgenTet10ToVtk maps it.
// The quadratic volume cells' parametric nodes, shape functions and derivatives in VTK's own
// parametric coordinates are cells/quadratic_cells.hpp (checked against VTK 9.1, which also checks
// the gmsh permutations below against gmsh's documented edge lists, tests [cells][quadratic]).
// Shape functions: `shape` names the cells/shape_functions.hpp family for the types that have one
// (quadratic tetrahedron: tet10; hexahedron: hex8; quadratic hexahedron: hex20).
#include <array>
#include <optional>
#include <string>

#include "rayint/cells/shape_functions.hpp"

namespace rayint {

enum class CellSupport { Traversed, Quadratic, Skipped, CellPath, NotYet, Isoparametric };

struct CellTypeInfo {
  int vtk_id = 0;
  const char* name = "";  // VTK's name without "VTK_", lower case ("tetra", "quadratic tetra")
  int nodes = 0;          // -1: variable (polygon, poly-line, ...)
  int dimension = 0;
  int gmsh_id = 0;                       // 0: gmsh has no such element
  std::array<int, 27> gmsh_to_vtk{};     // first `nodes` entries used when gmsh_id != 0
  CellSupport support = CellSupport::NotYet;
  std::optional<CellType> shape;         // cells/shape_functions.hpp family, when there is one
};

// VTK type ids used by name in readers.
inline constexpr int kVtkVertex = 1, kVtkLine = 3, kVtkTriangle = 5, kVtkQuad = 9, kVtkTetra = 10,
                     kVtkVoxel = 11, kVtkHexahedron = 12, kVtkWedge = 13, kVtkPyramid = 14,
                     kVtkQuadraticTetra = 24, kVtkQuadraticHexahedron = 25, kVtkQuadraticWedge = 26;

// The quadratic tetrahedron's mid-edge nodes in VTK's order (vtkQuadraticTetra.h): node 4 + e
// lies on the edge (kTet10Edges[e][0], kTet10Edges[e][1]) of the corners 0-3.
inline constexpr std::array<std::array<int, 2>, 6> kTet10Edges{{{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}}};
// TetGen's 10-node tetrahedron in VTK's order: vtk node i = tetgen node kTetgenTet10ToVtk[i].
inline constexpr std::array<int, 10> kTetgenTet10ToVtk{0, 1, 2, 3, 6, 7, 9, 5, 8, 4};

// The row of a VTK type id / gmsh element type id, or nullptr for an id rayint does not know.
const CellTypeInfo* cell_type_from_vtk(long long vtk_id);
const CellTypeInfo* cell_type_from_gmsh(long long gmsh_id);

// For a CellPath row: "cell type hexahedron (VTK id 12): the tetrahedral path integrates only
// tetrahedra; integrate this file with --cells split (VTK's tetrahedralisation, an approximation
// of the cell's own interpolation)"; for a NotYet row "cell type X (VTK id N) is not supported
// yet; ..."; for a VTK type outside the table "cell type triquadratic pyramid (VTK id 37) is not
// supported; VTK ids 10-14, 24-27, 29 and 32 are integrated"; for an unknown id "cell type N is
// not a VTK cell type".
std::string unsupported_cell_message(long long vtk_id);

// Why `--cells split` refuses a quadratic cell: "--cells split: quadratic pyramid (VTK id 27): VTK's
// vtkDataSetTriangleFilter splits quadratic cells into linear tetrahedra on all their nodes in a
// way that depends on point ids and positions, which rayint does not reproduce; integrate this
// file without --cells split (its own isoparametric interpolation)". VTK 9.1 measured
// (python3-vtk9): vtkCell::Triangulate gives 8 (tet10), 22 (hex20), 16 (wedge15), 14 (pyramid13),
// 48 (hex27), 24 (wedge18) tetrahedra, and 12 to 20 different splits of one cell over 20 random
// point-id orders and perturbations, for every quadratic type.
std::string quadratic_split_message(long long vtk_id);

// "triangle" etc. for a VTK id, "VTK id N" for an unknown one.
std::string cell_type_label(long long vtk_id);

}  // namespace rayint
