// Own-interpolation rendering of cell meshes (see cell_mesh_render.hpp).
#include "rayint/render/cell_mesh_render.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <limits>
#include <stdexcept>

#include "rayint/core/parallel.hpp"
#include "rayint/core/shard.hpp"

namespace rayint {
namespace {

// A worker's or a shard part's counters added to the render's: counts, seconds and traversal
// statistics summed, the largest error estimate kept.
template <class Counts>
void add_counts(CellMeshRender& out, const Counts& c) {
  out.rays += c.rays;
  out.chords += c.chords;
  out.failed_pixels += c.failed_pixels;
  out.max_error_estimate = std::max(out.max_error_estimate, c.max_error_estimate);
  out.traversal_seconds += c.traversal_seconds;
  out.integration_seconds += c.integration_seconds;
  out.traversal.add(c.traversal);
}

}  // namespace

CellMeshRender render_cell_mesh(const MeshCase& mc, const CellTraversal& mesh, const MeshRenderSettings& settings) {
  using Clock = std::chrono::steady_clock;
  const auto seconds = [](Clock::duration d) { return std::chrono::duration<double>(d).count(); };
  if (!mc.camera) throw std::invalid_argument(mc.source + ": camera: a mesh case needs a \"camera\" to render");
  const Camera& cam = *mc.camera;
  const CameraRays camera_rays(cam);  // the camera's frame once per render, the rays cam's bits
  const int width = cam.width, height = cam.height;
  const IndexRange rows = shard_range(static_cast<std::size_t>(height), settings.shard);
  const int band = static_cast<int>(rows.size());
  const unsigned threads = parallel_workers(band, settings.threads);
  CellMeshRender out;
  out.image = Image(width, height);
  out.failed.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0);
  const LinearCellIntegrator integrator(mc.transfer);
  struct Worker {
    CellTrace trace;
    CellTraversalStats traversal;
    long rays = 0, chords = 0, failed_pixels = 0;
    double max_error_estimate = 0.0, traversal_seconds = 0.0, integration_seconds = 0.0;
  };
  std::vector<Worker> workers(threads);
  std::atomic<int> rows_done{0};
  const auto render_row = [&](long long row, unsigned id) {
    const int y = static_cast<int>(rows.begin) + static_cast<int>(row);
    Worker& w = workers[id];
    for (int x = 0; x < width; ++x) {
      const auto t0 = Clock::now();
      mesh.trace(camera_rays.ray_for_pixel(x, y), w.trace, &w.traversal);
      const auto t1 = Clock::now();
      const CellRayResult r = mesh.integrate(w.trace, integrator, mc.background);
      w.integration_seconds += seconds(Clock::now() - t1);
      w.traversal_seconds += seconds(t1 - t0);
      ++w.rays;
      w.chords += r.chords;
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
      if (r.converged) {
        out.image.pixels[i] = r.intensity;
        w.max_error_estimate = std::max(w.max_error_estimate, r.error_estimate);
      } else {
        const double nan = std::numeric_limits<double>::quiet_NaN();
        out.image.pixels[i] = Rgb{nan, nan, nan};
        out.failed[i] = 1;
        ++w.failed_pixels;
      }
    }
    rows_done.fetch_add(1);
  };
  const auto start = Clock::now();
  parallel_for(band, settings.threads, render_row, 0.2, [&] {
    const int reported = rows_done.load();
    if (settings.progress && reported < band) settings.progress(reported, band);
  });
  if (settings.progress) settings.progress(band, band);
  out.wall_seconds = seconds(Clock::now() - start);
  out.threads = threads;
  for (const Worker& w : workers) add_counts(out, w);
  return out;
}

namespace {

// The error summary over `pixel`: a pixel whose own ray failed has no error (NaN in rel_error);
// it is counted among the non-finite ones and left out of the statistics.
ErrorSummary own_error_summary(const CellMeshRender& r, const std::vector<std::size_t>& pixel) {
  std::vector<std::size_t> ok;
  std::vector<double> rel;
  long failed = 0;
  for (std::size_t i : pixel) {
    if (r.failed[i]) {
      ++failed;
      continue;
    }
    ok.push_back(i);
    rel.push_back(r.rel_error[i]);
  }
  ErrorSummary s;
  if (!ok.empty()) s = error_summary(r.image, r.compared, rel, ok);
  s.pixels += failed;
  s.non_finite += failed;
  return s;
}

}  // namespace

void compare_cell_mesh_render(CellMeshRender& own, const Image& compared, const ShardSpec& shard) {
  const int width = own.image.width, height = own.image.height;
  if (compared.width != width || compared.height != height)
    throw std::invalid_argument("compare_cell_mesh_render: images of different sizes");
  own.compared = compared;
  own.rel_error.assign(own.image.pixels.size(), 0.0);
  const IndexRange rows = shard_range(static_cast<std::size_t>(height), shard);
  std::vector<std::size_t> pixel;
  for (std::size_t y = rows.begin; y < rows.end; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t i = y * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
      own.rel_error[i] = own.failed[i] ? std::numeric_limits<double>::quiet_NaN()
                                       : relative_pixel_error(own.image.pixels[i], compared.pixels[i]);
      pixel.push_back(i);
    }
  own.error = own_error_summary(own, pixel);
}

CellMeshRenderPart cell_mesh_render_part(const CellMeshRender& r, const ShardSpec& shard) {
  CellMeshRenderPart p;
  const IndexRange px = cut_band(p, r, shard);
  p.failed.assign(r.failed.begin() + static_cast<long>(px.begin), r.failed.begin() + static_cast<long>(px.end));
  p.failed_pixels = r.failed_pixels;
  p.rays = r.rays;
  p.chords = r.chords;
  p.max_error_estimate = r.max_error_estimate;
  p.wall_seconds = r.wall_seconds;
  p.traversal_seconds = r.traversal_seconds;
  p.integration_seconds = r.integration_seconds;
  p.threads = r.threads;
  p.traversal = r.traversal;
  return p;
}

CellMeshRender assemble_cell_mesh_render(const std::vector<CellMeshRenderPart>& parts) {
  CellMeshRender out;
  out.threads = 0;
  const std::vector<std::size_t> pixel =
      assemble_bands(parts, out, "cell mesh render", [&](const CellMeshRenderPart& p, std::size_t first) {
        if (p.failed.size() != p.image.size())
          throw std::invalid_argument("cell mesh render: parts of different renders, or overlapping");
        out.failed.resize(out.image.pixels.size(), 0);  // sized with the image, at the first part
        std::copy(p.failed.begin(), p.failed.end(), out.failed.begin() + static_cast<long>(first));
        add_counts(out, p);
        out.wall_seconds += p.wall_seconds;
        out.threads = std::max(out.threads, p.threads);
      });
  if (!pixel.empty()) out.error = own_error_summary(out, pixel);
  return out;
}

}  // namespace rayint
