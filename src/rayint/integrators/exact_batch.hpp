#pragma once
// The exact integral of exact.hpp on many pieces at once: structure-of-arrays in and out, pieces
// grouped by branch, each group evaluated with vector erfcx/Dawson/exp (Google Highway, target
// picked at run time); runs of thin pieces (the common regime of mesh renders) go through the
// thin kernel in their own order, with the same results. exact_piece (exact.cpp) stays the
// readable scalar reference; this path computes the same formulas in the same regions. See
// exact_batch.cpp for the error bounds.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "rayint/integrators/exact.hpp"

namespace rayint {

// n pieces, one channel each (the fields of ChannelPiece as columns).
struct PieceColumns {
  const double* length = nullptr;
  const double* rho_far = nullptr;
  const double* rho_exit = nullptr;
  const double* kappa_far = nullptr;
  const double* kappa_exit = nullptr;
  std::size_t size = 0;
};

// The columns of an array of ChannelPiece, owned: how a caller with pieces as structs reaches the
// column functions (exact_batch, exact_pieces_grad). assign() returns the view of n pieces.
struct PieceColumnStore {
  std::vector<double> length, rho_far, rho_exit, kappa_far, kappa_exit;
  PieceColumns assign(const ChannelPiece* pieces, std::size_t n);
};

// Results per piece: the transmittance and emission of PieceOptics; the introspection columns
// are optional (null: not written).
struct OpticsColumns {
  double* transmittance = nullptr;
  double* emission = nullptr;
  ExactBranch* branch = nullptr;        // branch taken
  std::int32_t* terms = nullptr;        // series terms (thin_series), else 0
  unsigned char* converged = nullptr;   // 0 if the thin series hit its term budget
  // For the gradient (integrators/exact_grad.hpp, exact_pieces_grad): all five or none (m1 null).
  // The emission weights of PieceOptics, and the moments M1, M2, e0 of PieceOpticsGrad where the
  // batch forms them: thin_series lanes (exact_grad.cpp's midpoint_moments, the same series and
  // stop) and transparent lanes (1/2, 1/3, 1); NaN for the other branches.
  double* weight_exit = nullptr;
  double* weight_far = nullptr;
  double* m1 = nullptr;
  double* m2 = nullptr;
  double* e0 = nullptr;
};

// out[i] = exact_piece(in[i]) for i < in.size, to the accuracy stated in exact_batch.cpp.
// Thread safe (per-thread scratch); no allocation once a thread's scratch has grown.
void exact_batch(const PieceColumns& in, const OpticsColumns& out);

// n pieces of a grey medium (TransferFunctions::grey(): one density for every channel), as
// columns: the density once per piece, the kappas per channel. Each piece's transmittance and
// emission weights are computed once and its emission formed for every channel.
struct GreyPieceView {
  const double* length = nullptr;
  const double* rho_far = nullptr;
  const double* rho_exit = nullptr;
  std::array<const double*, kChannels> kappa_far{};
  std::array<const double*, kChannels> kappa_exit{};
  std::size_t size = 0;
};
struct GreyOpticsColumns {
  double* transmittance = nullptr;              // per piece, every channel's
  std::array<double*, kChannels> emission{};    // per channel, per piece
};

// The results of the channel overload with the density repeated in every channel, bit for bit
// (tests/test_exact_batch.cpp): transmittance[i] is each channel's, emission[c][i] channel c's.
void exact_batch(const GreyPieceView& in, const GreyOpticsColumns& out);

// The Highway target exact_batch runs on this CPU ("AVX3", "AVX2", "SSE4", ...).
const char* exact_batch_target();

}  // namespace rayint
