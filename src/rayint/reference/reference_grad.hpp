#pragma once
// The 50-digit reference gradient of a ray's intensity (issue 28), independent of the analytic
// derivatives of integrators/exact_grad.*: fourth-order finite differences, taken in
// cpp_bin_float_50, of the 50-digit reference integral (reference_detail::integrate_piece, Gauss-
// Kronrod quadrature of Eq. 4), with the ray and the transfer functions themselves held and
// perturbed in 50 digits (so a step of 1e-20 relative is exact, far below a double's ulp).
//
// Error: the stencil's truncation is O(h^4) ~ 1e-80 where I is smooth and O(h) ~ 1e-20 where only
// its first derivative is continuous (a segment end on a node); rounding of the 50-digit sums,
// ~1e-50 / h ~ 1e-30 relative. `noise` reports |D4 - D2| (the fourth- and second-order stencils
// on the same points), which bounds both. See docs/gradients.md.
//
// Stencils never step across a point where I is not smooth (steps capped at 1/16 of the distance
// to it) and are one-sided where the parameter sits on one: forward for a node value within two
// steps of 0 (values stay >= 0); for a segment scalar on a node, into the segment (forward for a
// constant-scalar segment: the kink convention of model/ray_gradient.hpp); for a node position on
// another node or a segment end, backward (the convention again for a constant segment there).
//
// Jumps (model/ray_gradient.hpp): piece ends take one-sided limits in 50 digits; a jump's
// position entry differences the integral with both of its nodes moved (the second node's entry
// is 0, the tie); the entries that do not exist (a segment end on a jump, density and colour
// jumping together) are NaN, decided from the inputs. A node whose interval [scalar[k-1],
// scalar[k+1]] the ray's scalars never reach has derivative exactly 0 and is not differenced.
#include "rayint/model/ray_gradient.hpp"

namespace rayint {

struct ReferenceGradientOptions {
  double step = 1e-20;   // relative step (of max(|x|, 1)), capped at 1/16 of the distance
                         // to the nearest other node of the same function
  unsigned threads = 1;  // parameters in parallel (core/parallel.hpp; 0: all cores)
};

struct ReferenceGradient {
  RayGradient gradient;  // the derivatives, rounded to double; gradient.intensity is I in 50 digits
  Rgb noise{};           // per channel: max |D4 - D2| over the entries (an error estimate)
  int evaluations = 0;   // 50-digit segment integrations done
};

// Throws std::invalid_argument for the inputs reference_ray refuses.
ReferenceGradient reference_gradient(const TransferFunctions& tf, const Ray& ray,
                                     const ReferenceGradientOptions& options = {});

}  // namespace rayint
