// exact_batch.cpp -- the exact piece integral of exact.cpp (Williams & Max 1992, Eq. 4 with rho and
// kappa linear, Sec. 3.3) on structure-of-arrays batches, vectorised with Google Highway.
//
// The formulas, regions and thresholds are exactly those of exact.cpp (kThinDepth, kQ2Relative,
// the same series and closed forms); what differs is how they are evaluated, in chunks of 4096
// piece-channels so that every column stays in cache:
//   0. the columns are read in place (the last partial vector through a padded copy);
//      without introspection or gradient columns, each chunk first goes in piece order through
//      the thin kernel and the emission, pair of vectors by pair, while every lane of a pair is
//      thin (ThinInOrder: the render's common regime, all 13M pieces of the 105k-tet ball at
//      512^2), and steps 1-3 take the chunk from the first pair that is not, and its last
//      partial pair; the results are the same bit for bit (tests/test_exact_batch.cpp);
//   1. classification, lane-parallel (ClassifyColumns): a = rho_exit L, b = rho_far L, T, B and
//      the branch tests of exact_piece as masks; each lane is appended to its branch's columns
//      with a compressing store, and the masks are kept as bits per vector. (A scalar pass
//      that wrote each piece to its branch's columns cost a third of the batch: every store
//      waited for the previous piece's count.)
//   2. each branch's columns, padded to whole pairs of vectors with copies of the group's first
//      piece, are evaluated lane-parallel (GroupKernel):
//        thin_series  the midpoint Taylor recurrence of exact.cpp on two vectors at once until
//                     every lane met its own stop test (a lane stops accumulating at the same
//                     term as the scalar loop), weights from Expm1; pieces with T < 1/64 form a
//                     group of their own so they do not wait for the deeper ones' terms;
//        q2_series    the three-term series in B with Expm1;
//        erfcx        erfcx from special/erfcx_simd-inl.hpp (table + asymptotic, x >= 0);
//        dawson       Dawson from the same file;
//      exp(-T) is Highway's Exp (documented 1 ulp; -T below -1000 gives 0), expm1 Highway's
//      Expm1 (documented 4 ulp);
//   3. the results go back in piece order (ExpandBack): per vector, each group's lanes take the
//      group's next transmittance and weights (an expanding load on AVX-512), and the emission
//      kappa_exit w_exit + kappa_far w_far is formed there with the pieces' kappas read in order
//      (compressing the kappas into the groups cost more); transparent lanes get 1 and 0.
// For the gradient (OpticsColumns::m1 and the four columns beside it, exact_grad.hpp's
// exact_pieces_grad), the thin kernel also accumulates exact_grad.cpp's midpoint sums S_P, S_Q
// (the same recurrence, each lane stopping at the same term) and forms the moments e0, M1, M2;
// step 3 then also puts the weights and those moments back in piece order (other branches: NaN).
// Without those columns the forward kernels are unchanged (template flags).
// A grey batch (GreyPieceView: one density per piece, TransferFunctions::grey) runs steps 0-2 once
// per piece and forms the emission of each channel in step 3 from the same weights: a piece's
// a and b are every channel's, so each lane's results are the channel batch's, bit for bit.
// The run-time dispatch (HWY_DYNAMIC_DISPATCH over hwy/foreach_target.h) picks SSE4, AVX2 or
// AVX-512 on x86-64, so one binary runs on any of them; exact_batch_target() names the choice,
// and tests/test_exact_batch.cpp runs every target this CPU supports.
// Accuracy (against the 50-digit reference): `rayint stress --count 100000 --seed 1 --methods
// exact,exact:path=scalar --no-worst` gives max relative error 5.23e-14 and median 0.36 ulp over
// 104,018 pieces (scalar exact_piece in the same run: 5.25e-14, 0.406 ulp; 2026-12-03, after the
// width-1 tables); tests/test_exact_batch.cpp asserts 1e-13 in every regime, the same branch and
// series terms as exact_piece, and a median within 1 ulp of the scalar path's.
#include "rayint/integrators/exact_batch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <vector>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "rayint/integrators/exact_batch.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>
#include <hwy/contrib/math/math-inl.h>

#include "rayint/core/default_init.hpp"
#include "rayint/special/erfcx_simd-inl.hpp"

#ifndef RAYINT_EXACT_BATCH_SHARED
#define RAYINT_EXACT_BATCH_SHARED
namespace rayint::exact_batch_detail {
// Branch groups evaluated by the vector kernels (transparent pieces never reach them).
// The thin branch is split by depth: its series runs until the slowest lane of a vector pair has
// converged (about 20 terms at T = 1, 6 at T = 1e-3: the terms fall like (T/2)^n/n!), so pieces
// thinner than kShortThinDepth (at most ~8 terms) are kept apart from the others instead of
// waiting for them. 1/64 is a round power of two between the two, not tuned; the split changes
// no result, only which lanes share a vector.
enum Group : int { kThin = 0, kQ2 = 1, kErfcx = 2, kDawson = 3, kThinShort = 4, kGroups = 5 };
constexpr double kShortThinDepth = 1.0 / 64;
constexpr int kSeriesBudget = 100;  // as exact.cpp
struct Reciprocals {                // 1/(n+1), as exact.cpp
  double r[kSeriesBudget + 2];
  constexpr Reciprocals() : r() {
    for (int n = 0; n < kSeriesBudget + 2; ++n) r[n] = 1.0 / (n + 1);
  }
};
inline constexpr Reciprocals kRecip;
// For targets without AVX-512's compress/expand instructions (vectors of at most 4 doubles):
// for every mask of L lanes, the indices of its set lanes in order (compress), and each set
// lane's rank among them (expand); used with a lane permutation. (Highway 1.0.3's own emulated
// CompressStore copied a 2 KB table per call and made the AVX2 batch 5x slower than AVX-512's.)
template <std::size_t L>
struct LanePermutations {
  std::int64_t compress[1u << L][L];
  std::int64_t expand[1u << L][L];
  constexpr LanePermutations() : compress(), expand() {
    for (unsigned m = 0; m < (1u << L); ++m) {
      std::int64_t k = 0;
      for (std::size_t j = 0; j < L; ++j)
        if ((m >> j) & 1u) {
          compress[m][k] = static_cast<std::int64_t>(j);
          expand[m][j] = k++;
        }
    }
  }
};
// Where classification appends each branch's pieces: per group the columns a and b and how many
// each holds so far; and, per vector of pieces, each group's lanes as mask
// bits (kGroups + 1 slots of kMaskBytes: the last slot marks transparent pieces, which need no
// kernel), from which the results are put back in piece order.
constexpr std::size_t kMaskBytes = 8;  // up to 64 lanes
constexpr std::size_t kMaskSlots = kGroups + 1;
struct GroupSink {
  double* a[kGroups];
  double* b[kGroups];
  std::size_t count[kGroups];
  unsigned char* bits;  // [vector][slot][kMaskBytes]
};
// A group's results, in the order of its columns: transmittance, the two emission weights
// (emission = kappa_exit w_exit + kappa_far w_far, formed in piece order) and the series terms.
struct GroupResults {
  const double* tr[kGroups];
  const double* w_exit[kGroups];
  const double* w_far[kGroups];
  const double* terms[kGroups];
  // The moments of the thin lanes (M1, M2, e0: exact_grad.cpp's midpoint_moments), when asked
  // for (OpticsColumns::m1); NaN in the other groups, whose moments exact_grad.cpp forms.
  const double* m1[kGroups];
  const double* m2[kGroups];
  const double* e0[kGroups];
};
}  // namespace rayint::exact_batch_detail
#endif

