#pragma once
// The independent high-precision reference: Eq. 4 integrated numerically, piece by piece, in
// 50-digit binary floating point (Boost.Multiprecision cpp_bin_float_50) with Gauss-Kronrod
// quadrature (Boost.Math). It never calls the closed-form code: it splits segments at
// breakpoints itself, in 50-digit arithmetic.
#include <array>
#include <cstddef>
#include <functional>

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

// How reference_ray runs on a long ray. The pieces' quadratures do not depend on each other, only
// the compositing does: a block of segments at a time, the quadratures run on `threads` workers
// (core/parallel.hpp parallel_for; 0: all cores) and are then composited far -> near in order on
// the calling thread -- the same operations in the same order as with one thread, so the result is
// bit-identical for every thread count (tests/test_reference.cpp). progress(done, total) is called
// on the calling thread after each block with the segments done so far.
struct ReferenceRun {
  unsigned threads = 1;
  std::function<void(std::size_t done, std::size_t total)> progress;
};
ReferenceRay reference_ray(const TransferFunctions& tf, const Ray& ray, const ReferenceRun& run);

}  // namespace rayint
