#include "rayint/model/pieces.hpp"

#include <algorithm>

namespace rayint {
namespace {

Piece make_piece(const TransferFunctions& tf, double length, double s_far, double s_exit) {
  Piece p;
  p.length = length;
  p.scalar_far = s_far;
  p.scalar_exit = s_exit;
  for (int c = 0; c < kChannels; ++c) {
    p.rho_far[c] = tf.density[c](s_far);
    p.rho_exit[c] = tf.density[c](s_exit);
    p.kappa_far[c] = tf.color[c](s_far);
    p.kappa_exit[c] = tf.color[c](s_exit);
  }
  return p;
}

}  // namespace

void append_pieces(const TransferFunctions& tf, const Segment& seg,
                   const std::vector<double>& breakpoints, std::vector<Piece>& out) {
  if (!(seg.length > 0.0)) return;
  const double s0 = seg.scalar_far, s1 = seg.scalar_exit;
  if (s0 == s1) {  // w = 0: the scalar, and so every transfer function, is constant
    out.push_back(make_piece(tf, seg.length, s0, s1));
    return;
  }
  // Breakpoints strictly inside (min, max), visited in the direction of travel far -> near.
  const double lo = std::min(s0, s1), hi = std::max(s0, s1);
  auto first = std::upper_bound(breakpoints.begin(), breakpoints.end(), lo);
  auto last = std::lower_bound(breakpoints.begin(), breakpoints.end(), hi);
  std::vector<double> ends;
  ends.reserve(static_cast<std::size_t>(last - first) + 2);
  ends.push_back(s0);
  if (s0 < s1) {
    ends.insert(ends.end(), first, last);
  } else {
    ends.insert(ends.end(), std::make_reverse_iterator(last), std::make_reverse_iterator(first));
  }
  ends.push_back(s1);
  // Fraction of the segment first, then the length: L / (s1 - s0) overflows when the scalar
  // span is tiny (a span of one denormal over L = 24 gave inf pieces in `rayint stress`), while
  // the fraction is always in [0, 1]. Differences of nearby breakpoints are exact (Sterbenz).
  const double span = s1 - s0;
  for (std::size_t k = 0; k + 1 < ends.size(); ++k) {
    const double len = seg.length * ((ends[k + 1] - ends[k]) / span);
    if (len > 0.0) out.push_back(make_piece(tf, len, ends[k], ends[k + 1]));
  }
}

std::vector<Piece> split_ray(const TransferFunctions& tf, const Ray& ray) {
  const std::vector<double> bps = tf.breakpoints();
  std::vector<Piece> pieces;
  for (const auto& seg : ray.segments) append_pieces(tf, seg, bps, pieces);
  return pieces;
}


PieceSplitter::PieceSplitter(const TransferFunctions& tf) : tf_(&tf), breakpoints_(tf.breakpoints()) {
  const std::size_t m = breakpoints_.size();
  knot_values_.resize(m);
  interval_.resize(m);
  for (std::size_t j = 0; j < m; ++j) {
    for (int f = 0; f < kFunctions; ++f) {
      const PiecewiseLinear& fn = function(f);
      knot_values_[j][static_cast<std::size_t>(f)] = fn(breakpoints_[j]);
      // For s in [bp[j-1], bp[j]) no breakpoint of fn lies in (bp[j-1], s], so upper_bound(s)
      // is upper_bound(bp[j-1]).
      if (j > 0)
        interval_[j][static_cast<std::size_t>(f)] = static_cast<std::size_t>(
            std::upper_bound(fn.scalar.begin(), fn.scalar.end(), breakpoints_[j - 1]) - fn.scalar.begin());
    }
  }
}

PieceSplitter::Values PieceSplitter::at(double s) const {
  Values v;
  const std::size_t m = breakpoints_.size();
  if (!(s > breakpoints_.front() && s < breakpoints_.back())) {  // outside, at an end, NaN
    for (int f = 0; f < kFunctions; ++f) v[static_cast<std::size_t>(f)] = function(f)(s);
    return v;
  }
  std::size_t j = 1;  // bp[j-1] <= s < bp[j], 1 <= j < m
  if (m <= 8) {
    while (breakpoints_[j] <= s) ++j;
  } else {
    j = static_cast<std::size_t>(std::upper_bound(breakpoints_.begin(), breakpoints_.end(), s) - breakpoints_.begin());
  }
  if (s == breakpoints_[j - 1]) return knot_values_[j - 1];
  // operator()'s clamps, then PiecewiseLinear::interpolate's arithmetic on the interval it would
  // find (s0 < s there, so its s == s0 case cannot occur), for the six functions at once and
  // without a jump per function: which end is nearer is unpredictable. A clamped function gets
  // its constant (the line computed for it, on this interval of breakpoints, is discarded).
  double s0[kFunctions], s1[kFunctions], v0[kFunctions], v1[kFunctions], clamp[kFunctions];
  bool clamped[kFunctions];
  for (int f = 0; f < kFunctions; ++f) {
    const PiecewiseLinear& fn = function(f);
    clamped[f] = true;
    s0[f] = breakpoints_[j - 1];
    s1[f] = breakpoints_[j];
    v0[f] = v1[f] = 0.0;
    if (s <= fn.scalar.front()) {
      clamp[f] = fn.value.front();
    } else if (s >= fn.scalar.back()) {
      clamp[f] = fn.value.back();
    } else {
      const std::size_t k = interval_[j][static_cast<std::size_t>(f)];
      clamped[f] = false;
      clamp[f] = 0.0;
      s0[f] = fn.scalar[k - 1];
      s1[f] = fn.scalar[k];
      v0[f] = fn.value[k - 1];
      v1[f] = fn.value[k];
    }
  }
  for (int f = 0; f < kFunctions; ++f) {
    const double d0 = s - s0[f], d1 = s1[f] - s, span = s1[f] - s0[f];
    const bool near0 = d0 <= d1;
    const double d = near0 ? d0 : d1, base = near0 ? v0[f] : v1[f], other = near0 ? v1[f] : v0[f];
    const double line = base + (d / span) * (other - base);
    v[static_cast<std::size_t>(f)] = clamped[f] ? clamp[f] : line;
  }
  return v;
}

void PieceSplitter::append(const Segment& seg, std::vector<Piece>& out) const {
  // The steps of append_pieces (above), with the ends evaluated through at()/at_breakpoint().
  if (!(seg.length > 0.0)) return;
  const double s0 = seg.scalar_far, s1 = seg.scalar_exit;
  const auto put = [&out](double length, double s_far, double s_exit, const Values& far, const Values& exit) {
    Piece& p = out.emplace_back();
    p.length = length;
    p.scalar_far = s_far;
    p.scalar_exit = s_exit;
    for (std::size_t c = 0; c < kChannels; ++c) {
      p.rho_far[c] = far[c];
      p.rho_exit[c] = exit[c];
      p.kappa_far[c] = far[c + kChannels];
      p.kappa_exit[c] = exit[c + kChannels];
    }
  };
  if (s0 == s1) {
    const Values v = at(s0);
    put(seg.length, s0, s1, v, v);
    return;
  }
  const double lo = std::min(s0, s1), hi = std::max(s0, s1);
  const auto first = static_cast<std::size_t>(
      std::upper_bound(breakpoints_.begin(), breakpoints_.end(), lo) - breakpoints_.begin());
  const auto last = static_cast<std::size_t>(
      std::lower_bound(breakpoints_.begin(), breakpoints_.end(), hi) - breakpoints_.begin());
  const double span = s1 - s0;
  double s_prev = s0;
  Values v_prev = at(s0);
  const std::size_t inner = last > first ? last - first : 0;
  for (std::size_t k = 0; k < inner; ++k) {  // interior ends, in the direction of travel
    const std::size_t j = s0 < s1 ? first + k : last - 1 - k;
    const double s = breakpoints_[j];
    const Values v = at_breakpoint(j);
    const double len = seg.length * ((s - s_prev) / span);
    if (len > 0.0) put(len, s_prev, s, v_prev, v);
    s_prev = s;
    v_prev = v;
  }
  const double len = seg.length * ((s1 - s_prev) / span);
  if (len > 0.0) put(len, s_prev, s1, v_prev, at(s1));
}

const std::vector<Piece>& PieceSplitter::pieces(const Segment& segment) const {
  thread_local std::vector<Piece> buffer;
  buffer.clear();
  append(segment, buffer);
  return buffer;
}

}  // namespace rayint