HWY_BEFORE_NAMESPACE();
namespace rayint {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
using namespace exact_batch_detail;

// exact_piece's optical depths of the vector of pieces from i: a = rho_exit L, b = rho_far L and
// T = (a + b)/2, with the scalar path's operations in its order. Classification and the in-order
// thin pass (ThinInOrder) both form them here, so a lane's T and thin test agree bit for bit.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V OpticalDepths(D d, const double* HWY_RESTRICT len, const double* HWY_RESTRICT rho_far,
                           const double* HWY_RESTRICT rho_exit, std::size_t i, V& a, V& b) {
  const V length = hn::LoadU(d, len + i);
  a = hn::Mul(hn::LoadU(d, rho_exit + i), length);
  b = hn::Mul(hn::LoadU(d, rho_far + i), length);
  return hn::Mul(hn::Set(d, 0.5), hn::Add(a, b));
}

// 1. Classification, lane-parallel: a = rho_exit L, b = rho_far L, T = (a + b)/2, B = (b - a)/2
// with the scalar path's operations in its order, the branch tests of exact_piece as masks, and
// each lane appended to its branch's columns with a compressing store (no branch per piece, no
// dependency of one piece's store on the previous piece's branch); the masks are kept as bits.
// n is a multiple of the lane count; lanes at or beyond n_valid belong to no group; the masks
// are written from vector number first_vector on.
void ClassifyColumns(const double* HWY_RESTRICT len, const double* HWY_RESTRICT rho_far,
                     const double* HWY_RESTRICT rho_exit, std::size_t n, std::size_t n_valid,
                     std::size_t first_vector, GroupSink* HWY_RESTRICT sink) {
  using D = hn::ScalableTag<double>;
  const D d;
  const std::size_t L = hn::Lanes(d);
  const auto zero = hn::Zero(d), half = hn::Set(d, 0.5), thin_depth = hn::Set(d, kThinDepth),
             q2_relative = hn::Set(d, kQ2Relative);
  // The lists' ends in locals (the compressing stores could alias the sink's fields otherwise).
  double *A[kGroups], *Bc[kGroups];
  std::size_t count[kGroups];
  for (int g = 0; g < kGroups; ++g) {
    A[g] = sink->a[g];
    Bc[g] = sink->b[g];
    count[g] = sink->count[g];
  }
  unsigned char* bits = sink->bits + first_vector * kMaskSlots * kMaskBytes;
  for (std::size_t i = 0; i < n; i += L, bits += kMaskSlots * kMaskBytes) {
    const auto valid = hn::FirstN(d, n_valid > i ? n_valid - i : 0);
    hn::Vec<D> a, b;
    const auto T = OpticalDepths(d, len, rho_far, rho_exit, i, a, b);
    const auto B = hn::Mul(half, hn::Sub(b, a));
    const auto positive = hn::Gt(T, zero);  // false for NaN, as !(T > 0) in exact_piece
    const auto live = hn::And(positive, valid);
    const auto deep = hn::And(live, hn::Gt(T, thin_depth));
    const auto q2 = hn::Le(hn::Abs(B), hn::Mul(hn::Mul(q2_relative, a), a));
    const auto closed = hn::AndNot(q2, deep);
    const auto up = hn::Gt(B, zero);
    const auto thin = hn::AndNot(deep, live);
    const auto short_thin = hn::Lt(T, hn::Set(d, kShortThinDepth));
    const decltype(valid) mask[kGroups] = {hn::AndNot(short_thin, thin), hn::And(deep, q2), hn::And(closed, up),
                                           hn::AndNot(up, closed), hn::And(thin, short_thin)};
    for (int g = 0; g < kGroups; ++g) {
      hn::StoreMaskBits(d, mask[g], bits + static_cast<std::size_t>(g) * kMaskBytes);
      if (hn::AllFalse(d, mask[g])) continue;
      const std::size_t c = count[g];
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX3
      hn::CompressStore(a, mask[g], d, A[g] + c);  // native vcompresspd
      count[g] = c + hn::CompressStore(b, mask[g], d, Bc[g] + c);
#else
      // a lane permutation, then a whole-vector store (the columns have room past the count)
      static constexpr LanePermutations<HWY_LANES(double)> kPermutations;
      const unsigned pattern = bits[static_cast<std::size_t>(g) * kMaskBytes];
      const auto order = hn::SetTableIndices(d, kPermutations.compress[pattern]);
      hn::StoreU(hn::TableLookupLanes(a, order), d, A[g] + c);
      hn::StoreU(hn::TableLookupLanes(b, order), d, Bc[g] + c);
      count[g] = c + static_cast<std::size_t>(__builtin_popcount(pattern));
#endif
    }
    hn::StoreMaskBits(d, hn::AndNot(positive, valid), bits + kGroups * kMaskBytes);
  }
  for (int g = 0; g < kGroups; ++g) sink->count[g] = count[g];
}

