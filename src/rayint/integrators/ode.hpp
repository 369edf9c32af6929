#pragma once
// Eq. 3 of Williams & Max (1992), dI/dt = -rho I + kappa rho, integrated by the adaptive
// Dormand-Prince 5(4) pair of Boost.Odeint with error control rtol/atol. See ode.cpp.
#include <vector>

#include "rayint/integrators/integrator.hpp"
#include "rayint/model/pieces.hpp"

namespace rayint {

struct OdeOptions {
  double rtol = 1e-8;
  double atol = 2.2250738585072014e-308;  // DBL_MIN: control is relative (see ode.cpp)
};
// Reads rtol (in [1e-15, 1)) and atol (> 0); throws std::invalid_argument otherwise.
OdeOptions ode_options(const MethodSpec& spec);

// Attempted steps per ray before `ode` gives up and returns NaN (2^20: a piece of optical depth
// 1e6 needs ~3e5 steps of the explicit method, whose stability bounds rho h below ~3.3).
inline constexpr long kOdeStepBudget = 1L << 20;

class OdeIntegrator final : public RayIntegrator {
 public:
  OdeIntegrator(const TransferFunctions& tf, const OdeOptions& options);
  RayResult integrate_segments(const Ray& ray, Diagnostics* diag) const override;

 private:
  PieceSplitter splitter_;
  OdeOptions opt_;
};

}  // namespace rayint
