#pragma once
// The absorption and emission terms (Max 1995, Sec. 2-4).
//   absorption: B * T, T = exp(-int sigma_t) over the viewing ray's span (Sec. 2);
//   emission:   int g(t) T(t) dt with absorption, int g(t) dt without (Sec. 3), g = kappa sigma_t.
// Methods:
//   exact      - media that are piecewise linear along rays (homogeneous, voxel grids): the ray's
//                segments go to integrators/exact (Williams & Max Sec. 3.3); emission without
//                absorption is int kappa*rho over each piece, a quadratic, integrated exactly
//                (Simpson's rule). Refused for other media.
//   riemann:n  - n midpoint samples over the span (media/riemann_march.hpp).
// References: reference/ (50-digit Gauss-Kronrod) on piecewise-linear media with absorption;
// otherwise the adaptive quadrature of scene/term_references.hpp.
#include <memory>

#include "rayint/scene/effect.hpp"

namespace rayint {

std::unique_ptr<Effect> make_absorption_effect(const EffectContext& context);
std::unique_ptr<Effect> make_emission_effect(const EffectContext& context);

// int kappa * sigma_t along a piecewise-linear ray (no attenuation): exact per piece.
Rgb emission_only_exact(const TransferFunctions& tf, const Ray& ray);

}  // namespace rayint
