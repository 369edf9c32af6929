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
  // --compare (compare_cell_mesh_render): another image of the same camera, e.g. a method on
  // VTK's split of the cells, against this one; per pixel the relative error (largest channel,
  // as render_mesh), NaN where this render's pixel failed; the summary over the rows rendered.
  Image compared;                 // empty when nothing was compared
  std::vector<double> rel_error;  // per pixel, row-major (empty when nothing was compared)
  ErrorSummary error;
};

// Renders mesh_case.camera (must be set) through `mesh` (built from *mesh_case.cells): the rows
// of settings.shard's band (core/shard.hpp; {0, 1}: every row), the others left black.
CellMeshRender render_cell_mesh(const MeshCase& mesh_case, const CellTraversal& mesh,
                                const MeshRenderSettings& settings);

// Fills own.compared / rel_error / error from `compared` (same size), over the rows of `shard`.
void compare_cell_mesh_render(CellMeshRender& own, const Image& compared, const ShardSpec& shard);

// A shard's band of rows of an own-mode render (rayint render --shard): the pixels, failed
// flags, the compared pixels and errors when compared, and the counts and times of the band.
struct CellMeshRenderPart {
  int width = 0, height = 0;
  int row_begin = 0, row_end = 0;
  bool compared = false;
  std::vector<Rgb> image, compared_image;  // (row_end - row_begin) * width, row-major
  std::vector<std::uint8_t> failed;
  std::vector<double> rel_error;
  long failed_pixels = 0, rays = 0, chords = 0;
  double max_error_estimate = 0.0, wall_seconds = 0.0, traversal_seconds = 0.0, integration_seconds = 0.0;
  unsigned threads = 1;
  CellTraversalStats traversal;
};
CellMeshRenderPart cell_mesh_render_part(const CellMeshRender& render, const ShardSpec& shard);
// The render from its parts (all of them: the single run's image exactly; some: the missing
// rows black, left out of the counts and the error summary). Throws std::invalid_argument for
// parts of different renders or overlapping bands.
CellMeshRender assemble_cell_mesh_render(const std::vector<CellMeshRenderPart>& parts);

}  // namespace rayint
