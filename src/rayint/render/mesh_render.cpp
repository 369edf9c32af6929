// Mesh rendering, per-pixel comparison and the error heat map (see mesh_render.hpp).
#include "rayint/render/mesh_render.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <utility>

#include "rayint/core/lanes.hpp"
#include "rayint/core/parallel.hpp"
#include "rayint/core/statistics.hpp"
#include "rayint/mesh/gradients.hpp"
#include "rayint/mesh/quadratic_tets.hpp"
#include "rayint/model/pieces.hpp"

namespace rayint {
namespace {

using Clock = std::chrono::steady_clock;

double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

// Pieces of a ray's segments: per segment with length > 0, one more than the breakpoints strictly
// inside its scalar range. With at most 8 breakpoints they are counted two lanes at a time without
// a jump (the NaN padding never counts; a NaN end counts one piece), else by two binary searches;
// the same count either way. (Issue 33: counted one segment at a time in scalar code, this
// statistic took ~7% of a mesh render.) The exact method's batch path gives the same count from
// its splitting (RayIntegrator::integrate_many's `pieces`, round 8); this counts for the others.
class PieceCounter {
 public:
  explicit PieceCounter(std::vector<double> bps) : bps_(std::move(bps)) {
    padded_.fill(std::numeric_limits<double>::quiet_NaN());
    if (bps_.size() <= padded_.size()) std::copy(bps_.begin(), bps_.end(), padded_.begin());
  }
  long operator()(const std::vector<Segment>& segments) const {
    if (bps_.size() > padded_.size()) {
      long n = 0;
      for (const Segment& s : segments) n += count_searched(s);
      return n;
    }
    using lanes::M2;
    using lanes::V2;
    V2 b[4];
    std::memcpy(b, padded_.data(), sizeof b);
    M2 inside = {0, 0};
    long n = 0;
    for (const Segment& s : segments) {
      if (!(s.length > 0.0)) continue;
      ++n;
      const double lo = std::min(s.scalar_far, s.scalar_exit), hi = std::max(s.scalar_far, s.scalar_exit);
      if (!(hi > lo)) continue;  // constant or NaN: one piece
      // -1 per breakpoint above lo, +1 per breakpoint at or above hi: -1 per one inside (lo, hi).
      // (Two sums, not one of (p > lo) & (p < hi): GCC scalarises that mask.)
      const V2 lov = {lo, lo}, hiv = {hi, hi};
      for (const V2& p : b) {
        inside += p > lov;
        inside -= p >= hiv;
      }
    }
    return n - (inside[0] + inside[1]);
  }

