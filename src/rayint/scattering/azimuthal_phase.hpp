#pragma once
// The azimuthally averaged phase function of a plane-parallel medium,
//   p0(mu_a, mu_b) = 1/(2 pi) int_0^{2 pi} p(mu_a mu_b + sqrt((1 - mu_a^2)(1 - mu_b^2)) cos phi) dphi,
// per steradian, for signed direction cosines mu_a, mu_b against the same axis. It is the
// m = 0 Fourier term of the phase function (Chandrasekhar 1950, Sec. 48), all that the
// azimuth-independent fields of the slab benchmarks need.
//
// Methods by phase function:
// - isotropic: 1/(4 pi).
// - Henyey-Greenstein: closed form with the complete elliptic integral of the second kind,
//   int_0^pi (A - B cos phi)^(-3/2) dphi = 2 E(k) / ((A - B) sqrt(A + B)), k^2 = 2B/(A + B),
//   A = 1 + g^2 - 2 g mu_a mu_b, B = 2 g sqrt((1 - mu_a^2)(1 - mu_b^2)); E(k) by the AGM
//   (complete_elliptic_e), faster than the library forms, which the Monte Carlo's
//   next-event estimator calls at every collision and detector.
// - Lambert sphere: periodic trapezoid rule in phi with 512 nodes (its p has a square-root edge at
//   Theta = 0 and pi, so the error is algebraic where mu_a = +-mu_b; measured <= 1e-7 relative
//   against 8192 nodes).
// tests/test_scatter_slab.cpp checks HG and isotropic against the trapezoid rule with 4096
// nodes to 1e-12 relative.
#include "rayint/optics/phase.hpp"

namespace rayint {

double azimuthal_phase(const PhaseFunction& phase, double mu_a, double mu_b);

// The same average by the periodic trapezoid rule with `nodes` points (any phase function).
// Complete elliptic integral of the second kind E(k), modulus k in [0, 1].
double complete_elliptic_e(double k);

double azimuthal_phase_trapezoid(const PhaseFunction& phase, double mu_a, double mu_b, int nodes);

}  // namespace rayint
