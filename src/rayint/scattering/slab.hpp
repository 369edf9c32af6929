#pragma once
// The plane-parallel slab of the radiative-transfer literature (Chandrasekhar 1950; van de
// Hulst 1980; the DISORT test problems, Stamnes et al. 1988): a homogeneous layer, infinite
// laterally, of optical thickness tau, single-scattering albedo omega and phase function p,
// no emission, over a black (non-reflecting) or Lambertian lower boundary (ground albedo A: the
// ground reflects the fraction A of the total downward flux reaching it, direct beam included,
// as radiance A F / pi in every upward direction), lit from the top either by
// - a collimated beam travelling downward at cosine mu0, whose flux on a horizontal surface is
//   pi (DISORT's fbeam = pi/mu0), or
// - isotropic incident intensity 1 from the whole upper hemisphere (DISORT's fisot = 1).
//
// Detectors: the upward intensity leaving the top and the downward intensity leaving the bottom
// at given cosines mu > 0 (measured from the outward normal of the face), azimuthally averaged
// (for isotropic scattering or mu0 = 1 the field has no azimuth dependence), and the fluxes:
// upward at the top, diffuse and direct downward at the bottom. "Direct" is the unscattered
// beam pi exp(-tau/mu0); with isotropic incidence everything is "diffuse", including the
// unscattered incident light (2 pi E3(tau) of flux, intensity exp(-tau/mu)), as in DISORT.
#include <optional>
#include <vector>

#include "rayint/optics/phase.hpp"

namespace rayint {

enum class SlabSource { beam, isotropic };

struct SlabProblem {
  double tau = 1;     // optical thickness
  double albedo = 1;  // single-scattering albedo omega in [0, 1]
  double ground_albedo = 0;  // Lambertian lower boundary A in [0, 1]; 0: black
  PhaseFunction phase = PhaseFunction::isotropic();
  SlabSource source = SlabSource::beam;
  double mu0 = 1;                   // beam cosine in (0, 1]
  std::vector<double> mu_up;        // detector cosines, reflected intensity at the top
  std::vector<double> mu_down;      // detector cosines, transmitted (diffuse) intensity at the bottom
};

// One solution; every figure in the units of the conventions above.
struct SlabValues {
  double flux_up_top = 0;
  double diffuse_down_bottom = 0;
  double direct_down_bottom = 0;  // 0 for isotropic incidence
  std::vector<double> intensity_up_top;        // per SlabProblem::mu_up
  std::vector<double> intensity_down_bottom;   // per SlabProblem::mu_down
};

// Throws std::invalid_argument naming the field when a problem is out of range.
void validate(const SlabProblem& problem);

// The adding of a Lambertian ground to a homogeneous slab (Chandrasekhar 1950, Sec. 72, the
// "planetary problem"; van de Hulst 1980, Sec. 18.1): exact, given two black-ground solutions of
// the same slab, `black` (the problem's own source, A = 0) and `isotropic` (isotropic incidence
// of intensity 1 from the top, A = 0, detectors mu_up = problem.mu_down and mu_down =
// problem.mu_up). A homogeneous slab is the same seen from below, so `isotropic` is also its
// response to the ground's isotropic radiance. With F the total downward flux of `black` at the
// bottom and s = isotropic.flux_up_top / pi the slab's spherical albedo from below, the ground
// sends up the flux F_g = A F / (1 - A s) as radiance F_g / pi, which adds
//   F_g t to flux_up_top (t = isotropic.diffuse_down_bottom / pi), F_g s to diffuse_down_bottom,
//   F_g / pi * isotropic.intensity_down_bottom to intensity_up_top,
//   F_g / pi * isotropic.intensity_up_top to intensity_down_bottom.
// The ground's own radiance is not part of diffuse_down_bottom (a downward flux).
SlabValues add_lambertian_ground(const SlabProblem& problem, const SlabValues& black,
                                 const SlabValues& isotropic);

}  // namespace rayint