// The midpoint Taylor recurrence of exact.cpp (thin_weights) on two vectors at once (its
// recurrence is a chain of dependent multiplies: two independent chains keep the FMA units
// busy). Each lane stops accumulating at the term where the scalar loop stops: its activity is
// a vector of 1.0 / 0.0 (an inactive lane adds (e_{n+1}/(n+2)) * 0 = 0, an active one the exact
// product by 1, so the sum is the scalar loop's, bit for bit), and its term count is 1 + the
// iterations it was active in (kept only with kTerms: only the introspection columns read it).
// The loop runs until every lane of both vectors has stopped.
// (Masks for the activity cost as much again: mask-register operations have one port.)
// With kMoments it also accumulates the sums of the derivative in P and Q of exact_grad.cpp's
// midpoint_sums (the same recurrence, the same stop): S_P = sum_{n odd} e_n/(n+2) and
// S_Q = sum_{n even} e_n/(n+3), from S_P = P/3, S_Q = 1/3; each lane stops accumulating them at
// the same term as its S - 1.
template <bool kMoments, bool kTerms, class D, class V = hn::Vec<D>>
HWY_INLINE void ThinSeriesPair(D d, V T0, V a0, V b0, V T1, V a1, V b1, V& s0_minus_1, V& terms0,
                               V& s1_minus_1, V& terms1, V* sp = nullptr, V* sq = nullptr) {
  const V P0 = hn::Mul(hn::Set(d, -0.5), T0), P1 = hn::Mul(hn::Set(d, -0.5), T1);
  const V Q20 = hn::Mul(hn::Set(d, -0.25), hn::Sub(b0, a0));  // 2 Q, Q = -B/4 = -(b - a)/8
  const V Q21 = hn::Mul(hn::Set(d, -0.25), hn::Sub(b1, a1));
  const V stop0 = hn::Mul(hn::Set(d, 0x1p-56 * 0.25), T0), stop1 = hn::Mul(hn::Set(d, 0x1p-56 * 0.25), T1);
  const V one = hn::Set(d, 1.0);
  V e0_prev = one, e0 = P0, e1_prev = one, e1 = P1;
  V s0 = hn::Zero(d), s1 = hn::Zero(d);
  V active0 = one, active1 = one;  // 1.0 while the lane's series runs
  V iterations0 = hn::Zero(d), iterations1 = hn::Zero(d);
  V abs_e0 = hn::Abs(e0), abs_e1 = hn::Abs(e1);  // |e_n|, |e_{n-1}| of the next stop test
  const V third = hn::Set(d, kRecip.r[2]);
  V sp0 = hn::Mul(P0, third), sp1 = hn::Mul(P1, third), sq0 = third, sq1 = third;
  // One term; the odd ones (n + 1 even) are accumulated. The exit test runs once per two terms:
  // a lane that stopped adds nothing more, so a term past the last lane's stop is harmless.
  const auto term = [&](int nn, bool accumulate) {
    const V r = hn::Set(d, kRecip.r[nn]);
    const V e0_next = hn::Mul(hn::MulAdd(P0, e0, hn::Mul(Q20, e0_prev)), r);
    const V e1_next = hn::Mul(hn::MulAdd(P1, e1, hn::Mul(Q21, e1_prev)), r);
    if (accumulate) {
      const V r2 = hn::Set(d, kRecip.r[nn + 1]);
      s0 = hn::MulAdd(hn::Mul(e0_next, r2), active0, s0);
      s1 = hn::MulAdd(hn::Mul(e1_next, r2), active1, s1);
      if (kMoments) {
        const V r4 = hn::Set(d, kRecip.r[nn + 3]);
        sq0 = hn::MulAdd(hn::Mul(e0_next, r4), active0, sq0);
        sq1 = hn::MulAdd(hn::Mul(e1_next, r4), active1, sq1);
      }
    } else if (kMoments) {
      const V r3 = hn::Set(d, kRecip.r[nn + 2]);
      sp0 = hn::MulAdd(hn::Mul(e0_next, r3), active0, sp0);
      sp1 = hn::MulAdd(hn::Mul(e1_next, r3), active1, sp1);
    }
    if (kTerms) {
      iterations0 = hn::Add(iterations0, active0);
      iterations1 = hn::Add(iterations1, active1);
    }
    e0_prev = e0;
    e0 = e0_next;
    e1_prev = e1;
    e1 = e1_next;
    const V abs_e0_next = hn::Abs(e0_next), abs_e1_next = hn::Abs(e1_next);
    active0 = hn::IfThenZeroElse(hn::Le(hn::Add(abs_e0_next, abs_e0), stop0), active0);
    active1 = hn::IfThenZeroElse(hn::Le(hn::Add(abs_e1_next, abs_e1), stop1), active1);
    abs_e0 = abs_e0_next;
    abs_e1 = abs_e1_next;
  };
  static_assert(kSeriesBudget % 2 == 0, "terms n = 1 .. kSeriesBudget - 1 in pairs, then the last");
  for (int nn = 1; nn < kSeriesBudget; nn += 2) {
    term(nn, true);
    if (nn + 1 < kSeriesBudget) term(nn + 1, false);
    if (hn::AllTrue(d, hn::Eq(hn::Add(active0, active1), hn::Zero(d)))) break;
  }
  s0_minus_1 = s0;
  s1_minus_1 = s1;
  if (kMoments) {
    sp[0] = sp0;
    sp[1] = sp1;
    sq[0] = sq0;
    sq[1] = sq1;
  }
  // a lane still active used the whole budget: kSeriesBudget + 1 terms, as exact.cpp reports
  const V budget = hn::Set(d, kSeriesBudget + 1.0);
  terms0 = hn::IfThenElse(hn::Eq(active0, one), budget, hn::Add(iterations0, one));
  terms1 = hn::IfThenElse(hn::Eq(active1, one), budget, hn::Add(iterations1, one));
}

// The weights of the thin branch from S - 1 (exact.cpp, thin_weights).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V ThinWeights(D d, V a, V b, V s_minus_1, V& w_exit, V& w_far) {
  const V eighth = hn::Set(d, 0.125), three = hn::Set(d, 3.0);
  const V em1_mid = hn::Expm1(d, hn::Neg(hn::Mul(eighth, hn::MulAdd(three, a, b))));
  const V em1_rest = hn::Expm1(d, hn::Neg(hn::Mul(eighth, hn::MulAdd(three, b, a))));
  const V decay_mid = hn::Add(hn::Set(d, 1.0), em1_mid);
  w_exit = hn::NegMulAdd(decay_mid, s_minus_1, hn::Neg(em1_mid));
  w_far = hn::Mul(decay_mid, hn::Sub(s_minus_1, em1_rest));
  return decay_mid;  // e^{-tau_m}
}

// The thin lanes' moments from the sums (exact_grad.cpp, midpoint_moments): S = 1 + (S - 1),
// e0 = e^{-tau_m} S, M1 = e^{-tau_m} (S + S_P)/2, M2 = e^{-tau_m} (S + 2 S_P + S_Q)/4.
template <class D, class V = hn::Vec<D>>
HWY_INLINE void ThinMoments(D d, V decay_mid, V s_minus_1, V S_P, V S_Q, V& m1, V& m2, V& e0) {
  const V S = hn::Add(hn::Set(d, 1.0), s_minus_1);
  e0 = hn::Mul(decay_mid, S);
  m1 = hn::Mul(hn::Mul(hn::Set(d, 0.5), decay_mid), hn::Add(S, S_P));
  m2 = hn::Mul(hn::Mul(hn::Set(d, 0.25), decay_mid), hn::Add(hn::Add(S, hn::Add(S_P, S_P)), S_Q));
}

