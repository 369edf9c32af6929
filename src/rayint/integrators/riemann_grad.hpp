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
//
// Jumps (a node scalar stored twice, model/transfer_function.hpp). The discrete sum is piecewise
// differentiable: a sample's values depend on the nodes of the side it lies on, and no sample
// changes side under a small enough change of any input, so there is no crossing term -- the
// derivative in the jump's position x_j is only what it moves in the linear pieces beside it (the
// node-position terms of a sample in [p_{j-1}, x_j] or [x_j, p_{j+1}]; exactly 0 when both sides
// are constant, as for a step). The exact integral has, in addition, the crossing term
// A [rho_b (kappa_b - I*) - rho_a (kappa_a - I*)] dl/dx_j (docs/gradients.md, "Jumps"), which a
// sampled renderer's autodiff never sees: that is the bias of a differentiable renderer with a step.
// A sample exactly ON x_j takes the value PiecewiseLinear's operator() returns there, the left
// one, so its derivative is the left interval's (in the sample's scalar, the left-hand slope; in
// x_j, the derivative for moving x_j up, the side on which the sample stays left of it). The two
// position entries of a jump follow the tie of model/ray_gradient.hpp: the first node's entry
// holds the derivative for moving both nodes together, the second's is 0. No entry is NaN.
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
