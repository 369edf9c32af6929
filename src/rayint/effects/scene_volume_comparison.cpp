#include "rayint/effects/scene_volume_comparison.hpp"

#include <stdexcept>
#include <utility>

#include "rayint/scattering/scattering_volume.hpp"

namespace rayint {

SceneVolumeSetup scene_volume_setup(const Scene& scene, int width, int height, int points) {
  if (!scene.camera) throw std::invalid_argument(scene.source + ": rayint scatter needs a camera");
  if (!is_grey(scene.medium, scene.lights))
    throw std::invalid_argument(scene.source +
                                ": rayint scatter needs the same extinction, albedo and light in r, g, b");
  SceneVolumeSetup s{volume_from_medium(scene.medium, scene.lights, scene.phase, 0, points), *scene.camera};
  s.camera.width = width;
  s.camera.height = height;
  s.volume.background = 0.0;
  return s;
}

SceneVolumeComparison compare_volume_methods_on_scene(
    const Scene& scene, int width, int height, int points, const ComparisonOptions& options,
    const std::function<void(const std::string&)>& progress) {
  SceneVolumeSetup s = scene_volume_setup(scene, width, height, points);
  SceneVolumeComparison r;
  r.volume = std::move(s.volume);
  r.comparison = compare_volume_methods(r.volume, s.camera, options, progress);
  return r;
}

}  // namespace rayint
