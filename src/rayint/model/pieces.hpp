#pragma once
// Splitting a segment at every breakpoint of the six transfer functions (Williams & Max Sec. 3.3,
// Fig. 2): on each resulting piece rho and kappa are linear in t, so kappa*rho is quadratic.
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
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

  Piece() = default;
  // From the six functions' values at each end, in the order rho r, g, b, kappa r, g, b (what
  // PieceSplitter builds in place: a Piece{} copied in would be zeroed first).
  Piece(double length_, double s_far, double s_exit, const double* far, const double* exit)
      : length(length_), scalar_far(s_far), scalar_exit(s_exit),
        rho_far{far[0], far[1], far[2]}, rho_exit{exit[0], exit[1], exit[2]},
        kappa_far{far[3], far[4], far[5]}, kappa_exit{exit[3], exit[4], exit[5]} {}

  ChannelPiece channel(int c) const {
    return {length, rho_far[c], rho_exit[c], kappa_far[c], kappa_exit[c]};
  }
};

// Appends the pieces of `segment` (far -> near) to `out`. A segment whose scalar is constant
// (w = 0) is one piece. Each piece end takes the transfer functions' one-sided limit from inside
// the piece (PiecewiseLinear::limit), so at a jump the piece below uses the left value and the
// piece above the right value; a constant-scalar piece takes operator()'s value. Interior piece ends sit exactly on breakpoints, where the transfer
// functions take their stored values; piece lengths are L * (s_{k+1} - s_k) / (s_exit - s_far),
// so pieces between breakpoints 1e-12 apart keep full relative accuracy. Zero-length pieces
// are dropped (they transmit everything and emit nothing).
void append_pieces(const TransferFunctions& tf, const Segment& segment,
                   const std::vector<double>& breakpoints, std::vector<Piece>& out);

std::vector<Piece> split_ray(const TransferFunctions& tf, const Ray& ray);

// Pieces as channel columns, piece-major: entry kChannels * k + c holds channel c of piece k
// (its length, and rho and kappa at its far and exit ends): the layout a batch of single-channel
// integrals reads (integrators/exact_batch.hpp's PieceColumns), written without Piece structs.
// The columns hold size() entries; the vectors may be longer (they grow in steps and are never
// shrunk by clear()), so that push() checks the capacity once per piece, not once per column
// (issue 33: the nine push_backs of a grey piece took ~4% of a mesh render).
struct PieceChannelColumns {
  std::vector<double> length, rho_far, rho_exit, kappa_far, kappa_exit;
  void clear() { n_ = 0; }
  std::size_t size() const { return n_; }
  void push(double len, const double* far, const double* exit) {  // far/exit: rho r, g, b, kappa r, g, b
    if (n_ + kChannels > length.size()) grow();
    for (std::size_t c = 0; c < kChannels; ++c) {
      length[n_ + c] = len;
      rho_far[n_ + c] = far[c];
      rho_exit[n_ + c] = exit[c];
      kappa_far[n_ + c] = far[c + kChannels];
      kappa_exit[n_ + c] = exit[c + kChannels];
    }
    n_ += kChannels;
  }

 private:
  void grow();
  std::size_t n_ = 0;
};

// Pieces of a grey medium (TransferFunctions::grey()) as columns, one entry per piece: its
// length, its one density at the far and exit ends, and each channel's kappa (the layout of
// integrators/exact_batch.hpp's GreyPieceView). The density is channel 0's.
// Sized like PieceChannelColumns (size() entries, longer vectors).
struct GreyPieceColumns {
  std::vector<double> length, rho_far, rho_exit;
  std::array<std::vector<double>, kChannels> kappa_far, kappa_exit;
  void clear() { n_ = 0; }
  std::size_t size() const { return n_; }
  void push(double len, const double* far, const double* exit) {  // far/exit: rho r, g, b, kappa r, g, b
    if (n_ == length.size()) grow();
    length[n_] = len;
    rho_far[n_] = far[0];
    rho_exit[n_] = exit[0];
    for (std::size_t c = 0; c < kChannels; ++c) {
      kappa_far[c][n_] = far[c + kChannels];
      kappa_exit[c][n_] = exit[c + kChannels];
    }
    ++n_;
  }

