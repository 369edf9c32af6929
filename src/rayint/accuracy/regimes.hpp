#pragma once
// Named numerical regimes of the piece integral and a reproducible sampler for each. Tests, the
// accuracy sample behind the README figures, and `rayint stress` all draw from here, so a
// regime means the same thing everywhere.
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "rayint/model/pieces.hpp"

namespace rayint {

enum class Regime {
  thin,              // optical depth T in [1e-16, 1e-3]
  moderate,          // T in [1e-3, 30]
  thick,             // T in [30, 1e6]
  q2_near_zero_pos,  // density increasing toward the eye, relative slope 1e-16 .. 1e-4
  q2_near_zero_neg,  // decreasing, same
  q2_zero,           // density constant on the piece (q2 == 0)
  steep_up,          // rho_exit / rho_far in [1e2, 1e12]
  steep_down,        // rho_far / rho_exit in [1e2, 1e12]
  zero_density,      // rho == 0 on the whole piece
  zero_density_end,  // rho == 0 at one end
  huge_kappa_tiny_rho,  // kappa in [1e6, 1e12], rho*L in [1e-12, 1e-6]
  extreme_magnitudes,   // lengths 1e-12 .. 1e6, densities and colours 0 .. 1e12
};

const std::vector<Regime>& all_regimes();
std::string regime_name(Regime r);
bool parse_regime(const std::string& name, Regime& out);

struct RegimeSample {
  ChannelPiece piece;
  double incoming = 0.0;  // light entering the far end
};

// Deterministic for a given engine state.
RegimeSample sample_piece(Regime r, std::mt19937_64& rng);

}  // namespace rayint
