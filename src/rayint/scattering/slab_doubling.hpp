#pragma once
// Deterministic solution of the plane-parallel slab (slab.hpp) by the adding-doubling method in
// discrete ordinates (van de Hulst 1963; Hansen & Travis 1974, Sec. 3; Wiscombe 1976), for the
// azimuthally averaged (m = 0) field.
//
// Directions: n-point Gauss-Legendre cosines per hemisphere ("double Gauss"), carrying the
// integration weights 2 pi w_j, plus every detector cosine as an extra direction of weight 0:
// such a direction receives light exactly as the quadrature directions do but feeds nothing
// back, so intensities come out at arbitrary cosines without interpolation. The beam is a
// separate column with weight pi/mu0 (its solid-angle integral F0/mu0).
//
// Operators of a homogeneous layer (rows: outgoing direction, columns: incoming, weights in the
// columns; symmetric top/bottom): diffuse reflection R, diffuse transmission Td, direct
// transmission E = diag(exp(-t/mu_i)), and the beam's r, t, e.
// - Start: a layer of thickness t0 = tau / 2^k <= 1e-10 * min(mu) in single scattering
//   (closed forms as in slab_single_scattering.hpp); the neglected double scattering is
//   O(omega t0 / mu_min) relative, below 1e-9.
// - Doubling (two identical layers, Hansen & Travis Eqs. 3.14-3.21), with S = (I - R R)^-1 R R:
//     Y = Td + S (E + Td),   R' = R + (E + Td) R (E + Y),   Td' = E Y + Td (E + Y),
//     D = (I - R R)^-1 (t + e R r),   r' = r + (E + Td)(e r + R D),   t' = e t + (E + Td) D,
//   every term non-negative, so nothing cancels (the diffuse part never comes from
//   subtracting the direct one).
// Fluxes are the Gauss sums 2 pi sum w_j mu_j I(mu_j); the unscattered isotropic incidence
// adds 2 pi E3(tau) (Boost.Math expint).
//
// Accuracy: limited by the quadrature of the internal field. Measured against the DISORT
// benchmark values (6 digits): see tests/test_scatter_slab.cpp and reports/scattering/.
#include "rayint/scattering/slab.hpp"

namespace rayint {

struct DoublingOptions {
  int streams = 64;               // Gauss cosines per hemisphere
  double start_thickness = 1e-8;  // upper bound of the start layer's optical thickness t0
  bool richardson = true;         // extrapolate 2 f(t0) - f(2 t0)
};

struct DoublingDiagnostics {
  int doublings = 0;
  int directions = 0;  // matrix size: streams + extra detector cosines
  double start_thickness = 0;
};

SlabValues solve_slab_doubling(const SlabProblem& problem, const DoublingOptions& options = {},
                               DoublingDiagnostics* diagnostics = nullptr);

}  // namespace rayint
