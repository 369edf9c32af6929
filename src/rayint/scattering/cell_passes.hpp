#pragma once
// The passes that discrete ordinates and the zonal method share (discrete_ordinates.hpp):
//   first_pass: the cells over the volume's box, sigma_t at their centres and the light's
//     irradiance there (steps 1-2);
//   gather_march: the final gathering (step 5), the midpoint rule along the viewing ray with steps
//     of at most h/4 (h the smallest cell size), trilinear sigma_t, and the in-scattered source
//     J(x, sigma_t) that each method computes from its solution.
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

}  // namespace rayint
