// ode.cpp -- Williams & Max (1992) Eq. 3, dI/dt = -rho(t) I + kappa(t) rho(t) for r, g, b,
// integrated from the far end (I = background) to the eye by the adaptive Dormand-Prince 5(4)
// pair (boost::numeric::odeint::runge_kutta_dopri5, controlled by make_controlled(atol, rtol)).
//
// State: x = (I_r, I_g, I_b, tau_r, tau_g, tau_b), with d tau/dt = rho; the transmittance is
// computed exactly from the integrated optical depth, exp(-tau), at the end. The right-hand side
// is written rho (kappa - I), which is Eq. 3.
// Intervals: the ray is integrated piece by piece (segments split at every transfer-function
// breakpoint, model/pieces.hpp), with rho and kappa linear in the distance on each piece, so the
// right-hand side is a polynomial on every integration interval and the 5(4) error estimate is
// valid; the state carries over from piece to piece, the FSAL derivative does not (reset).
// Steps: our own loop over try_step (what integrate_adaptive does inside; integrators/
// ode_stepping.hpp, shared with cells/poly_ode.cpp) so that a budget can
// be kept: each piece starts with h = its length, the last step is clipped to end exactly on the
// piece end, and at most kOdeStepBudget attempted steps per ray are made. Running out of budget,
// or a step size that stops advancing, returns NaN intensity and transmittance (counted as the
// branch "step_budget_exhausted" or "step_size_collapsed") rather than a silently wrong number.
// Error control: odeint's default checker, |err_i| <= atol + rtol (|x_i| + h |x_i'|), max over
// the six components.
// Defaults rtol = 1e-8, atol = DBL_MIN: the control is relative down to the smallest normal
// double (atol = 1e-14 would stop resolving a background dimmed below 1e-14 -- e^{-700} came out
// as 1e-15); atol must be > 0, or the error ratio is 0/0 where I = 0 and rho = 0.
// Stiffness: the method is explicit, so an optically thick piece costs ~(rho L)/3 steps
// whatever the tolerance (stability, not accuracy, limits h): tau = 1e6 takes ~3e5 steps.
// Diagnostics: stats "steps" (accepted), "rejected_steps", "pieces"; the failure branches above.
// Accuracy (tests/test_methods.cpp): on the smooth ray the global relative error is 0.05..0.27
// rtol for rtol in [1e-13, 1e-3] (test bound: <= rtol), 30 steps at rtol = 1e-8; constant kappa
// and rho within rtol; rho = 0 returns the background exactly.
#include "rayint/integrators/ode.hpp"

#include <boost/numeric/odeint.hpp>
#include <stdexcept>
#include <utility>

#include "rayint/integrators/factories.hpp"
#include "rayint/integrators/ode_stepping.hpp"
#include "rayint/model/pieces.hpp"

namespace rayint {
namespace {

namespace odeint = boost::numeric::odeint;
using State = eq3::State;

// Eq. 3 on one piece; s is the distance from the piece's far end, rho and kappa linear in s.
struct PieceSystem {
  const Piece* piece;
  double inv_length;
  void operator()(const State& x, State& dxdt, double s) const {
    const double f = s * inv_length;  // 0 at the far end, 1 at the exit
    eq3::derivative(x, dxdt, [&](int c) {
      return std::pair{piece->rho_far[c] + f * (piece->rho_exit[c] - piece->rho_far[c]),
                       piece->kappa_far[c] + f * (piece->kappa_exit[c] - piece->kappa_far[c])};
    });
  }
};

}  // namespace

OdeOptions ode_options(const MethodSpec& spec) {
  OdeOptions o;
  // Ranges in the method table (registry.cpp): rtol in [1e-15, 1) (below ~1e-15 the error
  // estimate is rounding noise and the step size collapses); atol > 0 (atol = 0 would make the
  // error ratio 0/0 where I = 0 and rho = 0).
  o.rtol = spec.number("rtol");
  o.atol = spec.number("atol");
  return o;
}

OdeIntegrator::OdeIntegrator(const TransferFunctions& tf, const OdeOptions& options)
    : splitter_(tf), opt_(options) {}

RayResult OdeIntegrator::integrate_segments(const Ray& ray, Diagnostics* diag) const {
  auto stepper = odeint::make_controlled(opt_.atol, opt_.rtol, odeint::runge_kutta_dopri5<State>());
  State x = eq3::start(ray.background);
  ode_stepping::Counters counts;
  long n_pieces = 0;
  const char* failed = nullptr;  // why the integration stopped early, if it did
  for (const auto& seg : ray.segments) {
    const std::vector<Piece>& pieces = splitter_.pieces(seg);
    for (const auto& piece : pieces) {
      ++n_pieces;
      const double L = piece.length;
      const PieceSystem system{&piece, 1.0 / L};
      stepper.reset();  // the stored first-same-as-last derivative belongs to the last piece
      failed = ode_stepping::integrate_interval(stepper, system, x, L, counts, kOdeStepBudget);
      if (failed) break;
    }
    if (failed) break;
  }
  return ode_stepping::finish(x, failed, counts, n_pieces, diag);
}

std::unique_ptr<RayIntegrator> make_ode(const MethodSpec& spec, const TransferFunctions& tf) {
  return std::make_unique<OdeIntegrator>(tf, ode_options(spec));
}

}  // namespace rayint