// e0 of the q2 branch (exact.cpp, q2_series_e0). m0 = -expm1(-A)/A is divided as in the scalar
// path; the corrections m2, m4 and the huge-A form use 1/A once (they enter multiplied by
// |B| <= kQ2Relative A^2, so their last-bit differences are below 1e-22 of e0): two divisions
// per vector instead of eight.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V Q2SeriesE0(D d, V A, V B, V em1_A) {
  const V one = hn::Set(d, 1.0), half = hn::Set(d, 0.5);
  const V m0 = hn::Div(hn::Neg(em1_A), A);
  const V inv_A = hn::Div(one, A);
  const V eA = hn::Add(one, em1_A);
  const V A2 = hn::Mul(A, A);
  const V A3 = hn::Mul(A2, A);
  const V p2 = hn::Add(hn::Add(one, A), hn::Mul(half, A2));
  const V p4 = hn::Add(hn::Add(p2, hn::Mul(A3, hn::Set(d, 1.0 / 6.0))), hn::Mul(hn::Mul(A2, A2), hn::Set(d, 1.0 / 24.0)));
  const V inv_A2 = hn::Mul(inv_A, inv_A);
  const V inv_A3 = hn::Mul(inv_A2, inv_A);
  const V m2 = hn::Mul(hn::Add(inv_A3, inv_A3), hn::NegMulAdd(eA, p2, one));
  const V m4 = hn::Mul(hn::Mul(hn::Set(d, 24.0), hn::Mul(inv_A3, inv_A2)), hn::NegMulAdd(eA, p4, one));
  const V series = hn::Add(hn::NegMulAdd(B, m2, m0), hn::Mul(hn::Mul(half, hn::Mul(B, B)), m4));
  // A^5 overflows (A > ~1e61): (1 - 2r + 12 r^2)/A with r = B/A^2, as exact.cpp
  const V r = hn::Mul(hn::Mul(B, inv_A), inv_A);
  const V huge_A = hn::Mul(hn::MulAdd(hn::Mul(hn::Set(d, 12.0), r), r, hn::NegMulAdd(hn::Set(d, 2.0), r, one)), inv_A);
  const V general = hn::IfThenElse(hn::IsFinite(hn::Mul(hn::Mul(A2, A2), A)), series, huge_A);
  return hn::IfThenElse(hn::Eq(B, hn::Zero(d)), m0, general);  // B == 0: m0 alone, as exact.cpp
}

// 2. One group's columns: a, b in; transmittance, w_exit, w_far, terms out; with m1_col non-null
// also M1, M2, e0 (thin groups; NaN in the others, for exact_grad.cpp to form).
// n is a multiple of twice the lane count.
void GroupKernel(int group, const double* HWY_RESTRICT a_col, const double* HWY_RESTRICT b_col, std::size_t n,
                 double* HWY_RESTRICT tr_col, double* HWY_RESTRICT w_exit_col, double* HWY_RESTRICT w_far_col,
                 double* HWY_RESTRICT terms_col, double* HWY_RESTRICT m1_col, double* HWY_RESTRICT m2_col,
                 double* HWY_RESTRICT e0_col) {
  using D = hn::ScalableTag<double>;
  using V = hn::Vec<D>;
  const D d;
  const std::size_t L = hn::Lanes(d);
  const V one = hn::Set(d, 1.0), half = hn::Set(d, 0.5);
  const auto finish = [&](std::size_t i, V trans, V w_exit, V w_far, V terms) {
    hn::StoreU(trans, d, tr_col + i);
    hn::StoreU(w_exit, d, w_exit_col + i);
    hn::StoreU(w_far, d, w_far_col + i);
    if (terms_col) hn::StoreU(terms, d, terms_col + i);
  };
  if ((group == kThin || group == kThinShort) && m1_col) {
    for (std::size_t i = 0; i < n; i += 2 * L) {
      const V a0 = hn::LoadU(d, a_col + i), b0 = hn::LoadU(d, b_col + i);
      const V a1 = hn::LoadU(d, a_col + i + L), b1 = hn::LoadU(d, b_col + i + L);
      const V T0 = hn::Mul(half, hn::Add(a0, b0)), T1 = hn::Mul(half, hn::Add(a1, b1));
      V s0, terms0, s1, terms1, w_exit, w_far, sp[2], sq[2], m1, m2, e0;
      ThinSeriesPair<true, true>(d, T0, a0, b0, T1, a1, b1, s0, terms0, s1, terms1, sp, sq);
      ThinMoments(d, ThinWeights(d, a0, b0, s0, w_exit, w_far), s0, sp[0], sq[0], m1, m2, e0);
      finish(i, hn::Exp(d, hn::Neg(T0)), w_exit, w_far, terms0);
      hn::StoreU(m1, d, m1_col + i);
      hn::StoreU(m2, d, m2_col + i);
      hn::StoreU(e0, d, e0_col + i);
      ThinMoments(d, ThinWeights(d, a1, b1, s1, w_exit, w_far), s1, sp[1], sq[1], m1, m2, e0);
      finish(i + L, hn::Exp(d, hn::Neg(T1)), w_exit, w_far, terms1);
      hn::StoreU(m1, d, m1_col + i + L);
      hn::StoreU(m2, d, m2_col + i + L);
      hn::StoreU(e0, d, e0_col + i + L);
    }
    return;
  }
  if (m1_col) {  // moments of the other groups: formed by exact_grad.cpp
    const V nan = hn::Set(d, std::numeric_limits<double>::quiet_NaN());
    for (std::size_t i = 0; i < n; i += L) {
      hn::StoreU(nan, d, m1_col + i);
      hn::StoreU(nan, d, m2_col + i);
      hn::StoreU(nan, d, e0_col + i);
    }
  }
  if (group == kThin || group == kThinShort) {
    const auto thin = [&](auto with_terms) {
      for (std::size_t i = 0; i < n; i += 2 * L) {
        const V a0 = hn::LoadU(d, a_col + i), b0 = hn::LoadU(d, b_col + i);
        const V a1 = hn::LoadU(d, a_col + i + L), b1 = hn::LoadU(d, b_col + i + L);
        const V T0 = hn::Mul(half, hn::Add(a0, b0)), T1 = hn::Mul(half, hn::Add(a1, b1));
        V s0, terms0, s1, terms1, w_exit, w_far;
        ThinSeriesPair<false, decltype(with_terms)::value>(d, T0, a0, b0, T1, a1, b1, s0, terms0, s1, terms1);
        ThinWeights(d, a0, b0, s0, w_exit, w_far);
        finish(i, hn::Exp(d, hn::Neg(T0)), w_exit, w_far, terms0);
        ThinWeights(d, a1, b1, s1, w_exit, w_far);
        finish(i + L, hn::Exp(d, hn::Neg(T1)), w_exit, w_far, terms1);
      }
    };
    if (terms_col) {
      thin(std::true_type());
    } else {
      thin(std::false_type());  // no term counts asked for: the loop does not keep them
    }
    return;
  }
  for (std::size_t i = 0; i < n; i += L) {
    const V a = hn::LoadU(d, a_col + i);
    const V b = hn::LoadU(d, b_col + i);
    const V T = hn::Mul(half, hn::Add(a, b));
    const V trans = hn::Exp(d, hn::Neg(T));
    const V A = a;
    const V B = hn::Mul(half, hn::Sub(b, a));
    V e0;
    if (group == kQ2) {
      e0 = Q2SeriesE0(d, A, B, hn::Expm1(d, hn::Neg(A)));
    } else if (group == kErfcx) {
      const V beta = hn::Sqrt(B);
      const V z0 = hn::Div(A, hn::Add(beta, beta));
      const V z1 = hn::Add(z0, beta);
      const V bracket = hn::NegMulAdd(trans, special::HWY_NAMESPACE::ErfcxNonneg(d, z1),
                                      special::HWY_NAMESPACE::ErfcxNonneg(d, z0));
      e0 = hn::Mul(hn::Div(hn::Set(d, 1.7724538509055160273), hn::Add(beta, beta)), bracket);
    } else {
      const V gamma = hn::Sqrt(hn::Neg(B));
      const V two_gamma = hn::Add(gamma, gamma);
      const V y0 = hn::Div(A, two_gamma);
      const V y1 = hn::Div(b, two_gamma);
      const V bracket = hn::NegMulAdd(trans, special::HWY_NAMESPACE::DawsonNonneg(d, y1),
                                      special::HWY_NAMESPACE::DawsonNonneg(d, y0));
      e0 = hn::Div(bracket, gamma);
    }
    finish(i, trans, hn::Sub(one, e0), hn::Sub(e0, trans), hn::Zero(d));
  }
}

