#include "rayint/effects/scene_volume_comparison.hpp"

#include <stdexcept>

#include "rayint/scattering/scattering_volume.hpp"

namespace rayint {

SceneVolumeComparison compare_volume_methods_on_scene(
    const Scene& scene, int width, int height, int points, const ComparisonOptions& options,
    const std::function<void(const std::string&)>& progress) {
  if (!scene.camera) throw std::invalid_argument(scene.source + ": rayint scatter needs a camera");
  if (!is_grey(scene.medium, scene.lights))
    throw std::invalid_argument(scene.source +
                                ": rayint scatter needs the same extinction, albedo and light in r, g, b");
  Camera cam = *scene.camera;
  cam.width = width;
  cam.height = height;
  SceneVolumeComparison r;
  r.volume = volume_from_medium(scene.medium, scene.lights, scene.phase, 0, points);
  r.volume.background = 0.0;
  r.comparison = compare_volume_methods(r.volume, cam, options, progress);
  return r;
}

}  // namespace rayint
