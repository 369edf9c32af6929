#pragma once
// ray_gradient_chain.hpp -- private helper of the ray gradients whose per-piece optics have the
// form of exact.cpp's (emission and transmittance of a piece on which rho and kappa are linear):
// exact_grad.cpp (the exact piece) and psi_table_grad.cpp (Psi read from a table). It takes the
// segments' pieces and end values from PieceSplitter (model/pieces.hpp: append_pieces' pieces, bit
// for bit, as the forward's batch path splits), composites far -> near and differentiates in reverse,
// carrying each piece's derivatives (PieceOpticsGrad) to the lengths, end scalars, background and
// transfer-function nodes. The mathematics and the kink convention: docs/gradients.md, "Through
// the splitting and the compositing".
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "rayint/integrators/exact_batch.hpp"
#include "rayint/integrators/exact_grad.hpp"
#include "rayint/model/pieces.hpp"
#include "rayint/model/ray_gradient.hpp"

namespace rayint::detail {

// A piece of a segment, as append_pieces makes it, with what the chain rule needs.
struct PieceRecord {
  std::size_t segment = 0;
  double s_far = 0.0, s_exit = 0.0;  // scalar at its ends
  double length = 0.0;
  double fraction = 1.0;             // length / segment length
  // Where its ends lie along the segment, 0 at the far end to 1 at the exit: the end scalars
  // are s_far + phi (s_exit - s_far), so d s/d s_far = 1 - phi, d s/d s_exit = phi.
  double phi_far = 0.0, phi_exit = 1.0;
  // Whether each end is the segment's own end (else a breakpoint strictly inside the segment),
  // and the segment's scalar span s_exit - s_far (0 for a constant segment).
  bool far_is_end = true, exit_is_end = true;
  double span = 0.0;
  // For a piece of a non-constant segment, the interval of the sorted union of the transfer
  // functions' breakpoints that holds its interior: upper_bound(breakpoints, smaller end). No
  // breakpoint lies strictly inside a piece, so each function's interval follows from it
  // (chain_ray_gradient's region tables). kConstantPiece for a piece of a constant segment.
  std::uint32_t region = 0;
};
inline constexpr std::uint32_t kConstantPiece = static_cast<std::uint32_t>(-1);

// How the end scalars of the pieces are differentiated.
enum class PieceEnds {
  // Points fixed along the segment, piece lengths held fixed (exact): the same first derivative
  // as moving ends for the exact integral, without that form's cancellation (docs/gradients.md).
  fixed_along_segment,
  // As the renderer computes them (what autodiff through a split renderer returns, for an
  // approximation whose value depends on where a piece is split, e.g. psi_table): a piece end at
  // a breakpoint moves with the node that put it there, a piece's length is
  // L (e_exit - e_far) / (s_exit - s_far). A breakpoint is owned by the first node at its
  // position among density[c] then color[c] of the channel differentiated; a breakpoint of
  // another channel's function moves that function's node, an entry the per-channel layout of
  // RayGradient has no place for: that derivative is left out (documented in psi_table_grad.hpp).
  moving,
};

// The crossing of a jump between piece `before` (farther) and piece `after` (nearer the eye) of
// one segment, at e = after.s_far, an interior breakpoint where density[c] or color[c] jumps.
// With l the distance of the crossing from the segment's far end, l = L (x_j - s_far)/(s_exit -
// s_far), moving the crossing by dl turns a slab of length dl from `after`'s values into
// `before`'s, so (Williams & Max Eq. 1: a slab of length dl emits kappa rho dl and absorbs
// rho I dl of the light I entering it, then is attenuated by the transmittance A to the eye)
//   dI/dl = A [rho_b (kappa_b - I*) - rho_a (kappa_a - I*)],
// b/a the one-sided limits at the crossing from `before`'s and `after`'s side, I* the light at
// the crossing (entering `after`), A the transmittance from it to the eye (`adjoint`, after
// `after`'s). Then dl/dx_j = L/span, dl/ds_far = -(L/span)(1 - phi), dl/ds_exit = -(L/span) phi,
// span = s_exit - s_far, phi = (x_j - s_far)/span (signed: a decreasing scalar works the same).
// The length moves nothing here (the crossing stays at the same fraction, as the pieces do).
// When density[c] and color[c] both jump at x_j, moving one jump alone is not differentiable
// (the slab takes the other function's value from the side it moves into): that position is
// marked NaN, the scalar entries (moving both together) keep the term.
// Measured against the jump-aware 50-digit reference gradient (tests/test_grad_jumps.cpp):
// worst 3.3e-15 of each channel's largest entry over 48 random rays with 445 crossings; 2.2e-14
// on a saturated zig-zag ray (L = 10), the conditioning limit of saturated rays generally.
// With PieceEnds::moving (psi_table) the crossing's motion is already in the piece lengths (the
// ends at x_j move with it, routed to the jump's node): with_term false then only marks the
// positions NaN where density[c] and color[c] both jump at x_j.
inline void add_jump_crossing(const TransferFunctions& tf, const Ray& ray, const PieceRecord& before,
                              const PieceRecord& after, int c, double light, double adjoint, RayGradient& grad,
                              bool with_term = true, bool nodes = true) {
  const double e = after.s_far;
  if (before.segment != after.segment || before.s_exit != e) return;
  const PiecewiseLinear& rho = tf.density[c];
  const PiecewiseLinear& kappa = tf.color[c];
  const std::size_t jd = jump_node(rho, e), jc = jump_node(kappa, e);
  if (jd == kNoJump && jc == kNoJump) return;
  if (!with_term && (jd == kNoJump || jc == kNoJump)) return;
  const bool before_above = e < before.s_far, after_above = e < after.s_exit;
  const double rho_b = rho.limit(e, before_above), kappa_b = kappa.limit(e, before_above);
  const double rho_a = rho.limit(e, after_above), kappa_a = kappa.limit(e, after_above);
  const double dI_dl = adjoint * (rho_b * (kappa_b - light) - rho_a * (kappa_a - light));
  const double l_per_x = ray.segments[after.segment].length / after.span;
  const double phi = after.phi_far;
  if (with_term) {
    grad.scalar_far[after.segment][c] -= dI_dl * l_per_x * (1.0 - phi);
    grad.scalar_exit[after.segment][c] -= dI_dl * l_per_x * phi;
  }
  if (!nodes) return;  // GradientBlocks::segments: no position entries to fill or mark
  if (jd != kNoJump && jc != kNoJump) {
    grad.density[c][jd].position = std::nan("");
    grad.color[c][jc].position = std::nan("");
    if (!grad.undefined.empty()) grad.undefined += "; ";
    grad.undefined += "density and color of channel " + std::to_string(c) + " both jump at " + std::to_string(e) +
                      ": moving one of the two jumps alone is not differentiable";
    return;
  }
  (jd != kNoJump ? grad.density[c][jd] : grad.color[c][jc]).position += dI_dl * l_per_x;
}

// NaN (no derivative) where the ray touches a jump at a segment end (see model/ray_gradient.hpp):
// the jump's position entry and that end's scalar entry, in the channel of the function that jumps.
// With nodes false (GradientBlocks::segments) only the scalar entries are marked.
inline void mark_jump_tangencies(const TransferFunctions& tf, const Ray& ray, RayGradient& grad, bool nodes = true) {
  static const char* const kChannel[kChannels] = {"r", "g", "b"};
  for (std::size_t j = 0; j < ray.segments.size(); ++j) {
    const Segment& seg = ray.segments[j];
    if (!(seg.length > 0.0)) continue;
    for (int c = 0; c < kChannels; ++c)
      for (const bool density : {true, false}) {
        const PiecewiseLinear& f = density ? tf.density[c] : tf.color[c];
        for (const bool far : {true, false}) {
          const double s = far ? seg.scalar_far : seg.scalar_exit;
          const std::size_t i = jump_node(f, s);
          if (i == kNoJump) continue;
          if (nodes) (density ? grad.density : grad.color)[c][i].position = std::nan("");
          (far ? grad.scalar_far : grad.scalar_exit)[j][c] = std::nan("");
          if (!grad.undefined.empty()) grad.undefined += "; ";
          grad.undefined += "segment " + std::to_string(j) + "'s " + (far ? "far" : "exit") + " scalar lies on the jump of " +
                            (density ? "density " : "color ") + kChannel[c] + " at " + std::to_string(s) +
                            " (the ray touches it: one-sided derivatives differ)";
        }
      }
  }
}

// Whether every segment's length and scalars are finite: their exponent bits, or-ed without a
// branch per number (a branch per number was ~2% of a long ray's gradient).
inline bool all_finite(const std::vector<Segment>& segments) {
  constexpr std::uint64_t kExponent = 0x7ff0000000000000u;
  std::uint64_t not_finite = 0;
  for (const Segment& seg : segments)
    for (const double x : {seg.length, seg.scalar_far, seg.scalar_exit}) {
      std::uint64_t bits;
      std::memcpy(&bits, &x, sizeof bits);
      not_finite |= static_cast<std::uint64_t>((bits & kExponent) == kExponent);
    }
  return not_finite == 0;
}

// The same transfer functions, point for point and bit for bit (the free gradient functions keep
// a preparation for the last functions seen).
inline bool same_points(const TransferFunctions& a, const TransferFunctions& b) {
  const auto same = [](const std::vector<double>& x, const std::vector<double>& y) {
    return x.size() == y.size() && (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(double)) == 0);
  };
  for (int c = 0; c < kChannels; ++c)
    for (const bool density : {true, false}) {
      const PiecewiseLinear& f = density ? a.density[c] : a.color[c];
      const PiecewiseLinear& g = density ? b.density[c] : b.color[c];
      if (!same(f.scalar, g.scalar) || !same(f.value, g.value)) return false;
    }
  return true;
}

