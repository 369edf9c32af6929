// particle.cpp -- Sabella's particle model (Williams & Max 1992, Sec. 2, Eq. 2):
//   I = c int_{t1}^{t2} rho(t) exp(-tau int_t^{t2} rho(u) du) dt,   c = kappa tau,
// light from glowing particles of colour kappa, occluded with Poisson probability
// exp(-tau int rho). The model has ONE transfer function: a single particle density and a
// constant colour per channel. It applies to a case whose three density functions are identical
// and whose three colour functions are each constant; any other case is refused at construction
// (std::invalid_argument "particle: needs a single transfer function: ..."), which `rayint eval`
// reports as the method's failure. (Max, Hanrahan & Crawfis let c and tau be RGB vectors, which
// would also admit densities proportional to each other; not supported here.)
//
// Evaluation: in closed form, as Max, Hanrahan and Crawfis [8] do when int rho can be computed:
// with R(t) = int_t^{t2} rho, d/dt exp(-tau R(t)) = tau rho exp(-tau R(t)), so
//   I = (c/tau) (1 - exp(-tau R_total)) = kappa (1 - exp(-tau R_total)),
// with R_total = sum over pieces of L (rho_far + rho_exit)/2 (exact: rho is linear on a piece)
// and 1 - exp(-x) evaluated as -expm1(-x). tau = 3/(4r) only rescales the density; we take
// tau = 1 so that rho is the continuous model's optical density, and then Eq. 2 coincides with
// the continuous model (Eq. 5) for a single transfer function, as Williams & Max state.
// Background: Eq. 2 assumes a black one; a non-black background is composited behind the cloud
// with the cloud's transparency exp(-tau R_total) (Max 1995: "simple compositing of the colour on
// top of the background"). Transmittance: exp(-tau R_total).
// Diagnostics: stat "pieces".
// Accuracy (tests/test_methods.cpp): equals `exact` within 1e-14 relative on single-TF rays.
#include "rayint/integrators/particle.hpp"

#include <cmath>
#include <stdexcept>

#include "rayint/integrators/factories.hpp"
#include "rayint/model/pieces.hpp"

namespace rayint {
namespace {

constexpr double kTau = 1.0;  // 3/(4 r), absorbed into the density (see the file comment)
const char* const kChannelName[kChannels] = {"r", "g", "b"};

bool same_function(const PiecewiseLinear& a, const PiecewiseLinear& b) {
  return a.scalar == b.scalar && a.value == b.value;
}

}  // namespace

std::string particle_model_mismatch(const TransferFunctions& tf) {
  for (int c = 1; c < kChannels; ++c)
    if (!same_function(tf.density[0], tf.density[c]))
      return std::string("the density of channel ") + kChannelName[c] +
             " differs from that of channel r (the model has one particle density)";
  for (int c = 0; c < kChannels; ++c)
    for (const double v : tf.color[c].value)
      if (v != tf.color[c].value.front())
        return std::string("the colour of channel ") + kChannelName[c] +
               " is not constant (the particles have one colour)";
  return {};
}

ParticleIntegrator::ParticleIntegrator(const TransferFunctions& tf)
    : PieceIntegrator(tf) {
  const std::string why = particle_model_mismatch(tf);
  if (!why.empty())
    throw std::invalid_argument("particle: needs a single transfer function: " + why);
  for (int c = 0; c < kChannels; ++c) kappa_[c] = tf.color[c].value.front();
}

RayResult ParticleIntegrator::integrate_segments(const Ray& ray, Diagnostics* diag) const {
  double R = 0.0;  // int rho along the whole ray
  long n_pieces = 0;
  for (const auto& seg : ray.segments) {
    const std::vector<Piece>& pieces = splitter_.pieces(seg);
    for (const auto& p : pieces) R += 0.5 * (p.rho_far[0] + p.rho_exit[0]) * p.length;
    n_pieces += static_cast<long>(pieces.size());
  }
  const double transparency = std::exp(-kTau * R);
  const double opacity = -std::expm1(-kTau * R);
  RayResult r;
  for (int c = 0; c < kChannels; ++c) {
    const double c_particle = kappa_[c] * kTau;  // Eq. 2's c
    r.intensity[c] = (c_particle / kTau) * opacity + ray.background[c] * transparency;
    r.transmittance[c] = transparency;
  }
  if (diag) diag->add_stat("pieces", static_cast<double>(n_pieces));
  return r;
}

std::unique_ptr<RayIntegrator> make_particle(const MethodSpec&, const TransferFunctions& tf) {
  return std::make_unique<ParticleIntegrator>(tf);
}

}  // namespace rayint
