// Monte Carlo volumetric path tracing; see volume_path_tracer.hpp.
#include "rayint/scattering/volume_path_tracer.hpp"

#include <chrono>
#include <cmath>
#include <mutex>

#include "rayint/core/parallel.hpp"

namespace rayint {

namespace {
constexpr double kRouletteWeight = 0.1;

// Ratio-tracking transmittance from x along unit direction w to the box boundary.
double ratio_tracking(const ScatteringVolume& v, const Vec3& x, const Vec3& w, double sigma_maj,
                      Rng& rng, PathTraceStats& s) {
  const RaySpan iv = v.density.clip(ViewRay{x, w});
  if (!iv.hit || sigma_maj <= 0) return 1.0;
  double t = iv.t_enter, T = 1.0;
  for (;;) {
    t -= std::log(rng.uniform_open0()) / sigma_maj;
    if (t >= iv.t_exit) return T;
    ++s.tentative_collisions;
    T *= 1.0 - v.sigma_t(x + t * w) / sigma_maj;
    if (T <= 0) return 0.0;
  }
}

}  // namespace

double trace_path(const ScatteringVolume& v, const ViewRay& ray, Rng& rng, int max_order,
                  PathTraceStats* stats, int min_order, double sigma_maj) {
  PathTraceStats local;
  PathTraceStats& s = stats ? *stats : local;
  ++s.paths;
  if (sigma_maj < 0) sigma_maj = v.majorant();
  const Vec3 to_light = -v.light.direction;
  Vec3 x = ray.origin, d = ray.direction.normalized();
  double L = 0, throughput = 1;
  int order = 0;
  for (;;) {
    const RaySpan iv = v.density.clip(ViewRay{x, d});
    bool collided = false;
    if (iv.hit && sigma_maj > 0) {
      double t = iv.t_enter;
      for (;;) {
        t -= std::log(rng.uniform_open0()) / sigma_maj;
        if (t >= iv.t_exit) break;
        ++s.tentative_collisions;
        const Vec3 p = x + t * d;
        if (rng.uniform() * sigma_maj < v.sigma_t(p)) {
          x = p;
          collided = true;
          break;
        }
      }
    }
    if (!collided) {
      if (order == 0 && min_order == 0) L += throughput * v.background;
      return L;
    }
    ++order;
    ++s.real_collisions;
    // Next event toward the light: light propagating along light.direction scatters into -d.
    if (order >= min_order) {
      ++s.shadow_rays;
      const double T = ratio_tracking(v, x, to_light, sigma_maj, rng, s);
      L += throughput * v.albedo * v.phase.eval(v.light.direction.dot(-d)) * v.light.irradiance * T;
    }
    if (max_order > 0 && order >= max_order) return L;
    throughput *= v.albedo;
    if (throughput < kRouletteWeight) {
      if (throughput <= 0 || rng.uniform() * kRouletteWeight >= throughput) return L;
      throughput = kRouletteWeight;
    }
    const double u1 = rng.uniform(), u2 = rng.uniform();
    d = v.phase.sample(d, u1, u2);
  }
}

Estimate trace_ray(const ScatteringVolume& v, const ViewRay& ray, int samples, std::uint64_t seed,
                   std::uint64_t index, int max_order, PathTraceStats* stats, int min_order,
                   double sigma_maj) {
  Rng rng = block_rng(seed, index);
  if (sigma_maj < 0) sigma_maj = v.majorant();
  double sum = 0, sum2 = 0;
  for (int i = 0; i < samples; ++i) {
    const double x = trace_path(v, ray, rng, max_order, stats, min_order, sigma_maj);
    sum += x;
    sum2 += x * x;
  }
  Estimate e;
  e.samples = samples;
  const double n = samples;
  e.mean = sum / n;
  const double var = n > 1 ? std::max(0.0, (sum2 - n * e.mean * e.mean) / (n - 1)) : 0.0;
  e.std_error = std::sqrt(var / n);
  return e;
}

EstimateImage path_trace_image(const ScatteringVolume& v, const Camera& camera,
                               const PathTracerOptions& o) {
  return path_trace_rows(v, camera, o, 0, camera.height);
}

EstimateImage path_trace_rows(const ScatteringVolume& v, const Camera& camera,
                              const PathTracerOptions& o, int row_begin, int row_end) {
  v.validate();
  camera.validate();
  if (o.samples_per_pixel < 1) throw std::invalid_argument("path tracer: samples_per_pixel must be >= 1");
  if (row_begin < 0 || row_end > camera.height || row_begin > row_end)
    throw std::invalid_argument("path tracer: rows must lie in [0, height]");
  EstimateImage img;
  img.width = camera.width;
  img.height = row_end - row_begin;
  const std::size_t n = static_cast<std::size_t>(camera.width) * static_cast<std::size_t>(img.height);
  img.mean.assign(n, 0.0);
  img.std_error.assign(n, 0.0);
  std::mutex stats_mutex;
  const double sigma_maj = v.majorant();
  const auto start = std::chrono::steady_clock::now();
  const CameraRays camera_rays(camera);  // the camera's frame once, the rays its bits
  parallel_for(img.height, o.threads, [&](std::size_t local_row) {
    const std::size_t row = local_row + static_cast<std::size_t>(row_begin);
    PathTraceStats s;
    for (int x = 0; x < camera.width; ++x) {
      const std::size_t i = row * static_cast<std::size_t>(camera.width) + static_cast<std::size_t>(x);
      const Estimate e = trace_ray(v, camera_rays.ray_for_pixel(x, static_cast<int>(row)),
                                   o.samples_per_pixel, o.seed, i, o.max_order, &s, o.min_order,
                                   sigma_maj);
      const std::size_t local = i - static_cast<std::size_t>(row_begin) * static_cast<std::size_t>(camera.width);
      img.mean[local] = e.mean;
      img.std_error[local] = e.std_error;
    }
    std::lock_guard<std::mutex> lock(stats_mutex);
    img.stats.paths += s.paths;
    img.stats.real_collisions += s.real_collisions;
    img.stats.tentative_collisions += s.tentative_collisions;
    img.stats.shadow_rays += s.shadow_rays;
  });
  img.stats.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return img;
}

}  // namespace rayint
