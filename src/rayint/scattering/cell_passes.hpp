#pragma once
// The passes that discrete ordinates and the zonal method share (discrete_ordinates.hpp):
//   first_pass: the cells over the volume's box, sigma_t at their centres and the light's
//     irradiance there (steps 1-2);
//   gather_march: the final gathering (step 5), the midpoint rule along the viewing ray with steps
//     of at most h/4 (h the smallest cell size), trilinear sigma_t, and the in-scattered source
//     J(x, sigma_t) that each method computes from its solution; gather_along, the same from a
//     viewing ray for the methods whose J needs only the sun's phase value (diffusion, zonal).
#include <algorithm>
#include <cmath>

#include "rayint/core/math.hpp"
#include "rayint/scattering/discrete_ordinates.hpp"

namespace rayint {

// Sets sol.cells (grid cells per axis), sol.sigma_t and sol.irradiance.
template <class Solution>
void first_pass(const ScatteringVolume& v, int grid, unsigned threads, Solution& sol) {
  sol.cells = make_cell_grid(v, grid);
  sol.sigma_t = centre_sigma_t(v, sol.cells);
  sol.irradiance = first_pass_irradiance(v, sol.cells, threads);
}

// L = sum_i T_i J_i a_i + T background, a_i = int_0^dt e^{-sigma_i t} dt, over the span `iv` of the
// ray from `origin` along the unit direction `d`.
template <class Source>
double gather_march(const ScatteringVolume& v, const CellGrid& g, const Vec3& origin, const Vec3& d,
                    const RaySpan& iv, double background, Source&& source) {
  const double step = 0.25 * g.h.minCoeff();  // h/4: measured effect in discrete_ordinates.hpp
  const double len = iv.t_exit - iv.t_enter;
  const int steps = std::max(1, static_cast<int>(std::ceil(len / step)));
  const double dt = len / steps;
  double L = 0, T = 1;
  for (int s = 0; s < steps; ++s) {
    const Vec3 x = origin + (iv.t_enter + (s + 0.5) * dt) * d;
    const double sigma = v.sigma_t(x);
    if (sigma <= 0) continue;
    const double J = source(x, sigma);
    const double a1 = attenuated_length(sigma, dt);
    L += T * J * a1;
    T *= 1 - sigma * a1;
  }
  return L + T * background;
}

// The final gathering of a method whose source needs only the sun's phase value (diffusion,
// zonal): the ray's unit direction d and its span through the volume's box, the background it
// sees (0 without the single-scattered part, include_single false) and p_sun = p(light . -d)
// toward the eye (0 without it); source(x, sigma, d, p_sun) is the method's J. A ray that misses
// the box sees the background.
template <class Source>
double gather_along(const ScatteringVolume& v, const CellGrid& g, const ViewRay& ray, bool include_single,
                    Source&& source) {
  const Vec3 d = ray.direction.normalized();
  const RaySpan iv = v.density.clip(ViewRay{ray.origin, d});
  const double background = include_single ? v.background : 0.0;
  if (!iv.hit) return background;
  const double p_sun = include_single ? v.phase.eval(v.light.direction.dot(-d)) : 0.0;
  return gather_march(v, g, ray.origin, d, iv, background,
                      [&](const Vec3& x, double sigma) { return source(x, sigma, d, p_sun); });
}

}  // namespace rayint
