#pragma once
// Eq. 3 of Williams & Max (1992) by the classic fourth-order Runge-Kutta method with a fixed
// number of steps per segment, as the paper suggests. See rk4.cpp.
#include "rayint/integrators/integrator.hpp"

namespace rayint {

// At most this many steps per ray (2^24, ~2 s); beyond it integrate() throws std::runtime_error.
inline constexpr double kRk4StepBudget = 16777216.0;

class Rk4Integrator final : public SamplingIntegrator {
 public:
  Rk4Integrator(const TransferFunctions& tf, int steps_per_segment);
  RayResult integrate_segments(const Ray& ray, Diagnostics* diag) const override;

 private:
  int n_;
};

}  // namespace rayint
