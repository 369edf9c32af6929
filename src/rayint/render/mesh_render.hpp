#pragma once
// Rendering a mesh case's camera: one viewing ray per pixel traced through the mesh
// (mesh/tet_traversal.hpp) and integrated by a method (normally `exact`), in tiles of 4 x 8
// pixels, multithreaded over strips of 8 image rows (core/parallel.hpp). Optionally a second method is run on the same segments and
// compared pixel by pixel with the first (relative error, the largest of the three channels;
// max, median and p99 as core/statistics.hpp defines them).
// Progress is reported through a callback from the calling thread only (it monitors the
// workers), so the callback needs no locking. Library code: nothing is printed.
#include <algorithm>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "rayint/core/shard.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/mesh/mesh_case.hpp"
#include "rayint/mesh/tet_traversal.hpp"
#include "rayint/render/image.hpp"

namespace rayint {

struct MeshRenderSettings {
  unsigned threads = 0;  // 0: all cores
  // Called every ~0.2 s and once at the end with (rows done, rows total).
  std::function<void(int, int)> progress;
  // Shard (core/shard.hpp): render only the band of rows shard_range(height, shard); the other
  // rows stay black. {0, 1}: every row.
  ShardSpec shard;
};

struct MeshRenderCost {
  double wall_seconds = 0.0;
  double traversal_seconds = 0.0;    // summed over threads: tracing rays through the mesh
  double integration_seconds = 0.0;  // summed over threads: the method on the segments
  long rays = 0;
  long segments = 0;                 // cell crossings
  long pieces = 0;                   // segments split at transfer-function breakpoints
  unsigned threads = 1;
  TraversalStats traversal;
};

struct ErrorSummary {
  long pixels = 0;
  double max_rel = 0.0, mean_rel = 0.0, median_rel = 0.0, p99_rel = 0.0;
  double max_abs = 0.0;
  long non_finite = 0;
};

struct MeshRender {
  Image image;              // with `method`
  MeshRenderCost cost;      // of `method` (traversal + integration)
  Image compared;           // with `compare` (empty when none)
  std::vector<double> rel_error;  // per pixel, row-major (empty when none)
  ErrorSummary error;
};

// The relative error of a compared pixel: the largest over channels of |got - ref| / |ref|
// (0 / 0 = 0; x / 0 and a non-finite `got` = infinity).
double relative_pixel_error(const Rgb& ref, const Rgb& got);
// The summary of the relative errors `rel` of the pixels `pixel` of two images (all pixels when
// `pixel` is empty): max, mean (of the finite ones), median, p99, max absolute difference,
// non-finite count.
ErrorSummary error_summary(const Image& image, const Image& compared, const std::vector<double>& rel,
                           std::vector<std::size_t> pixel = {});

// Renders mesh_case.camera (which must be set). `compare` may be null. With mesh_case.shading
// enabled, both methods go through integrate_shaded (mesh/surface_shading.hpp).
MeshRender render_mesh(const MeshCase& mesh_case, const TetTraversal& mesh,
                       const RayIntegrator& method, const RayIntegrator* compare,
                       const MeshRenderSettings& settings);

// A shard's band of rows (row_begin..row_end) of a render: the pixels of both images, the
// per-pixel errors and the cost counters (rays, segments, pieces, traversal statistics are
// integers; the seconds are wall and busy times, summed when merged).
struct MeshRenderPart {
  int width = 0, height = 0;
  int row_begin = 0, row_end = 0;
  bool compared = false;
  std::vector<Rgb> image, compared_image;  // (row_end - row_begin) * width, row-major
  std::vector<double> rel_error;            // likewise, when compared
  MeshRenderCost cost;
};
MeshRenderPart mesh_render_part(const MeshRender& render, const ShardSpec& shard);

// The band fields both mesh renders' parts share (width, height, row_begin/row_end, compared,
// image, compared_image, rel_error), for MeshRenderPart and CellMeshRenderPart alike.
// cut_band: a render's band of rows for `shard`; returns the band's first and one-past-last pixel.
template <class Part, class Render>
IndexRange cut_band(Part& p, const Render& r, const ShardSpec& shard) {
  p.width = r.image.width;
  p.height = r.image.height;
  const IndexRange rows = shard_range(static_cast<std::size_t>(p.height), shard);
  p.row_begin = static_cast<int>(rows.begin);
  p.row_end = static_cast<int>(rows.end);
  p.compared = !r.rel_error.empty();
  const auto w = static_cast<std::size_t>(p.width);
  const IndexRange px{rows.begin * w, rows.end * w};
  const auto at = [&](const auto& v, std::size_t i) { return v.begin() + static_cast<long>(i); };
  p.image.assign(at(r.image.pixels, px.begin), at(r.image.pixels, px.end));
  if (p.compared) {
    p.compared_image.assign(at(r.compared.pixels, px.begin), at(r.compared.pixels, px.end));
    p.rel_error.assign(at(r.rel_error, px.begin), at(r.rel_error, px.end));
  }
  return px;
}
// order_bands: the start of an assembly: `out` sized from the first part (image; compared image and
// rel_error when the parts are compared), and the parts in row order for place_band. Throws
// std::invalid_argument "WHAT: no parts to assemble" when there are none.
template <class Part, class Render>
std::vector<const Part*> order_bands(const std::vector<Part>& parts, Render& out, const char* what) {
  if (parts.empty()) throw std::invalid_argument(std::string(what) + ": no parts to assemble");
  const int width = parts.front().width, height = parts.front().height;
  out.image = Image(width, height);
  if (parts.front().compared) {
    out.compared = Image(width, height);
    out.rel_error.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0.0);
  }
  std::vector<const Part*> ordered;
  for (const Part& p : parts) ordered.push_back(&p);
  std::sort(ordered.begin(), ordered.end(), [](const Part* a, const Part* b) { return a->row_begin < b->row_begin; });
  return ordered;
}
// place_band: part p's pixels into the assembled render `out` (already sized from the first
// part), after checking that p belongs to the same render and starts at or after covered_to
// (what the parts before it covered); `what` names the render in the exception. Returns the
// band's first pixel; covered_to moves to p's end.
template <class Part, class Render>
std::size_t place_band(const Part& p, Render& out, int& covered_to, const char* what) {
  const int width = out.image.width, height = out.image.height;
  const bool compared = !out.rel_error.empty();
  const std::size_t n = static_cast<std::size_t>(p.row_end - p.row_begin) * static_cast<std::size_t>(width);
  if (p.width != width || p.height != height || p.compared != compared || p.row_begin < covered_to ||
      p.row_end > height || p.image.size() != n || (compared && (p.compared_image.size() != n || p.rel_error.size() != n)))
    throw std::invalid_argument(std::string(what) + ": parts of different renders, or overlapping");
  covered_to = p.row_end;
  const auto first = static_cast<long>(p.row_begin) * width;
  std::copy(p.image.begin(), p.image.end(), out.image.pixels.begin() + first);
  if (compared) {
    std::copy(p.compared_image.begin(), p.compared_image.end(), out.compared.pixels.begin() + first);
    std::copy(p.rel_error.begin(), p.rel_error.end(), out.rel_error.begin() + first);
  }
  return static_cast<std::size_t>(first);
}
// assemble_bands: the assembly both mesh renders share: every part's band into `out` in row order
// (order_bands, place_band), then merge(part, its first pixel) for the rest of each part.
// Returns the placed pixels when the parts are compared (for the error summary), else none.
template <class Part, class Render, class Merge>
std::vector<std::size_t> assemble_bands(const std::vector<Part>& parts, Render& out, const char* what, Merge&& merge) {
  const std::vector<const Part*> ordered = order_bands(parts, out, what);
  const bool compared = parts.front().compared;
  std::vector<std::size_t> pixel;
  int covered_to = 0;
  for (const Part* p : ordered) {
    const std::size_t first = place_band(*p, out, covered_to, what);
    if (compared)
      for (std::size_t i = 0; i < p->rel_error.size(); ++i) pixel.push_back(first + i);
    merge(*p, first);
  }
  return pixel;
}
// The render from its parts (all of them: the single run's render exactly; some: a partial
// merge, the missing rows black and left out of the error summary).
MeshRender assemble_mesh_render(const std::vector<MeshRenderPart>& parts);

// The heat map of a per-pixel relative error: log10 of the error mapped from 1e-16 (dark blue)
// through 1e-8 (green) to >= 1 (white); an error of exactly 0 is black, a non-finite one magenta.
// Linear RGB, to be written with write_png.
Image error_heat_map(const std::vector<double>& rel_error, int width, int height);

}  // namespace rayint
