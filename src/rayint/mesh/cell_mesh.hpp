#pragma once
// A mesh of linear volume cells of any VTK type rayint reads (tetrahedron 10, voxel 11,
// hexahedron 12, wedge 13, pyramid 14; cells/cell_types.hpp, support Traversed or CellPath), with
// one scalar per point or per cell: what the readers give for a file that holds cells other than
// tetrahedra (input/cell_mesh_reader.hpp), `rayint mesh info` reports, and `--cells split`
// (mesh/cell_split.hpp) turns into a TetMesh. Node order is VTK's (vtkVoxel.h, vtkHexahedron.h,
// vtkWedge.h, vtkPyramid.h); readers of other orders (gmsh) permute through the cell-type table.
//
// The tetrahedral path (TetMesh) is separate and unchanged: a file of tetrahedra only is read
// straight into a TetMesh; a CellMesh of tetrahedra only converts with take_tets().
//
// Structured grids (.vts, .vtr) keep their point dimensions: their cells are the grid's
// (i, j, k) cells in VTK's order (i fastest), and vtkDataSetTriangleFilter splits them with a
// different rule than unstructured cells (cell_split.hpp), so `structured` says which.
#include <array>
#include <map>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rayint/geometry/vec3.hpp"
#include "rayint/mesh/tet_mesh.hpp"

namespace rayint {

// VTK type ids of the cells a CellMesh holds (vtkCellType.h).
// The quadratic ones (24-27, 29, 32: tet10, hex20, wedge15, pyramid13, hex27, wedge18; corners first, then
// the mid-edge nodes, then face and cell centres, VTK's order) are integrated in their own
// isoparametric interpolation only (cells/quadratic_isoparametric.hpp).
enum class MeshCellType : std::uint8_t {
  tetra = 10, voxel = 11, hexahedron = 12, wedge = 13, pyramid = 14,
  quadratic_tetra = 24, quadratic_hexahedron = 25, quadratic_wedge = 26, quadratic_pyramid = 27,
  triquadratic_hexahedron = 29, biquadratic_quadratic_wedge = 32
};
// Whether the type is one of the quadratic cells (24-27, 29, 32).
bool is_quadratic(MeshCellType type);

// Nodes of a cell type (4, 8, 8, 6, 5; quadratic 10, 20, 15, 13, 27, 18); 0 for an id that is not one.
int mesh_cell_nodes(long long vtk_id);
// "tetra", "voxel", "hexahedron", "wedge", "pyramid" (the table's names).
const char* mesh_cell_name(MeshCellType type);

struct CellMesh {
  std::vector<Vec3> points;
  std::vector<double> scalars;        // one per point (empty when cell_scalars is used)
  std::vector<double> cell_scalars;   // one per cell, constant over it (empty for point data)
  std::vector<MeshCellType> types;      // per cell
  std::vector<std::uint32_t> offsets{0};        // cell c: connectivity[offsets[c], offsets[c + 1])
  std::vector<std::int32_t> connectivity;       // point indices, VTK node order
  // Point dimensions (nx, ny, nz) of a structured grid (.vts: hexahedra, .vtr: voxels), i fastest;
  // cell (i, j, k) is cell i + (nx - 1) (j + (ny - 1) k).
  std::optional<std::array<int, 3>> structured;
  MeshFileInfo info;  // cells_by_type, skipped, arrays, scalar; cell_ids: per cell its index in the file

  std::size_t cell_count() const { return types.size(); }
  std::size_t nodes_of(std::size_t c) const { return offsets[c + 1] - offsets[c]; }
  const std::int32_t* cell(std::size_t c) const { return connectivity.data() + offsets[c]; }
  bool only_tets() const;
};

// Kept cells by type name ("hexahedron" -> 120, ...).
std::vector<std::pair<std::string, long>> cell_counts(const CellMesh& mesh);

// Structure only: at least one cell, node counts per type, indices in range, finite points and
// scalars, one scalar per point (or per cell). Throws InputError "<source>: <field>: <what>".
void validate_cell_mesh_structure(const CellMesh& mesh, const std::string& source,
                                  const MeshFieldNames& names = {});

// The CellMesh of a TetMesh (moves the arrays): a tet with mid-edge nodes (TetMesh::edge_nodes)
// becomes a quadratic tetra (corners, then the edge nodes in VTK's order), the others tetrahedra.
CellMesh cell_mesh_of(TetMesh&& mesh);

// The TetMesh of a CellMesh that holds only tetrahedra (moves the arrays). Precondition: only_tets().
TetMesh take_tets(CellMesh&& mesh);

// Signed Jacobian determinants at the corners of a cell are what orientation means for a
// non-simplex; mesh info reports, per type, how many cells have all corner Jacobians positive in
// VTK's sense, all negative (gmsh's prisms: the same nodes in the mirrored order), or mixed signs
// (a twisted or degenerate cell).
struct CellOrientationCounts {
  long positive = 0, negative = 0, mixed = 0;
};
// For cell c: +1 all corners positive, -1 all negative, 0 mixed or zero.
int cell_orientation(const CellMesh& mesh, std::size_t c);

// Zero-volume cells. Cell c has zero volume when its Jacobian determinant |det J| is at most
// kDegenerateTetRatio l^3 (tet_mesh.hpp: 1e-12; l the cell's longest node-node distance) at
// every point of the grid {0, 1/2, 1}^3 of parametric space. For every linear type det J is a
// polynomial of degree <= 2 in each of r, s, t (the columns of J are each free of one variable
// and at most linear in the others), so it vanishes on that grid if and only if it vanishes
// everywhere; with the tolerance, |det J| <= ~2e-12 l^3 everywhere (the grid's Lebesgue
// constant is 1.25 per axis). For a tetrahedron det J = 6V: the tetrahedral path's "zero volume"
// and "sliver" together. A collapsed cell that still has volume (a hexahedron with two nodes
// merged, as meshers write wedges) is not one. Such a cell covers no volume and has no length
// along any ray: the own mode drops it (drop_zero_volume_cells), counts it, and its neighbours
// across it see boundary faces, as for a dropped tetrahedron (tet_mesh.hpp).
bool zero_volume_cell(const CellMesh& mesh, std::size_t c);
// Removes the zero-volume cells (cell data kept for the others, in order); returns how many,
// by type name. Throws InputError "<source>: cells: ..." when no cell is left.
std::map<std::string, long> drop_zero_volume_cells(CellMesh& mesh, const std::string& source);
// Strict (--strict-mesh): InputError "<source>: cells[i]: ... zero volume ..." for the first one.
void refuse_zero_volume_cells(const CellMesh& mesh, const std::string& source);

}  // namespace rayint