 private:
  void grow();
  std::size_t n_ = 0;
};

// Where a piece of a ray lies, for a gradient through the splitting
// (integrators/ray_gradient_chain.hpp): its segment, its end scalars, and the interval of the
// sorted breakpoints (PieceSplitter::breakpoints()) that holds its interior, as the count
// upper_bound(breakpoints, smaller end) -- no breakpoint lies strictly inside a piece, so each
// transfer function's interval there follows from it. kNoRegion for the piece of a constant
// segment (s_far == s_exit), whose interval at a jump depends on the function.
struct PiecePlace {
  static constexpr std::uint32_t kNoRegion = static_cast<std::uint32_t>(-1);
  std::uint32_t segment = 0;
  std::uint32_t region = 0;
  double s_far = 0.0, s_exit = 0.0;
};

// What every piece-wise integrator needs: the transfer functions' breakpoints, collected once,
// and the pieces of one segment at a time. pieces() returns a per-thread buffer that stays valid
// until the next pieces() call on the same thread (no allocation per segment in timing loops).
// The pieces are those of append_pieces, bit for bit (tests/test_piece_splitter.cpp, [splitter]), found
// faster: the scalar line is cut by the m breakpoints into 2m + 1 regions (below the first, at
// each breakpoint, between two, above the last), and each region has a row holding, for each of
// the six functions, either its constant there (at a breakpoint, or where operator() clamps) or
// the ends of its own interval (PiecewiseLinear::interpolate's operands, differences included).
// An end then costs two counts among the breakpoints (which region it is in, and how many
// breakpoints lie strictly inside the segment) and one branch-free pass over the six functions
// with interpolate's arithmetic, which the compiler vectorises; no allocation per segment. For a
// grey transfer function (TransferFunctions::grey) the pass covers the four distinct functions
// only: its divisions are most of an end's cost.
class PieceSplitter {
 public:
  explicit PieceSplitter(const TransferFunctions& tf);
  PieceSplitter() = default;  // no functions until reset()
  // Rebuilt for `tf` (kept by reference, as by the constructor), reusing the storage held: no
  // allocation once it has grown (the gradient's per-thread splitter, for rays with their own
  // transfer functions).
  void reset(const TransferFunctions& tf);
  const std::vector<Piece>& pieces(const Segment& segment) const;
  // Appends the pieces of `segment` to `out` (the same pieces as pieces()).
  void append(const Segment& segment, std::vector<Piece>& out) const;
  // The same pieces as channel columns.
  void append(const Segment& segment, PieceChannelColumns& out) const;
  // The same pieces as grey columns (for a grey transfer(): the densities of channels 1 and 2
  // are dropped, so they must be channel 0's).
  void append(const Segment& segment, GreyPieceColumns& out) const;
  // The pieces of every segment in order, as the per-segment append()s give them; faster along a
  // ray, whose consecutive segment ends mostly lie between the same two breakpoints (RegionHint).
  // Returns the segments' piece count as a render states it (render/mesh_render.cpp, its
  // `pieces` statistic): per segment with length > 0, one more than the breakpoints strictly
  // inside its scalar range (one for a constant scalar or a NaN end). The split finds those
  // breakpoints anyway; the count can exceed the pieces appended by the zero-length pieces
  // dropped (issue 33, round 8: the render counted them in a second pass, ~4% of its CPU).
  long append(const std::vector<Segment>& segments, PieceChannelColumns& out) const;
  long append(const std::vector<Segment>& segments, GreyPieceColumns& out) const;
  // The per-ray append() with each piece's place: places[k] is piece k's (entries kChannels k ..
  // of `out`). Every scalar must be finite (the gradient's check; throws std::invalid_argument
  // otherwise). `places` is cleared first.
  long append(const std::vector<Segment>& segments, PieceChannelColumns& out, std::vector<PiecePlace>& places) const;
  // The sorted, de-duplicated breakpoints of the six functions (TransferFunctions::breakpoints).
  const std::vector<double>& breakpoints() const { return breakpoints_; }
  const TransferFunctions& transfer() const { return *tf_; }
  // transfer().grey(), computed once: the grey columns may be asked for.
  bool grey() const { return grey_; }

