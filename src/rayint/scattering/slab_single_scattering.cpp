// Single scattering closed forms of a beam-lit slab; see slab_single_scattering.hpp.
#include "rayint/scattering/slab_single_scattering.hpp"

#include <algorithm>
#include <boost/math/special_functions/expint.hpp>
#include <cmath>
#include <stdexcept>

#include "rayint/core/math.hpp"
#include "rayint/scattering/azimuthal_phase.hpp"
#include "rayint/special/gauss_legendre.hpp"

namespace rayint {

namespace {

double beam_reflected(const SlabProblem& p, double mu0, double mu) {
  return p.albedo * kPi * azimuthal_phase(p.phase, mu, -mu0) / (mu + mu0) *
         -std::expm1(-p.tau * (1 / mu + 1 / mu0));
}

double beam_transmitted(const SlabProblem& p, double mu0, double mu) {
  const double d = std::fabs(1 / mu - 1 / mu0);
  const double m = std::max(mu, mu0);
  const double h = std::exp(-p.tau / m) * attenuated_length(d, p.tau);
  return p.albedo * kPi * azimuthal_phase(p.phase, mu, mu0) * h / (mu * mu0);
}

// Isotropic incidence: int_0^1 2 mu' I_beam(mu; mu') dmu' (I_beam is per flux pi).
template <class F>
double over_incidence(F beam) {
  static const GaussLegendre q = gauss_legendre_01(256);
  double sum = 0;
  for (std::size_t i = 0; i < q.nodes.size(); ++i)
    sum += q.weights[i] * 2 * q.nodes[i] * beam(q.nodes[i]);
  return sum;
}

}  // namespace

double single_scattering_reflected(const SlabProblem& p, double mu) {
  if (p.source == SlabSource::beam) return beam_reflected(p, p.mu0, mu);
  return over_incidence([&](double m0) { return beam_reflected(p, m0, mu); });
}

double single_scattering_transmitted(const SlabProblem& p, double mu) {
  if (p.source == SlabSource::beam) return beam_transmitted(p, p.mu0, mu);
  return over_incidence([&](double m0) { return beam_transmitted(p, m0, mu); });
}

double unscattered_flux_down(const SlabProblem& p) {
  return p.source == SlabSource::isotropic ? 2 * kPi * boost::math::expint(3, p.tau) : 0.0;
}

double unscattered_intensity_down(const SlabProblem& p, double mu) {
  return p.source == SlabSource::isotropic ? std::exp(-p.tau / mu) : 0.0;
}

SlabValues single_scattering(const SlabProblem& p) {
  validate(p);
  SlabValues v;
  for (double mu : p.mu_up) v.intensity_up_top.push_back(single_scattering_reflected(p, mu));
  for (double mu : p.mu_down) v.intensity_down_bottom.push_back(single_scattering_transmitted(p, mu));
  const GaussLegendre q = gauss_legendre_01(64);
  for (std::size_t i = 0; i < q.nodes.size(); ++i) {
    const double mu = q.nodes[i], w = 2 * kPi * q.weights[i] * mu;
    v.flux_up_top += w * single_scattering_reflected(p, mu);
    v.diffuse_down_bottom += w * single_scattering_transmitted(p, mu);
  }
  if (p.source == SlabSource::beam) v.direct_down_bottom = kPi * std::exp(-p.tau / p.mu0);
  return v;
}

}  // namespace rayint