 private:
  long count_searched(const Segment& s) const {
    if (!(s.length > 0.0)) return 0;
    const double lo = std::min(s.scalar_far, s.scalar_exit), hi = std::max(s.scalar_far, s.scalar_exit);
    const auto a = std::upper_bound(bps_.begin(), bps_.end(), lo);
    const auto b = std::lower_bound(bps_.begin(), bps_.end(), hi);
    return 1 + (b > a ? static_cast<long>(b - a) : 0L);
  }
  std::vector<double> bps_;
  std::array<double, 8> padded_{};
};

void summarize_errors(MeshRender& out, const std::vector<double>& rel, std::vector<std::size_t> pixel = {}) {
  out.error = error_summary(out.image, out.compared, rel, std::move(pixel));
}

}  // namespace

double relative_pixel_error(const Rgb& ref_pixel, const Rgb& got_pixel) {
  double e = 0.0;
  for (int ch = 0; ch < kChannels; ++ch) {
    const double ref = ref_pixel[ch], got = got_pixel[ch];
    double rel;
    if (!std::isfinite(got)) rel = std::numeric_limits<double>::infinity();
    else if (ref == 0.0) rel = got == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
    else rel = std::fabs(got - ref) / std::fabs(ref);
    e = std::max(e, rel);
  }
  return e;
}

ErrorSummary error_summary(const Image& image, const Image& compared, const std::vector<double>& rel,
                           std::vector<std::size_t> pixel) {
  if (pixel.empty())
    for (std::size_t i = 0; i < rel.size(); ++i) pixel.push_back(i);
  ErrorSummary s;
  s.pixels = static_cast<long>(rel.size());
  double sum = 0.0;
  for (std::size_t i = 0; i < rel.size(); ++i) {
    if (!std::isfinite(rel[i])) ++s.non_finite;
    else sum += rel[i];
    const Rgb& a = image.pixels[pixel[i]];
    const Rgb& b = compared.pixels[pixel[i]];
    for (int ch = 0; ch < kChannels; ++ch) s.max_abs = std::max(s.max_abs, std::fabs(a[ch] - b[ch]));
  }
  if (!rel.empty()) {
    const ErrorStats st = error_stats(rel);
    s.max_rel = st.max;
    s.median_rel = st.median;
    s.p99_rel = st.p99;
    const long finite = s.pixels - s.non_finite;
    s.mean_rel = finite > 0 ? sum / static_cast<double>(finite) : 0.0;
  }
  return s;
}

MeshRender render_mesh(const MeshCase& mc, const TetTraversal& mesh, const RayIntegrator& method,
                       const RayIntegrator* compare, const MeshRenderSettings& settings) {
  if (!mc.camera) throw std::invalid_argument(mc.source + ": camera: a mesh case needs a \"camera\" to render");
  const Camera& cam = *mc.camera;
  const CameraRays camera_rays(cam);
  const int width = cam.width, height = cam.height;
  const unsigned threads = parallel_workers(height, settings.threads);
  MeshRender out;
  out.image = Image(width, height);
  if (compare) {
    out.compared = Image(width, height);
    out.rel_error.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0.0);
  }
  std::unique_ptr<GradientField> gradients;
  if (mc.shading.enabled) gradients = std::make_unique<GradientField>(mesh, mc.shading.gradient);
  const PieceCounter count_pieces(mc.transfer.breakpoints());
  // Quadratic tetrahedra (mesh/quadratic_tets.hpp): the image is their exact quadratic integral;
  // the methods of `method` and `compare` take linear segments only.
  std::unique_ptr<QuadraticTraceIntegrator> quadratic;
  if (mesh.quadratic()) {
    if (compare || mc.shading.enabled)
      throw std::invalid_argument(mc.mesh_source + ": quadratic tetrahedra: a render with a compared method or shading "
                                  "takes linear tetrahedra only");
    quadratic = std::make_unique<QuadraticTraceIntegrator>(mc.transfer);
  }

