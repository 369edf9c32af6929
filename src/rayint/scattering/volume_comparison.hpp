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

#include "rayint/geometry/camera.hpp"
#include "rayint/scattering/volume_path_tracer.hpp"

namespace rayint {

struct ComparisonOptions {
  PathTracerOptions reference;             // spp, seed, threads
  std::vector<int> do_grids{8, 16, 24, 32};
  std::vector<int> do_bins{1, 2, 3, 4};    // bins per cube-face edge: 6 b^2 bins
  std::vector<int> zonal_grids{6, 8, 10};  // isotropic phase only
  unsigned threads = 0;  // 0: all cores
};

struct ImageError {
  double mean_abs = 0, rms = 0, max_abs = 0;
  double mean_rel_brightness = 0;  // (mean(image) - mean(reference)) / mean(reference)
};

struct MethodRun {
  std::string method;  // "discrete_ordinates" / "zonal"
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

}  // namespace rayint
