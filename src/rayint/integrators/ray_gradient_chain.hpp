#pragma once
// ray_gradient_chain.hpp -- private helper of the ray gradients whose per-piece optics have the
// form of exact.cpp's (emission and transmittance of a piece on which rho and kappa are linear):
// exact_grad.cpp (the exact piece) and psi_table_grad.cpp (Psi read from a table). It splits the
// segments into append_pieces' pieces, composites far -> near and differentiates in reverse,
// carrying each piece's derivatives (PieceOpticsGrad) to the lengths, end scalars, background and
// transfer-function nodes. The mathematics and the kink convention: docs/gradients.md, "Through
// the splitting and the compositing".
#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "rayint/integrators/exact_grad.hpp"
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
};

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

// The values of f at a piece's two ends from k = upper_bound(f.scalar, lo), for a piece lo < hi
// with no breakpoint strictly inside (append_pieces'): at lo the limit from above, at hi the
// limit from below (the limits from inside the piece), bit for bit PiecewiseLinear::limit's --
// its searches return this same k (scalar[k-1] <= lo < hi <= scalar[k]) -- without searching.
inline double limit_above_in(const PiecewiseLinear& f, std::size_t k, double lo) {
  if (k == 0) return f.value.front();
  if (k == f.scalar.size()) return f.value.back();
  return f.interpolate(lo, k);
}
inline double limit_below_in(const PiecewiseLinear& f, std::size_t k, double hi) {
  if (k == 0) return f.value.front();
  if (k == f.scalar.size()) return f.value.back();
  return f.scalar[k] == hi ? f.value[k] : f.interpolate(hi, k);
}

