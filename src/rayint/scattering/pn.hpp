#pragma once
// The spherical-harmonics (P_N) method for the plane-parallel slab (slab.hpp), the third of the
// four multiple-scattering methods Max (1995, Sec. 7) names, for the azimuthally averaged field.
// P_1 is the diffusion approximation that volume renderers use (diffusion with Marshak's
// boundary condition); docs/multiple-scattering.md, "P_N".
//
// Equations: the spherical-harmonics moment equations of neutron-transport texts (Davison 1957,
// "Neutron Transport Theory"; Case & Zweifel 1967, "Linear Transport Theory"); boundary
// conditions of Marshak (1947, Phys. Rev. 71, 443) and Mark (1944); the even/odd reduction to a
// half-size eigenproblem is the one DISORT uses for discrete ordinates (Stamnes et al. 1988,
// Appl. Opt. 27, 2502). Optical depth t downward from the
// top, direction cosine mu > 0 downward, diffuse intensity expanded as
//   I(t, mu) = sum_{l=0}^{N} a_l(t) P_l(mu),        (N odd)
// phase function p(cos Theta) = 1/(4 pi) sum_l (2l + 1) chi_l P_l(cos Theta), chi_0 = 1 (its
// Legendre coefficients truncated to order N). Projecting mu dI/dt = -I + omega int p I + Q on
// P_k, with mu P_l = ((l+1) P_{l+1} + l P_{l-1})/(2l+1) and a_{N+1} = 0:
//   k/(2k-1) a'_{k-1} + (k+1)/(2k+3) a'_{k+1} = -(1 - omega chi_k) a_k + q_k e^{-t/mu0},   (1)
// q_k = omega (2k+1) chi_k P_k(mu0) / (4 mu0) for the beam (F0 = pi/mu0), 0 for isotropic
// incidence. Written A a' = -B a + q e^{-t/mu0}.
// Homogeneous solutions: (1) splits into the even moments a_e and the odd ones a_o,
// C a_o' = -B_e a_e and D a_e' = -B_o a_o, so a_e'' = kappa^2 a_e with
//   B_e u = kappa^2 (C B_o^{-1} D) u,   a_o = -B_o^{-1} D a_e',                               (2)
// a symmetric-definite generalized eigenproblem after scaling row l by 1/(2l+1) (that scaling
// makes A symmetric), solved by Eigen's GeneralizedSelfAdjointEigenSolver: (N+1)/2 real
// kappa_j^2 >= 0, each giving the pair e^{-kappa t}, e^{-kappa (tau - t)}.
// Particular solution of the beam: (B - A/mu0) p = q (LU).
// Boundary conditions (N+1 of them): Marshak's (default), the half-range moments
//   int_0^1 P_i(mu) I(0, mu) dmu = int_0^1 P_i(mu) I_inc(mu) dmu,  int_0^1 P_i(mu) I(tau, -mu) dmu = 0,
// i = 1, 3, ..., N; or Mark's, I(0, mu_j) = I_inc(mu_j) and I(tau, -mu_j) = 0 at the (N+1)/2
// positive roots mu_j of P_{N+1}. I_inc = 1 for isotropic incidence, 0 for the beam (the direct
// beam is carried separately). Lambertian lower boundary of albedo A (SlabProblem::ground_albedo):
// the bottom's incoming intensity is I_g = (A/pi) F_down(tau), F_down = 2 pi sum_l h_l a_l(tau)
// + pi e^{-tau/mu0} (beam), h_l = int_0^1 mu P_l dmu, so Marshak's bottom rows become
//   int_0^1 P_i(mu) I(tau, -mu) dmu = I_g int_0^1 P_i dmu   (Mark's: I(tau, -mu_j) = I_g),
// still linear in the moments (a rank-one change of the rows); A = 0 is the black ground.
// The source-function integration adds I_g e^{-tau/mu} to the upward intensity at the top.
//
// Regions and thresholds:
// - Scaled exponentials: every decaying mode is normalised at the face it decays away from
//   (e^{-kappa t} and e^{-kappa (tau - t)}), as discrete_ordinates / DISORT do, so no
//   exponential in the boundary system exceeds 1 and thick slabs (tau = 1e4 tested) stay
//   finite and accurate.
// - Conservative scattering (omega chi_0 = 1 exactly): kappa = 0 is a double root; its two
//   solutions are the constant and the ramp t/tau (diffusion's linear profile), exactly. Near
//   it (1 - omega tiny but > 0; kappa ~ sqrt(3 (1 - omega))) the pair e^{+-kappa t} is nearly
//   dependent (PnDiagnostics::rcond falls to 1.6e-5 at 1 - omega = 1e-12), but the answers stay
//   continuous: for 1 - omega = 1e-6 .. 1e-12 at tau = 32 and 1000 (P31, beam mu0 0.5) the
//   change from omega = 1 is linear in 1 - omega, as the physics, down to 3.8e-11 relative, so
//   any loss is below that.
// - Beam resonance: where 1/mu0 equals some kappa_j, (B - A/mu0) is singular. When
//   |kappa_j mu0 - 1| < kPnResonanceGap (1e-6: the particular solution loses about eps/gap,
//   <= 2e-10 beyond it) the solve is the average of mu0 (1 +- 1e-4), an error second order in
//   the shift (the field is smooth in mu0; only the representation is singular): the second
//   difference at a shift of 1e-3 measured 2.9e-7 relative (P1, omega 0.5), so ~3e-9 at 1e-4.
// - Angular intensities by source-function integration: the formal solution integrated on
//   J(t, mu) = omega sum_l chi_l a_l(t) P_l(mu) + omega F0 p0(mu, mu0) e^{-t/mu0}, whose single-
//   scattering part uses the exact (untruncated) azimuthally averaged phase function (the
//   single-scattering correction of Nakajima & Tanaka 1988, JQSRT 40, 51), every term a sum of exponentials or the ramp, integrated in closed
//   form with exponentials <= 1 (attenuated_length, and the series of (1 - e^{-x}(1+x))/x^2 below
//   x = 0.5). The truncated series sum_l a_l P_l(mu) at the faces is reported beside them.
// - Fluxes from the moments: 2 pi int_0^1 mu I(+-mu) dmu = 2 pi sum_l a_l (+-1)^l int_0^1 mu P_l.
// - Orders: odd N in [1, kPnMaxOrder]. Beyond ~N = 127 the largest kappa (~ 1/mu_min of the
//   P_{N+1} roots, growing as N^2) and the Legendre sums lose digits; not needed for the slab
//   benchmarks, which converge well before.
// Accuracy. The error is P_N's truncation: not spectral, algebraic in N, from the jump of the
// angular distribution at mu = 0 at the faces. Measured against the adding-doubling solver
// (64 streams, itself within 5e-8 of the integral equation), as the largest relative error over
// the fluxes and the intensities at mu = 0.1, 0.5, 1 on the DISORT problems 1a-1f, 3a, 3b
// (reports/scattering/pn.md):
//   P31 <= 5.9e-3 (thin slabs tau = 1/32), <= 2.0e-3 (tau = 1..32);
//   P127 <= 4.8e-4 (thin), <= 1.3e-4 (tau >= 1).
// The order is ~2 (tau >= 1) and ~1.5 (thin, grazing beam). The intensities from the series
// alone are off by 0.1-2.6 at the faces even at P127. Rounding: P1 matches its closed form to
// 1.6e-13, and energy (omega = 1, Marshak) is conserved to 7.8e-15. tests/test_scatter_pn.cpp
// holds these figures (bounds in tests/tolerances.hpp, PnTolerances).
#include <vector>

