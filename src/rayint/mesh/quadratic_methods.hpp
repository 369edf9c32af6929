#pragma once
// The methods of `rayint eval`, `check`, `bench` and `gate` on rays that may hold quadratic chords
// (straight-edged quadratic tetrahedra, mesh/quadratic_tets.hpp; model/ray.hpp, Ray::quadratic).
//
// - "exact" (either path): on a ray with a quadratic chord, the polynomial path of
//   grid/trilinear_integral.hpp on the same ray as polynomials (to_poly_ray): each chord is split
//   at the quadratic's extremum and at every transfer-function breakpoint it crosses, rho and
//   kappa are then quadratics in s, the optical depth their exact antiderivative and the emission
//   Gauss-Legendre on panels of optical depth <= 0.5 (exact to rounding; measured against the
//   50-digit polynomial reference in tests/test_tet10_eval.cpp, [tet10eval]). A ray of linear
//   segments goes to the closed form (integrators/exact.hpp) as always, bit for bit.
// - riemann, nerf, pl_nerf, rk4 sample the quadratic scalar along the chord themselves
//   (RayIntegrator::takes_quadratic_segments).
// - every other method (paper, eq5-8, particle, ode, preintegrated, psi_table, VTK's peers)
//   assumes a scalar linear along each segment: it throws on such a ray, which evaluate_case
//   shows as that method failed on that ray (null, counted, exit 1), never as a number.
#include <memory>

#include "rayint/integrators/integrator.hpp"
#include "rayint/model/transfer_function.hpp"

namespace rayint {

// make_integrator(spec, tf), with "exact" able to take quadratic chords (above).
std::unique_ptr<RayIntegrator> make_case_integrator(const MethodSpec& spec, const TransferFunctions& tf);

}  // namespace rayint