// piece_grad(const ChannelPiece&, double kappa_far_minus_exit, const PieceOpticsGrad* same_depth)
// -> PieceOpticsGrad: the optics of one channel of one piece and their derivatives. same_depth is
// non-null when the piece's length, rho_far and rho_exit are those of an earlier channel's result
// it points to (a grey medium, TransferFunctions::grey): a piece_grad may reuse what depends on
// them alone, or ignore it. blocks = GradientBlocks::segments leaves the node blocks empty and
// skips their accumulation. Throws std::invalid_argument for a non-finite length, scalar or
// background.
template <class PieceGrad>
void chain_ray_gradient(const TransferFunctions& tf, const Ray& ray, RayGradient& grad, PieceGrad&& piece_grad,
                        PieceEnds ends_mode = PieceEnds::fixed_along_segment,
                        GradientBlocks blocks = GradientBlocks::all) {
  for (int c = 0; c < kChannels; ++c)
    if (!std::isfinite(ray.background[c]))
      throw std::invalid_argument("gradient: background must be finite");
  // The interval of density[c] and color[c] (upper_bound of the scalar that chooses it, see
  // interval_lo below) a piece-channel's values come from.
  struct Intervals {
    std::size_t rho = 0, kappa = 0;
  };
  // Per-thread scratch: no allocation per ray once warm (timing loops, images).
  struct Scratch {
    std::vector<double> breakpoints, ends, incoming;
    std::vector<PieceRecord> pieces;
    std::vector<PieceOpticsGrad> optics;
    std::vector<Intervals> intervals;
  };
  thread_local Scratch scratch;
  std::vector<double>& breakpoints = scratch.breakpoints;
  breakpoints.clear();
  for (const auto* group : {&tf.density, &tf.color})
    for (const PiecewiseLinear& f : *group) breakpoints.insert(breakpoints.end(), f.scalar.begin(), f.scalar.end());
  std::sort(breakpoints.begin(), breakpoints.end());
  breakpoints.erase(std::unique(breakpoints.begin(), breakpoints.end()), breakpoints.end());
  std::vector<PieceRecord>& pieces = scratch.pieces;
  pieces.clear();
  std::vector<double>& ends = scratch.ends;
  for (std::size_t j = 0; j < ray.segments.size(); ++j) {
    const Segment& seg = ray.segments[j];
    if (!(std::isfinite(seg.length) && std::isfinite(seg.scalar_far) && std::isfinite(seg.scalar_exit)))
      throw std::invalid_argument("gradient: segment " + std::to_string(j) +
                                  ": length and scalars must be finite");
    if (!(seg.length > 0.0)) continue;
    const double s0 = seg.scalar_far, s1 = seg.scalar_exit;
    if (s0 == s1) {
      pieces.push_back({j, s0, s1, seg.length, 1.0, 0.0, 1.0, true, true, 0.0});
      continue;
    }
    // append_pieces' ends: s0, the breakpoints strictly inside, s1, in the direction of travel.
    const double lo = std::min(s0, s1), hi = std::max(s0, s1);
    auto first = std::upper_bound(breakpoints.begin(), breakpoints.end(), lo);
    auto last = std::lower_bound(breakpoints.begin(), breakpoints.end(), hi);
    ends.assign(1, s0);
    if (s0 < s1)
      ends.insert(ends.end(), first, last);
    else
      ends.insert(ends.end(), std::make_reverse_iterator(last), std::make_reverse_iterator(first));
    ends.push_back(s1);
    const double span = s1 - s0;
    const std::size_t n_ends = ends.size();
    for (std::size_t k = 0; k + 1 < n_ends; ++k) {
      const double fraction = (ends[k + 1] - ends[k]) / span;
      const double len = seg.length * fraction;
      if (len > 0.0)
        pieces.push_back({j, ends[k], ends[k + 1], len, n_ends == 2 ? 1.0 : fraction,
                          k == 0 ? 0.0 : (ends[k] - s0) / span, k + 2 == n_ends ? 1.0 : (ends[k + 1] - s0) / span,
                          k == 0, k + 2 == n_ends, span});
    }
  }

  const bool nodes_wanted = blocks == GradientBlocks::all;
  grad.reset(tf, ray);
  if (!nodes_wanted)
    for (int c = 0; c < kChannels; ++c) {
      grad.density[c].clear();
      grad.color[c].clear();
    }
  const bool jumps = tf.has_jump();
  // Every channel's density is the same function (bit for bit): one depth per piece.
  const bool grey = tf.grey();
  const auto upper = [](const PiecewiseLinear& f, double x) {
    return static_cast<std::size_t>(std::upper_bound(f.scalar.begin(), f.scalar.end(), x) - f.scalar.begin());
  };
  // The scalar whose interval a piece's values come from, per function: lo, the smaller end,
  // except for a constant piece on a jump, which takes the left value (operator()): the interval
  // below.
  const auto interval_lo = [jumps](const PiecewiseLinear& f, const PieceRecord& pr, double lo) {
    return jumps && pr.s_far == pr.s_exit && jump_node(f, lo) != kNoJump
               ? std::nextafter(lo, -std::numeric_limits<double>::infinity())
               : lo;
  };
  const std::size_t n = pieces.size();
  // Forward: the optics of every piece-channel and the light entering it.
  std::vector<PieceOpticsGrad>& optics = scratch.optics;
  std::vector<double>& incoming = scratch.incoming;
  std::vector<Intervals>& intervals = scratch.intervals;
  if (optics.size() < n * kChannels) {
    optics.resize(n * kChannels);
    incoming.resize(n * kChannels);
    intervals.resize(n * kChannels);
  }
  Rgb intensity = ray.background;
  for (std::size_t k = 0; k < n; ++k) {
    const PieceRecord& pr = pieces[k];
    const bool constant = pr.s_far == pr.s_exit;
    const double lo = std::min(pr.s_far, pr.s_exit), hi = std::max(pr.s_far, pr.s_exit);
    const bool far_is_lo = pr.s_far < pr.s_exit;
    double rho_lo = 0.0, rho_hi = 0.0;
    for (int c = 0; c < kChannels; ++c) {
      const std::size_t i = k * kChannels + static_cast<std::size_t>(c);
      const PiecewiseLinear& rho = tf.density[c];
      const PiecewiseLinear& kappa = tf.color[c];
      Intervals& iv = intervals[i];
      double kappa_lo, kappa_hi;
      // Each end takes the limit from inside the piece (append_pieces': at a jump the value on
      // the piece's side); a constant piece takes operator()'s, the left value at a jump.
      // kappa_far - kappa_exit from the interval's slope: the difference of the rounded end
      // values loses its digits on short pieces (narrow_pulse: 4% of a 1e-14 difference,
      // multiplied by a density slope of 3e23 in dI/ds).
      // (A constant piece has s_far == s_exit: no difference at all.)
      double dkappa = 0.0;
      if (constant) {
        if (!(grey && c > 0)) {
          iv.rho = upper(rho, interval_lo(rho, pr, lo));
          rho_lo = rho_hi = rho(lo);
        }
        iv.kappa = upper(kappa, interval_lo(kappa, pr, lo));
        kappa_lo = kappa_hi = kappa(lo);
      } else {
        if (!(grey && c > 0)) {
          iv.rho = upper(rho, lo);
          rho_lo = limit_above_in(rho, iv.rho, lo);
          rho_hi = limit_below_in(rho, iv.rho, hi);
        }
        iv.kappa = upper(kappa, lo);
        kappa_lo = limit_above_in(kappa, iv.kappa, lo);
        kappa_hi = limit_below_in(kappa, iv.kappa, hi);
        dkappa = interval_slope(kappa, iv.kappa) * (pr.s_far - pr.s_exit);  // 0 on the extensions
      }
      if (grey && c > 0) iv.rho = intervals[i - static_cast<std::size_t>(c)].rho;
      const ChannelPiece cp{pr.length, far_is_lo ? rho_lo : rho_hi, far_is_lo ? rho_hi : rho_lo,
                            far_is_lo ? kappa_lo : kappa_hi, far_is_lo ? kappa_hi : kappa_lo};
      optics[i] = piece_grad(cp, dkappa, grey && c > 0 ? &optics[i - static_cast<std::size_t>(c)] : nullptr);
      incoming[i] = intensity[c];
      intensity[c] = intensity[c] * optics[i].optics.transmittance + optics[i].optics.emission;
    }
  }
  grad.intensity = intensity;

  // Reverse: adjoint = transmittance of everything nearer than the piece.
  Rgb adjoint{1.0, 1.0, 1.0};
  for (std::size_t k = n; k-- > 0;) {
    const PieceRecord& pr = pieces[k];
    for (int c = 0; c < kChannels; ++c) {
      const std::size_t i = k * kChannels + static_cast<std::size_t>(c);
      const PieceOpticsGrad& g = optics[i];
      const double e_bar = adjoint[c];
      const double t_bar = adjoint[c] * incoming[i];
      const double len_bar = e_bar * g.de_length + t_bar * g.dt_length;
      const double rho_far_bar = e_bar * g.de_rho_far + t_bar * g.dt_rho_far;
      const double rho_exit_bar = e_bar * g.de_rho_exit + t_bar * g.dt_rho_exit;
      const double kappa_far_bar = e_bar * g.de_kappa_far;
      const double kappa_exit_bar = e_bar * g.de_kappa_exit;
      // Length: len = L * (fraction of the segment); the fraction does not depend on L.
      grad.length[pr.segment][c] += len_bar * pr.fraction;
      // Moving ends: s_bar at an end goes to the segment's end scalar or the breakpoint's node.
      const auto route = [&](bool far_side, double e, double s_bar) {
        if (far_side ? pr.far_is_end : pr.exit_is_end) {
          (far_side ? grad.scalar_far : grad.scalar_exit)[pr.segment][c] += s_bar;
          return;
        }
        if (!nodes_wanted) return;
        // A jump owns its breakpoint: moving it moves the crossing (the split); another
        // function's node at the same scalar moved alone leaves the split there.
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
      if (ends_mode == PieceEnds::moving && pr.span != 0.0 && pr.fraction != 1.0) {
        // len = L (e_exit - e_far) / (s_exit - s_far): through both ends and through the span.
        const double per_end = len_bar * ray.segments[pr.segment].length / pr.span;
        route(false, pr.s_exit, per_end);
        route(true, pr.s_far, -per_end);
        const double per_span = len_bar * pr.length / pr.span;
        grad.scalar_far[pr.segment][c] += per_span;
        grad.scalar_exit[pr.segment][c] -= per_span;
      }
      // End values through the transfer functions. The end scalars are differentiated as points
      // fixed along the segment (s = s_far + phi (s_exit - s_far)) with fixed piece lengths: the
      // same first derivative as moving the piece ends with the breakpoints (a kink moved by
      // delta inside a piece changes I by O(delta^2)), without the factor L/(s_exit - s_far)
      // and the cancellation between the two pieces at a breakpoint that the latter carries
      // (it cost 1e-6 of the channel's largest entry on a 7e-13-wide segment of narrow_pulse).
      // k_f: the interval the piece's values come from (the forward's).
      const auto through = [&](const PiecewiseLinear& f, std::vector<NodeDerivative>& nodes, std::size_t k_f,
                               double s, double bar, double phi) {
        if (bar == 0.0) return;
        double slope;
        if (nodes_wanted) {
          const NodeWeights nw = node_weights_in(f, k_f, s);
          for (int q = 0; q < nw.count; ++q) {
            nodes[nw.node[q]].value += bar * nw.w[q];
            nodes[nw.node[q]].position += bar * nw.dp[q];
          }
          slope = nw.slope;
        } else {
          slope = interval_slope(f, k_f);
        }
        const double s_bar = bar * slope;
        if (s_bar == 0.0) return;
        if (ends_mode == PieceEnds::moving) {
          route(s == pr.s_far && phi == pr.phi_far, s, s_bar);
          return;
        }
        grad.scalar_far[pr.segment][c] += s_bar * (1.0 - phi);
        grad.scalar_exit[pr.segment][c] += s_bar * phi;
      };
      const Intervals& iv = intervals[i];
      through(tf.density[c], grad.density[c], iv.rho, pr.s_far, rho_far_bar, pr.phi_far);
      through(tf.density[c], grad.density[c], iv.rho, pr.s_exit, rho_exit_bar, pr.phi_exit);
      through(tf.color[c], grad.color[c], iv.kappa, pr.s_far, kappa_far_bar, pr.phi_far);
      through(tf.color[c], grad.color[c], iv.kappa, pr.s_exit, kappa_exit_bar, pr.phi_exit);
      adjoint[c] *= g.optics.transmittance;
      if (jumps && !pr.far_is_end && k > 0)
        add_jump_crossing(tf, ray, pieces[k - 1], pr, c, incoming[i], adjoint[c], grad,
                          ends_mode == PieceEnds::fixed_along_segment, nodes_wanted);
    }
  }
  grad.background = adjoint;
  if (jumps) {
    if (nodes_wanted) tie_jump_positions(tf, grad.density, grad.color);
    mark_jump_tangencies(tf, ray, grad, nodes_wanted);
  }
}

}  // namespace rayint::detail
