#pragma once
// Set-ups the scattering tests share: a forward-scattering slab problem (the P_N tests) and the
// oblique view of the unit cube (the volume tests: Monte Carlo against diffusion, discrete
// ordinates and zonal).
#include <vector>

#include "rayint/geometry/camera.hpp"
#include "rayint/scattering/slab.hpp"
#include "rayint/scattering/scattering_volume.hpp"

namespace rayint::test {

// tau 2, albedo 0.95, sun at mu0 0.6, Henyey-Greenstein with asymmetry g, read at mu 0.2 and 1
// up and down.
inline SlabProblem hg_slab(double g) {
  SlabProblem p;
  p.tau = 2;
  p.albedo = 0.95;
  p.mu0 = 0.6;
  p.phase = PhaseFunction::henyey_greenstein(g);
  p.mu_up = {0.2, 1.0};
  p.mu_down = {0.2, 1.0};
  return p;
}

// A homogeneous unit cube [0, 1]^3 of extinction sigma, lit by a sun from `light` (its direction of
// travel, normalized here) with irradiance `irradiance`.
inline ScatteringVolume unit_cube(double sigma, double albedo, PhaseFunction phase, const Vec3& light,
                                  double irradiance) {
  ScatteringVolume v;
  v.density = VoxelGrid({2, 2, 2}, Vec3::Zero(), Vec3::Ones(), std::vector<double>(8, 1.0));
  v.extinction_per_density = sigma;
  v.albedo = albedo;
  v.phase = phase;
  v.light.direction = light.normalized();
  v.light.irradiance = irradiance;
  return v;
}

// The unit cube [0, 1]^3 seen obliquely from above: from (0.5, 2.5, 3.5) at its centre, fov 30
// degrees, pixels x pixels.
inline Camera oblique_cube_view(int pixels) {
  Camera cam;
  cam.position = Vec3(0.5, 2.5, 3.5);
  cam.look_at = Vec3(0.5, 0.5, 0.5);
  cam.fov_deg = 30;
  cam.width = pixels;
  cam.height = pixels;
  return cam;
}

}  // namespace rayint::test