// What chain_ray_gradient prepares once per transfer functions, as ExactIntegrator holds its
// splitter: a copy of the functions, their PieceSplitter (the forward's pieces), and per function
// (slot c: density[c], slot kChannels + c: color[c]) its interval_slope per interval and its
// interval for each interval u = 0..m of the union of breakpoints: upper_bound(f.scalar,
// breakpoints[u - 1]), 0 below the first. For any x in [breakpoints[u - 1], breakpoints[u]) that
// is upper_bound(f.scalar, x): no node of f lies in between, so a non-constant piece's intervals
// are read from its region, no search per piece. Not copyable (the splitter refers to the copy).
class GradientPreparation {
 public:
  GradientPreparation() = default;
  explicit GradientPreparation(const TransferFunctions& tf) { reset(tf); }
  GradientPreparation(const GradientPreparation&) = delete;
  GradientPreparation& operator=(const GradientPreparation&) = delete;
  // Prepared for `tf` (copied), reusing the storage held.
  void reset(const TransferFunctions& tf) {
    tf_ = tf;  // vector assignments: the storage held is reused
    splitter_.reset(tf_);
    jumps_ = tf_.has_jump();
    grey_ = tf_.grey();
    const std::vector<double>& breakpoints = splitter_.breakpoints();
    for (int c = 0; c < kChannels; ++c)
      for (const bool density : {true, false}) {
        const PiecewiseLinear& f = density ? tf_.density[c] : tf_.color[c];
        const std::size_t slot = density ? static_cast<std::size_t>(c) : static_cast<std::size_t>(kChannels + c);
        std::vector<std::uint32_t>& table = region_interval_[slot];
        table.resize(breakpoints.size() + 1);
        table[0] = 0;
        std::size_t k = 0;
        for (std::size_t u = 1; u <= breakpoints.size(); ++u) {
          while (k < f.scalar.size() && f.scalar[k] <= breakpoints[u - 1]) ++k;
          table[u] = static_cast<std::uint32_t>(k);
        }
        std::vector<double>& slopes = slopes_[slot];
        slopes.resize(f.scalar.size() + 1);
        for (std::size_t i = 0; i < slopes.size(); ++i) slopes[i] = interval_slope(f, i);
      }
    ready_ = true;
  }
  // Whether it was prepared for functions equal to `tf` point for point.
  bool ready_for(const TransferFunctions& tf) const { return ready_ && same_points(tf_, tf); }
  const TransferFunctions& transfer() const { return tf_; }
  const PieceSplitter& splitter() const { return splitter_; }
  bool jumps() const { return jumps_; }
  bool grey() const { return grey_; }
  const double* slopes(std::size_t slot) const { return slopes_[slot].data(); }
  const std::uint32_t* region_interval(std::size_t slot) const { return region_interval_[slot].data(); }

