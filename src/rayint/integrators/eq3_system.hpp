#pragma once
// Eq. 3 of Williams & Max (1992), dI/ds = rho (kappa - I), as the first-order system that the
// Boost.Odeint methods step (integrators/ode.cpp, integrators/rk4.cpp, cells/poly_ode.cpp).
// State: x = (I_r, I_g, I_b, tau_r, tau_g, tau_b) with d tau/ds = rho, s running from the far
// end toward the eye; the transmittance is exp(-tau) from the integrated optical depth.
#include <array>
#include <cmath>
#include <utility>

#include "rayint/integrators/integrator.hpp"

namespace rayint::eq3 {

using State = std::array<double, 2 * kChannels>;

// The right-hand side at one s; `rho_kappa(c)` gives channel c's (rho, kappa) there.
template <class RhoKappa>
void derivative(const State& x, State& dxdt, const RhoKappa& rho_kappa) {
  for (int c = 0; c < kChannels; ++c) {
    const auto [rho, kappa] = rho_kappa(c);
    dxdt[c] = rho * (kappa - x[c]);
    dxdt[kChannels + c] = rho;
  }
}

// The system where rho and kappa are the transfer functions of a scalar given along s by
// `scalar_at(s)` (linear along a segment for rk4, a polynomial for cells/poly_ode.cpp).
// `toward`: a scalar inside the piece being stepped (cells/poly_ode.cpp: its middle); at a
// transfer-function jump the value is then the limit from that side (a piece that starts on a
// jump takes the value inside it). NaN: the value at the scalar itself (operator(), the left
// value at a jump), for steppers that ignore breakpoints (rk4).
template <class ScalarAt>
struct ScalarSystem {
  const TransferFunctions* tf;
  ScalarAt scalar_at;
  double toward;
  void operator()(const State& x, State& dxdt, double s) const {
    const double f = scalar_at(s);
    const bool above = f < toward;  // false for a NaN toward: limit(f, false) is operator()
    derivative(x, dxdt, [&](int c) { return std::pair{tf->density[c].limit(f, above), tf->color[c].limit(f, above)}; });
  }
};
template <class ScalarAt>
ScalarSystem<ScalarAt> scalar_system(const TransferFunctions& tf, ScalarAt scalar_at,
                                     double toward = std::nan("")) {
  return {&tf, scalar_at, toward};
}

// The state at the start of a ray: the background, no optical depth yet.
inline State start(const Rgb& background) {
  State x{};
  for (int c = 0; c < kChannels; ++c) x[c] = background[c];
  return x;
}

// The ray's result from the state at the eye: I as integrated, T = exp(-tau).
inline RayResult result(const State& x) {
  RayResult r;
  for (int c = 0; c < kChannels; ++c) {
    r.intensity[c] = x[c];
    r.transmittance[c] = std::exp(-x[kChannels + c]);
  }
  return r;
}

}  // namespace rayint::eq3
