#pragma once
// The zonal method for isotropic multiple scattering (Rushmeier & Torrance 1987; Max 1995,
// Sec. 7): the volume is cut into n^3 cells (zones) of constant extinction sigma_i (the value
// at the cell centre); the power P_i that cell i scatters satisfies the linear system
//   P_i = omega (P_i^light + sum_j F_ij P_j),
// where P_i^light is the light's power extinguished in zone i and F_ij is the fraction of the
// power zone j scatters (isotropically, uniformly over its volume) that zone i extinguishes
// before any other interaction: the volume-to-volume exchange factor
//   F_ij = (1 / V_j) int_{V_j} int_{V_i} sigma_i e^{-tau(x, y)} / (4 pi |x - y|^2) dy dx,
// the self term F_jj included. Both are computed by tracing rays through the zones with exact
// chords (3-D DDA), so that they conserve energy by construction:
//   - P^light: a lattice of `light_rays_per_face`^2 parallel rays per cell face on the faces
//     that see the light, each carrying its share of the incident power; zone i takes
//     T (1 - e^{-sigma_i l_i}) of what reaches it, the rest leaves the box (direct light).
//   - F_.j: `rays_per_cell` rays from uniform points of zone j in uniform directions (stream
//     block_rng(seed, j)), each carrying 1/rays_per_cell, deposited the same way (the self
//     term is the deposit inside zone j). sum_i F_ij + escape_j = 1 exactly for every j.
// Accuracy: the exchange factors are Monte Carlo estimates (relative noise of an entry ~
// 1/sqrt(rays hitting it)); the energy balance incident = direct + escaped + absorbed holds to
// the Gauss-Seidel tolerance (test in tests/test_scatter_volume.cpp, 1e-6). The zone
// discretisation error falls with the grid: measured against the Monte Carlo on a thick
// homogeneous cube and on the cloud in reports/scattering/README.md.
// (Until Dec 2026 the off-diagonal F_ij were the point-to-point estimate
// T A_i (1 - e^{-sigma_i s_i}) / (4 pi r^2) next to a Wigner self term; that pair double-counts
// the power that stays in zone j, so column sums exceeded 1 for optically thick zones and the
// iteration amplified, or diverged, as zones got thicker.)
// Solved by Gauss-Seidel to `tolerance` (relative change), budget `max_iterations` (reported).
// Gathering: single scattering exactly as in discrete_ordinates.hpp (first-pass E with the phase
// toward the eye) plus the multiply scattered part omega sum_j F_ij P_j / (4 pi V_i),
// interpolated between cell centres. Isotropic scattering only: other phase functions are
// refused. The F matrix has n^6 entries: n <= 20.
#include <cstdint>

#include "rayint/scattering/discrete_ordinates.hpp"

namespace rayint {

struct ZonalOptions {
  int grid = 12;
  int max_iterations = 2000;
  double tolerance = 1e-6;
  int rays_per_cell = 1024;      // exchange-factor rays from each zone
  int light_rays_per_face = 4;   // per cell face and axis on the lit faces
  std::uint64_t seed = 1;
  unsigned threads = 0;  // 0: all cores
};

struct ZonalSolution {
  CellGrid cells;
  std::vector<double> sigma_t, irradiance;
  std::vector<double> multiple;  // omega sum_j F_ij P_j / (4 pi V_i): radiance per length
  std::vector<double> power;     // P_i, power scattered by zone i (all orders)
  std::vector<double> escape;    // escape_j = 1 - sum_i F_ij
  // Energy balance (albedo omega): incident = direct + escaped + absorbed, with
  // escaped = sum_j P_j escape_j and absorbed = (1 - omega)/omega sum_j P_j.
  double power_incident = 0, power_direct = 0, power_escaped = 0, power_absorbed = 0;
  int iterations = 0;
  bool converged = false;
  double seconds = 0;
};

ZonalSolution solve_zonal(const ScatteringVolume& volume, const ZonalOptions& options);
double gather_zonal(const ScatteringVolume& volume, const ZonalSolution& solution, const ViewRay& ray,
    bool include_single = true);

}  // namespace rayint