#include "rayint/scattering/slab.hpp"

namespace rayint {

inline constexpr int kPnMaxOrder = 127;
inline constexpr double kPnResonanceGap = 1e-6;

enum class PnBoundary { marshak, mark };

struct PnOptions {
  int order = 15;  // N, odd, 1..kPnMaxOrder
  PnBoundary boundary = PnBoundary::marshak;
  // Tabulated phase function as Legendre coefficients chi_0 = 1, chi_1, ... (any length >= 1,
  // |chi_l| < 1 for l >= 1). Empty: the problem's phase function (isotropic: chi = (1);
  // Henyey-Greenstein: chi_l = g^l; Lambert sphere: phase_legendre_coefficients). The P_N
  // equations use chi_0..chi_N; the exact single-scattering term of the source-function
  // integration uses the whole table.
  std::vector<double> legendre;
};

struct PnDiagnostics {
  int order = 0;
  int modes = 0;                 // (N+1)/2 eigenvalue pairs
  double kappa_min = 0, kappa_max = 0;
  bool conservative = false;     // kappa = 0 handled as constant + ramp
  double resonance_gap = 1;      // min_j |kappa_j mu0 - 1| (beam)
  bool resonance_averaged = false;  // the mu0 (1 +- 1e-4) average ran
  double rcond = 0;              // reciprocal condition estimate of the boundary system (LU)
};

struct PnSolution {
  SlabValues values;  // intensities by source-function integration, fluxes from the moments
  // The truncated series sum_l a_l P_l(mu) at the faces, per mu_up / mu_down (for comparison).
  std::vector<double> series_up_top, series_down_bottom;
  PnDiagnostics diagnostics;
};

// Throws std::invalid_argument for a bad order or table, std::runtime_error if the solve
// produced a non-finite number (never returns one).
PnSolution solve_slab_pn(const SlabProblem& problem, const PnOptions& options = {});

// chi_0..chi_lmax of a phase function: isotropic and Henyey-Greenstein exactly; others by
// 2048-point Gauss-Legendre in cos Theta (the Lambert sphere's square-root edge at +-1 makes
// that algebraic: the same formula with numpy's 2048- and 4096-point rules differs by
// <= 2.6e-13 absolute for l <= 127; chi_1 within 1.5e-13 of -4/9).
std::vector<double> phase_legendre_coefficients(const PhaseFunction& phase, int lmax);

// chi_0..chi_lmax of a tabulated phase function p(cos Theta) per steradian, linear between the
// points (cos_theta strictly increasing from -1 to 1, values >= 0), normalised to chi_0 = 1 (the
// table's own integral 2 pi int p is divided out, so an unnormalised table is accepted).
// Exact for the piecewise-linear p: Gauss-Legendre with (lmax + 3) / 2 points per interval
// integrates the degree-(lmax + 1) integrand exactly, to rounding. Throws std::invalid_argument
// for a table that does not span [-1, 1], is not increasing, has a negative value or integral 0.
std::vector<double> legendre_from_table(const std::vector<double>& cos_theta, const std::vector<double>& value,
                                        int lmax);

}  // namespace rayint
