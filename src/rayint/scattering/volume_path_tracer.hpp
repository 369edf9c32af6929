#pragma once
// Unbiased Monte Carlo volumetric path tracing of a ScatteringVolume (scattering_volume.hpp),
// the reference for the 3-D multiple-scattering approximations.
//
// - Free paths: delta tracking (Woodcock et al. 1965) with the constant majorant
//   sigma_maj = extinction_per_density * max(density) >= sigma_t(x) (trilinear interpolation
//   never exceeds the largest grid value): tentative collisions at rate sigma_maj, accepted as
//   real with probability sigma_t(x)/sigma_maj. Unbiased for any sigma_t <= sigma_maj.
// - Transmittance toward the light: ratio tracking (Novak et al. 2014), the product of
//   (1 - sigma_t/sigma_maj) over tentative collisions: an unbiased estimate of exp(-tau).
// - Next-event estimation at every real collision: throughput * albedo * p(light.direction . -d)
//   * irradiance * T_ratio; the path then continues in a direction sampled from the phase
//   function (throughput *= albedo; Russian roulette below 0.1, unbiased).
// - Orders: a collision's next-event term is light scattered `order` times; `max_order` = 1 gives
//   single scattering with shadows, 0 every order.
// Each pixel (or ray) i draws from block_rng(seed, i), so results are identical for any thread
// count. Every pixel carries its standard error (sample standard deviation / sqrt(spp)).
#include <cstdint>
#include <vector>

#include "rayint/geometry/camera.hpp"
#include "rayint/scattering/estimate.hpp"
#include "rayint/scattering/scattering_volume.hpp"

namespace rayint {

struct PathTracerOptions {
  int samples_per_pixel = 64;
  std::uint64_t seed = 1;
  unsigned threads = 0;  // 0: all cores
  int max_order = 0;  // 0: every order; 1: single scattering with shadows
  int min_order = 0;  // 2: multiple scattering only
};

struct PathTraceStats {
  long long paths = 0, real_collisions = 0, tentative_collisions = 0, shadow_rays = 0;
  double seconds = 0;
};

// One path sample of the radiance along `ray` (origin, unit direction).
// Orders below `min_order` are not scored (2: multiple scattering only; the background counts
// as order 0). `sigma_maj`: the volume's majorant() (a scan of the grid), computed once by the
// caller; negative: computed here.
double trace_path(const ScatteringVolume& volume, const ViewRay& ray, Rng& rng, int max_order,
                  PathTraceStats* stats = nullptr, int min_order = 0, double sigma_maj = -1);

// spp paths along one ray: mean and standard error; stream block_rng(seed, index).
Estimate trace_ray(const ScatteringVolume& volume, const ViewRay& ray, int samples,
                   std::uint64_t seed, std::uint64_t index, int max_order,
                   PathTraceStats* stats = nullptr, int min_order = 0, double sigma_maj = -1);

struct EstimateImage {
  int width = 0, height = 0;
  std::vector<double> mean, std_error;  // row-major, row 0 at the top
  PathTraceStats stats;
};

EstimateImage path_trace_image(const ScatteringVolume& volume, const Camera& camera,
                               const PathTracerOptions& options);

// The rows [row_begin, row_end) of path_trace_image, pixel for pixel the same (each pixel draws
// from its own stream): width = camera.width, height = row_end - row_begin (`--shard`).
EstimateImage path_trace_rows(const ScatteringVolume& volume, const Camera& camera,
                              const PathTracerOptions& options, int row_begin, int row_end);

}  // namespace rayint
