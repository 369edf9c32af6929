// Own-interpolation rendering of cell meshes (see cell_mesh_render.hpp).
#include "rayint/render/cell_mesh_render.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <limits>
#include <stdexcept>

#include "rayint/core/parallel.hpp"

namespace rayint {

CellMeshRender render_cell_mesh(const MeshCase& mc, const CellTraversal& mesh, const MeshRenderSettings& settings) {
  using Clock = std::chrono::steady_clock;
  const auto seconds = [](Clock::duration d) { return std::chrono::duration<double>(d).count(); };
  if (!mc.camera) throw std::invalid_argument(mc.source + ": camera: a mesh case needs a \"camera\" to render");
  const Camera& cam = *mc.camera;
  const int width = cam.width, height = cam.height;
  const unsigned threads = parallel_workers(height, settings.threads);
  CellMeshRender out;
  out.image = Image(width, height);
  out.failed.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0);
  const LinearCellIntegrator integrator(mc.transfer);
  struct Worker {
    CellTrace trace;
    CellTraversalStats stats;
    long rays = 0, chords = 0, failed = 0;
    double max_estimate = 0.0, traversal_seconds = 0.0, integration_seconds = 0.0;
  };
  std::vector<Worker> workers(threads);
  std::atomic<int> rows_done{0};
  const auto render_row = [&](long long row, unsigned id) {
    const int y = static_cast<int>(row);
    Worker& w = workers[id];
    for (int x = 0; x < width; ++x) {
      const auto t0 = Clock::now();
      mesh.trace(cam.ray_for_pixel(x, y), w.trace, &w.stats);
      const auto t1 = Clock::now();
      const CellRayResult r = mesh.integrate(w.trace, integrator, mc.background);
      w.integration_seconds += seconds(Clock::now() - t1);
      w.traversal_seconds += seconds(t1 - t0);
      ++w.rays;
      w.chords += r.chords;
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
      if (r.converged) {
        out.image.pixels[i] = r.intensity;
        w.max_estimate = std::max(w.max_estimate, r.error_estimate);
      } else {
        const double nan = std::numeric_limits<double>::quiet_NaN();
        out.image.pixels[i] = Rgb{nan, nan, nan};
        out.failed[i] = 1;
        ++w.failed;
      }
    }
    rows_done.fetch_add(1);
  };
  const auto start = Clock::now();
  parallel_for(height, settings.threads, render_row, 0.2, [&] {
    const int reported = rows_done.load();
    if (settings.progress && reported < height) settings.progress(reported, height);
  });
  if (settings.progress) settings.progress(height, height);
  out.wall_seconds = seconds(Clock::now() - start);
  out.threads = threads;
  for (const Worker& w : workers) {
    out.rays += w.rays;
    out.chords += w.chords;
    out.failed_pixels += w.failed;
    out.max_error_estimate = std::max(out.max_error_estimate, w.max_estimate);
    out.traversal_seconds += w.traversal_seconds;
    out.integration_seconds += w.integration_seconds;
    out.traversal.add(w.stats);
  }
  return out;
}

}  // namespace rayint
