#pragma once
// Gradients of the sampled renderers -- riemann (integrators/riemann.hpp), nerf and pl_nerf
// (integrators/nerf.hpp) -- with respect to every input of the ray: the exact derivative of
// their discrete sums, i.e. what automatic differentiation through such a renderer computes
// (issue 28), by reverse-mode differentiation of the sample march in double. Compared with
// exact_ray_gradient it measures the error a renderer's gradient carries (studies/grad_study.hpp).
//
// Every step is: optical depth x = h * sum_i w_i rho(s_i), colour sum_i c_i kappa(s_i),
// composited I <- colour (1 - e^{-x}) + e^{-x} I far -> near (the same sum as front to back up to
// rounding), with h = L/n and each sample scalar s_i linear in the segment's end scalars at the
// renderer's own sample positions:
//   riemann   n midpoints per segment, one sample (w = c = 1); correction=exp, no ref_dt, no dt;
//   nerf      n intervals per segment sampled at the midpoint (at=mid) or eye-side end (at=near),
//             one sample; last=inf adds NeRF 2020's far sample with h = 1e10 (no length in it);
//   pl_nerf   n intervals between n + 1 samples, w = 1/2, 1/2; colour the mean (color=mid) or the
//             eye-side sample (color=near).
// A sample exactly on a transfer-function node takes the interval toward its segment's interior
// (toward the eye for an interior sample; to the right of the node on a constant-scalar segment,
// the kink convention of model/ray_gradient.hpp); otherwise every derivative is two-sided.
#include "rayint/integrators/nerf.hpp"
#include "rayint/integrators/riemann.hpp"
#include "rayint/model/ray_gradient.hpp"

namespace rayint {

// Throws std::invalid_argument for options it does not support (dt mode, ref_dt, linear).
RayGradient riemann_ray_gradient(const TransferFunctions& tf, const Ray& ray, const RiemannOptions& options);
// nerf (piecewise_linear false) or pl_nerf (true).
RayGradient nerf_ray_gradient(const TransferFunctions& tf, const Ray& ray, const NerfOptions& options,
                              bool piecewise_linear);

}  // namespace rayint
