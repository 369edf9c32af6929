#pragma once
// Riemann-sum compositing along a ray through a 3-D medium (Max 1995, "calculation methods"): n
// equal steps h = (t_exit - t_enter)/n over the ray's span inside the bounds, one midpoint sample
// per step, the medium and the source held constant over the step. Front to back, the step's
// contribution is T_i * S_i * alpha_i / sigma_i (= S_i h phi(sigma_i h), phi(x) = (1 - e^{-x})/x:
// Williams & Max 1992 Eq. 6 applied per step, exact for a constant step) and T_{i+1} = T_i
// (1 - alpha_i), alpha_i = 1 - e^{-sigma_i h} from step_opacity (integrators/riemann.hpp): the
// same step as the `riemann` integrator's front-to-back sum, one transcendental per step and
// channel. Without absorption every step contributes S_i h.
// Error: O(h^2) for a smooth medium (midpoint rule), O(h) where the medium has a kink or jump
// inside a step; measured per scene against the references (reports/figures/README.md).
#include <cmath>

#include "rayint/integrators/riemann.hpp"
#include "rayint/media/medium.hpp"

namespace rayint {

// source(p, optics) -> Rgb source per unit length at p.
template <class Source>
Rgb riemann_march(const Medium& medium, const ViewRay& ray, int n, bool attenuate, Source&& source,
                  long long& samples) {
  Rgb sum{};
  const RaySpan span = medium.bounds().clip(ray);
  if (!span.hit || n < 1) return sum;
  const double h = span.length() / n;
  Rgb T{1.0, 1.0, 1.0};
  for (int i = 0; i < n; ++i) {
    const Vec3 p = ray.origin + ray.direction * (span.t_enter + (i + 0.5) * h);
    const Optics o = medium.optics_at_density(medium.density(p));
    const Rgb S = source(p, o);
    for (int c = 0; c < kChannels; ++c) {
      if (attenuate) {
        const double x = o.sigma_t[c] * h;
        const StepOpacity step = step_opacity(x);
        const double weight = x > 0.0 ? step.alpha / o.sigma_t[c] : h;
        sum[c] += T[c] * S[c] * weight;
        T[c] *= step.transparency;
      } else {
        sum[c] += S[c] * h;
      }
    }
  }
  samples += n;
  return sum;
}

// The optical depth sum sigma_i h over n midpoint samples of t in [t_begin, t_end] (t_end >
// t_begin, n >= 1): the depth of the viewing ray (riemann_transmittance) and of shadow rays
// (scene/shadowing.hpp).
inline Rgb riemann_optical_depth(const Medium& medium, const ViewRay& ray, double t_begin,
                                 double t_end, int n) {
  const double h = (t_end - t_begin) / n;
  Rgb tau{};
  for (int i = 0; i < n; ++i) {
    const Rgb s = medium.extinction(ray.origin + ray.direction * (t_begin + (i + 0.5) * h));
    for (int c = 0; c < kChannels; ++c) tau[c] += s[c] * h;
  }
  return tau;
}

// exp(-sum sigma_i h) over the midpoint samples of the ray's span inside the bounds.
inline Rgb riemann_transmittance(const Medium& medium, const ViewRay& ray, int n, long long& samples) {
  const RaySpan span = medium.bounds().clip(ray);
  if (!span.hit || n < 1) return {1.0, 1.0, 1.0};
  const Rgb tau = riemann_optical_depth(medium, ray, span.t_enter, span.t_exit, n);
  samples += n;
  return {std::exp(-tau[0]), std::exp(-tau[1]), std::exp(-tau[2])};
}

}  // namespace rayint
