#pragma once
// The emission integrand of one smooth piece of a cell's chord (cell_integral.cpp, step 3),
// g_c(x) = kappa_c(f(x)) rho_c(f(x)) exp(-tau_c(x)) for every channel c at a batch of nodes x in
// [-1, 1], vectorised over the nodes with Google Highway (run-time dispatch: SSE4, AVX2,
// AVX-512): f(x) = sum_k c_k T_k(x) and its antiderivative P by Clenshaw's recurrence, rho_c and
// kappa_c the transfer functions' linear parts on the piece, tau_c(x) = h (v0 (x - x0) + beta
// ((P(x) - P0) - s0 (x - x0))) the exact optical depth from x0. The operations are those of the
// scalar form in the same order, but on targets with FMA (AVX2, AVX-512) the compiler fuses
// multiply-adds (GCC's default -ffp-contract=fast; the baseline scalar build has no FMA), so f,
// P, rho, kappa and tau agree with the scalar form to rounding, not bit for bit, and differ
// between targets at that level; exp is Highway's Exp (documented 1 ulp), an exponent outside [-700,
// 700] (or NaN) goes to std::exp (Highway's Exp is valid up to +706 and maps NaN to 0, so a
// failure stays inf or NaN, never a number). g_c = 0 where kappa_c rho_c = 0.
#include <array>
#include <cstddef>

#include "rayint/model/transfer_function.hpp"

namespace rayint {

struct EmissionLinear {  // v0 + beta (f - s0); not zeroed (filled per piece, on the hot path)
  double v0, beta, s0;
};

struct EmissionPiece {
  const double* c = nullptr;  // Chebyshev coefficients of f, c[0 .. nc - 1]
  std::size_t nc = 0;
  const double* P = nullptr;  // of its antiderivative, P[0 .. nP - 1]
  std::size_t nP = 0;
  double x0 = 0.0, P0 = 0.0, h = 0.0;  // the piece's start, P(x0), world length per unit x
  std::array<EmissionLinear, kChannels> rho, kappa;
};

inline constexpr std::size_t kMaxEmissionNodes = 16;

// out[kChannels j + c] = g_c(x_j) at x_j = centre + half u[j], for j < n <= kMaxEmissionNodes;
// u is read up to kMaxEmissionNodes entries (pad with anything finite). The nodes are formed in
// the vector registers: filling them lane by lane through memory stalled the load (the
// store-to-load forwarding of 8 scalar stores to one vector load fails).
void emission_at_nodes(const EmissionPiece& piece, double centre, double half, const double* u, std::size_t n,
                       double* out);

}  // namespace rayint
