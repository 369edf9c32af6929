#pragma once
// `rayint scatter` on a scene: its medium as the ScatteringVolume of scattering/scattering_volume.hpp (volume_from_medium) (channel r,
// points^3 grid points, background 0) seen by the scene's camera at width x height, and the
// multiple-scattering methods compared on it (scattering/volume_comparison.hpp).
// Throws std::invalid_argument (one line, naming scene.source) when the scene has no camera or
// differs between r, g and b, and whatever volume_from_medium throws.
#include <functional>
#include <string>

#include "rayint/scattering/volume_comparison.hpp"
#include "rayint/scene/scene.hpp"

namespace rayint {

struct SceneVolumeComparison {
  ScatteringVolume volume;
  VolumeComparison comparison;
};

// The volume and camera compare_volume_methods_on_scene compares the methods on (for `rayint
// scatter --shard I/N`, which runs compare_volume_methods_part on them, and the merge).
struct SceneVolumeSetup {
  ScatteringVolume volume;
  Camera camera;
};
SceneVolumeSetup scene_volume_setup(const Scene& scene, int width, int height, int points);

SceneVolumeComparison compare_volume_methods_on_scene(
    const Scene& scene, int width, int height, int points, const ComparisonOptions& options,
    const std::function<void(const std::string&)>& progress = {});

}  // namespace rayint
