#pragma once
// The independent 50-digit reference for rays whose scalar is a polynomial along each segment
// (model/poly_ray.hpp: higher-order cells, trilinear voxels). Williams & Max (1992) Eq. 4 with
// the transfer functions of Sec. 3.1 applied to a curved scalar; see poly_reference.cpp.
#include "rayint/model/poly_ray.hpp"
#include "rayint/model/transfer_function.hpp"
#include "rayint/reference/reference.hpp"

namespace rayint {

// Per channel: intensity and transmittance as hi + lo (~30+ digits), an absolute error bound of
// the intensity, and the pieces and quadrature subintervals used. Throws std::invalid_argument
// for non-finite or negative lengths, non-finite coefficients or background, bad transfer
// functions, and std::runtime_error if a root or a quadrature misses its budget.
ReferenceRay reference_poly_ray(const TransferFunctions& tf, const PolyRay& ray);

}  // namespace rayint
