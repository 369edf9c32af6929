// Mesh rendering, per-pixel comparison and the error heat map (see mesh_render.hpp).
#include "rayint/render/mesh_render.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <thread>

#include "rayint/mesh/gradients.hpp"
#include "rayint/model/pieces.hpp"

namespace rayint {
namespace {

using Clock = std::chrono::steady_clock;

double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

// Pieces of a segment: one more than the breakpoints strictly inside its scalar range.
long count_pieces(const std::vector<double>& bps, const Segment& s) {
  if (!(s.length > 0.0)) return 0;
  const double lo = std::min(s.scalar_far, s.scalar_exit), hi = std::max(s.scalar_far, s.scalar_exit);
  const auto a = std::upper_bound(bps.begin(), bps.end(), lo);
  const auto b = std::lower_bound(bps.begin(), bps.end(), hi);
  return 1 + (b > a ? static_cast<long>(b - a) : 0L);
}

}  // namespace

MeshRender render_mesh(const MeshCase& mc, const TetTraversal& mesh, const RayIntegrator& method,
                       const RayIntegrator* compare, const MeshRenderSettings& settings) {
  if (!mc.camera) throw std::invalid_argument(mc.source + ": camera: a mesh case needs a \"camera\" to render");
  const Camera& cam = *mc.camera;
  const int width = cam.width, height = cam.height;
  unsigned threads = settings.threads != 0 ? settings.threads : std::max(1u, std::thread::hardware_concurrency());
  threads = std::min<unsigned>(threads, static_cast<unsigned>(height));
  MeshRender out;
  out.image = Image(width, height);
  if (compare) {
    out.compared = Image(width, height);
    out.rel_error.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0.0);
  }
  std::unique_ptr<GradientField> gradients;
  if (mc.shading.enabled) gradients = std::make_unique<GradientField>(mesh, mc.shading.gradient);
  const std::vector<double> bps = mc.transfer.breakpoints();

  std::atomic<int> next_row{0}, rows_done{0};
  std::vector<MeshRenderCost> per_thread(threads);
  std::exception_ptr failure;
  std::atomic<bool> failed{false};
  auto worker = [&](unsigned id) {
    try {
      MeshRenderCost& cost = per_thread[id];
      RayTrace trace;
      for (int y; !failed && (y = next_row.fetch_add(1)) < height;) {
        for (int x = 0; x < width; ++x) {
          const ViewRay vr = cam.ray_for_pixel(x, y);
          const auto t0 = Clock::now();
          mesh.trace(vr, trace, &cost.traversal);
          const Ray ray = ray_from_trace(trace, mc.background);
          const auto t1 = Clock::now();
          const RayResult r = mc.shading.enabled
                                  ? integrate_shaded(method, trace, mc.background, mc.shading, *gradients)
                                  : method.integrate(ray, nullptr);
          const auto t2 = Clock::now();
          cost.traversal_seconds += seconds(t1 - t0);
          cost.integration_seconds += seconds(t2 - t1);
          ++cost.rays;
          cost.segments += static_cast<long>(ray.segments.size());
          for (const Segment& s : ray.segments) cost.pieces += count_pieces(bps, s);
          out.image.at(x, y) = r.intensity;
          if (compare) {
            const RayResult c = mc.shading.enabled
                                    ? integrate_shaded(*compare, trace, mc.background, mc.shading, *gradients)
                                    : compare->integrate(ray, nullptr);
            out.compared.at(x, y) = c.intensity;
            double e = 0.0;
            for (int ch = 0; ch < kChannels; ++ch) {
              const double ref = r.intensity[ch], got = c.intensity[ch];
              double rel;
              if (!std::isfinite(got)) rel = std::numeric_limits<double>::infinity();
              else if (ref == 0.0) rel = got == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
              else rel = std::fabs(got - ref) / std::fabs(ref);
              e = std::max(e, rel);
            }
            out.rel_error[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)] = e;
          }
        }
        rows_done.fetch_add(1);
      }
    } catch (...) {
      if (!failed.exchange(true)) failure = std::current_exception();
    }
  };
  const auto start = Clock::now();
  std::vector<std::thread> pool;
  for (unsigned i = 0; i < threads; ++i) pool.emplace_back(worker, i);
  int reported = -1;
  while (rows_done.load() < height && !failed.load()) {
    // Poll (the callback runs on this thread only).
    for (int i = 0; i < 20 && rows_done.load() < height && !failed.load(); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    reported = rows_done.load();
    if (settings.progress && reported < height) settings.progress(reported, height);
  }
  for (auto& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  if (settings.progress) settings.progress(height, height);  // always once at the end
  out.cost.wall_seconds = seconds(Clock::now() - start);
  out.cost.threads = threads;
  for (const auto& c : per_thread) {
    out.cost.traversal_seconds += c.traversal_seconds;
    out.cost.integration_seconds += c.integration_seconds;
    out.cost.rays += c.rays;
    out.cost.segments += c.segments;
    out.cost.pieces += c.pieces;
    out.cost.traversal.add(c.traversal);
  }
  if (compare) {
    ErrorSummary& s = out.error;
    std::vector<double> sorted = out.rel_error;
    s.pixels = static_cast<long>(sorted.size());
    double sum = 0.0;
    for (std::size_t i = 0; i < sorted.size(); ++i) {
      if (!std::isfinite(sorted[i])) ++s.non_finite;
      else sum += sorted[i];
      const Rgb& a = out.image.pixels[i];
      const Rgb& b = out.compared.pixels[i];
      for (int ch = 0; ch < kChannels; ++ch) s.max_abs = std::max(s.max_abs, std::fabs(a[ch] - b[ch]));
    }
    std::sort(sorted.begin(), sorted.end());
    if (!sorted.empty()) {
      s.max_rel = sorted.back();
      s.median_rel = sorted[sorted.size() / 2];
      s.p99_rel = sorted[std::min(sorted.size() - 1, sorted.size() * 99 / 100)];
      const long finite = s.pixels - s.non_finite;
      s.mean_rel = finite > 0 ? sum / static_cast<double>(finite) : 0.0;
    }
  }
  return out;
}

Image error_heat_map(const std::vector<double>& rel, int width, int height) {
  Image img(width, height);
  // Colour stops in sRGB along log10(error) in [-16, 0].
  static const double kStops[5][3] = {{0.05, 0.05, 0.45}, {0.0, 0.45, 0.9}, {0.1, 0.75, 0.2}, {0.95, 0.8, 0.1}, {1.0, 1.0, 1.0}};
  for (std::size_t i = 0; i < rel.size() && i < img.pixels.size(); ++i) {
    const double e = rel[i];
    Rgb c{0.0, 0.0, 0.0};
    if (!std::isfinite(e)) {
      c = {1.0, 0.0, 1.0};
    } else if (e > 0.0) {
      const double u = std::clamp((std::log10(e) + 16.0) / 16.0, 0.0, 1.0) * 4.0;
      const int k = std::min(3, static_cast<int>(u));
      const double f = u - k;
      for (int ch = 0; ch < 3; ++ch)
        c[ch] = srgb_decode((1.0 - f) * kStops[k][ch] + f * kStops[k + 1][ch]);
    }
    img.pixels[i] = c;
  }
  return img;
}

}  // namespace rayint
