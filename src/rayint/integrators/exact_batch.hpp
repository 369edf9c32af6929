#pragma once
// exact_piece (exact.hpp) over arrays of pieces of one channel: the one call site of batch users
// (the Python module's exact_pieces), so that a vectorised path can replace the loop here without
// touching them. Same numbers as calling exact_piece on each piece, bit for bit.
#include <cstddef>

namespace rayint {

// Structure of arrays, `count` entries each; exit = the eye side, far = where light enters
// (model/ray.hpp). Preconditions as exact_piece's: finite, rho >= 0, length >= 0.
struct PieceArrays {
  const double* rho_exit = nullptr;
  const double* rho_far = nullptr;
  const double* kappa_exit = nullptr;
  const double* kappa_far = nullptr;
  const double* length = nullptr;
  std::size_t count = 0;
};

// `count` entries each: int kappa rho exp(-tau) ds over the piece, and exp(-T).
struct PieceOpticsArrays {
  double* emission = nullptr;
  double* transmittance = nullptr;
};

void exact_pieces_batch(const PieceArrays& in, const PieceOpticsArrays& out);

}  // namespace rayint
