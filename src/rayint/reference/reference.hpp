#pragma once
// The independent high-precision reference: Eq. 4 integrated numerically, piece by piece, in
// 50-digit binary floating point (Boost.Multiprecision cpp_bin_float_50) with Gauss-Kronrod
// quadrature (Boost.Math). It never calls the closed-form code: it splits segments at
// breakpoints itself, in 50-digit arithmetic.
#include <array>

#include "rayint/model/pieces.hpp"
#include "rayint/model/ray.hpp"

namespace rayint {

// A value known to ~30+ digits as an unevaluated sum hi + lo (hi = correctly rounded double).
struct ExtendedValue {
  double hi = 0.0;
  double lo = 0.0;
};

struct ReferencePiece {
  ExtendedValue transmittance;  // exp(-T)
  ExtendedValue emission;       // integral of kappa*rho*exp(-tau to exit)
  ExtendedValue intensity;      // incoming * transmittance + emission
  double error_bound = 0.0;     // absolute bound on |intensity - exact|
  int subintervals = 0;
};

// One channel of one piece, with `incoming` light entering its far end.
ReferencePiece reference_piece(const ChannelPiece& piece, double incoming);

struct ReferenceRay {
  std::array<ExtendedValue, 3> intensity;
  std::array<ExtendedValue, 3> transmittance;
  Rgb error_bound{};        // absolute error estimate of intensity, per channel
  int subintervals = 0;     // quadrature subintervals used, all channels
  int pieces = 0;
};

ReferenceRay reference_ray(const TransferFunctions& tf, const Ray& ray);

}  // namespace rayint
