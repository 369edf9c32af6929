#pragma once
// The zonal method for isotropic multiple scattering (Rushmeier & Torrance 1987; Max 1995,
// Sec. 7): the volume is cut into n^3 cells (zones) of constant properties; the power P_i
// that cell i scatters satisfies the linear system
//   P_i = omega (P_i^light + sum_j F_ji P_j),
// where P_i^light is the light's power extinguished in cell i (first-pass irradiance at the
// centre, cross-section A_i(d) (1 - e^{-sigma_i s_i(d)}) along the light direction d), and F_ji is the
// fraction of the power cell j scatters isotropically that cell i extinguishes:
//   F_ji = T_ji A_i(d) (1 - e^{-sigma_i s_i(d)}) / (4 pi r^2),  d = (c_i - c_j)/r,
// with A_i(d) = sum_a |d_a| h_b h_c the projected area of the cell, s_i(d) = V_i / A_i(d) its
// mean chord along d, and T_ji the transmittance between the two cells (optical depth by the
// midpoint rule with cell-centre sigma_t, minus the half chords inside both end cells). The
// self term uses Wigner's rational escape probability, F_ii = 1 - 1/(1 + sigma_i 4V/S).
// Solved by Gauss-Seidel to `tolerance` (relative change), budget `max_iterations` (reported).
// Gathering: single scattering exactly as in discrete_ordinates.hpp (first-pass E with the phase
// toward the eye) plus the multiply scattered part (P_i - omega P_i^light) / (4 pi V_i),
// interpolated between cell centres. Isotropic scattering only: other phase functions are
// refused. The F matrix has n^6 entries: n <= 20.
#include "rayint/scattering/discrete_ordinates.hpp"

namespace rayint {

struct ZonalOptions {
  int grid = 12;
  int max_iterations = 500;
  double tolerance = 1e-6;
  int threads = 0;
};

struct ZonalSolution {
  CellGrid cells;
  std::vector<double> sigma_t, irradiance;
  std::vector<double> multiple;  // (P_i - omega P_i^light) / (4 pi V_i): radiance per length
  int iterations = 0;
  bool converged = false;
  double seconds = 0;
};

ZonalSolution solve_zonal(const ScatteringVolume& volume, const ZonalOptions& options);
double gather_zonal(const ScatteringVolume& volume, const ZonalSolution& solution, const ViewRay& ray,
    bool include_single = true);

}  // namespace rayint
