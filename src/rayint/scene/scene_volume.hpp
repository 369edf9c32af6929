#pragma once
// From a scene (scene/scene.hpp) to the ScatteringVolume the multiple-scattering methods solve:
// the scene medium's extinction of one colour channel sampled on a VoxelGrid of points^3 points
// over its (finite) bounds, trilinear in between, with extinction_per_density = 1; the albedo,
// which must be constant over the medium's densities; the scene's single directional light; its
// phase function; background 0 (the multiple-scattering term has no background).
// Resampling is a stated approximation of these methods (the single-scattering effect of the
// scene uses the exact medium); its size is part of the reported error of each method.
// Throws std::invalid_argument (one line) for what the methods cannot do: unbounded media
// (slabs: use `rayint slab`), no or several lights, point lights, density-dependent albedo.
#include "rayint/scattering/scattering_volume.hpp"
#include "rayint/scene/scene.hpp"

namespace rayint {

ScatteringVolume volume_from_scene(const Scene& scene, int channel, int points);

// True when the three channels give the same volume (same extinction, albedo, light):
// then one solve serves all three.
bool scene_is_grey(const Scene& scene);

}  // namespace rayint
