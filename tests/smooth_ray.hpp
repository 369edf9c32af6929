#pragma once
// The smooth case the method tests share (test_methods.cpp, test_nerf.cpp): per-channel
// densities and colours linear on [0, 1], every segment strictly inside (0, 1) -- no breakpoint
// inside any segment, so rho and kappa are linear on each segment and the integrand is smooth
// there; the scalar turns at segment joins (kinks only). Optical depth ~2.3 (r), ~1.9 (g), ~2.0
// (b); non-black background. And the error measure they report against it.
#include <algorithm>

#include "rayint/integrators/integrator.hpp"
#include "rayint/metrics/error_metrics.hpp"
#include "transfer_builders.hpp"

namespace rayint::test {

struct SmoothCase {
  TransferFunctions tf;
  Ray ray;
  SmoothCase() {
    tf.density = {line(0, 0.3, 1, 1.5), line(0, 1.2, 1, 0.4), line(0, 0.8, 1, 0.9)};
    tf.color = {line(0, 0.9, 1, 0.2), line(0, 0.3, 1, 1.1), line(0, 0.6, 1, 0.6)};
    ray.background = {0.2, 0.5, 0.1};
    ray.segments = {{0.7, 0.1, 0.6}, {0.5, 0.6, 0.95}, {0.9, 0.95, 0.3}, {0.4, 0.3, 0.35}};
  }
};

// Largest relative error over the three channels of the intensity.
inline double max_rel(const RayResult& r, const RayResult& ref) {
  double e = 0.0;
  for (int c = 0; c < kChannels; ++c) e = std::max(e, relative_error(r.intensity[c], ref.intensity[c]));
  return e;
}

}  // namespace rayint::test