// The kC kappa columns of the pieces (exit and far ends) and the emission columns of a kernel,
// copied into locals (the kernel's stores could alias the caller's arrays of pointers otherwise,
// and the per-vector loop would reload them).
template <int kC>
struct KappaColumns {
  const double* exit[kC];
  const double* far[kC];
  double* em[kC];
  KappaColumns(const double* const* exit_cols, const double* const* far_cols, double* const* em_cols) {
    for (int c = 0; c < kC; ++c) {
      exit[c] = exit_cols[c];
      far[c] = far_cols[c];
      em[c] = em_cols[c];
    }
  }
};

// 3. The results back in piece order, vector by vector: each group's lanes take the group's next
// transmittance and weights (AVX-512: an expanding load per group and column; other targets lane
// by lane), and the emission kappa_exit w_exit + kappa_far w_far is formed for each of the
// `channels` kappa columns (1, or kChannels for a grey batch) with the pieces' own kappas (the
// arithmetic of exact_piece); transparent lanes get transmittance 1 and emission 0.
// n: whole vectors; only the first n_valid results are stored. The kappas are read in place up
// to the last whole vector of n_valid, and from tail_kappa_exit/far (one padded vector per
// channel) after it. The channel count is a template argument (ExpandBack picks it) and the
// column pointers are copied into locals, so the per-vector loop reloads nothing.
// kFull (the gradient's batch, one channel): also the weights and the thin lanes' moments, to
// full_out = {w_exit, w_far, m1, m2, e0}; transparent lanes get 0, 0 and the moments of tau = 0
// (1/2, 1/3, 1).
template <int kC, bool kFull>
HWY_INLINE void ExpandBackChannels(const unsigned char* HWY_RESTRICT bits, std::size_t n, std::size_t n_valid,
                                   const GroupResults* HWY_RESTRICT res, const double* const* kappa_exit_cols,
                                   const double* const* kappa_far_cols, const double* const* tail_kappa_exit_cols,
                                   const double* const* tail_kappa_far_cols, double* HWY_RESTRICT tr_out,
                                   double* const* em_out_cols, double* const* full_out) {
  const KappaColumns<kC> cols(kappa_exit_cols, kappa_far_cols, em_out_cols);
  const auto& kappa_exit = cols.exit;
  const auto& kappa_far = cols.far;
  const auto& em_out = cols.em;
  const double *tail_kappa_exit[kC], *tail_kappa_far[kC];
  for (int c = 0; c < kC; ++c) {
    tail_kappa_exit[c] = tail_kappa_exit_cols[c];
    tail_kappa_far[c] = tail_kappa_far_cols[c];
  }
  using D = hn::ScalableTag<double>;
  using V = hn::Vec<D>;
  const D d;
  const std::size_t L = hn::Lanes(d);
  // each group's next results, in locals (the stores below could alias *res otherwise)
  const double *next_tr[kGroups], *next_w_exit[kGroups], *next_w_far[kGroups];
  const double *next_m1[kGroups], *next_m2[kGroups], *next_e0[kGroups];
  for (int g = 0; g < kGroups; ++g) {
    next_tr[g] = res->tr[g];
    next_w_exit[g] = res->w_exit[g];
    next_w_far[g] = res->w_far[g];
    next_m1[g] = res->m1[g];
    next_m2[g] = res->m2[g];
    next_e0[g] = res->e0[g];
  }
  for (std::size_t i = 0; i < n; i += L, bits += kMaskSlots * kMaskBytes) {
    V tr = hn::Set(d, 1.0), w_exit = hn::Zero(d), w_far = hn::Zero(d);
    V m1 = hn::Set(d, 0.5), m2 = hn::Set(d, 1.0 / 3.0), e0 = hn::Set(d, 1.0);
    for (int g = 0; g < kGroups; ++g) {
      const unsigned char* group_bits = bits + static_cast<std::size_t>(g) * kMaskBytes;
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX3
      const __mmask8 k = group_bits[0];
      if (k == 0) continue;
      tr = V{_mm512_mask_expandloadu_pd(tr.raw, k, next_tr[g])};
      w_exit = V{_mm512_mask_expandloadu_pd(w_exit.raw, k, next_w_exit[g])};
      w_far = V{_mm512_mask_expandloadu_pd(w_far.raw, k, next_w_far[g])};
      const int taken = __builtin_popcount(k);
      next_tr[g] += taken;
      next_w_exit[g] += taken;
      next_w_far[g] += taken;
      if (kFull) {
        m1 = V{_mm512_mask_expandloadu_pd(m1.raw, k, next_m1[g])};
        m2 = V{_mm512_mask_expandloadu_pd(m2.raw, k, next_m2[g])};
        e0 = V{_mm512_mask_expandloadu_pd(e0.raw, k, next_e0[g])};
        next_m1[g] += taken;
        next_m2[g] += taken;
        next_e0[g] += taken;
      }
#else
      // the group's next L results (the columns have room past the count), each set lane taking
      // the one of its rank
      static constexpr LanePermutations<HWY_LANES(double)> kPermutations;
      const unsigned pattern = group_bits[0];
      if (pattern == 0) continue;
      const auto rank = hn::SetTableIndices(d, kPermutations.expand[pattern]);
      const auto in_group = hn::LoadMaskBits(d, group_bits);
      tr = hn::IfThenElse(in_group, hn::TableLookupLanes(hn::LoadU(d, next_tr[g]), rank), tr);
      w_exit = hn::IfThenElse(in_group, hn::TableLookupLanes(hn::LoadU(d, next_w_exit[g]), rank), w_exit);
      w_far = hn::IfThenElse(in_group, hn::TableLookupLanes(hn::LoadU(d, next_w_far[g]), rank), w_far);
      const int taken = __builtin_popcount(pattern);
      next_tr[g] += taken;
      next_w_exit[g] += taken;
      next_w_far[g] += taken;
      if (kFull) {
        m1 = hn::IfThenElse(in_group, hn::TableLookupLanes(hn::LoadU(d, next_m1[g]), rank), m1);
        m2 = hn::IfThenElse(in_group, hn::TableLookupLanes(hn::LoadU(d, next_m2[g]), rank), m2);
        e0 = hn::IfThenElse(in_group, hn::TableLookupLanes(hn::LoadU(d, next_e0[g]), rank), e0);
        next_m1[g] += taken;
        next_m2[g] += taken;
        next_e0[g] += taken;
      }
#endif
    }
    const auto transparent = hn::LoadMaskBits(d, bits + kGroups * kMaskBytes);
    const bool whole = i + L <= n_valid;
    if (!whole && i >= n_valid) continue;
    const auto head = hn::FirstN(d, n_valid - i);
    const auto store = [&](V v, double* to) {
      if (whole) {
        hn::StoreU(v, d, to);
      } else {
        hn::BlendedStore(v, head, d, to);
      }
    };
    store(tr, tr_out + i);
    if (kFull) {
      store(w_exit, full_out[0] + i);
      store(w_far, full_out[1] + i);
      store(m1, full_out[2] + i);
      store(m2, full_out[3] + i);
      store(e0, full_out[4] + i);
    }
    for (int c = 0; c < kC; ++c) {
      const V ke = hn::LoadU(d, whole ? kappa_exit[c] + i : tail_kappa_exit[c]);
      const V kf = hn::LoadU(d, whole ? kappa_far[c] + i : tail_kappa_far[c]);
      store(hn::IfThenZeroElse(transparent, hn::MulAdd(ke, w_exit, hn::Mul(kf, w_far))), em_out[c] + i);
    }
  }
}

