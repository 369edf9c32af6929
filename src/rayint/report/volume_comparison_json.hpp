#pragma once
// The report of `rayint scatter`: the Monte Carlo references and each discrete-ordinates and
// zonal run against them (scattering/volume_comparison.hpp), as JSON and as PNG images.
#include <nlohmann/json.hpp>
#include <string>

#include "rayint/scattering/scattering_volume.hpp"
#include "rayint/scattering/volume_comparison.hpp"

namespace rayint {

// `scene`: the scene file's path; `points`: grid points per axis the medium was resampled on.
nlohmann::json volume_comparison_json(const std::string& scene, int points, const ScatteringVolume& volume,
                                      const ComparisonOptions& options, const VolumeComparison& comparison);

// monte_carlo_multiple.png, monte_carlo_single_shadows.png and one image per run, into `dir`
// (created if missing).
void write_volume_comparison_images(const VolumeComparison& comparison, const std::string& dir,
                                    double exposure);

}  // namespace rayint
