// exact_batch.cpp -- exact_piece in a loop (see exact_batch.hpp).
#include "rayint/integrators/exact_batch.hpp"

#include "rayint/integrators/exact.hpp"

namespace rayint {

void exact_pieces_batch(const PieceArrays& in, const PieceOpticsArrays& out) {
  for (std::size_t i = 0; i < in.count; ++i) {
    ChannelPiece piece;
    piece.length = in.length[i];
    piece.rho_far = in.rho_far[i];
    piece.rho_exit = in.rho_exit[i];
    piece.kappa_far = in.kappa_far[i];
    piece.kappa_exit = in.kappa_exit[i];
    const PieceOptics o = exact_piece(piece);
    out.emission[i] = o.emission;
    out.transmittance[i] = o.transmittance;
  }
}

}  // namespace rayint
