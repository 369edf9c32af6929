#pragma once
// Single scattering from a homogeneous slab lit by a collimated beam (flux F0 = pi on a
// horizontal surface, cosine mu0), the closed forms every multiple-scattering solver must
// reduce to when only one scattering is counted (Chandrasekhar 1950, Sec. 13; Liou 2002,
// Eq. 6.1.x). With p0 the azimuthally averaged phase function (azimuthal_phase.hpp) and the
// source J(t) = omega p0 (F0/mu0) exp(-t/mu0) at vertical optical depth t:
//   reflected   I(mu) = omega F0 p0(mu, -mu0) / (mu + mu0) * (1 - exp(-tau (1/mu + 1/mu0))),
//   transmitted I(mu) = omega F0 p0(mu, mu0) / (mu - mu0) * (exp(-tau/mu) - exp(-tau/mu0)),
//              mu = mu0: omega F0 p0(mu0, mu0) tau / mu0^2 * exp(-tau/mu0).
// The transmitted form is evaluated as (F0/(mu mu0)) omega p0 h with
//   h = int_0^tau exp(-t/mu0 - (tau - t)/mu) dt = exp(-tau/m) (-expm1(-|1/mu - 1/mu0| tau)) / |1/mu - 1/mu0|,
// m = max(mu, mu0), which has no cancellation or overflow for any mu, mu0 in (0, 1] and tau
// (h -> tau exp(-tau/mu0) continuously as mu -> mu0; tests check the limit to 1e-12).
#include "rayint/scattering/slab.hpp"

namespace rayint {

// Isotropic incidence of intensity 1: the beam forms per unit flux, integrated over the incident
// hemisphere, I(mu) = int_0^1 2 mu' I_beam(mu; mu') dmu', by 256-point Gauss-Legendre (the
// integrand is smooth; exp(-tau/mu') vanishes with all its derivatives at mu' = 0); measured
// change from 128 to 256 points <= 1e-10 relative on the benchmark problems.
//
// The first-order values of a slab: intensities at the detector cosines and the scattered
// fluxes (fluxes by 64-point Gauss-Legendre quadrature of the closed-form intensities over each
// hemisphere). Orders 0 are not included, except direct_down_bottom = pi exp(-tau/mu0) (the
// beam); unscattered_flux / unscattered_intensity give isotropic incidence's order 0.
SlabValues single_scattering(const SlabProblem& problem);
double unscattered_flux_down(const SlabProblem& problem);                // 2 pi E3(tau) or 0
double unscattered_intensity_down(const SlabProblem& problem, double mu); // exp(-tau/mu) or 0

double single_scattering_reflected(const SlabProblem& problem, double mu);
double single_scattering_transmitted(const SlabProblem& problem, double mu);

}  // namespace rayint
