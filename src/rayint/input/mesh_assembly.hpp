#pragma once
// The one place where a VTK-style dataset (points, cells with VTK type ids, point and cell arrays)
// becomes a TetMesh: the legacy .vtk reader, the .vtu reader and the .pvtu reader (pieces
// concatenated) map their format onto a RawMesh and call assemble_tet_mesh, so every rule below
// holds for all of them alike.
//
// Cells (cells/cell_types.hpp): tetrahedra are kept, quadratic tetrahedra as their corners with
// the mid-edge nodes in TetMesh::edge_nodes (VTK's order is the files' order); cells of dimension
// 0-2 are skipped and counted by type (TetMesh::info); other volume cells are refused with
// unsupported_cell_message ("cell type hexahedron (VTK id 12): ... --cells split ..."); an
// unknown type id is refused. Ghost cells: a cell array named vtkGhostType marks duplicated cells
// (bit 1, vtkDataSetAttributes::DUPLICATECELL: the copy of a cell another piece owns); they are
// dropped and counted once (TetMesh::info.ghost_cells). Ghost points need nothing: a ghost point
// is a copy of a point another piece holds, and merge_points joins copies with equal coordinates.
//
// The scalar (one rule for every VTK reader):
//   - a name given (ScalarChoice::name): the point array of that name, else the cell array of that name; it
//     must have one component. Not found: one line listing the arrays that exist.
//   - otherwise the first point array flagged active (legacy SCALARS, XML PointData Scalars="..."),
//     else the first one-component point array, else the first one-component cell array (cell
//     data: constant per cell, TetMesh::cell_scalars); region markers and physical tags
//     (is_marker_array) are never taken. Nothing left: one line listing the arrays that exist.
// ScalarChoice::cell_to_point (from the case's "cell_data": "point_average") turns a chosen cell array into point
// data the way ParaView's Cell Data to Point Data does (cell_to_point_average).
#include <cstdint>
#include <string>
#include <vector>

#include "rayint/core/prefaulted.hpp"
#include "rayint/geometry/vec3.hpp"
#include "rayint/input/scalar_choice.hpp"
#include "rayint/mesh/cell_mesh.hpp"
#include "rayint/mesh/tet_mesh.hpp"

namespace rayint {

struct RawArray {
  std::string name;
  bool cell = false;           // cell data (else point data)
  std::size_t components = 1;
  bool active = false;         // the file marks it as the active scalars
  std::vector<double> values;  // tuples x components (may be left empty for arrays never usable)
};

// The cell arrays are reserved to (about: the legacy cell list's size counts the per-cell counts
// too) their size and then written: prefaulted (core/prefaulted.hpp).
struct RawMesh {
  template <class T>
  using Array = std::vector<T, PrefaultedAllocator<T>>;
  std::vector<Vec3> points;
  Array<long long> types;                 // VTK cell type id per cell
  Array<std::size_t> offsets{0};          // cell i: connectivity[offsets[i], offsets[i+1])
  Array<long long> connectivity;          // point indices
  std::vector<RawArray> arrays;
};

// Names of the file's fields for messages: points, point data, cells, cell types.
struct RawMeshFields {
  std::string points = "POINTS", point_data = "POINT_DATA", cell_data = "CELL_DATA", cells = "CELLS",
              types = "CELL_TYPES";
};

struct AssemblyOptions {
  ScalarChoice scalar;         // name "" = the rule above; cell_to_point: a cell field becomes averaged point data
  bool merge_points = false;   // join points with bitwise-equal coordinates (pieces of a .pvtu)
};

// Throws InputError "<source>: <field>: <what>". The result passes validate_tet_mesh_structure.
TetMesh assemble_tet_mesh(RawMesh raw, const std::string& source, const AssemblyOptions& options,
                          const RawMeshFields& fields = {});

// The same dataset as a CellMesh (mesh/cell_mesh.hpp): every linear volume cell kept (tetrahedra,
// voxels, hexahedra, wedges, pyramids) and the quadratic tetrahedra, hexahedra and wedges (their
// own interpolation; `--cells split` refuses them), dimensions 0-2 skipped and counted, ghost
// cells dropped, the scalar chosen by the same rule. Other quadratic cells and polyhedra are
// refused naming their type.
CellMesh assemble_cell_mesh(RawMesh raw, const std::string& source, const AssemblyOptions& options,
                            const RawMeshFields& fields = {});

// The array the scalar rule above takes from `arrays` (by name, association, components and the
// active flag: values are not looked at), or nullptr when it takes none (the assembly then
// refuses the file naming its arrays). Lets a reader decode only the arrays used.
const RawArray* find_scalar_array(const std::vector<RawArray>& arrays, const AssemblyOptions& options);

// `"name" (point, 1 component), ...` for messages.
std::string list_arrays(const std::vector<MeshArrayInfo>& arrays);

}  // namespace rayint