 private:
  TransferFunctions tf_;
  PieceSplitter splitter_;
  bool ready_ = false, jumps_ = false, grey_ = false;
  std::vector<double> slopes_[2 * kChannels];
  std::vector<std::uint32_t> region_interval_[2 * kChannels];
};

// The free gradient functions' preparation: one per thread, for the last transfer functions seen
// (rebuilt when they change, compared point for point).
inline const GradientPreparation& thread_preparation(const TransferFunctions& tf) {
  thread_local GradientPreparation prep;
  if (!prep.ready_for(tf)) prep.reset(tf);
  return prep;
}

// The reverse pass's node entries of one transfer function, summed per interval and formed once
// per ray. A piece whose values come from interval k (nodes p0 = scalar[k-1], p1 = scalar[k])
// gives an end at s with adjoint bar the node terms
//   value[k-1] += bar w0, value[k] += bar w1, position[k-1] -= slope bar w0, position[k] -= slope bar w1,
// w0 = (p1 - s)/span, w1 = (s - p0)/span, span = p1 - p0 (node_weights_in's weights): so per
// interval it is enough to sum bar (p1 - s) and bar (s - p0) over the ends that fall in it, and
// divide by span and multiply by -slope once at the end (flush). On an extension (k = 0 or
// k = n) the end node takes bar with weight 1 and its position bar * 0 (0, or NaN for a
// non-finite bar, as node_weights_in's). The differences p1 - s, s - p0 are node_weights_in's
// operands; the sums are rounded differently from a per-end sum of weighted terms (against the
// 50-digit reference, `[grad]`: steep_up's worst 2.11e-15 -> 1.24e-15 of the channel's largest
// entry, the case corpus 1.92e-15 -> 1.98e-15, every other regime unchanged; docs/gradients.md).
class IntervalSums {
 public:
  // For f, whose interval_slope per interval is slopes[0..n] (GradientPreparation's table).
  // Zeroes the sums in place (no call per vector: a ray of a few pieces pays this per function).
  void reset(const PiecewiseLinear& f, const double* slopes) {
    f_ = &f;
    slopes_ = slopes;
    n_ = f.scalar.size();
    if (lo_.size() < n_ + 1) {
      lo_.resize(n_ + 1);
      hi_.resize(n_ + 1);
    }
    std::fill_n(lo_.data(), n_ + 1, 0.0);
    std::fill_n(hi_.data(), n_ + 1, 0.0);
  }
  // The two ends of a piece lying in interval k, far end first.
  void add(std::size_t k, double s_far, double far_bar, double s_exit, double exit_bar) {
    if (k == 0 || k == n_) {
      lo_[k] += far_bar + exit_bar;
      return;
    }
    const double p0 = f_->scalar[k - 1], p1 = f_->scalar[k];
    lo_[k] += far_bar * (p1 - s_far) + exit_bar * (p1 - s_exit);
    hi_[k] += far_bar * (s_far - p0) + exit_bar * (s_exit - p0);
  }
  // Adds the sums to the function's node entries.
  void flush(std::vector<NodeDerivative>& nodes) const {
    if (n_ == 0) return;
    nodes.front().value += lo_[0];
    nodes.front().position += lo_[0] * 0.0;
    nodes.back().value += lo_[n_];
    nodes.back().position += lo_[n_] * 0.0;
    for (std::size_t k = 1; k < n_; ++k) {
      if (lo_[k] == 0.0 && hi_[k] == 0.0) continue;  // no end here (a jump's zero-width interval)
      const double span = f_->scalar[k] - f_->scalar[k - 1];
      const double slope = slopes_[k];  // interval_slope(*f_, k)
      const double u0 = lo_[k] / span, u1 = hi_[k] / span;
      nodes[k - 1].value += u0;
      nodes[k - 1].position += -slope * u0;
      nodes[k].value += u1;
      nodes[k].position += -slope * u1;
    }
  }

