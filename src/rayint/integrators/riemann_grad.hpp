#pragma once
// The gradient of the Riemann sum (integrators/riemann.hpp) with respect to every input of the
// ray: the exact derivative of the discrete sum -- what automatic differentiation through a
// Riemann front-to-back or back-to-front renderer computes (issue 28) -- by reverse-mode
// differentiation of the march, in double. Compared with exact_ray_gradient it measures the
// error a renderer's gradient carries (studies/grad_study.hpp).
//
// Supported: n samples per segment at the midpoints (the default `riemann:n=N`), opacity
// correction=exp without ref_dt (alpha = 1 - exp(-rho h)); either order (they sum the same terms).
// A sample exactly on a transfer-function node takes the interval to its right (the kink
// convention of model/ray_gradient.hpp); otherwise every derivative is two-sided.
#include "rayint/integrators/riemann.hpp"
#include "rayint/model/ray_gradient.hpp"

namespace rayint {

// Throws std::invalid_argument for options it does not support (dt mode, ref_dt, linear).
RayGradient riemann_ray_gradient(const TransferFunctions& tf, const Ray& ray, const RiemannOptions& options);

}  // namespace rayint
