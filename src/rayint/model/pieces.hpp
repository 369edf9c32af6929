#pragma once
// Splitting a segment at every breakpoint of the six transfer functions (Williams & Max Sec. 3.3,
// Fig. 2): on each resulting piece rho and kappa are linear in t, so kappa*rho is quadratic.
#include <array>
#include <cstddef>
#include <vector>

#include "rayint/model/ray.hpp"

namespace rayint {

// One channel of one piece; its two ends are "far" and "exit" as defined in model/ray.hpp.
struct ChannelPiece {
  double length = 0.0;
  double rho_far = 0.0;
  double rho_exit = 0.0;
  double kappa_far = 0.0;
  double kappa_exit = 0.0;
};

struct Piece {
  double length = 0.0;
  double scalar_far = 0.0;
  double scalar_exit = 0.0;
  Rgb rho_far{}, rho_exit{}, kappa_far{}, kappa_exit{};

  ChannelPiece channel(int c) const {
    return {length, rho_far[c], rho_exit[c], kappa_far[c], kappa_exit[c]};
  }
};

// Appends the pieces of `segment` (far -> near) to `out`. A segment whose scalar is constant
// (w = 0) is one piece. Interior piece ends sit exactly on breakpoints, where the transfer
// functions take their stored values; piece lengths are L * (s_{k+1} - s_k) / (s_exit - s_far),
// so pieces between breakpoints 1e-12 apart keep full relative accuracy. Zero-length pieces
// are dropped (they transmit everything and emit nothing).
void append_pieces(const TransferFunctions& tf, const Segment& segment,
                   const std::vector<double>& breakpoints, std::vector<Piece>& out);

std::vector<Piece> split_ray(const TransferFunctions& tf, const Ray& ray);

// What every piece-wise integrator needs: the transfer functions' breakpoints, collected once,
// and the pieces of one segment at a time. pieces() returns a per-thread buffer that stays valid
// until the next pieces() call on the same thread (no allocation per segment in timing loops).
// The pieces are those of append_pieces, bit for bit (tests/test_piece_splitter.cpp, [splitter]), found
// faster: the six functions' values at every breakpoint and, per interval between breakpoints,
// each function's own interval are tabulated once, so an end costs one search among the
// breakpoints instead of six, an interior end (a breakpoint) none, and the end shared by two
// pieces is evaluated once; no allocation per segment.
class PieceSplitter {
 public:
  explicit PieceSplitter(const TransferFunctions& tf);
  const std::vector<Piece>& pieces(const Segment& segment) const;
  // Appends the pieces of `segment` to `out` (the same pieces as pieces()).
  void append(const Segment& segment, std::vector<Piece>& out) const;
  const TransferFunctions& transfer() const { return *tf_; }

 private:
  static constexpr int kFunctions = 2 * kChannels;  // rho r, g, b; kappa r, g, b
  using Values = std::array<double, kFunctions>;
  const PiecewiseLinear& function(int f) const {
    return f < kChannels ? tf_->density[static_cast<std::size_t>(f)]
                         : tf_->color[static_cast<std::size_t>(f - kChannels)];
  }
  Values at(double s) const;           // the six functions at s, as operator() gives them
  Values at_breakpoint(std::size_t j) const { return knot_values_[j]; }

  const TransferFunctions* tf_;
  std::vector<double> breakpoints_;
  std::vector<Values> knot_values_;                                // at breakpoints_[j]
  std::vector<std::array<std::size_t, kFunctions>> interval_;      // for s in [bp[j-1], bp[j])
};

}  // namespace rayint