 private:
  const PiecewiseLinear* f_ = nullptr;
  const double* slopes_ = nullptr;
  std::size_t n_ = 0;
  std::vector<double> lo_, hi_;  // per interval 0..n: sums of bar (p1 - s), of bar (s - p0)
};

// A PieceSource (chain_ray_gradient) from piece_grad(const ChannelPiece&, const PieceOpticsGrad*
// same_depth) -> PieceOpticsGrad, one piece-channel at a time; same_depth points to channel 0's
// result of a grey medium's piece, else null. Its derivatives are kept per piece-channel for the
// whole ray (PieceDerivatives).
template <class PieceGrad>
class EachPieceChannel {
 public:
  explicit EachPieceChannel(PieceGrad piece_grad) : piece_grad_(std::move(piece_grad)) {}
  void start(std::size_t piece_channels, bool grey) {
    derivs_.resize(piece_channels);
    grey_ = grey;
  }
  void evaluate(const PieceColumns& in, std::size_t first) {
    PieceOpticsGrad channel0;  // a piece's channel 0, for the other channels of a grey medium
    for (std::size_t i = 0; i < in.size; ++i) {
      const std::size_t c = i % kChannels;
      const ChannelPiece cp{in.length[i], in.rho_far[i], in.rho_exit[i], in.kappa_far[i], in.kappa_exit[i]};
      const PieceOpticsGrad g = piece_grad_(cp, grey_ && c > 0 ? &channel0 : nullptr);
      derivs_[first + i] = derivatives_of(g);
      if (c == 0) channel0 = g;
    }
  }
  double transmittance(std::size_t k, int c) const { return at(k, c).transmittance; }
  double emission(std::size_t k, int c) const { return at(k, c).emission; }
  PieceDerivatives derivatives(std::size_t k, int c, const ChannelPiece&, double) const { return at(k, c); }

