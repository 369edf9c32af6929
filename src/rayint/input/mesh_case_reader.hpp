#pragma once
// Reading mesh cases (format: cases/README.md, "Mesh cases") through the shared JsonSchema walk.
// The mesh is inline ("mesh": {"points", "scalars", "tets"}) or a file ("mesh_file", relative to
// the case file's folder): VTK legacy .vtk, VTK XML .vtu (input/vtk_xml_reader.hpp, registered
// below like any other reader), or what register_mesh_reader adds. Every problem is one InputError line naming
// the file and the field (or, for a .vtk file, the file and its section).
#include <nlohmann/json.hpp>
#include <string>

#include "rayint/input/scalar_choice.hpp"
#include "rayint/mesh/cell_mesh.hpp"
#include "rayint/mesh/mesh_case.hpp"

namespace rayint {

// True when `root` is a mesh case (an object with "mesh" or "mesh_file").
bool is_mesh_case(const nlohmann::json& root);

// How a mesh's tets are taken (mesh/tet_mesh.hpp). Default: inverted tets are reoriented and
// degenerate ones (zero volume, slivers) dropped, counted in MeshCase::repairs. strict
// (`--strict-mesh`): refused with one line naming the tet, as validate_tet_mesh does.
// Either way a mesh with overlapping tetrahedra is refused naming two of them
// (mesh/mesh_check.hpp; measured cost in docs/meshes.md).
// split_cells (`--cells split`): a mesh file of hexahedra, wedges, pyramids, voxels (and
// tetrahedra) is tetrahedralised as VTK's vtkDataSetTriangleFilter does (mesh/cell_split.hpp), an
// approximation that MeshCase::split records; without it such a file is refused with one line
// (exit 2) saying so.
struct MeshReadOptions {
  bool strict = false;
  bool split_cells = false;
};

// A mesh file alone, by extension (.vtk, .vtu, .pvtu, .msh, .ele, .vts, .vtr, .pvts, .pvtr, .vti, or a registered one), as a
// mesh case's "mesh_file" reads it, before repair and checks (for `rayint mesh info`).
TetMesh read_mesh_file(const std::string& path, const ScalarChoice& scalar = {});

// Any mesh file as a CellMesh (mesh/cell_mesh.hpp): .vtk, .vtu, .pvtu, .msh, .vts, .vtr, .pvts, .pvtr, .vti keep every
// linear volume cell; formats of tetrahedra only (.ele, registered readers) give their tetrahedra.
CellMesh read_cell_mesh_file(const std::string& path, const ScalarChoice& scalar = {});

MeshCase parse_mesh_case(const nlohmann::json& root, const std::string& source,
                         const MeshReadOptions& options = {});
// Refuses (InputError "<source>: rays[i].origin: ...") a ray whose origin is so far from the
// mesh that a double's step along it exceeds the mesh's extent (it would miss silently).
// parse_mesh_case applies it to every ray of a case.
void refuse_far_origins(const MeshCase& mesh_case, const std::string& source);
MeshCase read_mesh_case_file(const std::string& path, const MeshReadOptions& options = {});

// Readers validate the structure only (validate_tet_mesh_structure); orientation and degenerate
// tets are then handled here by `options` for every format alike.
// Adds a reader for "mesh_file" paths ending in `extension` (e.g. ".vtu"; optional libraries such
// as src/rayint/vtk/). The reader throws InputError "<file>: <field>: <what>". Register before
// reading from several threads; a later registration of the same extension replaces the earlier.
using MeshFileReader = TetMesh (*)(const std::string& path, const std::string& scalar_name);
void register_mesh_reader(const std::string& extension, MeshFileReader read);

}  // namespace rayint
