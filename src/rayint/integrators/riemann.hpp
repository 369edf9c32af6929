#pragma once
// Riemann-sum compositing of the ray integral (Max 1995, Sec. "calculation methods"; Williams &
// Max 1992 Eq. 6 applied per sample): midpoint samples, back-to-front or front-to-back, with the
// per-sample opacity exact, tabulated for a reference step (with or without the correction to
// the actual step), or linearised. See riemann.cpp for the definitions and measured orders.
#include <cmath>

#include "rayint/integrators/integrator.hpp"

namespace rayint {

enum class CompositingOrder {
  back_to_front,  // "btf": I <- kappa*alpha + (1 - alpha) I, starting from the background
  front_to_back,  // "ftb": C += T kappa*alpha, T *= (1 - alpha), starting at the eye
};

enum class OpacityRule {
  exact,      // correction=exp, no ref_dt: alpha = 1 - exp(-rho dt)
  corrected,  // correction=exp with ref_dt: alpha = 1 - (1 - alpha_ref)^(dt/ref_dt)
  none,       // correction=none with ref_dt: alpha = alpha_ref = 1 - exp(-rho ref_dt), unchanged
  linear,     // correction=linear: alpha = min(1, rho dt)  (Eq. 8 per sample)
};

struct RiemannOptions {
  int n = 64;       // samples per segment (used when dt == 0)
  double dt = 0.0;  // > 0: fixed step along the whole ray instead of n per segment
  CompositingOrder order = CompositingOrder::back_to_front;
  OpacityRule opacity = OpacityRule::exact;
  double ref_dt = 0.0;  // reference step of the opacity table (corrected / none)
};

// Reads n, dt, order (btf|ftb), correction (exp|none|linear) and ref_dt from the spec;
// throws std::invalid_argument for values out of range or combinations that mean nothing.
RiemannOptions riemann_options(const MethodSpec& spec);

// One step of optical depth x >= 0: opacity alpha = 1 - e^{-x} and transparency e^{-x}, with one
// transcendental call: the smaller of the two is computed directly (expm1 below ln 2, exp above)
// and the larger as 1 minus it, which is then >= 1/2 and so carries at most ~1 ulp relative
// error. Every midpoint Riemann march composites with it: this integrator's exact and corrected
// opacities, and the march through a 3-D medium (media/riemann_march.hpp).
struct StepOpacity {
  double alpha;
  double transparency;
};

inline StepOpacity step_opacity(double x) {
  constexpr double kLn2 = 0.69314718055994530942;
  if (x < kLn2) {
    const double alpha = -std::expm1(-x);
    return {alpha, 1.0 - alpha};
  }
  const double transparency = std::exp(-x);
  return {1.0 - transparency, transparency};
}

// At most this many samples per ray (2^26, ~3 s at ~45 ns per sample); beyond it integrate()
// throws std::runtime_error instead of running for minutes.
inline constexpr double kRiemannSampleBudget = 67108864.0;

class RiemannIntegrator final : public SamplingIntegrator {
 public:
  RiemannIntegrator(const TransferFunctions& tf, const RiemannOptions& options);
  RayResult integrate_segments(const Ray& ray, Diagnostics* diag) const override;

 private:
  RiemannOptions opt_;
};

}  // namespace rayint