 private:
  static constexpr int kFunctions = 2 * kChannels;  // rho r, g, b; kappa r, g, b
  const PiecewiseLinear& function(int f) const {
    return f < kChannels ? tf_->density[static_cast<std::size_t>(f)]
                         : tf_->color[static_cast<std::size_t>(f - kChannels)];
  }
  // The rows hold the functions in slot order: slot k is function kSlotFunction[k]. The four
  // distinct functions of a grey medium (rho, kappa r, g, b) come first, so that two pairs of
  // lanes evaluate them; slots 4 and 5 (rho g, b) are evaluated only when not grey.
  static constexpr int kSlotFunction[kFunctions] = {0, 3, 4, 5, 1, 2};
  // One region's operands, slot-major in k = 0..5: the value is
  //   keep[k] (all bits set) ? constant[k] : PiecewiseLinear::interpolate's line on [s0[k], s1[k]].
  // The constant is selected, never computed (v + 0 * x would turn a stored -0.0 into +0.0).
  struct Row {
    alignas(16) double s0[kFunctions], s1[kFunctions], span[kFunctions];
    alignas(16) double v0[kFunctions], v1[kFunctions], dv01[kFunctions], dv10[kFunctions];
    alignas(16) double constant[kFunctions];
    alignas(16) std::int64_t keep[kFunctions];
  };
  // The region of s, 0..2m: (number of breakpoints < s) + (number <= s); `lt` and `le` get the
  // two counts (the append_pieces bounds lower_bound and upper_bound). s is not NaN.
  std::size_t region(double s, std::size_t& lt, std::size_t& le) const;
  // The last region found strictly between two breakpoints, lo < s < hi (lo = -inf below the
  // first, hi = +inf above the last), as its count j = lt = le: an end s inside it needs two
  // comparisons instead of the counts. NaN bounds (the start) never match.
  struct RegionHint {
    double lo = std::numeric_limits<double>::quiet_NaN(), hi = std::numeric_limits<double>::quiet_NaN();
    std::size_t j = 0;
  };
  std::size_t region(double s, std::size_t& lt, std::size_t& le, RegionHint& hint) const;
  // The six functions at s, in the row of its region, as operator() gives them, in function order
  // (rho r, g, b, kappa r, g, b).
  void eval(const Row& row, double s, double* v) const;
  // The pieces of a segment with finite scalar ends, each handed to
  // put(length, s_far, s_exit, far values, exit values); both append()s are this. Returns one
  // more than the breakpoints strictly inside the scalar range (the count of append() above).
  template <class Put>
  long split(const Segment& segment, Put&& put, RegionHint& hint) const;
  // The column append()s: split(), or append_pieces for a NaN scalar end; returns the count
  // of append() above for this segment.
  template <class Columns>
  long append_columns(const Segment& segment, Columns& out, RegionHint& hint) const;
  // The per-ray column append()s: append_columns over the segments with one hint; returns the
  // sum of their counts. Inlined into each of the append()s' CPU-specific copies.
  template <class Columns>
  long append_ray_columns(const std::vector<Segment>& segments, Columns& out) const;

  const TransferFunctions* tf_ = nullptr;
  std::vector<double> breakpoints_;
  std::array<double, 8> padded_{};  // breakpoints_ then NaN (never counted), when m <= 8
  std::vector<Row> rows_;           // 2m + 1
  // The six functions at each breakpoint, in function order (the constants of its row: at a
  // jump the left value), and their limits from above (at a jump the right value).
  std::vector<std::array<double, kFunctions>> at_breakpoint_;
  std::vector<std::array<double, kFunctions>> above_breakpoint_;
  bool jumps_ = false;              // tf_->has_jump(): segment ends on a breakpoint need limits
  bool grey_ = false;               // tf_->grey(): slots 4 and 5 repeat slot 0
};

}  // namespace rayint
