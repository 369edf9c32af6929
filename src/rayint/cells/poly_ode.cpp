// poly_ode.cpp -- Eq. 3 of Williams & Max (1992), dI/ds = rho(f(s)) (kappa(f(s)) - I) per
// channel, along segments whose scalar f is a polynomial in s (distance from the far end),
// integrated from the background to the eye.
//
// Pieces: each segment is split at the critical points of f and at every crossing of a
// transfer-function breakpoint (poly_split_points: model/polynomial.hpp in double, TOMS 748 on
// the monotone stretches). On a piece f is monotone and between two breakpoints, so rho(f(s))
// and kappa(f(s)) are polynomials in s and the 5(4) error estimate is valid (across a kink it
// is not: the step control would see an O(h^2) local error it cannot model).
// Right-hand side: rho and kappa through PiecewiseLinear::limit at f(s), toward the piece's middle
// scalar; inside a piece that is the piece's linear branch, and at a piece end on a jump the
// value inside the piece (at a piece end rounding may select the neighbouring branch, which
// agrees there to rounding where the transfer functions are continuous).
// Stepping, budgets, failures and state (I_r, I_g, I_b, tau_r, tau_g, tau_b): exactly as the
// `ode` method (integrators/ode.cpp, shared loop integrators/ode_stepping.hpp); transmittance
// exp(-tau) at the end.
// Accuracy (tests [cells]): against the polynomial reference on quadratic to quartic scalars
// crossing breakpoints, the relative error stays below rtol (measured in the test's log).
#include "rayint/cells/poly_ode.hpp"

#include <boost/numeric/odeint.hpp>

#include "rayint/integrators/ode_stepping.hpp"
#include "rayint/model/polynomial.hpp"

namespace rayint {

namespace {

namespace odeint = boost::numeric::odeint;
using State = eq3::State;

}  // namespace

std::vector<double> poly_split_points(const PolySegment& segment,
                                      const std::vector<double>& breakpoints) {
  if (segment.coeffs.empty()) return {0.0, segment.length};
  return poly::split_points(segment.coeffs, breakpoints, segment.length);
}

PolyOdeIntegrator::PolyOdeIntegrator(const TransferFunctions& tf, const OdeOptions& options)
    : tf_(&tf), breakpoints_(tf.breakpoints()), opt_(options) {}

RayResult PolyOdeIntegrator::integrate(const PolyRay& ray, Diagnostics* diag) const {
  auto stepper =
      odeint::make_controlled(opt_.atol, opt_.rtol, odeint::runge_kutta_dopri5<State>());
  State x = eq3::start(ray.background);
  ode_stepping::Counters counts;
  long n_pieces = 0;
  const char* failed = nullptr;
  for (const PolySegment& seg : ray.segments) {
    if (!(seg.length > 0.0)) continue;
    const std::vector<double> knots = poly_split_points(seg, breakpoints_);
    for (std::size_t k = 0; k + 1 < knots.size() && !failed; ++k) {
      const double L = knots[k + 1] - knots[k];
      if (!(L > 0.0)) continue;
      ++n_pieces;
      // s from the piece's start, knots[k] in the segment's s
      // Values at a piece end that sits on a transfer-function jump: the limit from inside the
      // piece (f is monotone on it, so toward its middle scalar).
      const auto system = eq3::scalar_system(
          *tf_, [&seg, s0 = knots[k]](double s) { return seg(s0 + s); }, seg(knots[k] + 0.5 * L));
      stepper.reset();
      failed = ode_stepping::integrate_interval(stepper, system, x, L, counts, kOdeStepBudget);
    }
    if (failed) break;
  }
  return ode_stepping::finish(x, failed, counts, n_pieces, diag);
}

}  // namespace rayint
