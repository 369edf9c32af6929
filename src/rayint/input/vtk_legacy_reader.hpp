#pragma once
// Reading VTK legacy unstructured grids (.vtk, "DATASET UNSTRUCTURED_GRID") into a TetMesh —
// the format ParaView and VTK write with "Save Data" / vtkUnstructuredGridWriter.
//
// Supported: file versions 2.0-4.2 (CELLS as [count, ids...] runs) and 5.1 (CELLS followed by
// OFFSETS and CONNECTIVITY arrays); ASCII and BINARY (big-endian, as VTK writes it); POINTS of
// type float or double; CELL_TYPES all 10 (VTK_TETRA); POINT_DATA SCALARS of any numeric type
// with one component (the first SCALARS array, or the one named `scalar_name`; with no SCALARS
// array and no name, the first one-component FIELD array, as meshio writes). Other point or
// cell arrays (VECTORS, NORMALS, FIELD, ...) and METADATA blocks are skipped.
// Refused with one line naming the file and the section: any cell type other than 10 (the
// message names the type, e.g. "12 (hexahedron)"), other datasets, missing POINT_DATA
// scalars, truncated binary data, and everything validate_tet_mesh_structure rejects (orientation
// and degenerate tets are the mesh case reader's policy: mesh_case_reader.hpp).
#include <string>
#include <string_view>

#include "rayint/mesh/tet_mesh.hpp"

namespace rayint {

// `source` names the file in messages. Throws InputError. The mesh's structure is validated.
TetMesh parse_vtk_legacy(std::string_view bytes, const std::string& source,
                         const std::string& scalar_name = "");
TetMesh read_vtk_legacy(const std::string& path, const std::string& scalar_name = "");

}  // namespace rayint
