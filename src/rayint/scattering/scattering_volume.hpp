#pragma once
// A scattering medium on a voxel grid, lit by a directional light: the 3-D setting of Max
// (1995, Sec. 6-7) in which the multiple-scattering methods of this folder are compared.
//
//   sigma_t(x) = extinction_per_density * density(x)   (trilinear VoxelGrid::sample inside the
//                                                       box, 0 outside)
//   sigma_s = albedo * sigma_t, phase function p (optics/phase.hpp), no emission.
// The light is a distant source: parallel light travelling along `light.direction`, irradiance
// `light.irradiance` on a surface perpendicular to it (outside the volume). Rays that leave the
// volume without scattering see `background` (a radiance behind the volume); the environment
// does not illuminate the volume (so all methods solve the same problem).
//
// Radiance seen along a viewing ray (direction d, from the eye), Max Eq. (14)-(16) with the
// multiple-scattering source:
//   L = background T(ray) + int T(t) sigma_s(x) [ E(x) p(light.direction . -d) + int L(x, w) p(w . -d) dw ] dt,
//   E(x) = light.irradiance * exp(-int sigma_t along the ray from x toward the light).
// Truncating the inner integral (max_order = 1) leaves single scattering with shadows.
//
// A volume is one colour channel of a medium and its light (media/medium.hpp, media/light.hpp):
// volume_from_medium() resamples it, so scenes and these methods describe one medium and one
// light; the light is media's DirectionalLight.
#include <vector>

#include "rayint/grid/voxel_grid.hpp"
#include "rayint/media/light.hpp"
#include "rayint/media/medium.hpp"
#include "rayint/optics/phase.hpp"

namespace rayint {

struct ScatteringVolume {
  VoxelGrid density;
  double extinction_per_density = 1.0;
  double albedo = 0.9;
  PhaseFunction phase = PhaseFunction::isotropic();
  DirectionalLight light;
  double background = 0.0;

  double sigma_t(const Vec3& x) const;  // 0 outside the box
  double majorant() const;              // extinction_per_density * max(density), >= sigma_t
  void validate() const;                // std::invalid_argument naming the field
};

// Channel `channel` of `medium` lit by `lights` as a ScatteringVolume: the medium's extinction
// sampled on a VoxelGrid of points^3 points over its (finite) bounds, trilinear in between, with
// extinction_per_density = 1; the albedo, which must be constant over the medium's densities; the
// single directional light (Light::channel); `phase`; background 0 (the multiple-scattering term
// has no background). Resampling is a stated approximation of these methods (a scene's
// single-scattering effect uses the exact medium); its size is part of the reported error of
// each method. Throws std::invalid_argument (one line, "multiple_scattering: ...") for what the
// methods cannot do: unbounded media (slabs: use `rayint slab`), no or several lights, point
// lights, density-dependent albedo, points < 2.
ScatteringVolume volume_from_medium(const Medium& medium, const std::vector<Light>& lights,
                                    const PhaseFunction& phase, int channel, int points);

// True when the three channels give the same volume (same extinction, albedo, light
// irradiance): then one solve serves all three.
bool is_grey(const Medium& medium, const std::vector<Light>& lights);

}  // namespace rayint
