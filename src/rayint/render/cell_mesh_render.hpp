#pragma once
// Rendering a mesh case of linear cells in their own interpolation ("mode": "own";
// mesh/cell_traversal.hpp): one viewing ray per pixel, its chords integrated by
// LinearCellIntegrator (cells/cell_integral.hpp) and composited, multithreaded over rows. A pixel
// whose ray had a chord that could not be located or integrated is not a result: it is counted
// (failed_pixels), marked in `failed`, and its value in the image is NaN. Library code: nothing
// is printed.
#include <cstdint>
#include <vector>

#include "rayint/mesh/cell_traversal.hpp"
#include "rayint/mesh/mesh_case.hpp"
#include "rayint/render/image.hpp"
#include "rayint/render/mesh_render.hpp"

namespace rayint {

struct CellMeshRender {
  Image image;
  std::vector<std::uint8_t> failed;  // per pixel, row-major: 1 = not a result
  long failed_pixels = 0;
  long rays = 0, chords = 0;
  double max_error_estimate = 0.0;   // the largest per-ray error estimate (cell_integral.hpp)
  double wall_seconds = 0.0;
  double traversal_seconds = 0.0, integration_seconds = 0.0;  // summed over threads
  unsigned threads = 1;
  CellTraversalStats traversal;
};

// Renders mesh_case.camera (must be set) through `mesh` (built from *mesh_case.cells).
// settings.shard is ignored (the whole image).
CellMeshRender render_cell_mesh(const MeshCase& mesh_case, const CellTraversal& mesh,
                                const MeshRenderSettings& settings);

}  // namespace rayint
