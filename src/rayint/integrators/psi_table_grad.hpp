#pragma once
// The gradient of psi_table (integrators/psi_table.hpp, partial pre-integration after Moreland &
// Angel 2004) with respect to every input of a ray: what automatic differentiation through that
// renderer computes (issue 28, "gradients of the tables"). Per piece and channel, psi_table's
// branches, in the same order and with the same tests:
//   T = 0 (no density):  the piece is skipped (emission 0, transmittance 1) -> every derivative 0
//                        (autodiff through a skipped branch sees constants; the exact derivative
//                        in rho is not 0 there);
//   T <= kThinDepth:     w_exit = clamp(1 - Psi, 0, alpha), alpha = 1 - e^{-T}, w_far = alpha - w_exit:
//                        d w_exit = d(1 - Psi) unclamped, 0 clamped at 0, d alpha clamped at alpha;
//   T > kThinDepth:      Psi clamped to [e^{-T}, 1]: d Psi unclamped, d e^{-T} at the lower
//                        bound, 0 at 1; w_exit = 1 - Psi, w_far = Psi - e^{-T};
// with d Psi from PsiTable::lookup_grad (the slopes of the interpolated table: bilinear for
// lookup=linear, 0 for nearest and floor, which are piecewise constant). Then
// emission = kappa_exit w_exit + kappa_far w_far, transmittance e^{-T}, and the same splitting,
// node interpolation and compositing chain as exact (integrators/ray_gradient_chain.hpp).
// The forward intensity is psi_table's, bit for bit (tests/test_table_grad.cpp, [grad]).
#include "rayint/integrators/psi_table.hpp"
#include "rayint/model/ray_gradient.hpp"

namespace rayint {

RayGradient psi_table_ray_gradient(const TransferFunctions& tf, const Ray& ray, int size, table::Lookup lookup);

}  // namespace rayint
