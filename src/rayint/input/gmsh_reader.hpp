#pragma once
// Reading gmsh meshes (.msh, gmsh reference manual section 10 "Gmsh file formats": MSH 2.2 and
// MSH 4.1, ASCII and binary) into a TetMesh.
//
// Read: $MeshFormat, $Nodes, $Elements, $NodeData and $ElementNodeData; every other section
// ($PhysicalNames, $Entities, $Periodic, ...) is skipped. Element types go through the cell-type
// table (cells/cell_types.hpp): elements of dimension 0-2 (points, lines, triangles,
// quadrangles: the boundary gmsh writes beside the volume) are skipped and counted by type
// (TetMesh::info); 4-node tetrahedra (type 4) are the cells; hexahedra, prisms and pyramids are
// refused by read_gmsh with a line pointing to --cells split and read by read_gmsh_cells; other
// 3-D elements (10-node tetrahedra, ...) are refused with "cell type X (VTK id N) is not
// supported yet". Physical and elementary tags are labels, never the scalar.
// Scalars: the first one-component $NodeData (meshio writes point data so), else the first
// one-component $ElementNodeData (what gmsh's own "Save View" writes for a MathEval view), else
// the first one-component $ElementData (cell data: constant per tetrahedron), or the one whose
// name (first string tag) is ScalarChoice::name. Blocks named like markers (is_marker_array, e.g.
// meshio's "gmsh:physical") are never taken unless named. Element node data must agree at every node
// (a continuous field): a node given two different values is refused. Every node of a tet needs a
// value. Node tags may be sparse; tets refer to nodes by tag.
// Orientation: gmsh 4.8 writes every tet positively oriented in VTK's sense (measured on the
// fixtures in tests/fixtures/meshes/); either order is accepted (mesh_case_reader.hpp).
// Every problem is one InputError line "<file>: <section>, line N: <what>".
#include <string>
#include <string_view>

#include "rayint/input/scalar_choice.hpp"
#include "rayint/mesh/cell_mesh.hpp"
#include "rayint/mesh/tet_mesh.hpp"

namespace rayint {

// `source` names the file in messages. Throws InputError. The mesh's structure is validated
// (validate_tet_mesh_structure).
// `scalar.cell_to_point`: a cell field ($ElementData) becomes point data averaged as ParaView does.
TetMesh parse_gmsh(std::string_view bytes, const std::string& source, const ScalarChoice& scalar = {});
TetMesh read_gmsh(const std::string& path, const ScalarChoice& scalar = {});

// The same file as a CellMesh: every linear volume element kept (4-node tetrahedra, 8-node
// hexahedra, 6-node prisms, 5-node pyramids), nodes permuted to VTK's order through the cell-type
// table, $ElementNodeData values with them; interface points, lines, triangles and quadrangles
// gmsh writes between its volumes are skipped and counted like boundary ones (they are never
// boundaries: a CellMesh's boundary comes from its volume cells only).
CellMesh parse_gmsh_cells(std::string_view bytes, const std::string& source, const ScalarChoice& scalar = {});
CellMesh read_gmsh_cells(const std::string& path, const ScalarChoice& scalar = {});

}  // namespace rayint
