#pragma once
// Named numerical regimes of the ray integral (Williams & Max 1992, Eq. 4 and Sec. 3.3) and a
// reproducible sampler for each. Tests, the accuracy sample behind the README figures, and
// `rayint stress` all draw from here, so a regime means the same thing everywhere.
//
// Two kinds:
//  - piece-level regimes describe one channel of one piece (rho and kappa linear along it);
//    sample_piece draws one. piece_as_ray turns such a sample into a one-segment case so that
//    any method of the registry can integrate it.
//  - ray-level regimes need a whole case -- transfer functions with breakpoints and a ray
//    through them -- because what they stress (breakpoint splitting, compositing over many
//    pieces, end values outside the transfer functions' range) does not exist on one piece.
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "rayint/model/pieces.hpp"
#include "rayint/model/ray.hpp"

namespace rayint {

enum class Regime {
  // piece-level (sample_piece)
  thin,              // optical depth T in [1e-16, 1e-3]
  moderate,          // T in [1e-3, 30]
  thick,             // T in [30, 1e6]
  q2_near_zero_pos,  // density increasing toward the eye, relative slope
                     // (rho_exit - rho_far) / (rho_exit + rho_far) in 1e-16 .. 1e-4, and the
                     // ends at least one ulp apart (so never q2 == 0), T in [1e-3, 1e3]
  q2_near_zero_neg,  // decreasing, same
  q2_zero,           // density constant on the piece (q2 == 0)
  steep_up,          // rho_exit / rho_far in [1e2, 1e12]
  steep_down,        // rho_far / rho_exit in [1e2, 1e12]
  zero_density,      // rho == 0 on the whole piece
  zero_density_end,  // rho == 0 at one end
  huge_kappa_tiny_rho,  // kappa in [1e6, 1e12], rho*L in [1e-12, 1e-6]
  extreme_magnitudes,   // lengths 1e-12 .. 1e6, densities and colours 0 .. 1e12
  // ray-level (sample_ray)
  narrow_pulse,  // transfer-function pulses whose breakpoints are 1e-15 .. 1e-12 apart,
                 // peaks up to 1e12; rays crossing them, ending on them, or sitting on them
  long_ray,      // 10^4 segments through 2..12 breakpoints, total optical depth 1e-2 .. 1e3
  out_of_range,  // scalars below and above the transfer functions' range, by up to 1e6 times
                 // the range (end values hold there)
  // piece-level, opt-in (named with --regime, not in all_regimes / stress_regimes): the
  // optical-depth ranges of the VTK measurement in issue 8, tauD = T
  tau_moderate,  // T in [0.1, 10]
  tau_thin,      // T in [1e-8, 1e-3]
  tau_thick,     // T in [20, 1000]
};

// The piece-level regimes, in declaration order (what sample_piece accepts). Kept under this
// name for the per-piece tests and benchmarks that iterate over it.
const std::vector<Regime>& all_regimes();
const std::vector<Regime>& ray_regimes();     // narrow_pulse, long_ray, out_of_range
const std::vector<Regime>& stress_regimes();  // piece-level then ray-level: every default regime
const std::vector<Regime>& extra_regimes();   // the opt-in piece-level regimes (tau_*)
bool is_ray_regime(Regime r);
std::string regime_name(Regime r);
bool parse_regime(const std::string& name, Regime& out);

struct RegimeSample {
  ChannelPiece piece;
  double incoming = 0.0;  // light entering the far end
};

// Deterministic for a given engine state. Throws std::invalid_argument for a ray-level regime.
RegimeSample sample_piece(Regime r, std::mt19937_64& rng);

// `count` pieces, piece i from regime all_regimes()[i % size] with one engine seeded `seed`: the
// mixed set of the batch benchmark (bench/bench_exact.cpp BM_exact_pieces_batch) and of the Python
// module's throughput figure (scripts/examples/bench_exact_pieces.py), so both time the same pieces.
std::vector<ChannelPiece> mixed_regime_pieces(std::size_t count, std::uint64_t seed);

// A case without its name: transfer functions and one ray.
struct RaySample {
  TransferFunctions transfer;
  Ray ray;
};

// The piece as a one-segment ray, identical in all three channels: each transfer function is
// linear over the scalar range [0, 1] (rho(0) = rho_far, rho(1) = rho_exit, likewise kappa), the
// segment has the piece's length and runs from scalar 0 (far) to 1 (near), and the background
// is `incoming`. Splitting it reproduces the piece exactly (the end values are stored values and
// the length is L * (1 - 0) / (1 - 0) = L), so a method integrates the very same piece.
RaySample piece_as_ray(const RegimeSample& s);

// Deterministic for a given engine state; every regime is accepted (a piece-level regime gives
// piece_as_ray(sample_piece(r, rng))).
RaySample sample_ray(Regime r, std::mt19937_64& rng);

}  // namespace rayint
