#include "rayint/model/pieces.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "rayint/core/lanes.hpp"

namespace rayint {
namespace {

// Each end takes the one-sided limit from inside the piece (the far end from the exit's side);
// a piece of constant scalar takes the value at that scalar (at a jump, the left one).
Piece make_piece(const TransferFunctions& tf, double length, double s_far, double s_exit) {
  Piece p;
  p.length = length;
  p.scalar_far = s_far;
  p.scalar_exit = s_exit;
  const bool up = s_far < s_exit, down = s_far > s_exit;
  for (int c = 0; c < kChannels; ++c) {
    p.rho_far[c] = tf.density[c].limit(s_far, up);
    p.rho_exit[c] = tf.density[c].limit(s_exit, down);
    p.kappa_far[c] = tf.color[c].limit(s_far, up);
    p.kappa_exit[c] = tf.color[c].limit(s_exit, down);
  }
  return p;
}

}  // namespace

void append_pieces(const TransferFunctions& tf, const Segment& seg,
                   const std::vector<double>& breakpoints, std::vector<Piece>& out) {
  if (!(seg.length > 0.0)) return;
  const double s0 = seg.scalar_far, s1 = seg.scalar_exit;
  if (s0 == s1 || std::isnan(s0) || std::isnan(s1)) {
    // w = 0: the scalar, and so every transfer function, is constant. A NaN end: one piece whose
    // values at that end are NaN (the integral comes out non-finite, and is reported so).
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


PieceSplitter::PieceSplitter(const TransferFunctions& tf) { reset(tf); }

void PieceSplitter::reset(const TransferFunctions& tf) {
  tf_ = &tf;
  grey_ = tf.grey();
  tf.breakpoints_into(breakpoints_);  // into the storage already held
  const std::size_t m = breakpoints_.size();
  padded_.fill(std::numeric_limits<double>::quiet_NaN());
  if (m <= padded_.size()) std::copy(breakpoints_.begin(), breakpoints_.end(), padded_.begin());
  // PiecewiseLinear::limit at every breakpoint, from below and from above, with lower_bound and
  // upper_bound walked along the sorted breakpoints instead of searched for each.
  at_breakpoint_.resize(m);
  above_breakpoint_.resize(m);
  for (int f = 0; f < kFunctions; ++f) {
    const PiecewiseLinear& fn = function(f);
    const std::vector<double>& x = fn.scalar;
    const std::size_t nx = x.size();
    std::size_t lower = 0, upper = 0;  // lower_bound and upper_bound of s in x
    for (std::size_t j = 0; j < m; ++j) {
      const double s = breakpoints_[j];
      while (lower < nx && x[lower] < s) ++lower;
      while (upper < nx && x[upper] <= s) ++upper;
      at_breakpoint_[j][static_cast<std::size_t>(f)] = fn.limit(s, false, lower);
      above_breakpoint_[j][static_cast<std::size_t>(f)] = fn.limit(s, true, upper);
    }
  }
  rows_.resize(2 * m + 1);
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    Row& row = rows_[r];
    for (int f = 0; f < kFunctions; ++f) {  // f: the slot
      const PiecewiseLinear& fn = function(kSlotFunction[f]);
      // A constant by default; its (unused) line operands are a harmless unit interval.
      row.s0[f] = 0.0;
      row.s1[f] = row.span[f] = 1.0;
      row.v0[f] = row.v1[f] = row.dv01[f] = row.dv10[f] = 0.0;
      row.keep[f] = -1;
      if (r % 2 == 1) {  // at breakpoint (r - 1) / 2: the stored value, as operator() returns it
        // (operator() is limit(s, false): at_breakpoint_'s entry, formed above)
        row.constant[f] = at_breakpoint_[(r - 1) / 2][static_cast<std::size_t>(kSlotFunction[f])];
      } else if (r == 0) {  // below every function's first point
        row.constant[f] = fn.value.front();
      } else if (r == 2 * m) {  // above every function's last point
        row.constant[f] = fn.value.back();
      } else {  // strictly between bp[j-1] and bp[j]: fn's first and last points are breakpoints,
                // so fn is clamped over the whole open interval or over none of it
        const std::size_t j = r / 2;
        if (fn.scalar.front() >= breakpoints_[j]) {
          row.constant[f] = fn.value.front();
        } else if (fn.scalar.back() <= breakpoints_[j - 1]) {
          row.constant[f] = fn.value.back();
        } else {
          // No breakpoint of fn lies in (bp[j-1], s], so upper_bound(s) is upper_bound(bp[j-1]),
          // and scalar[k-1] <= bp[j-1] < s: interpolate's s == s0 case cannot occur.
          const auto k = static_cast<std::size_t>(
              std::upper_bound(fn.scalar.begin(), fn.scalar.end(), breakpoints_[j - 1]) - fn.scalar.begin());
          row.keep[f] = 0;
          row.constant[f] = 0.0;
          row.s0[f] = fn.scalar[k - 1];
          row.s1[f] = fn.scalar[k];
          row.span[f] = fn.scalar[k] - fn.scalar[k - 1];
          row.v0[f] = fn.value[k - 1];
          row.v1[f] = fn.value[k];
          row.dv01[f] = fn.value[k] - fn.value[k - 1];
          row.dv10[f] = fn.value[k - 1] - fn.value[k];
        }
      }
    }
  }
  jumps_ = tf.has_jump();
}

// Slots two or four at a time: core/lanes.hpp.
namespace {
using lanes::load2;
using lanes::M2;
using lanes::M4;
using lanes::V2;
using lanes::V4;
// PiecewiseLinear::interpolate's arithmetic at s for the slots f, f + 1, ... of a splitter row, as
// many as V has lanes, into out[0..lanes); a kept constant is selected over the line. (The vectors
// stay inside: a 32-byte vector passed or returned would change the calling convention.)
template <class V, class M, class Row>
[[gnu::always_inline]] inline void interpolate_slots(const Row& row, int f, double s, double* out) {
  V s0, s1, span, v0, v1, dv01, dv10, constant;
  M keep;
  std::memcpy(&s0, row.s0 + f, sizeof s0);
  std::memcpy(&s1, row.s1 + f, sizeof s1);
  std::memcpy(&span, row.span + f, sizeof span);
  std::memcpy(&v0, row.v0 + f, sizeof v0);
  std::memcpy(&v1, row.v1 + f, sizeof v1);
  std::memcpy(&dv01, row.dv01 + f, sizeof dv01);
  std::memcpy(&dv10, row.dv10 + f, sizeof dv10);
  std::memcpy(&constant, row.constant + f, sizeof constant);
  std::memcpy(&keep, row.keep + f, sizeof keep);
  V sv;
  for (std::size_t i = 0; i < sizeof(V) / sizeof(double); ++i) sv[i] = s;
  const V d0 = sv - s0, d1 = s1 - sv;
  const M near0 = d0 <= d1;
  const V d = near0 ? d0 : d1, base = near0 ? v0 : v1, delta = near0 ? dv01 : dv10;
  const V line = base + (d / span) * delta;
  const V value = keep ? constant : line;
  std::memcpy(out, &value, sizeof value);
}
}  // namespace

[[gnu::always_inline]] inline std::size_t PieceSplitter::region(double s, std::size_t& lt, std::size_t& le) const {
  if (breakpoints_.size() <= padded_.size()) {  // count without a jump (NaN padding never counts)
    const V2 sv = {s, s};
    M2 a = {0, 0}, b = {0, 0};
    for (std::size_t i = 0; i < padded_.size(); i += 2) {
      const V2 p = load2(padded_.data() + i);
      a += p < sv;  // -1 where true
      b += p <= sv;
    }
    lt = static_cast<std::size_t>(-(a[0] + a[1]));
    le = static_cast<std::size_t>(-(b[0] + b[1]));
  } else {
    le = static_cast<std::size_t>(std::upper_bound(breakpoints_.begin(), breakpoints_.end(), s) - breakpoints_.begin());
    lt = le > 0 && breakpoints_[le - 1] == s ? le - 1 : le;
  }
  return lt + le;
}

[[gnu::always_inline]] inline void PieceSplitter::eval(const Row& row, double s, double* v) const {
  // PiecewiseLinear::interpolate's arithmetic, for four slots (rho r, kappa r, g, b) at once and
  // then two (rho g, b), without a jump (which end is nearer is unpredictable); a constant is
  // selected over the line. Written in four lanes: one AVX2 instruction in the AVX2 copy of the
  // per-ray append()s below, two SSE2 ones otherwise; the same IEEE operations in every lane.
  static_assert(kFunctions == 6 && kSlotFunction[0] == 0 && kSlotFunction[1] == 3 && kSlotFunction[4] == 1);
  double grey4[4];  // slots 0-3: rho r, kappa r, g, b
  interpolate_slots<V4, M4>(row, 0, s, grey4);
  v[0] = grey4[0];
  v[3] = grey4[1];
  v[4] = grey4[2];
  v[5] = grey4[3];
  if (grey_) {
    v[1] = v[2] = v[0];
  } else {
    interpolate_slots<V2, M2>(row, 4, s, v + 1);  // slots 4, 5: rho g, b
  }
}

[[gnu::always_inline]] inline std::size_t PieceSplitter::region(double s, std::size_t& lt, std::size_t& le,
                                                                RegionHint& hint) const {
  if (s > hint.lo && s < hint.hi) {
    lt = le = hint.j;
    return 2 * hint.j;
  }
  const std::size_t r = region(s, lt, le);
  if (lt == le) {  // strictly between breakpoints lt - 1 and lt
    constexpr double inf = std::numeric_limits<double>::infinity();
    hint.j = lt;
    hint.lo = lt > 0 ? breakpoints_[lt - 1] : -inf;
    hint.hi = lt < breakpoints_.size() ? breakpoints_[lt] : inf;
  }
  return r;
}

template <class Put>
[[gnu::always_inline]] inline long PieceSplitter::split(const Segment& seg, Put&& put, RegionHint& hint) const {
  // The steps of append_pieces (above), with the ends evaluated through the rows.
  const double s0 = seg.scalar_far, s1 = seg.scalar_exit;
  std::size_t lt0 = 0, le0 = 0, lt1 = 0, le1 = 0;
  const Row& row0 = rows_[region(s0, lt0, le0, hint)];
  alignas(16) double v_far[kFunctions];
  eval(row0, s0, v_far);
  if (s0 == s1) {
    put(seg.length, s0, s1, v_far, v_far, PiecePlace::kNoRegion);
    return 1;
  }
  const Row& row1 = rows_[region(s1, lt1, le1, hint)];
  alignas(16) double v_exit[kFunctions];
  eval(row1, s1, v_exit);
  // An end on a breakpoint (lt < le) takes the limit from inside the segment: the row holds the
  // left value, which differs only at a jump.
  if (jumps_) {
    if (s0 < s1 && lt0 < le0) std::copy_n(above_breakpoint_[lt0].data(), kFunctions, v_far);
    if (s1 < s0 && lt1 < le1) std::copy_n(above_breakpoint_[lt1].data(), kFunctions, v_exit);
  }
  // Breakpoints strictly inside (min, max): upper_bound(lo) .. lower_bound(hi).
  const std::size_t first = s0 < s1 ? le0 : le1, last = s0 < s1 ? lt1 : lt0;
  const double span = s1 - s0;
  double s_prev = s0;
  const double* v_prev = v_far;
  const std::size_t inner = last > first ? last - first : 0;
  for (std::size_t k = 0; k < inner; ++k) {  // interior ends, in the direction of travel
    const std::size_t j = s0 < s1 ? first + k : last - 1 - k;
    const double s = breakpoints_[j];
    // The piece below the breakpoint ends on its left value, the one above on its right value
    // (the same unless a function jumps there).
    const double* below = at_breakpoint_[j].data();
    const double* above = above_breakpoint_[j].data();
    const double len = seg.length * ((s - s_prev) / span);
    // the piece's interior lies between breakpoints j - 1 and j (increasing) or j and j + 1
    if (len > 0.0) put(len, s_prev, s, v_prev, s0 < s1 ? below : above, s0 < s1 ? j : j + 1);
    s_prev = s;
    v_prev = s0 < s1 ? above : below;
  }
  // Without interior ends the fraction is span / span: exactly 1 when span is finite (it is not
  // 0, s0 != s1), so that division is skipped; an overflowed span keeps inf / inf = NaN.
  const double len = inner == 0 && std::isfinite(span) ? seg.length : seg.length * ((s1 - s_prev) / span);
  // the last piece's interior: above breakpoint last - 1 (increasing), above first - 1 (decreasing)
  if (len > 0.0) put(len, s_prev, s1, v_prev, v_exit, s0 < s1 ? last : first);
  return 1 + static_cast<long>(inner);
}

void PieceSplitter::append(const Segment& seg, std::vector<Piece>& out) const {
  if (!(seg.length > 0.0)) return;
  if (std::isnan(seg.scalar_far) || std::isnan(seg.scalar_exit)) {  // no region: the plain splitting itself
    append_pieces(*tf_, seg, breakpoints_, out);
    return;
  }
  static_assert(kFunctions == 6 && kChannels == 3);  // Piece's constructor takes rho r, g, b, kappa r, g, b
  RegionHint hint;
  split(
      seg,
      [&out](double length, double s_far, double s_exit, const double* far, const double* exit, std::size_t) {
        out.emplace_back(length, s_far, s_exit, far, exit);
      },
      hint);
}

template <class Columns>
[[gnu::always_inline]] inline long PieceSplitter::append_columns(const Segment& seg, Columns& out, RegionHint& hint) const {
  if (!(seg.length > 0.0)) return 0;
  if (std::isnan(seg.scalar_far) || std::isnan(seg.scalar_exit)) {
    std::vector<Piece> pieces;
    append_pieces(*tf_, seg, breakpoints_, pieces);
    for (const Piece& p : pieces) {
      const double far[kFunctions] = {p.rho_far[0],   p.rho_far[1],   p.rho_far[2],
                                      p.kappa_far[0], p.kappa_far[1], p.kappa_far[2]};
      const double exit[kFunctions] = {p.rho_exit[0],   p.rho_exit[1],   p.rho_exit[2],
                                       p.kappa_exit[0], p.kappa_exit[1], p.kappa_exit[2]};
      out.push(p.length, far, exit);
    }
    return 1;
  }
  return split(
      seg,
      [&out](double length, double, double, const double* far, const double* exit, std::size_t) {
        out.push(length, far, exit);
      },
      hint);
}

void PieceSplitter::append(const Segment& seg, PieceChannelColumns& out) const {
  RegionHint hint;
  append_columns(seg, out, hint);
}

void PieceSplitter::append(const Segment& seg, GreyPieceColumns& out) const {
  RegionHint hint;
  append_columns(seg, out, hint);
}

// The per-ray append()s (the render's): an AVX2 copy, picked at run time where the CPU has it,
// and the baseline one. AVX2 only, not FMA: no multiply-add can be contracted, so both copies
// compute the same IEEE operations in the same order (issue 33, round 6: the splitting took ~19%
// of a mesh render). GCC 12 contracts in C++ even under -std=c++17 (its ISO-mode
// -ffp-contract=off is C's only), so a copy for a CPU with FMA (x86-64-v4, AVX-512) would not: the
// build turns contraction off for this file (src/CMakeLists.txt). Issue 33, round 20, tried and
// dropped: both ends of a segment in one 8-lane pass with an x86-64-v4 copy (one zmm division
// instead of two ymm ones): images cmp-identical (once contraction was off), but append's perf
// samples level with main's (main 556-976, 8-lane 605-1038 per render, six runs each, load 9-10):
// Zen 5's division took the same time in one zmm as in two ymm ones, and spreading the eight lanes
// back to the six functions of two ends added shuffles; the same code in the AVX2 and baseline
// copies (the 8-lane vector lowered to memory) made append ~3x slower.
template <class Columns>
[[gnu::always_inline]] inline long PieceSplitter::append_ray_columns(const std::vector<Segment>& segments,
                                                                     Columns& out) const {
  RegionHint hint;
  long count = 0;
  for (const Segment& seg : segments) count += append_columns(seg, out, hint);
  return count;
}

__attribute__((target_clones("avx2", "default"))) long PieceSplitter::append(const std::vector<Segment>& segments,
                                                                             PieceChannelColumns& out) const {
  return append_ray_columns(segments, out);
}

__attribute__((target_clones("avx2", "default"))) long PieceSplitter::append(const std::vector<Segment>& segments,
                                                                             GreyPieceColumns& out) const {
  return append_ray_columns(segments, out);
}

__attribute__((target_clones("avx2", "default"))) long PieceSplitter::append(const std::vector<Segment>& segments,
                                                                             PieceChannelColumns& out,
                                                                             std::vector<PiecePlace>& places) const {
  RegionHint hint;
  long count = 0;
  places.clear();
  for (std::size_t j = 0; j < segments.size(); ++j) {
    const Segment& seg = segments[j];
    if (!(seg.length > 0.0)) continue;
    if (!(std::isfinite(seg.scalar_far) && std::isfinite(seg.scalar_exit)))
      throw std::invalid_argument("PieceSplitter: segment " + std::to_string(j) + ": scalars must be finite");
    count += split(
        seg,
        [&](double length, double s_far, double s_exit, const double* far, const double* exit, std::size_t region) {
          out.push(length, far, exit);
          // Written field by field in place: a PiecePlace formed on the stack and copied was read
          // back in 16 bytes over two 4-byte stores, a failed store forwarding per piece (~5% of
          // a ray gradient).
          PiecePlace& place = places.emplace_back();
          place.segment = static_cast<std::uint32_t>(j);
          place.region = static_cast<std::uint32_t>(region);
          place.s_far = s_far;
          place.s_exit = s_exit;
        },
        hint);
  }
  return count;
}

void PieceChannelColumns::grow() {
  const std::size_t n = std::max<std::size_t>(64 * kChannels, 2 * length.size());
  for (auto* col : {&length, &rho_far, &rho_exit, &kappa_far, &kappa_exit}) col->resize(n);
}

void GreyPieceColumns::grow() {
  const std::size_t n = std::max<std::size_t>(64, 2 * length.size());
  for (auto* col : {&length, &rho_far, &rho_exit}) col->resize(n);
  for (std::size_t c = 0; c < kChannels; ++c) {
    kappa_far[c].resize(n);
    kappa_exit[c].resize(n);
  }
}

const std::vector<Piece>& PieceSplitter::pieces(const Segment& segment) const {
  thread_local std::vector<Piece> buffer;
  buffer.clear();
  append(segment, buffer);
  return buffer;
}

}  // namespace rayint
