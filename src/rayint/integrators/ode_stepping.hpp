#pragma once
// The controlled stepping loop of the `ode` method (integrators/ode.cpp), shared with the
// polynomial-scalar ODE of cells/poly_ode.cpp: Boost.Odeint's try_step over one interval
// [0, length] of the independent variable, starting with h = length, clipping the last step to
// end exactly at `length`, within a budget of attempted steps per ray. What ode.cpp documents
// about budgets and failure branches holds for every user.
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <limits>

#include "rayint/integrators/eq3_system.hpp"

namespace rayint::ode_stepping {

struct Counters {
  long accepted = 0;
  long rejected = 0;
};

// Advances `x` over [0, length] with `stepper` (a controlled odeint stepper, reset() by the
// caller where the FSAL derivative must not carry over). Returns nullptr on success, or
// "step_budget_exhausted" when accepted + rejected reaches `budget`, or "step_size_collapsed"
// when a step no longer advances s or h becomes 0 or NaN.
template <class Stepper, class System, class State>
const char* integrate_interval(Stepper& stepper, const System& system, State& x, double length,
                               Counters& n, long budget) {
  namespace odeint = boost::numeric::odeint;
  double s = 0.0, h = length;
  while (s < length) {
    if (n.accepted + n.rejected >= budget) return "step_budget_exhausted";
    const bool last = s + h >= length;
    if (last) h = length - s;
    const double s_before = s;
    if (stepper.try_step(system, x, s, h) == odeint::success) {
      ++n.accepted;
      if (last) s = length;
      if (!(s > s_before)) return "step_size_collapsed";  // h below the spacing at s
    } else {
      ++n.rejected;
    }
    if (!(h > 0.0) || !std::isfinite(h)) return "step_size_collapsed";  // NaN error
  }
  return nullptr;
}

// The ray's result after the loop: NaN intensity and transmittance where `failed` (the reason,
// counted as a branch), otherwise eq3::result; stats "steps" (accepted), "rejected_steps" and
// "pieces".
inline RayResult finish(const eq3::State& x, const char* failed, const Counters& n, long pieces,
                        Diagnostics* diag) {
  RayResult r = eq3::result(x);
  if (failed) {
    r.intensity.fill(std::numeric_limits<double>::quiet_NaN());
    r.transmittance.fill(std::numeric_limits<double>::quiet_NaN());
  }
  if (diag) {
    diag->add_stat("steps", static_cast<double>(n.accepted));
    diag->add_stat("rejected_steps", static_cast<double>(n.rejected));
    diag->add_stat("pieces", static_cast<double>(pieces));
    if (failed) diag->count(failed);
  }
  return r;
}

}  // namespace rayint::ode_stepping
