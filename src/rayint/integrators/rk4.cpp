// rk4.cpp -- Williams & Max (1992) Eq. 3, dI/dt = rho (kappa - I) for r, g, b, by the classic
// fourth-order Runge-Kutta method (boost::numeric::odeint::runge_kutta4), which the paper names
// as one way to solve it ("by the fourth-order Runge-Kutta method").
//
// Steps: n equal steps per segment (param n, default 16), ignoring transfer-function breakpoints
// inside the segment, as a renderer stepping through cells does; the right-hand side evaluates
// the transfer functions at the scalar, linear along the segment. On segments without interior
// breakpoints the right-hand side is smooth and the method is fourth order; a breakpoint inside
// a step is a kink in rho(t) and leaves an O(h^2) local error there (then the global order is 2).
// State: (I_r, I_g, I_b, tau_r, tau_g, tau_b) with d tau/dt = rho; the transmittance is
// exp(-tau) from the integrated optical depth. (RK4 on tau is Simpson's rule on rho.)
// Stability: explicit, so a step with rho h > 2.785 amplifies instead of damping: optically
// thick segments with too few steps give huge or non-finite results (returned as they come).
// Budget: a ray needing more than kRk4StepBudget steps is refused (std::runtime_error).
// Diagnostics: stats "steps" and "rhs_evaluations" (4 per step).
// Accuracy (tests/test_methods.cpp): fitted orders 4.07, 4.04, 4.02 for n = 8..32 on a smooth ray;
// n = 16 per segment (64 steps, 256 right-hand sides) gives 2.6e-8 relative there. On constant
// kappa, rho the error stays below the bound N z^5/120 max(kappa, I0), z = rho h.
#include "rayint/integrators/rk4.hpp"

#include <boost/numeric/odeint/stepper/runge_kutta4.hpp>
#include <cmath>
#include <stdexcept>
#include <string>

#include "rayint/integrators/eq3_system.hpp"
#include "rayint/integrators/factories.hpp"

namespace rayint {
namespace {

namespace odeint = boost::numeric::odeint;
using State = eq3::State;

}  // namespace

Rk4Integrator::Rk4Integrator(const TransferFunctions& tf, int steps_per_segment)
    : SamplingIntegrator(tf), n_(steps_per_segment) {}

RayResult Rk4Integrator::integrate_segments(const Ray& ray, Diagnostics* diag) const {
  odeint::runge_kutta4<State> stepper;
  State x = eq3::start(ray.background);
  double planned = 0.0;
  for (const auto& seg : ray.segments)
    if (seg.length > 0.0) planned += n_;
  if (!(planned <= kRk4StepBudget))
    throw std::runtime_error("rk4: n=" + std::to_string(n_) + " needs " + std::to_string(planned) +
                             " steps on this ray, over the budget of " +
                             std::to_string(kRk4StepBudget));
  long steps = 0;
  for (std::size_t i = 0; i < ray.segments.size(); ++i) {
    const Segment& seg = ray.segments[i];
    if (!(seg.length > 0.0)) continue;
    const double h = seg.length / n_;
    // Eq. 3 along the segment, s the distance from its far end, the scalar linear in s (plus
    // q s (s - L) on a quadratic chord, model/ray.hpp; q = 0 adds nothing).
    const double slope = (seg.scalar_exit - seg.scalar_far) / seg.length;
    const double q = i < ray.quadratic.size() ? ray.quadratic[i] : 0.0;
    const auto system = eq3::scalar_system(
        tf_, [scalar_far = seg.scalar_far, slope, q, L = seg.length](double s) {
          return scalar_far + slope * s + q * s * (s - L);
        });
    for (int j = 0; j < n_; ++j) stepper.do_step(system, x, j * h, h);
    steps += n_;
  }
  const RayResult r = eq3::result(x);
  if (diag) {
    diag->add_stat("steps", static_cast<double>(steps));
    diag->add_stat("rhs_evaluations", 4.0 * static_cast<double>(steps));
  }
  return r;
}

std::unique_ptr<RayIntegrator> make_rk4(const MethodSpec& spec, const TransferFunctions& tf) {
  return std::make_unique<Rk4Integrator>(tf, spec.integer("n"));  // range: registry.cpp
}

}  // namespace rayint