 private:
  const PieceDerivatives& at(std::size_t k, int c) const { return derivs_[kChannels * k + static_cast<std::size_t>(c)]; }
  PieceGrad piece_grad_;
  std::vector<PieceDerivatives> derivs_;
  bool grey_ = false;
};
template <class PieceGrad>
EachPieceChannel<PieceGrad> each_piece_channel(PieceGrad piece_grad) {
  return EachPieceChannel<PieceGrad>(std::move(piece_grad));
}

// PieceEnds::moving's end scalars for channel c of piece pr: its length's adjoint len_bar (len =
// L (e_exit - e_far) / (s_exit - s_far), through both ends and the span) and the end values'
// adjoints through s (far_s_bar, exit_s_bar). An end's s_bar goes to the segment's end scalar, or
// at a breakpoint to the node that put it there: a jump owns its breakpoint (moving it moves the
// crossing, the split); else the first node at that scalar among density[c] then color[c].
inline void moving_ends(const TransferFunctions& tf, const Ray& ray, const PieceRecord& pr, int c, double len_bar,
                        double far_s_bar, double exit_s_bar, bool nodes_wanted, bool jumps, RayGradient& grad) {
  const auto route = [&](bool far_side, double e, double s_bar) {
    if (s_bar == 0.0) return;
    if (far_side ? pr.far_is_end : pr.exit_is_end) {
      (far_side ? grad.scalar_far : grad.scalar_exit)[pr.segment][c] += s_bar;
      return;
    }
    if (!nodes_wanted) return;
    if (jumps)
      for (auto* nodes : {&grad.density[c], &grad.color[c]}) {
        const std::size_t first = jump_node(nodes == &grad.density[c] ? tf.density[c] : tf.color[c], e);
        if (first != kNoJump) {
          (*nodes)[first].position += s_bar;
          return;
        }
      }
    for (auto* nodes : {&grad.density[c], &grad.color[c]}) {
      const PiecewiseLinear& f = nodes == &grad.density[c] ? tf.density[c] : tf.color[c];
      const auto it = std::lower_bound(f.scalar.begin(), f.scalar.end(), e);
      if (it != f.scalar.end() && *it == e) {
        (*nodes)[static_cast<std::size_t>(it - f.scalar.begin())].position += s_bar;
        return;
      }
    }
  };
  if (pr.span != 0.0 && pr.fraction != 1.0) {
    const double per_end = len_bar * ray.segments[pr.segment].length / pr.span;
    route(false, pr.s_exit, per_end);
    route(true, pr.s_far, -per_end);
    const double per_span = len_bar * pr.length / pr.span;
    grad.scalar_far[pr.segment][c] += per_span;
    grad.scalar_exit[pr.segment][c] -= per_span;
  }
  route(true, pr.s_far, far_s_bar);
  route(false, pr.s_exit, exit_s_bar);
}

