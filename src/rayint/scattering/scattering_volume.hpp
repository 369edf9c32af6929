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
#include "rayint/grid/voxel_grid.hpp"
#include "rayint/optics/phase.hpp"

namespace rayint {

struct DirectionalLight {
  Vec3 direction = Vec3(0, 0, -1);  // direction of propagation (unit)
  double irradiance = 1.0;
};

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

}  // namespace rayint