  const IndexRange rows = shard_range(static_cast<std::size_t>(height), settings.shard);
  const int band = static_cast<int>(rows.size());
  std::atomic<int> rows_done{0};
  std::vector<MeshRenderCost> per_thread(threads);
  // The rows are rendered in strips of kStrip rows, each strip in tiles of kTileW x kStrip pixels:
  // a tile's rays are traced, then integrated, so that the clock is read twice per tile instead of
  // twice per ray (issue 33). Tiles instead of rows keep the cells that neighbouring rays cross in
  // the cache: along a row, the rays between a pixel and the one below it walked ~4 MB of cell
  // records at 105k tets (more than a core's L2), within a tile a few KB.
  constexpr int kTileW = 4, kStrip = 8;
  constexpr int kChunk = kTileW * kStrip;
  const int strips = (band + kStrip - 1) / kStrip;
  struct Scratch {  // per worker, reused (no allocation per ray once warm)
    std::array<ViewRay, kChunk> view;
    std::array<RayTrace, kChunk> traces;
    std::array<Ray, kChunk> rays;
    std::array<RayResult, kChunk> results, compared;
  };
  std::vector<Scratch> scratch(threads);
  auto render_strip = [&](long long strip, unsigned id) {
    const int y0 = static_cast<int>(rows.begin) + static_cast<int>(strip) * kStrip;
    const int h = std::min(kStrip, static_cast<int>(rows.begin) + band - y0);
    MeshRenderCost& cost = per_thread[id];
    Scratch& sc = scratch[id];
    for (int x0 = 0; x0 < width; x0 += kTileW) {
      const int w = std::min(kTileW, width - x0);
      const int n = w * h;  // ray k is pixel (x0 + k % w, y0 + k / w)
      const auto t0 = Clock::now();
      // The tile's rays traced together: their first boundary queries go to Embree as packets.
      // Unshaded linear segments need only the Rays (rays_many: the walk writes their segments);
      // shading and quadratic tets take the crossings.
      const bool together = !quadratic && !mc.shading.enabled;
      for (int k = 0; k < n; ++k) sc.view[static_cast<std::size_t>(k)] = camera_rays.ray_for_pixel(x0 + k % w, y0 + k / w);
      if (together) {
        mesh.rays_many(sc.view.data(), static_cast<std::size_t>(n), mc.background, sc.rays.data(), &cost.traversal);
      } else {
        mesh.trace_many(sc.view.data(), static_cast<std::size_t>(n), sc.traces.data(), &cost.traversal);
        if (!quadratic)
          for (int k = 0; k < n; ++k)
            ray_from_trace(sc.traces[static_cast<std::size_t>(k)], mc.background, sc.rays[static_cast<std::size_t>(k)]);
      }
      const auto t1 = Clock::now();
      // Unshaded linear segments: the tile's rays in one call (the exact method integrates their
      // pieces in one kernel batch, and counts them on the way: tile_pieces).
      long tile_pieces = 0;
      bool pieces_counted = false;
      if (together) {
        pieces_counted = method.integrate_many(sc.rays.data(), static_cast<std::size_t>(n), sc.results.data(), &tile_pieces);
        if (compare) compare->integrate_many(sc.rays.data(), static_cast<std::size_t>(n), sc.compared.data());
      }
      for (int k = 0; k < n; ++k) {
        const int x = x0 + k % w, y = y0 + k / w;
        const RayTrace& trace = sc.traces[static_cast<std::size_t>(k)];
        const RayResult r = together  ? sc.results[static_cast<std::size_t>(k)]
                            : quadratic ? quadratic->integrate(trace, mc.background, &cost.pieces)
                                        : integrate_shaded(method, trace, mc.background, mc.shading, *gradients);
        out.image.at(x, y) = r.intensity;
        if (compare) {
          const RayResult c = together ? sc.compared[static_cast<std::size_t>(k)]
                                       : integrate_shaded(*compare, trace, mc.background, mc.shading, *gradients);
          out.compared.at(x, y) = c.intensity;
          const double e = relative_pixel_error(r.intensity, c.intensity);
          out.rel_error[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)] = e;
        }
      }
      const auto t2 = Clock::now();
      cost.traversal_seconds += seconds(t1 - t0);
      cost.integration_seconds += seconds(t2 - t1);
      cost.rays += n;
      cost.pieces += tile_pieces;
      for (int k = 0; k < n; ++k) {
        if (quadratic) {  // pieces counted by the integrator (split at extrema and crossings)
          cost.segments += static_cast<long>(sc.traces[static_cast<std::size_t>(k)].crossings.size());
        } else {
          const Ray& ray = sc.rays[static_cast<std::size_t>(k)];
          cost.segments += static_cast<long>(ray.segments.size());
          if (!pieces_counted) cost.pieces += count_pieces(ray.segments);
        }
      }
    }
    rows_done.fetch_add(h);
  };
  const auto start = Clock::now();
  // Progress every 0.2 s from this thread (the callback runs on this thread only).
  parallel_for(strips, settings.threads, render_strip, 0.2, [&] {
    const int reported = rows_done.load();
    if (settings.progress && reported < band) settings.progress(reported, band);
  });
  if (settings.progress) settings.progress(band, band);  // always once at the end
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
  if (compare) summarize_errors(out, out.rel_error);
  return out;
}

MeshRenderPart mesh_render_part(const MeshRender& r, const ShardSpec& shard) {
  MeshRenderPart p;
  cut_band(p, r, shard);
  p.cost = r.cost;
  return p;
}

MeshRender assemble_mesh_render(const std::vector<MeshRenderPart>& parts) {
  MeshRender out;
  std::vector<std::size_t> pixel = assemble_bands(parts, out, "mesh render", [&](const MeshRenderPart& p, std::size_t) {
    const MeshRenderCost& c = p.cost;
    out.cost.wall_seconds += c.wall_seconds;
    out.cost.traversal_seconds += c.traversal_seconds;
    out.cost.integration_seconds += c.integration_seconds;
    out.cost.rays += c.rays;
    out.cost.segments += c.segments;
    out.cost.pieces += c.pieces;
    out.cost.threads = std::max(out.cost.threads, c.threads);
    out.cost.traversal.add(c.traversal);
  });
  if (!pixel.empty()) {
    std::vector<double> rel;  // the placed pixels' errors, in their order
    for (const std::size_t i : pixel) rel.push_back(out.rel_error[i]);
    summarize_errors(out, rel, std::move(pixel));
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