// channels: 1 (the channel batch) or kChannels (a grey batch); full_out non-null: the weights and
// moments too (channel batch only).
void ExpandBack(const unsigned char* HWY_RESTRICT bits, std::size_t n, std::size_t n_valid,
                const GroupResults* HWY_RESTRICT res, int channels, const double* const* kappa_exit,
                const double* const* kappa_far, const double* const* tail_kappa_exit,
                const double* const* tail_kappa_far, double* HWY_RESTRICT tr_out, double* const* em_out,
                double* const* full_out) {
  if (full_out) {
    ExpandBackChannels<1, true>(bits, n, n_valid, res, kappa_exit, kappa_far, tail_kappa_exit, tail_kappa_far,
                                tr_out, em_out, full_out);
  } else if (channels == 1) {
    ExpandBackChannels<1, false>(bits, n, n_valid, res, kappa_exit, kappa_far, tail_kappa_exit, tail_kappa_far,
                                 tr_out, em_out, nullptr);
  } else {
    ExpandBackChannels<kChannels, false>(bits, n, n_valid, res, kappa_exit, kappa_far, tail_kappa_exit,
                                         tail_kappa_far, tr_out, em_out, nullptr);
  }
}

// The common regime in one pass (issue 33, round 20: every piece of the 105k-tet ball render is
// thin): pairs of vectors of pieces in their own order, while every lane of a pair is thin,
// go straight through the thin kernel and the emission, with no classification, groups or
// expansion back. A lane's operations are those of steps 1-3 (a, b and T as ClassifyColumns
// forms them, the thin test as its masks, the thin kernel of GroupKernel, the emission of
// ExpandBackChannels), and which lanes share a vector changes no lane's result, so the results
// are the grouped path's bit for bit. Returns how many pieces were done: n (a multiple of
// 2 lanes) or the start of the first pair with a lane that is not thin; the caller runs the
// grouped path from there. No series terms are counted (the introspection columns need the
// grouped path). Piece order mixes the short and long thin pieces that the groups keep apart,
// at 2.4% more series terms on that render (simulated on its pieces), against the whole of
// steps 1 and 3.
template <int kC>
HWY_INLINE std::size_t ThinInOrderChannels(const double* HWY_RESTRICT len, const double* HWY_RESTRICT rho_far,
                                           const double* HWY_RESTRICT rho_exit, std::size_t n,
                                           const double* const* kappa_exit_cols, const double* const* kappa_far_cols,
                                           double* HWY_RESTRICT tr_out, double* const* em_out_cols) {
  const KappaColumns<kC> cols(kappa_exit_cols, kappa_far_cols, em_out_cols);
  const auto& kappa_exit = cols.exit;
  const auto& kappa_far = cols.far;
  const auto& em_out = cols.em;
  using D = hn::ScalableTag<double>;
  using V = hn::Vec<D>;
  const D d;
  const std::size_t L = hn::Lanes(d);
  const V zero = hn::Zero(d), thin_depth = hn::Set(d, kThinDepth);
  for (std::size_t i = 0; i < n; i += 2 * L) {
    V a0, b0, a1, b1;
    const V T0 = OpticalDepths(d, len, rho_far, rho_exit, i, a0, b0);
    const V T1 = OpticalDepths(d, len, rho_far, rho_exit, i + L, a1, b1);
    // thin: T > 0 (false for NaN) and not T > kThinDepth, as ClassifyColumns' masks
    const auto thin0 = hn::AndNot(hn::Gt(T0, thin_depth), hn::Gt(T0, zero));
    const auto thin1 = hn::AndNot(hn::Gt(T1, thin_depth), hn::Gt(T1, zero));
    if (!hn::AllTrue(d, hn::And(thin0, thin1))) return i;
    V s0, terms0, s1, terms1, w_exit0, w_far0, w_exit1, w_far1;
    ThinSeriesPair<false, false>(d, T0, a0, b0, T1, a1, b1, s0, terms0, s1, terms1);
    ThinWeights(d, a0, b0, s0, w_exit0, w_far0);
    ThinWeights(d, a1, b1, s1, w_exit1, w_far1);
    hn::StoreU(hn::Exp(d, hn::Neg(T0)), d, tr_out + i);
    hn::StoreU(hn::Exp(d, hn::Neg(T1)), d, tr_out + i + L);
    for (int c = 0; c < kC; ++c) {
      const V ke0 = hn::LoadU(d, kappa_exit[c] + i), kf0 = hn::LoadU(d, kappa_far[c] + i);
      const V ke1 = hn::LoadU(d, kappa_exit[c] + i + L), kf1 = hn::LoadU(d, kappa_far[c] + i + L);
      hn::StoreU(hn::MulAdd(ke0, w_exit0, hn::Mul(kf0, w_far0)), d, em_out[c] + i);
      hn::StoreU(hn::MulAdd(ke1, w_exit1, hn::Mul(kf1, w_far1)), d, em_out[c] + i + L);
    }
  }
  return n;
}

// channels: 1 (the channel batch) or kChannels (a grey batch).
std::size_t ThinInOrder(const double* HWY_RESTRICT len, const double* HWY_RESTRICT rho_far,
                        const double* HWY_RESTRICT rho_exit, std::size_t n, int channels,
                        const double* const* kappa_exit, const double* const* kappa_far, double* HWY_RESTRICT tr_out,
                        double* const* em_out) {
  if (channels == 1) return ThinInOrderChannels<1>(len, rho_far, rho_exit, n, kappa_exit, kappa_far, tr_out, em_out);
  return ThinInOrderChannels<kChannels>(len, rho_far, rho_exit, n, kappa_exit, kappa_far, tr_out, em_out);
}

