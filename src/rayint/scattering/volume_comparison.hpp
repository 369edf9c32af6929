#pragma once
// Multiple scattering on a 3-D volume: the Monte Carlo reference image (every order) and single
// scattering with shadows (order 1, the same path tracer truncated), then Max's discrete
// ordinates over a sweep of grid sizes and bin counts and the zonal method over grid sizes, each
// against the reference: per-pixel errors, their mean and RMS, the error of the image's mean
// brightness, and cost. The reference's own noise is reported beside every error (the mean
// per-pixel standard error), so an error at that level means "not resolved".
#include <functional>
#include <string>
#include <vector>

#include "rayint/core/shard.hpp"
#include "rayint/geometry/camera.hpp"
#include "rayint/scattering/volume_path_tracer.hpp"

namespace rayint {

struct ComparisonOptions {
  PathTracerOptions reference;             // spp, seed, threads
  std::vector<int> do_grids{8, 16, 24, 32};
  std::vector<int> do_bins{1, 2, 3, 4};    // bins per cube-face edge: 6 b^2 bins
  std::vector<int> zonal_grids{6, 8, 10};  // isotropic phase only
  std::vector<int> diffusion_grids{};      // P1 / diffusion (diffusion.hpp); none by default
  unsigned threads = 0;  // 0: all cores
};

struct ImageError {
  double mean_abs = 0, rms = 0, max_abs = 0;
  double mean_rel_brightness = 0;  // (mean(image) - mean(reference)) / mean(reference)
};

struct MethodRun {
  std::string method;  // "discrete_ordinates" / "zonal" / "diffusion"
  int grid = 0, bins = 0;  // bins: total number (6 b^2); 0 for zonal
  int iterations = 0;
  bool converged = false;
  double setup_seconds = 0, gather_seconds = 0;
  ImageError error;
  std::vector<double> image;
};

struct VolumeComparison {
  int width = 0, height = 0;
  EstimateImage reference_all, reference_single;  // Monte Carlo: every order; order 1
  double mean_reference_se = 0;                   // mean per-pixel SE of reference_all
  double brightness_all = 0, brightness_single = 0;  // image means
  std::vector<MethodRun> runs;
};

ImageError image_error(const std::vector<double>& image, const std::vector<double>& reference);

VolumeComparison compare_volume_methods(const ScatteringVolume& volume, const Camera& camera,
                                        const ComparisonOptions& options,
                                        const std::function<void(const std::string&)>& progress = {});

// `rayint scatter --shard I/N` (README, "Shards and merge"): shard I traces the Monte Carlo
// reference images' rows shard_range(height, I/N) (every pixel draws from its own stream, so
// they are the single run's pixels) and runs the method runs shard_range(runs, I/N) of the
// run list (discrete ordinates per grid and bins, then zonal per grid; each is deterministic
// and independent of the thread count), keeping their images; errors are computed in the merge.
struct VolumeComparisonPart {
  int width = 0, height = 0;                         // the whole image
  int row_begin = 0, row_end = 0;                    // the reference rows this part traced
  EstimateImage reference_all, reference_single;     // those rows only
  std::vector<std::size_t> run_index;                // positions in the run list
  std::vector<MethodRun> runs;                       // those runs (image, iterations, times; no error)
};
// The number of method runs compare_volume_methods makes.
std::size_t volume_run_count(const ScatteringVolume& volume, const ComparisonOptions& options);
VolumeComparisonPart compare_volume_methods_part(const ScatteringVolume& volume, const Camera& camera,
                                                 const ComparisonOptions& options, const ShardSpec& shard,
                                                 const std::function<void(const std::string&)>& progress = {});
// The comparison from its parts in shard order: the reference rows assembled (path counts and
// seconds summed), then everything the single run derives from them (brightness, mean SE, each
// run's error) by the same code. Throws std::invalid_argument if the parts do not fit together.
VolumeComparison finish_volume_comparison(const std::vector<VolumeComparisonPart>& parts);

}  // namespace rayint
