#pragma once
// Reading VTK legacy files (.vtk): "DATASET UNSTRUCTURED_GRID" into a TetMesh (what ParaView and
// VTK write with "Save Data" / vtkUnstructuredGridWriter, gmsh with -format vtk, meshio) and
// "DATASET STRUCTURED_POINTS" into a VoxelGrid (vtkStructuredPointsWriter, image data).
//
// Supported: file versions 2.0-4.2 (CELLS as [count, ids...] runs) and 5.1 (CELLS followed by
// OFFSETS and CONNECTIVITY arrays); ASCII and BINARY (big-endian, as VTK writes it); values of
// every numeric type. ASCII values of type float are read as float32, exactly as VTK reads them
// (strtof, the nearest float: vtkDataReader reads them with istream >> float); double as double.
// Attributes: SCALARS (the active scalars), FIELD arrays (meshio writes point and cell data so),
// VECTORS, NORMALS, TENSORS, TEXTURE_COORDINATES, COLOR_SCALARS, GLOBAL_IDS, PEDIGREE_IDS are
// listed (TetMesh::info.arrays); METADATA blocks are skipped.
// Meshes go through the one assembly of VTK datasets (input/mesh_assembly.hpp): tetrahedra kept,
// cells of dimension 0-2 skipped and counted, other volume cells refused naming their type, the
// scalar chosen by one rule (point SCALARS, else a one-component point or cell array that is not
// a region marker; cell data is constant per cell), vtkGhostType duplicate cells dropped.
// Images: DIMENSIONS (>= 2 per axis), ORIGIN, SPACING (or ASPECT_RATIO, its old name), the
// POINT_DATA array named `scalar_name`, else the first one-component point array; x fastest, as
// VTK stores it. The voxel grid's origin is ORIGIN (structured points have no extent offset).
// Every problem is one InputError line naming the file and the section.
#include <string>
#include <string_view>

#include "rayint/grid/voxel_grid.hpp"
#include "rayint/input/scalar_choice.hpp"
#include "rayint/mesh/cell_mesh.hpp"
#include "rayint/mesh/tet_mesh.hpp"

namespace rayint {

// `source` names the file in messages. Throws InputError. The mesh's structure is validated.
// `scalar`: the array to integrate; with cell_to_point a cell field becomes point data averaged
// as ParaView's Cell Data to Point Data (input/scalar_choice.hpp).
TetMesh parse_vtk_legacy(std::string_view bytes, const std::string& source,
                         const ScalarChoice& scalar = {});
TetMesh read_vtk_legacy(const std::string& path, const ScalarChoice& scalar = {});

// The same file as a CellMesh: every linear volume cell kept (mesh_assembly.hpp, assemble_cell_mesh).
CellMesh parse_vtk_legacy_cells(std::string_view bytes, const std::string& source,
                                const ScalarChoice& scalar = {});
CellMesh read_vtk_legacy_cells(const std::string& path, const ScalarChoice& scalar = {});

VoxelGrid parse_vtk_legacy_image(std::string_view bytes, const std::string& source,
                                 const std::string& scalar_name = "");
VoxelGrid read_vtk_legacy_image(const std::string& path, const std::string& scalar_name = "");

}  // namespace rayint
