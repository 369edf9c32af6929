#pragma once
// Reading voxel grids (format: docs/voxel-grids.md). A grid is a JSON object
//   {"dims": [nx, ny, nz], "origin": [x, y, z], "spacing": [dx, dy, dz],
//    "values": [...]}                                  values inline, x fastest, or
//    "values_file": "data.raw", "value_type": "float32" | "float64" | "uint8" | "uint16" | "json"}
// where a raw file holds nx*ny*nz little-endian values and a "json" file one JSON array.
// Relative values_file paths are resolved against the directory of the JSON file. Every problem
// is one InputError line `<file>: <field path>: <what>` (input/json_schema.hpp).
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "rayint/grid/voxel_grid.hpp"
#include "rayint/input/json_schema.hpp"

namespace rayint {

// At most this many grid points (2^28: 2 GiB of doubles); larger grids are refused.
inline constexpr long long kMaxGridPoints = 1LL << 28;

// The grid object `j` found at field `path` of schema.source(); base_dir resolves values_file.
// For use inside other formats (scenes embed a grid as one of their fields).
VoxelGrid parse_voxel_grid(const nlohmann::json& j, const JsonSchema& schema,
                           const std::string& path, const std::string& base_dir);

// A whole JSON text / file that is one grid object.
VoxelGrid parse_voxel_grid_text(std::string_view text, const std::string& source,
                                const std::string& base_dir);
// A file ending in .vti / .pvti is read as VTK XML image data (read_vti / read_pvti,
// input/vtk_xml_reader.hpp), .vtk as a VTK legacy STRUCTURED_POINTS file
// (read_vtk_legacy_image): the point array named `array`, else the active point scalars, else the
// first one-component point array. Anything else is a JSON grid object (`array` must be empty).
VoxelGrid read_voxel_grid_file(const std::string& path, const std::string& array = "");

}  // namespace rayint
