#pragma once
// Reading TetGen's output (.node + .ele, TetGen 1.6 manual, section 5.2) into a TetMesh.
//
// A "mesh_file" ending in .ele names the tets; the points are read from the .node file beside it
// (same name, extension .node). .node: header "<points> 3 <attributes> <boundary markers 0|1>",
// then "<index> x y z [attributes] [marker]"; .ele: header "<tets> <4|10> <region attribute 0|1>",
// then "<index> n1 n2 n3 n4 [...]" (a 10-node tet's first four are its corners: they are read, the
// six edge nodes are not, so the field stays linear). '#' starts a comment. Indices start at the
// .node file's first index (0 or 1, TetGen's -z) and must run consecutively.
// Scalars: TetGen carries point attributes through (-q interpolates them for Steiner points only
// on some paths: check your output); the first attribute, or attribute K for scalar_field "K".
// Orientation: TetGen 1.6 writes every tet positively oriented in VTK's sense (measured on the
// fixtures in tests/fixtures/meshes/, all tets); either order is accepted (mesh_case_reader.hpp).
// Every problem is one InputError line "<file>: <field>, line N: <what>" naming the .node or .ele.
#include <string>
#include <string_view>

#include "rayint/mesh/tet_mesh.hpp"

namespace rayint {

// `node_source`/`ele_source` name the two files in messages. Throws InputError. The mesh's
// structure is validated (validate_tet_mesh_structure).
TetMesh parse_tetgen(std::string_view node_bytes, const std::string& node_source,
                     std::string_view ele_bytes, const std::string& ele_source,
                     const std::string& scalar_name = "");
// `ele_path` ends in .ele; its .node sibling is read too.
TetMesh read_tetgen(const std::string& ele_path, const std::string& scalar_name = "");

}  // namespace rayint
