#pragma once
// Blanking of VTK image data: which voxels (cubes) an image hides, read from its vtkGhostType
// arrays, as VTK itself reads them (vtkImageData::IsCellVisible; flag values of
// vtkDataSetAttributes, checked on VTK 9.1): a cube is hidden when its cell's vtkGhostType
// (CellData) has the HIDDENCELL bit (32) or the vtkGhostType (PointData) of any of its 8 points
// has the HIDDENPOINT bit (2). Other ghost bits (DUPLICATEPOINT / DUPLICATECELL = 1, ...) do not
// hide anything. ParaView's Resample To Image writes both arrays for the points it could not
// sample (outside its input, value 0 there) beside a vtkValidPointMask; the mask is not read:
// VTK's visibility uses the ghost arrays only.
// The result goes to VoxelGrid::set_hidden_cubes (grid/voxel_grid.hpp): hidden cubes are empty.
// Read from .vti, each piece of a .pvti, and legacy STRUCTURED_POINTS (VTK's legacy writer puts
// vtkGhostType in a FIELD block of POINT_DATA / CELL_DATA; vtk_legacy_reader.cpp).
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "rayint/input/vtk_xml_data_array.hpp"

namespace rayint {

inline constexpr unsigned kVtkHiddenPoint = 2;  // vtkDataSetAttributes::HIDDENPOINT
inline constexpr unsigned kVtkHiddenCell = 32;  // vtkDataSetAttributes::HIDDENCELL

// Hidden points and cells of one image <Piece> of `dims` points per axis (x fastest), one byte
// each (non-zero = hidden); an empty vector when the piece has no such array. A vtkGhostType
// array that is not one integer component per point/cell is an InputError naming it.
struct ImageGhosts {
  std::vector<unsigned char> hidden_points;  // size nx*ny*nz or empty
  std::vector<unsigned char> hidden_cells;   // size (nx-1)(ny-1)(nz-1) or empty
};
ImageGhosts read_image_ghosts(const vtk_xml::Document& d, pugi::xml_node piece, const std::string& piece_field,
                              const std::array<int, 3>& dims);

// One byte per value of a vtkGhostType array already read (a legacy file's FIELD array): non-zero
// where the value has `bit`; empty when none has. A value that is not an integer in [0, 255] sets
// *bad to its index (and returns empty); *bad = v.size() otherwise.
std::vector<unsigned char> ghost_flags(const std::vector<double>& v, unsigned bit, std::size_t* bad);

// The hidden cubes of a grid of `dims` points from its hidden points and cells (either may be
// empty): a cube is hidden if its cell is or any of its 8 points is. Empty if nothing is hidden.
std::vector<unsigned char> hidden_cubes(const std::array<int, 3>& dims, const std::vector<unsigned char>& hidden_points,
                                        const std::vector<unsigned char>& hidden_cells);

}  // namespace rayint
