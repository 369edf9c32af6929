#pragma once
// Bounds of the P_N Lambertian ground, the tabulated phase functions and diffusion on voxel grids
// (tests/test_scatter_pn_ground.cpp, test_scatter_pn_table.cpp, test_scatter_diffusion.cpp): each
// the measured figure it comes from, rounded up. Kept apart from tolerances.hpp so that tuning
// them rebuilds three test files, not the suite.

namespace rayint::test {

struct PnGroundTolerances {
  // Lambertian ground against the doubling with the ground added: largest relative error over
  // fluxes and intensities at mu 0.1, 0.5, 1; A 0.1..1, omega 0.5 and 1, beam (mu0 0.5) and
  // isotropic light, HG 0.75 at tau 1. Measured (Dec 2026): thin (tau 1/32) P31 5.44e-3, P127
  // 4.26e-4; tau 1 and 32 P31 4.51e-3, P127 3.00e-4 (as on a black ground, reports/scattering/pn.md).
  static constexpr double p31_thin = 7e-3, p127_thin = 5.5e-4;
  static constexpr double p31 = 6e-3, p127 = 4e-4;
  // Mark's conditions with the ground, P127, tau 1, omega 0.9, A 0.6: measured 1.35e-4 (beam
  // mu0 0.5), 6.0e-5 (isotropic light).
  static constexpr double mark_p127 = 1.8e-4;
  // omega = 1, A = 1: flux up = pi. Measured <= 1.3e-15 (N 1, 7, 31; tau 1/32, 1, 100).
  static constexpr double energy_rel = 1e-14;
  // legendre_from_table on exactly piecewise-linear tables (closed-form moments): measured
  // <= 2.7e-16 (linear p on 1 and 3 intervals, l <= 40; the V table, l <= 3).
  static constexpr double table_exact_abs = 2e-15;
  // HG 0.75 tabulated at 257, 1025, 4097 cosines against the analytic HG, P31, tau 2: measured
  // 2.27e-4, 1.42e-5, 8.86e-7 (second order in the spacing, the linear interpolation's error).
  static constexpr double hg_table_rel[3] = {3e-4, 2e-5, 1.2e-6};
};

// Diffusion (P1) on voxel grids against the Monte Carlo, multiple scattering only, 10 x 10
// pixels, grid 24 (tests/test_scatter_diffusion.cpp). Measured (Dec 2026; the MC seeded, so the
// same on every run): cube of optical size 10, albedo 0.99: brightness -0.077 (isotropic),
// -0.110 (HG 0.5), mean |pixel| / mean 0.112, 0.139, with the MC's brightness SE 0.014, 0.018
// (256 paths per pixel); optical size 1, albedo 0.5: brightness -0.149, mean |pixel| 0.166, SE
// 0.014 (1024 paths). Each bound is the worst measured value plus 4 SE of the MC.
struct DiffusionTolerances {
  static constexpr double mc_rel_se_max = 0.025;  // the reference must be this sharp
  static constexpr double thick_brightness_rel = 0.18, thick_mean_abs_rel = 0.21;
  static constexpr double thin_brightness_rel = 0.21;
  // The thin cube's brightness error over the thick cube's: measured 1.95.
  static constexpr double thin_over_thick = 1.5;
  // A 20 x 20 x 1 box against the slab's P1 at its centre (grid 64, omega 0.9): measured
  // 8.9e-5 (tau 1), 5.4e-4 (tau 4): the 3-D solve is the slab's P1 to its discretisation.
  static constexpr double slab_p1_rel = 7e-4;
  // Power balance of the finite-volume solve (thick cube, grid 12): measured 2.5e-13.
  static constexpr double balance_rel = 1e-11;
};

}  // namespace rayint::test
