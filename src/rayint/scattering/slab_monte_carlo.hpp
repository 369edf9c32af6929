#pragma once
// Unbiased Monte Carlo solution of the plane-parallel slab (slab.hpp): photons enter at the
// top (the beam at mu0, or isotropic incidence sampled cosine-weighted, mu = sqrt(u)), fly
// exponential free paths in optical depth (the slab is homogeneous, so delta tracking with the
// majorant equal to the extinction is plain free-path sampling), scatter with the phase
// function's own sampling, and keep albedo as a weight (survival biasing) with Russian roulette
// below weight 0.1 (survival probability w/0.1, weight 0.1 on survival: unbiased).
//
// Estimators, each per photon, multiplied by the incident flux pi:
// - fluxes: the weight escaping at the top (flux_up_top) and the bottom (diffuse_down_bottom;
//   unscattered escapes count as direct for the beam, diffuse for isotropic incidence);
//   unbiased.
// - intensities at detector cosine mu: a next-event (collision point) estimator toward the
//   detector direction at every collision at depth t,
//       w * omega * p0(mu_photon, -+mu) * exp(-t/mu) / mu   (top; exp(-(tau - t)/mu) at the bottom),
//   where p0 is the azimuthally averaged phase function (azimuthal_phase.hpp). Its expectation
//   is exactly the azimuthally averaged exitant intensity (the formal solution of the transfer
//   equation with the collision density as source), so the estimator has no angular-bin bias;
//   it is bounded by omega max(p) / mu, so its variance is finite. For isotropic incidence the
//   unscattered intensity exp(-tau/mu) is added at the bottom (deterministic, zero variance).
// Lambertian ground (SlabProblem::ground_albedo A > 0): a photon reaching the bottom is scored
// there (downward flux) and continues upward from the ground with weight A w in a cosine-weighted
// direction; the ground's radiance A w / pi is scored at the top detectors through exp(-tau/mu).
// A ground reflection is not a scattering (the order does not change); only with every order
// (max_order = min_order = 0), so not in the split estimator.
// `max_order` truncates the series at that many scatterings (1: single scattering, which must
// match slab_single_scattering.hpp); `min_order` drops the lower orders from every score
// (2: multiple scattering only, to be added to the exact single scattering; see
// solve_slab_monte_carlo_split).
//
// Reproducibility: photons are split into blocks of kBlockPhotons; block b draws from
// block_rng(seed, b) and block sums are reduced over a fixed pairwise tree (sample_blocks.hpp),
// so results are identical for any thread count and any split into shards (tested).
#include <cstdint>
#include <functional>

#include "rayint/scattering/estimate.hpp"
#include "rayint/scattering/sample_blocks.hpp"
#include "rayint/scattering/slab.hpp"

namespace rayint {

struct SlabMonteCarloOptions {
  long long photons = 1000000;  // rounded up to whole blocks
  std::uint64_t seed = 1;
  unsigned threads = 0;  // 0: all cores
  int max_order = 0;  // 0: no truncation
  int min_order = 0;  // score only light scattered at least this often (0: everything)
  // Shards (core/shard.hpp, sample_blocks.hpp): null runs every block; else record this shard's
  // blocks, or replay a merge. Not owned.
  MonteCarloShardIO* shard_io = nullptr;
};

struct SlabEstimates {
  Estimate flux_up_top, diffuse_down_bottom, direct_down_bottom;
  std::vector<Estimate> intensity_up_top, intensity_down_bottom;
  long long photons = 0;
  long long collisions = 0;
  double seconds = 0;  // wall time
};

inline constexpr long long kBlockPhotons = 4096;

SlabEstimates solve_slab_monte_carlo(const SlabProblem& problem,
                                     const SlabMonteCarloOptions& options = {});

// Orders 0 and 1 exact (slab_single_scattering.hpp), orders >= 2 by Monte Carlo (min_order = 2):
// still unbiased, and the standard error is that of the multiple-scattering part alone, which
// for thin or absorbing slabs is a small fraction of the total (the exact first order is a
// control variate). The estimator the benchmark uses.
SlabEstimates solve_slab_monte_carlo_split(const SlabProblem& problem,
                                           const SlabMonteCarloOptions& options = {});

}  // namespace rayint