const char* TargetName() { return hwy::TargetName(HWY_TARGET); }
std::size_t DoubleLanes() { return hn::Lanes(hn::ScalableTag<double>()); }

}  // namespace HWY_NAMESPACE
}  // namespace rayint
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace rayint {
HWY_EXPORT(ClassifyColumns);
HWY_EXPORT(GroupKernel);
HWY_EXPORT(ExpandBack);
HWY_EXPORT(ThinInOrder);
HWY_EXPORT(TargetName);
HWY_EXPORT(DoubleLanes);

namespace {
using namespace exact_batch_detail;

// Pieces are handled in chunks of at most kChunk piece-channels, so the scratch (5 groups x 6
// columns) stays ~1.2 MB, in cache, however large the batch.
constexpr std::size_t kChunk = 4096;

// The lane count of the target dispatched now (not cached: tests switch targets), and a bound on
// it for every target (SVE's 2048-bit vectors; x86 has at most 8 doubles).
std::size_t lanes() { return HWY_DYNAMIC_DISPATCH(DoubleLanes)(); }
constexpr std::size_t kMaxLanes = 32;

// One thread's scratch: the padded copy of a chunk's last partial vector of inputs, each
// group's columns and results, and the mask bits of every vector of the chunk.
struct Scratch {
  // Columns always written before they are read (the tail columns below are zero-padded where
  // they are filled): not zero-filled here, so a thread's pages are touched only as far as its
  // chunks reach (core/default_init.hpp).
  template <class T>
  using Column = std::vector<T, DefaultInitAllocator<T>>;
  Column<double> len, rho_far, rho_exit;
  Column<double> kappa_far[kChannels], kappa_exit[kChannels];
  Column<double> a[kGroups], b[kGroups], tr[kGroups], w_exit[kGroups], w_far[kGroups], terms[kGroups];
  Column<double> m1[kGroups], m2[kGroups], e0[kGroups];  // the gradient's batch only
  Column<unsigned char> bits;
  GroupSink sink{};
  GroupResults results{};
  Scratch() {
    // room for a whole chunk in one group, plus a vector tail and the padding to two vectors
    const std::size_t room = kChunk + 3 * kMaxLanes;
    for (auto* col : {&len, &rho_far, &rho_exit}) col->resize(kMaxLanes);
    for (int c = 0; c < kChannels; ++c) {
      kappa_far[c].resize(kMaxLanes);
      kappa_exit[c].resize(kMaxLanes);
    }
    for (int g = 0; g < kGroups; ++g) {
      for (auto* col : {&a[g], &b[g], &tr[g], &w_exit[g], &w_far[g], &terms[g]}) col->resize(room);
      for (auto* col : {&m1[g], &m2[g], &e0[g]}) col->resize(room);
      sink.a[g] = a[g].data();
      sink.b[g] = b[g].data();
    }
    bits.resize((room + 1) * kMaskSlots * kMaskBytes);  // one vector may hold a single lane
    sink.bits = bits.data();
  }
};

constexpr ExactBranch kGroupBranch[kGroups] = {ExactBranch::thin_series, ExactBranch::q2_series,
                                               ExactBranch::erfcx, ExactBranch::dawson, ExactBranch::thin_series};

// 1. classify n_valid piece-channels from the columns (n: n_valid rounded up to whole vectors,
// readable), their masks written from vector first_vector on.
void classify(Scratch& s, const double* len, const double* rho_far, const double* rho_exit, std::size_t n,
              std::size_t n_valid, std::size_t first_vector) {
  HWY_DYNAMIC_DISPATCH(ClassifyColumns)(len, rho_far, rho_exit, n, n_valid, first_vector, &s.sink);
}

// The introspection columns (branch, terms, converged), lane by lane from the mask bits: only
// diagnostics ask for them.
void write_introspection(const Scratch& s, std::size_t n_valid, std::size_t first, const OpticsColumns& out) {
  const std::size_t L = lanes();
  std::size_t pos[kGroups] = {};
  for (std::size_t i = 0; i < n_valid; ++i) {
    const unsigned char* bits = s.bits.data() + (i / L) * kMaskSlots * kMaskBytes;
    const std::size_t lane = i % L;
    const auto in = [&](std::size_t slot) { return (bits[slot * kMaskBytes + lane / 8] >> (lane % 8)) & 1; };
    ExactBranch branch = ExactBranch::transparent;
    double terms = 0.0;
    for (int g = 0; g < kGroups; ++g) {
      if (in(static_cast<std::size_t>(g))) {
        branch = kGroupBranch[g];
        terms = s.results.terms[g][pos[g]++];
      }
    }
    if (out.branch) out.branch[first + i] = branch;
    if (out.terms) out.terms[first + i] = static_cast<std::int32_t>(terms);
    if (out.converged) out.converged[first + i] = terms <= kSeriesBudget ? 1 : 0;
  }
}

// 2. evaluate each group on its contiguous columns, padded to whole pairs of vectors with copies
// of the group's first piece; 3. put the results back in piece order: the chunk's n_valid
// pieces (n: whole vectors) go to tr_out and em_out[c], c < channels.
// kappa_exit/far[c]: the chunk's kappas in piece order, readable up to the last whole vector;
// s.kappa_exit/far[c]: the partial last vector's, padded to a whole vector.
// full_out: null, or {w_exit, w_far, m1, m2, e0} columns of the chunk (OpticsColumns').
// terms: whether the thin groups count their series terms (s.terms; only the introspection
// columns read them).
void evaluate_groups(Scratch& s, std::size_t n, std::size_t n_valid, int channels, const double* const* kappa_exit,
                     const double* const* kappa_far, double* tr_out, double* const* em_out,
                     double* const* full_out, bool terms) {
  const std::size_t L = lanes();
  for (int g = 0; g < kGroups; ++g) {
    s.results.tr[g] = s.tr[g].data();
    s.results.w_exit[g] = s.w_exit[g].data();
    s.results.w_far[g] = s.w_far[g].data();
    s.results.terms[g] = s.terms[g].data();
    s.results.m1[g] = s.m1[g].data();
    s.results.m2[g] = s.m2[g].data();
    s.results.e0[g] = s.e0[g].data();
  }
  // Short thin pieces too few (or too few long ones) to fill a pair of vectors: the split would
  // cost more padding than it saves, so they run with the long ones, after them in the columns.
  std::size_t& m_thin = s.sink.count[kThin];
  std::size_t& m_short = s.sink.count[kThinShort];
  if (m_short > 0 && (m_short < 2 * L || m_thin < 2 * L)) {
    std::copy_n(s.a[kThinShort].begin(), m_short, s.a[kThin].begin() + static_cast<long>(m_thin));
    std::copy_n(s.b[kThinShort].begin(), m_short, s.b[kThin].begin() + static_cast<long>(m_thin));
    s.results.tr[kThinShort] = s.tr[kThin].data() + m_thin;
    s.results.w_exit[kThinShort] = s.w_exit[kThin].data() + m_thin;
    s.results.w_far[kThinShort] = s.w_far[kThin].data() + m_thin;
    s.results.terms[kThinShort] = s.terms[kThin].data() + m_thin;
    s.results.m1[kThinShort] = s.m1[kThin].data() + m_thin;
    s.results.m2[kThinShort] = s.m2[kThin].data() + m_thin;
    s.results.e0[kThinShort] = s.e0[kThin].data() + m_thin;
    m_thin += m_short;
    m_short = 0;
  }
  for (int g = 0; g < kGroups; ++g) {
    const std::size_t m = s.sink.count[g];
    if (m == 0) continue;
    s.sink.count[g] = 0;
    const std::size_t step = g == kThin || g == kThinShort ? 2 * L : L;  // the thin kernel takes pairs
    const std::size_t padded = (m + step - 1) / step * step;
    for (std::size_t k = m; k < padded; ++k) {
      s.a[g][k] = s.a[g][0];
      s.b[g][k] = s.b[g][0];
    }
    HWY_DYNAMIC_DISPATCH(GroupKernel)(g, s.a[g].data(), s.b[g].data(), padded, s.tr[g].data(), s.w_exit[g].data(),
                                      s.w_far[g].data(), terms ? s.terms[g].data() : nullptr, full_out ? s.m1[g].data() : nullptr,
                                      s.m2[g].data(), s.e0[g].data());
  }
  const double* tail_exit[kChannels];
  const double* tail_far[kChannels];
  for (int c = 0; c < kChannels; ++c) {
    tail_exit[c] = s.kappa_exit[c].data();
    tail_far[c] = s.kappa_far[c].data();
  }
  HWY_DYNAMIC_DISPATCH(ExpandBack)(s.bits.data(), n, n_valid, &s.results, channels, kappa_exit, kappa_far, tail_exit,
                                   tail_far, tr_out, em_out, full_out);
}

// The chunk loop of both overloads: n pieces whose length and density columns are `len`,
// `rho_far`, `rho_exit`, with `channels` kappa columns and emission columns; after each chunk,
// after_chunk(s, first, size) (the channel overload's introspection columns, which need `terms`).
template <class AfterChunk>
void run_chunks(std::size_t total, const double* len, const double* rho_far, const double* rho_exit, int channels,
                const double* const* kappa_far, const double* const* kappa_exit, double* tr_out,
                double* const* em_out, double* const* full_out, bool terms, AfterChunk&& after_chunk) {
  thread_local Scratch s;
  const std::size_t L = lanes();
  struct Columns {  // the kappa and emission columns from one piece on
    const double* ke[kChannels];
    const double* kf[kChannels];
    double* em[kChannels];
  };
  const auto from = [&](std::size_t first) {
    Columns at{};
    for (int c = 0; c < channels; ++c) {
      at.ke[c] = kappa_exit[c] + first;
      at.kf[c] = kappa_far[c] + first;
      at.em[c] = em_out[c] + first;
    }
    return at;
  };
  for (std::size_t chunk = 0; chunk < total; chunk += kChunk) {
    const std::size_t end = std::min(total, chunk + kChunk);
    std::size_t begin = chunk;
    if (!terms && !full_out) {
      // the chunk's whole pairs of vectors in piece order while every lane is thin (ThinInOrder);
      // the grouped path below from the first pair that is not, and for the last partial pair
      const Columns at = from(begin);
      const std::size_t pairs = (end - begin) / (2 * L) * (2 * L);
      begin += HWY_DYNAMIC_DISPATCH(ThinInOrder)(len + begin, rho_far + begin, rho_exit + begin, pairs, channels, at.ke,
                                                 at.kf, tr_out + begin, at.em);
      if (begin == end) continue;
    }
    const std::size_t size = end - begin;
    const std::size_t whole = size / L * L;  // whole vectors classified in place
    classify(s, len + begin, rho_far + begin, rho_exit + begin, whole, whole, 0);
    const std::size_t n = (size + L - 1) / L * L;
    if (whole < size) {  // the tail, copied into one padded vector
      for (std::size_t k = 0; k < L; ++k) {
        const bool in_tail = whole + k < size;
        const std::size_t at = begin + whole + k;
        s.len[k] = in_tail ? len[at] : 0.0;
        s.rho_far[k] = in_tail ? rho_far[at] : 0.0;
        s.rho_exit[k] = in_tail ? rho_exit[at] : 0.0;
        for (int c = 0; c < channels; ++c) {
          s.kappa_far[c][k] = in_tail ? kappa_far[c][at] : 0.0;
          s.kappa_exit[c][k] = in_tail ? kappa_exit[c][at] : 0.0;
        }
      }
      classify(s, s.len.data(), s.rho_far.data(), s.rho_exit.data(), L, size - whole, whole / L);
    }
    const Columns at = from(begin);
    double* full[5];
    if (full_out)
      for (int j = 0; j < 5; ++j) full[j] = full_out[j] + begin;
    evaluate_groups(s, n, size, channels, at.ke, at.kf, tr_out + begin, at.em, full_out ? full : nullptr, terms);
    after_chunk(s, begin, size);
  }
}

}  // namespace

const char* exact_batch_target() { return HWY_DYNAMIC_DISPATCH(TargetName)(); }

void exact_batch(const PieceColumns& in, const OpticsColumns& out) {
  const double* kappa_far[1] = {in.kappa_far};
  const double* kappa_exit[1] = {in.kappa_exit};
  double* emission[1] = {out.emission};
  double* full[5] = {out.weight_exit, out.weight_far, out.m1, out.m2, out.e0};
  const bool introspect = out.branch || out.terms || out.converged;
  run_chunks(in.size, in.length, in.rho_far, in.rho_exit, 1, kappa_far, kappa_exit, out.transmittance, emission,
             out.m1 ? full : nullptr, introspect,
             [&out, introspect](const Scratch& s, std::size_t first, std::size_t size) {
               if (introspect) write_introspection(s, size, first, out);
             });
}

void exact_batch(const GreyPieceView& in, const GreyOpticsColumns& out) {
  run_chunks(in.size, in.length, in.rho_far, in.rho_exit, kChannels, in.kappa_far.data(), in.kappa_exit.data(),
             out.transmittance, out.emission.data(), nullptr, false, [](const Scratch&, std::size_t, std::size_t) {});
}

PieceColumns PieceColumnStore::assign(const ChannelPiece* pieces, std::size_t n) {
  for (auto* v : {&length, &rho_far, &rho_exit, &kappa_far, &kappa_exit}) v->resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    length[i] = pieces[i].length;
    rho_far[i] = pieces[i].rho_far;
    rho_exit[i] = pieces[i].rho_exit;
    kappa_far[i] = pieces[i].kappa_far;
    kappa_exit[i] = pieces[i].kappa_exit;
  }
  return PieceColumns{length.data(), rho_far.data(), rho_exit.data(), kappa_far.data(), kappa_exit.data(), n};
}

}  // namespace rayint
#endif  // HWY_ONCE
