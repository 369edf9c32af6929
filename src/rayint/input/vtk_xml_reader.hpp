#pragma once
// Reading VTK XML files without VTK: .vtu unstructured grids into a TetMesh and .vti image data
// into a VoxelGrid, with pugixml (XML) and zlib (compressed blocks). The DataArray decoding is
// one decoder for both (vtk_xml_data_array.hpp): format ascii, binary (base64) and appended (raw
// or base64), compressor none or vtkZLibDataCompressor, header_type UInt32 or UInt64, byte_order
// LittleEndian or BigEndian, types Int8..UInt64, Float32, Float64.
//
// .vtu (VTKFile type="UnstructuredGrid", one or more Pieces, joined): Points (3 components),
// Cells (connectivity, offsets, types), PointData and CellData, through the one assembly of VTK
// datasets (input/mesh_assembly.hpp): tetrahedra kept, cells of dimension 0-2 skipped and
// counted, other volume cells refused naming their type (rayint does not split hexahedra or
// voxels itself: a split that conforms across neighbouring cells depends on how the mesh was
// built), ghost cells dropped, the scalar chosen by one rule (a point or a cell array).
// .vti (VTKFile type="ImageData", one Piece whose Extent is the WholeExtent): WholeExtent,
// Origin, Spacing (> 0), Direction (absent or the identity: rayint's grids are axis-aligned; a
// rotated image is refused), PointData. Point (i, j, k) of the extent lies at
// Origin + (i Spacing_x, j Spacing_y, k Spacing_z), as in vtkImageData, so the grid's origin is
// Origin + extent minimum * Spacing. Values must be finite.
//
// The point scalar: the PointData array named `scalar_name`; with no name, the array the
// PointData's Scalars attribute names (VTK's active scalars), else the first one-component
// array. It must have one component.
// Every problem is one InputError "<file>: <field>: <what>", e.g.
//   "mesh.vtu: UnstructuredGrid/Piece/Points/DataArray: header says 96 bytes, expected 1536 (...)".
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "rayint/grid/voxel_grid.hpp"
#include "rayint/input/scalar_choice.hpp"
#include "rayint/mesh/cell_mesh.hpp"
#include "rayint/mesh/tet_mesh.hpp"

namespace rayint {

// `source` names the file in messages. Throw InputError.
// `scalar`: the array to integrate; with cell_to_point a cell field becomes point data averaged
// as ParaView's Cell Data to Point Data (input/scalar_choice.hpp).
TetMesh parse_vtu(std::string_view bytes, const std::string& source, const ScalarChoice& scalar = {});
TetMesh read_vtu(const std::string& path, const ScalarChoice& scalar = {});
// A .pvtu (VTKFile type="PUnstructuredGrid"): the .vtu pieces its <Piece Source="..."> name,
// relative to its folder, joined: points with bitwise-equal coordinates merged (the pieces of
// one dataset repeat the points on their shared faces), ghost cells dropped (mesh_assembly.hpp).
// The piece files a .pvtu names (its Piece Source attributes, resolved against its folder), for
// a reader that reads them itself (VTK's): each is an input of the run (shard fingerprints).
std::vector<std::string> pvtu_piece_files(const std::string& path);
TetMesh read_pvtu(const std::string& path, const ScalarChoice& scalar = {});

// The same files as CellMeshes (mesh/cell_mesh.hpp): every linear volume cell kept (tetrahedra,
// voxels, hexahedra, wedges, pyramids), for `--cells split` and `rayint mesh info`.
CellMesh parse_vtu_cells(std::string_view bytes, const std::string& source, const ScalarChoice& scalar = {});
CellMesh read_vtu_cells(const std::string& path, const ScalarChoice& scalar = {});
CellMesh read_pvtu_cells(const std::string& path, const ScalarChoice& scalar = {});

// Structured grids (one Piece whose Extent is the WholeExtent; a grid flat on an axis is refused):
// .vts (VTKFile type="StructuredGrid": Points, PointData, CellData): hexahedral cells, VTK's
// vtkStructuredGrid order; .vtr (type="RectilinearGrid": Coordinates, three one-component
// DataArrays x, y, z in that order, strictly increasing, under any names): voxel cells, VTK's
// vtkRectilinearGrid order. The scalar by the rule of input/mesh_assembly.hpp. The result keeps
// its point dimensions (CellMesh::structured), which --cells split needs (mesh/cell_split.hpp).
CellMesh parse_vts(std::string_view bytes, const std::string& source, const ScalarChoice& scalar = {});
CellMesh read_vts(const std::string& path, const ScalarChoice& scalar = {});
CellMesh parse_vtr(std::string_view bytes, const std::string& source, const ScalarChoice& scalar = {});
CellMesh read_vtr(const std::string& path, const ScalarChoice& scalar = {});

// Parallel structured grids, .pvts (VTKFile type="PStructuredGrid") and .pvtr
// ("PRectilinearGrid"), as vtkXMLPStructuredGridWriter / vtkXMLPRectilinearGridWriter write
// them: a WholeExtent and Pieces, each an Extent and the Source of a serial .vts / .vtr holding
// that extent (relative to the parallel file's folder; pieces with an empty extent are skipped).
// Read as ONE structured grid of the WholeExtent, equal to the serial file of the same grid:
// pieces share their boundary points (and, with GhostLevel > 0, layers of ghost cells), and every
// point and cell is kept once. Shared points must have bitwise-equal coordinates (.pvtr: equal
// coordinate values) and equal values in every one-component array; vtkGhostType flags come
// from the owning piece with the duplicate bit cleared (no copies remain). Refused, naming the
// file and field: a piece outside the WholeExtent, a piece whose own Extent differs from the
// parallel file's, pieces that leave a point or cell uncovered, a missing piece file, an array
// missing in a piece. `load` returns a piece file's bytes given its resolved path (the readers:
// the file, an InputError when missing; the fuzzer: its input's parts).
using PieceFileLoader = std::function<std::string(const std::string& path)>;
CellMesh parse_pvts(std::string_view bytes, const std::string& source, const PieceFileLoader& load,
                    const ScalarChoice& scalar = {});
CellMesh parse_pvtr(std::string_view bytes, const std::string& source, const PieceFileLoader& load,
                    const ScalarChoice& scalar = {});
CellMesh read_pvts(const std::string& path, const ScalarChoice& scalar = {});
CellMesh read_pvtr(const std::string& path, const ScalarChoice& scalar = {});

// A .vti as a mesh of its voxels (CellMesh, like .vtr): points at Origin + Direction (index *
// spacing), voxel cells (hexahedra of the same corners when Direction rotates them), point and
// cell arrays, the scalar by the rule of input/mesh_assembly.hpp. The way to integrate an image
// whose field is cell data: constant per voxel, exactly, with --cells split (docs/images.md).
CellMesh parse_vti_cells(std::string_view bytes, const std::string& source, const ScalarChoice& scalar = {});
CellMesh read_vti_cells(const std::string& path, const ScalarChoice& scalar = {});

VoxelGrid parse_vti(std::string_view bytes, const std::string& source, const std::string& scalar_name = "");
VoxelGrid read_vti(const std::string& path, const std::string& scalar_name = "");
// A .pvti (VTKFile type="PImageData"): the .vti pieces it names, each placed at its Extent in the
// WholeExtent; points shared by two pieces must agree; every point must be covered.
VoxelGrid read_pvti(const std::string& path, const std::string& scalar_name = "");

}  // namespace rayint