// source, a PieceSource: the optics of the ray's piece-channels and their derivatives, formed a
// chunk at a time. With index kChannels k + c for channel c of the ray's k-th piece:
//   start(std::size_t piece_channels, bool grey): before the ray's first chunk. With grey true the
//     channels of a piece share its length, rho_far and rho_exit (a grey medium,
//     TransferFunctions::grey): the source may reuse channel 0's results for them, or ignore it.
//   evaluate(const PieceColumns& in, std::size_t first): forms piece-channels first ..
//     first + in.size - 1 (whole pieces) from their inputs in; called for consecutive chunks.
//   transmittance(k, c), emission(k, c): the optics of an evaluated piece-channel.
//   derivatives(k, c, const ChannelPiece& p, double kappa_far_minus_exit) -> PieceDerivatives:
//     its derivatives, given its inputs p and kappa_far - kappa_exit (the interval's slope times
//     s_far - s_exit; 0 for a constant piece). exact_grad.cpp's source forms them here, in the
//     reverse pass, from columns of the batch (no per-piece-channel record written and read back);
//     each_piece_channel keeps a PieceDerivatives per piece-channel.
// blocks = GradientBlocks::segments leaves the node blocks empty and skips their accumulation.
// Throws std::invalid_argument for a non-finite length, scalar or background.
//
// The pieces and their end values are the forward's: PieceSplitter (model/pieces.hpp), the
// splitter ExactIntegrator's batch path uses, with each piece's place (PiecePlace), so the
// gradient differentiates the very pieces the forward integrates. The transfer functions are
// prep.transfer(); the overload below takes them and uses the thread's preparation for the last
// functions seen (compared point for point, bit for bit).
template <class PieceSource>
void chain_ray_gradient(const GradientPreparation& prep, const Ray& ray, RayGradient& grad, PieceSource& source,
                        PieceEnds ends_mode = PieceEnds::fixed_along_segment,
                        GradientBlocks blocks = GradientBlocks::all) {
  const TransferFunctions& tf = prep.transfer();
  for (int c = 0; c < kChannels; ++c)
    if (!std::isfinite(ray.background[c]))
      throw std::invalid_argument("gradient: background must be finite");
  if (!all_finite(ray.segments))
    for (std::size_t j = 0; j < ray.segments.size(); ++j) {
      const Segment& seg = ray.segments[j];
      if (!(std::isfinite(seg.length) && std::isfinite(seg.scalar_far) && std::isfinite(seg.scalar_exit)))
        throw std::invalid_argument("gradient: segment " + std::to_string(j) +
                                    ": length and scalars must be finite");
    }
  // Per-thread scratch: no allocation per ray once warm (timing loops, images).
  struct Scratch {
    PieceChannelColumns columns;  // the pieces' inputs, written by the splitter
    std::vector<PiecePlace> places;
    std::vector<double> incoming;
    IntervalSums rho_sums[kChannels], kappa_sums[kChannels];
  };
  thread_local Scratch scratch;
  const PieceSplitter& splitter = prep.splitter();
  PieceChannelColumns& columns = scratch.columns;
  columns.clear();
  splitter.append(ray.segments, columns, scratch.places);
  const std::vector<PiecePlace>& places = scratch.places;
  const std::size_t n = places.size();

  const bool nodes_wanted = blocks == GradientBlocks::all;
  grad.reset(tf, ray);
  if (!nodes_wanted)
    for (int c = 0; c < kChannels; ++c) {
      grad.density[c].clear();
      grad.color[c].clear();
    }
  const bool jumps = prep.jumps();
  // Every channel's density is the same function (bit for bit): one depth per piece.
  const bool grey = prep.grey();
  // The scalar whose interval a piece's values come from, per function: lo, the smaller end,
  // except for a constant piece on a jump, which takes the left value (operator()): the interval
  // below.
  const auto interval_lo = [jumps](const PiecewiseLinear& f, const PieceRecord& pr, double lo) {
    return jumps && pr.s_far == pr.s_exit && jump_node(f, lo) != kNoJump
               ? std::nextafter(lo, -std::numeric_limits<double>::infinity())
               : lo;
  };
  // Per function, its interval for each region of the breakpoints and its slope per interval
  // (GradientPreparation): for kappa_far - kappa_exit and the reverse pass.
  const double* rho_slope[kChannels];
  const double* kappa_slope[kChannels];
  const std::uint32_t* rho_interval[kChannels];
  const std::uint32_t* kappa_interval[kChannels];
  for (int c = 0; c < kChannels; ++c) {
    rho_slope[c] = prep.slopes(static_cast<std::size_t>(c));
    kappa_slope[c] = prep.slopes(static_cast<std::size_t>(kChannels + c));
    rho_interval[c] = prep.region_interval(static_cast<std::size_t>(c));
    kappa_interval[c] = prep.region_interval(static_cast<std::size_t>(kChannels + c));
  }
  std::vector<double>& incoming = scratch.incoming;
  if (incoming.size() < n * kChannels) incoming.resize(n * kChannels);
  // The interval of a constant piece (a search; the value itself is the splitter's).
  const auto constant_interval = [&](const PiecewiseLinear& f, const PieceRecord& pr) {
    return static_cast<std::uint32_t>(
        std::upper_bound(f.scalar.begin(), f.scalar.end(), interval_lo(f, pr, pr.s_far)) - f.scalar.begin());
  };
  // The pieces go to the source in chunks of kChunkPieces (their inputs and the batch's scratch
  // stay in cache however long the ray), each composited as soon as it is evaluated. What the
  // reverse pass needs of a piece-channel is kept for the whole ray: the light entering it, and
  // what the source keeps. (Keeping them for one chunk only and forming every other chunk again
  // in the reverse pass, to spare the memory traffic of a long ray's ~5 MB, cost more than it
  // saved: 8.8 -> 10.2 ms on bench_grad's set 1.)
  constexpr std::size_t kChunkPieces = 512;
  // A piece's record (where its ends lie along its segment: the divisions of append_pieces'), formed
  // where it is used (the reverse pass, once per piece) from its place and its segment instead of
  // being kept for the whole ray: a piece's far end is the previous one's exit, so its phi_far is
  // that piece's phi_exit, the same division.
  const auto record = [&](std::size_t k) {
    const PiecePlace& pl = places[k];
    const Segment& seg = ray.segments[pl.segment];
    const double s0 = seg.scalar_far, s1 = seg.scalar_exit;
    PieceRecord pr;
    pr.segment = pl.segment;
    pr.s_far = pl.s_far;
    pr.s_exit = pl.s_exit;
    pr.length = columns.length[k * kChannels];
    if (s0 == s1) {  // a constant piece: one per segment, the whole of it
      pr.region = kConstantPiece;
      return pr;
    }
    const double span = s1 - s0;
    pr.region = pl.region;
    pr.span = span;
    pr.far_is_end = pl.s_far == s0;
    pr.exit_is_end = pl.s_exit == s1;
    // one piece: the fraction is exactly 1 (append_pieces' span / span)
    pr.fraction = pr.far_is_end && pr.exit_is_end ? 1.0 : (pl.s_exit - pl.s_far) / span;
    pr.phi_exit = pr.exit_is_end ? 1.0 : (pl.s_exit - s0) / span;
    pr.phi_far = pr.far_is_end ? 0.0 : (pl.s_far - s0) / span;
    return pr;
  };
  const std::size_t n_chunks = (n + kChunkPieces - 1) / kChunkPieces;
  // Forward: the optics of every piece-channel and the light entering it.
  source.start(n * kChannels, grey);
  Rgb intensity = ray.background;
  for (std::size_t q = 0; q < n_chunks; ++q) {
    const std::size_t k0 = q * kChunkPieces, k1 = std::min(n, k0 + kChunkPieces);
    const std::size_t i0 = k0 * kChannels, m = (k1 - k0) * kChannels;
    source.evaluate(PieceColumns{columns.length.data() + i0, columns.rho_far.data() + i0,
                                 columns.rho_exit.data() + i0, columns.kappa_far.data() + i0,
                                 columns.kappa_exit.data() + i0, m},
                    i0);
    for (std::size_t k = k0; k < k1; ++k)
      for (int c = 0; c < kChannels; ++c) {
        incoming[k * kChannels + static_cast<std::size_t>(c)] = intensity[c];
        intensity[c] = intensity[c] * source.transmittance(k, c) + source.emission(k, c);
      }
  }
  grad.intensity = intensity;

  // Reverse: adjoint = transmittance of everything nearer than the piece. The node entries are
  // summed per interval (IntervalSums) and formed after the pass; the slopes come from a table.
  IntervalSums* rho_sums = scratch.rho_sums;
  IntervalSums* kappa_sums = scratch.kappa_sums;
  if (nodes_wanted)
    for (int c = 0; c < kChannels; ++c) {
      rho_sums[c].reset(tf.density[c], rho_slope[c]);
      kappa_sums[c].reset(tf.color[c], kappa_slope[c]);
    }
  Rgb adjoint{1.0, 1.0, 1.0};
  // The arrays read and the blocks written, as local pointers: the pass's rare calls (a jump's
  // crossing) would otherwise make every piece reload them from the scratch and the gradient.
  const double* const piece_light = incoming.data();
  const double* const in_length = columns.length.data();
  const double* const in_rho_far = columns.rho_far.data();
  const double* const in_rho_exit = columns.rho_exit.data();
  const double* const in_kappa_far = columns.kappa_far.data();
  const double* const in_kappa_exit = columns.kappa_exit.data();
  Rgb* const length_block = grad.length.data();
  Rgb* const scalar_far_block = grad.scalar_far.data();
  Rgb* const scalar_exit_block = grad.scalar_exit.data();
  for (std::size_t k = n; k-- > 0;) {
    const PieceRecord pr = record(k);
    // the piece before it in the same segment, for a jump crossed between them
    const bool crossing = jumps && !pr.far_is_end && k > 0;
    const PieceRecord before = crossing ? record(k - 1) : PieceRecord{};
    Rgb& seg_length = length_block[pr.segment];
    Rgb& scalar_far = scalar_far_block[pr.segment];
    Rgb& scalar_exit = scalar_exit_block[pr.segment];
    const bool constant = pr.region == kConstantPiece;
    const double ds = pr.s_far - pr.s_exit;
    for (int c = 0; c < kChannels; ++c) {
      const std::size_t i = k * kChannels + static_cast<std::size_t>(c);
      // The intervals the piece's values come from: by the region of the breakpoints it lies in,
      // or by a search for a constant piece (no slope: kappa_far - kappa_exit is 0). Else
      // kappa_far - kappa_exit from the interval's slope: the difference of the rounded end
      // values loses its digits on short pieces (narrow_pulse: 4% of a 1e-14 difference,
      // multiplied by a density slope of 3e23 in dI/ds). The extensions have slope 0.
      std::uint32_t rho_k, kappa_k;
      double dkappa;
      if (constant) {
        rho_k = constant_interval(tf.density[c], pr);
        kappa_k = constant_interval(tf.color[c], pr);
        dkappa = 0.0;
      } else {
        rho_k = rho_interval[c][pr.region];
        kappa_k = kappa_interval[c][pr.region];
        dkappa = kappa_slope[c][kappa_k] * ds;
      }
      const ChannelPiece p{in_length[i], in_rho_far[i], in_rho_exit[i], in_kappa_far[i], in_kappa_exit[i]};
      const PieceDerivatives g = source.derivatives(k, c, p, dkappa);
      const double light = piece_light[i];
      const double e_bar = adjoint[c];
      const double t_bar = adjoint[c] * light;
      const double len_bar = e_bar * g.de_length + t_bar * g.dt_length;
      const double rho_far_bar = e_bar * g.de_rho_far + t_bar * g.dt_rho;
      const double rho_exit_bar = e_bar * g.de_rho_exit + t_bar * g.dt_rho;
      const double kappa_far_bar = e_bar * g.de_kappa_far;
      const double kappa_exit_bar = e_bar * g.de_kappa_exit;
      // Length: len = L * (fraction of the segment); the fraction does not depend on L.
      seg_length[c] += len_bar * pr.fraction;
      // End values through the transfer functions: the node entries (IntervalSums) and the end
      // scalars, differentiated as points fixed along the segment (s = s_far + phi (s_exit -
      // s_far)) with fixed piece lengths: the same first derivative as moving the piece ends
      // with the breakpoints (a kink moved by delta inside a piece changes I by O(delta^2)),
      // without the factor L/(s_exit - s_far) and the cancellation between the two pieces at a
      // breakpoint that the latter carries (it cost 1e-6 of the channel's largest entry on a
      // 7e-13-wide segment of narrow_pulse). d f/d s at both ends is the interval's slope.
      const double rho_slope_k = rho_slope[c][rho_k], kappa_slope_k = kappa_slope[c][kappa_k];
      const double far_s_bar = rho_far_bar * rho_slope_k + kappa_far_bar * kappa_slope_k;
      const double exit_s_bar = rho_exit_bar * rho_slope_k + kappa_exit_bar * kappa_slope_k;
      if (nodes_wanted) {
        rho_sums[c].add(rho_k, pr.s_far, rho_far_bar, pr.s_exit, rho_exit_bar);
        kappa_sums[c].add(kappa_k, pr.s_far, kappa_far_bar, pr.s_exit, kappa_exit_bar);
      }
      if (ends_mode == PieceEnds::fixed_along_segment) {
        scalar_far[c] += far_s_bar * (1.0 - pr.phi_far) + exit_s_bar * (1.0 - pr.phi_exit);
        scalar_exit[c] += far_s_bar * pr.phi_far + exit_s_bar * pr.phi_exit;
      } else {
        moving_ends(tf, ray, pr, c, len_bar, far_s_bar, exit_s_bar, nodes_wanted, jumps, grad);
      }
      adjoint[c] *= g.transmittance;
      if (crossing)
        add_jump_crossing(tf, ray, before, pr, c, light, adjoint[c], grad,
                          ends_mode == PieceEnds::fixed_along_segment, nodes_wanted);
    }
  }
  grad.background = adjoint;
  if (nodes_wanted)
    for (int c = 0; c < kChannels; ++c) {
      rho_sums[c].flush(grad.density[c]);
      kappa_sums[c].flush(grad.color[c]);
    }
  if (jumps) {
    if (nodes_wanted) tie_jump_positions(tf, grad.density, grad.color);
    mark_jump_tangencies(tf, ray, grad, nodes_wanted);
  }
}

template <class PieceSource>
void chain_ray_gradient(const TransferFunctions& tf, const Ray& ray, RayGradient& grad, PieceSource& source,
                        PieceEnds ends_mode = PieceEnds::fixed_along_segment,
                        GradientBlocks blocks = GradientBlocks::all) {
  chain_ray_gradient(thread_preparation(tf), ray, grad, source, ends_mode, blocks);
}

}  // namespace rayint::detail
