// Monte Carlo solution of the plane-parallel slab; see slab_monte_carlo.hpp.
#include "rayint/scattering/slab_monte_carlo.hpp"

#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "rayint/core/math.hpp"
#include "rayint/scattering/azimuthal_phase.hpp"
#include "rayint/scattering/sample_blocks.hpp"
#include "rayint/scattering/slab_single_scattering.hpp"

namespace rayint {

namespace {
constexpr double kRouletteWeight = 0.1;
}  // namespace

SlabEstimates solve_slab_monte_carlo(const SlabProblem& p, const SlabMonteCarloOptions& o) {
  validate(p);
  if (o.photons < 1) throw std::invalid_argument("slab Monte Carlo: photons must be >= 1");
  if (o.max_order < 0) throw std::invalid_argument("slab Monte Carlo: max_order must be >= 0");
  if (o.min_order < 0) throw std::invalid_argument("slab Monte Carlo: min_order must be >= 0");
  if (p.ground_albedo > 0 && (o.max_order != 0 || o.min_order != 0))
    throw std::invalid_argument("slab Monte Carlo: a ground albedo needs every order (no max_order, min_order)");
  const int min_order = o.min_order;
  const bool beam = p.source == SlabSource::beam;
  const std::size_t n_up = p.mu_up.size(), n_down = p.mu_down.size();
  // Score layout: flux up, diffuse down, direct down, intensities up, intensities down.
  const std::size_t n_scores = 3 + n_up + n_down;
  const std::size_t blocks =
      static_cast<std::size_t>((o.photons + kBlockPhotons - 1) / kBlockPhotons);
  std::atomic<long long> block_collisions_total{0};
  const double omega = p.albedo, tau = p.tau, ground = p.ground_albedo;

  auto run_block = [&](std::size_t b) {
    Rng rng = block_rng(o.seed, b);
    ScoreSums sums(n_scores);
    std::vector<double> score(n_scores);
    long long block_collisions = 0;
    for (long long ph = 0; ph < kBlockPhotons; ++ph) {
      std::fill(score.begin(), score.end(), 0.0);
      // z axis points down (into the slab); depth t in [0, tau].
      Vec3 dir;
      if (beam) {
        dir = Vec3(std::sqrt(std::max(0.0, 1 - p.mu0 * p.mu0)), 0, p.mu0);
      } else {
        const double mu = std::sqrt(rng.uniform_open0());  // cosine-weighted
        const double phi = 2 * kPi * rng.uniform();
        const double s = std::sqrt(std::max(0.0, 1 - mu * mu));
        dir = Vec3(s * std::cos(phi), s * std::sin(phi), mu);
      }
      double t = 0, w = 1;
      int order = 0;
      bool last_flight = false;  // max_order reached: fly to the next event, score only escapes
      for (;;) {
        const double step = -std::log(rng.uniform_open0());
        const double t_next = t + step * dir.z();
        if (t_next >= tau) {
          if (order >= min_order) score[(order == 0 && beam) ? 2 : 1] += w;
          if (ground <= 0) break;
          // Lambertian ground: the weight A w leaves upward, cosine-weighted. Its radiance
          // A w / pi reaches the top detector through exp(-tau/mu) (next event, exact in mean).
          w *= ground;
          for (std::size_t d = 0; d < n_up; ++d) score[3 + d] += w / kPi * std::exp(-tau / p.mu_up[d]);
          if (w < kRouletteWeight) {
            if (w <= 0 || rng.uniform() * kRouletteWeight >= w) break;
            w = kRouletteWeight;
          }
          const double mu = std::sqrt(rng.uniform_open0());
          const double phi = 2 * kPi * rng.uniform();
          const double sn = std::sqrt(std::max(0.0, 1 - mu * mu));
          dir = Vec3(sn * std::cos(phi), sn * std::sin(phi), -mu);
          t = tau;
          continue;
        }
        if (t_next <= 0) {
          if (order >= min_order) score[0] += w;
          break;
        }
        if (last_flight) break;  // a collision beyond max_order scores nothing
        t = t_next;
        ++order;
        ++block_collisions;
        const double nu = dir.z();
        for (std::size_t d = 0; d < n_up && order >= min_order; ++d) {
          const double mu = p.mu_up[d];
          score[3 + d] += w * omega * azimuthal_phase(p.phase, nu, -mu) * std::exp(-t / mu) / mu;
        }
        for (std::size_t d = 0; d < n_down && order >= min_order; ++d) {
          const double mu = p.mu_down[d];
          score[3 + n_up + d] +=
              w * omega * azimuthal_phase(p.phase, nu, mu) * std::exp(-(tau - t) / mu) / mu;
        }
        w *= omega;
        if (o.max_order > 0 && order >= o.max_order) last_flight = true;
        if (w < kRouletteWeight) {
          if (w <= 0 || rng.uniform() * kRouletteWeight >= w) break;
          w = kRouletteWeight;
        }
        const double u1 = rng.uniform(), u2 = rng.uniform();
        dir = p.phase.sample(dir, u1, u2);
      }
      sums.add(score);
    }
    block_collisions_total += block_collisions;
    return sums;
  };

  long long collisions = 0;
  double seconds = 0;
  const ScoreSums total = solve_sample_blocks(blocks, n_scores, o.threads, o.shard_io, run_block,
                                              block_collisions_total, collisions, seconds);

  SlabEstimates e;
  e.photons = total.samples();
  e.collisions = collisions;
  e.seconds = seconds;
  e.flux_up_top = total.estimate(0, kPi);
  e.diffuse_down_bottom = total.estimate(1, kPi);
  e.direct_down_bottom = total.estimate(2, kPi);
  if (!beam) {
    // Unscattered isotropic incidence is diffuse by convention; score 2 is always 0 here.
    e.direct_down_bottom = Estimate{0, 0, e.photons};
  }
  for (std::size_t d = 0; d < n_up; ++d) e.intensity_up_top.push_back(total.estimate(3 + d, kPi));
  for (std::size_t d = 0; d < n_down; ++d) {
    Estimate est = total.estimate(3 + n_up + d, kPi);
    if (!beam && min_order == 0) est.mean += std::exp(-tau / p.mu_down[d]);
    e.intensity_down_bottom.push_back(est);
  }
  return e;
}

SlabEstimates solve_slab_monte_carlo_split(const SlabProblem& p, const SlabMonteCarloOptions& o) {
  SlabMonteCarloOptions higher = o;
  higher.min_order = 2;
  if (o.max_order == 1) throw std::invalid_argument("slab Monte Carlo split: max_order must not be 1");
  if (p.ground_albedo > 0) throw std::invalid_argument("slab Monte Carlo split: black ground only");
  SlabEstimates e = solve_slab_monte_carlo(p, higher);
  const SlabValues s = single_scattering(p);
  e.flux_up_top.mean += s.flux_up_top;
  e.diffuse_down_bottom.mean += s.diffuse_down_bottom + unscattered_flux_down(p);
  e.direct_down_bottom = Estimate{s.direct_down_bottom, 0, e.photons};
  for (std::size_t d = 0; d < p.mu_up.size(); ++d) e.intensity_up_top[d].mean += s.intensity_up_top[d];
  for (std::size_t d = 0; d < p.mu_down.size(); ++d)
    e.intensity_down_bottom[d].mean +=
        s.intensity_down_bottom[d] + unscattered_intensity_down(p, p.mu_down[d]);
  return e;
}

}  // namespace rayint
