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


PieceSplitter::PieceSplitter(const TransferFunctions& tf) : tf_(&tf), breakpoints_(tf.breakpoints()) {}

const std::vector<Piece>& PieceSplitter::pieces(const Segment& segment) const {
  thread_local std::vector<Piece> buffer;
  buffer.clear();
  append_pieces(*tf_, segment, breakpoints_, buffer);
  return buffer;
}

}  // namespace rayint
