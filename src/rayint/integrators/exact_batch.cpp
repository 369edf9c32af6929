// exact_batch.cpp -- the exact piece integral of exact.cpp (Williams & Max 1992, Eq. 4 with rho and
// kappa linear, Sec. 3.3) on structure-of-arrays batches, vectorised with Google Highway.
//
// The formulas, regions and thresholds are exactly those of exact.cpp (kThinDepth, kQ2Relative,
// the same series and closed forms); what differs is how they are evaluated:
//   1. one scalar pass computes a = rho_exit L, b = rho_far L, T, B and appends each piece to its
//      branch's contiguous columns (the choice branch-free; transparent pieces are written at
//      once: transmittance 1, emission 0), in chunks of 4096 piece-channels so the columns stay
//      in cache;
//   2. each branch's columns, padded to whole vectors (the lane count of the target, not more)
//      with copies of the group's first piece, are evaluated lane-parallel:
//        thin_series  the midpoint Taylor recurrence of exact.cpp run on all lanes until every lane
//                     met its own stop test (a lane stops accumulating at the same term as the
//                     scalar loop), weights from Expm1;
//        q2_series    the three-term series in B with Expm1;
//        erfcx        erfcx from special/erfcx_simd-inl.hpp (table + asymptotic, x >= 0);
//        dawson       Dawson from the same file;
//      exp(-T) is Highway's Exp (documented 1 ulp; -T below -1000 gives 0), expm1 Highway's
//      Expm1 (documented 4 ulp);
//   3. results are scattered back to the pieces' places.
// The run-time dispatch (HWY_DYNAMIC_DISPATCH over hwy/foreach_target.h) picks SSE4, AVX2 or
// AVX-512 on x86-64, so one binary runs on any of them; exact_batch_target() names the choice.
// Accuracy (against the 50-digit reference): `rayint stress --count 100000 --seed 1 --methods
// exact,exact:path=scalar` gives max relative error 5.22e-14 and median 0.361 ulp over 104,018
// pieces (scalar exact_piece in the same run: 5.25e-14, 0.406 ulp); tests/test_exact_batch.cpp
// asserts 1e-13 in every regime, the same branch and series terms as exact_piece, and a median
// within 1 ulp of the scalar path's.
#include "rayint/integrators/exact_batch.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "rayint/integrators/exact_batch.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>
#include <hwy/contrib/math/math-inl.h>

#include "rayint/special/erfcx_simd-inl.hpp"

#ifndef RAYINT_EXACT_BATCH_SHARED
#define RAYINT_EXACT_BATCH_SHARED
namespace rayint::exact_batch_detail {
// Branch groups evaluated by the vector kernels (transparent pieces never reach them).
enum Group : int { kThin = 0, kQ2 = 1, kErfcx = 2, kDawson = 3, kGroups = 4 };
constexpr int kSeriesBudget = 100;  // as exact.cpp
struct Reciprocals {                // 1/(n+1), as exact.cpp
  double r[kSeriesBudget + 2];
  constexpr Reciprocals() : r() {
    for (int n = 0; n < kSeriesBudget + 2; ++n) r[n] = 1.0 / (n + 1);
  }
};
inline constexpr Reciprocals kRecip;
}  // namespace rayint::exact_batch_detail
#endif

HWY_BEFORE_NAMESPACE();
namespace rayint {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
using namespace exact_batch_detail;

// One group's columns: a, b, kappa_exit, kappa_far in; transmittance, emission, terms out.
// n is a multiple of the lane count.
void GroupKernel(int group, const double* HWY_RESTRICT a_col, const double* HWY_RESTRICT b_col,
                 const double* HWY_RESTRICT ke_col, const double* HWY_RESTRICT kf_col, std::size_t n,
                 double* HWY_RESTRICT tr_col, double* HWY_RESTRICT em_col,
                 double* HWY_RESTRICT terms_col) {
  using D = hn::ScalableTag<double>;
  using V = hn::Vec<D>;
  const D d;
  const std::size_t L = hn::Lanes(d);
  const V one = hn::Set(d, 1.0), half = hn::Set(d, 0.5), eighth = hn::Set(d, 0.125);
  for (std::size_t i = 0; i < n; i += L) {
    const V a = hn::LoadU(d, a_col + i);
    const V b = hn::LoadU(d, b_col + i);
    const V T = hn::Mul(half, hn::Add(a, b));
    const V trans = hn::Exp(d, hn::Neg(T));
    V w_exit, w_far, terms = hn::Zero(d);
    if (group == kThin) {
      const V P = hn::Mul(hn::Set(d, -0.5), T);
      const V Q2 = hn::Mul(hn::Set(d, -0.25), hn::Sub(b, a));  // 2 Q, Q = -B/4 = -(b - a)/8
      const V stop = hn::Mul(hn::Set(d, 0x1p-56 * 0.25), T);
      V e_prev = one, e = P, s_minus_1 = hn::Zero(d);
      auto active = hn::Eq(e_prev, e_prev);  // all lanes
      int nn = 1;
      for (; nn < kSeriesBudget; ++nn) {
        const V e_next = hn::Mul(hn::MulAdd(P, e, hn::Mul(Q2, e_prev)), hn::Set(d, kRecip.r[nn]));
        if ((nn & 1) == 1)
          s_minus_1 = hn::Add(s_minus_1, hn::IfThenElseZero(active, hn::Mul(e_next, hn::Set(d, kRecip.r[nn + 1]))));
        e_prev = e;
        e = e_next;
        const auto done = hn::Le(hn::Add(hn::Abs(e), hn::Abs(e_prev)), stop);
        terms = hn::IfThenElse(hn::And(active, done), hn::Set(d, nn + 1.0), terms);
        active = hn::AndNot(done, active);
        if (hn::AllFalse(d, active)) break;
      }
      terms = hn::IfThenElse(active, hn::Set(d, kSeriesBudget + 1.0), terms);
      const V tau_m = hn::Mul(eighth, hn::MulAdd(hn::Set(d, 3.0), a, b));
      const V em1_mid = hn::Expm1(d, hn::Neg(tau_m));
      const V em1_rest = hn::Expm1(d, hn::Neg(hn::Mul(eighth, hn::MulAdd(hn::Set(d, 3.0), b, a))));
      const V decay_mid = hn::Add(one, em1_mid);
      w_exit = hn::NegMulAdd(decay_mid, s_minus_1, hn::Neg(em1_mid));
      w_far = hn::Mul(decay_mid, hn::Sub(s_minus_1, em1_rest));
    } else {
      const V A = a;
      const V B = hn::Mul(half, hn::Sub(b, a));
      V e0;
      if (group == kQ2) {
        const V em1_A = hn::Expm1(d, hn::Neg(A));
        const V m0 = hn::Div(hn::Neg(em1_A), A);
        const V eA = hn::Add(one, em1_A);
        const V A2 = hn::Mul(A, A);
        const V p2 = hn::Add(hn::Add(one, A), hn::Mul(half, A2));
        const V p4 = hn::Add(hn::Add(p2, hn::Div(hn::Mul(A2, A), hn::Set(d, 6.0))),
                             hn::Div(hn::Mul(A2, A2), hn::Set(d, 24.0)));
        const V m2 = hn::Mul(hn::Div(hn::Set(d, 2.0), hn::Mul(A2, A)), hn::NegMulAdd(eA, p2, one));
        const V m4 = hn::Mul(hn::Div(hn::Set(d, 24.0), hn::Mul(hn::Mul(A2, A2), A)), hn::NegMulAdd(eA, p4, one));
        const V series = hn::Add(hn::NegMulAdd(B, m2, m0), hn::Mul(hn::Mul(half, hn::Mul(B, B)), m4));
        // A^5 overflows (A > ~1e61): (1 - 2r + 12 r^2)/A with r = B/A^2, as exact.cpp
        const V r = hn::Div(hn::Div(B, A), A);
        const V huge_A = hn::Div(hn::MulAdd(hn::Mul(hn::Set(d, 12.0), r), r, hn::NegMulAdd(hn::Set(d, 2.0), r, one)), A);
        const V general = hn::IfThenElse(hn::IsFinite(hn::Mul(hn::Mul(A2, A2), A)), series, huge_A);
        e0 = hn::IfThenElse(hn::Eq(B, hn::Zero(d)), m0, general);  // B == 0: m0 alone, as exact.cpp
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
      w_exit = hn::Sub(one, e0);
      w_far = hn::Sub(e0, trans);
    }
    const V emission = hn::MulAdd(hn::LoadU(d, ke_col + i), w_exit, hn::Mul(hn::LoadU(d, kf_col + i), w_far));
    hn::StoreU(trans, d, tr_col + i);
    hn::StoreU(emission, d, em_col + i);
    hn::StoreU(terms, d, terms_col + i);
  }
}

const char* TargetName() { return hwy::TargetName(HWY_TARGET); }
std::size_t DoubleLanes() { return hn::Lanes(hn::ScalableTag<double>()); }

}  // namespace HWY_NAMESPACE
}  // namespace rayint
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace rayint {
HWY_EXPORT(GroupKernel);
HWY_EXPORT(TargetName);
HWY_EXPORT(DoubleLanes);

namespace {
using namespace exact_batch_detail;

// One branch's pieces of the current chunk: inputs, results, and where each goes back to.
struct GroupColumns {
  std::vector<double> a, b, ke, kf, tr, em, terms;
  std::vector<std::size_t> index;
  std::size_t size = 0;
};

// Pieces are handled in chunks of at most kChunk piece-channels, so the scratch (4 groups x 8
// columns) stays ~1 MB, in cache, however large the batch.
constexpr std::size_t kChunk = 4096;

std::size_t lanes() {
  static const std::size_t lanes = HWY_DYNAMIC_DISPATCH(DoubleLanes)();
  return lanes;
}

struct Scratch {
  GroupColumns group[kGroups];
  Scratch() {
    for (auto& g : group) {  // room for a whole chunk in one group, plus the padding
      for (auto* col : {&g.a, &g.b, &g.ke, &g.kf, &g.tr, &g.em, &g.terms}) col->resize(kChunk + lanes());
      g.index.resize(kChunk + lanes());
    }
  }
};

constexpr ExactBranch kGroupBranch[kGroups] = {ExactBranch::thin_series, ExactBranch::q2_series,
                                               ExactBranch::erfcx, ExactBranch::dawson};

// 1. classify one piece-channel as exact_piece does: a transparent one is written at once, the
// others appended to their branch's columns. The choice among the four branches is branch-free:
// in a mixed batch it is unpredictable.
inline void classify(Scratch& s, const OpticsColumns& out, std::size_t i, double length, double rho_far,
                     double rho_exit, double kappa_far, double kappa_exit) {
  const double a = rho_exit * length;
  const double b = rho_far * length;
  const double T = 0.5 * (a + b);
  if (!(T > 0.0)) {
    out.transmittance[i] = 1.0;
    out.emission[i] = 0.0;
    if (out.branch) out.branch[i] = ExactBranch::transparent;
    if (out.terms) out.terms[i] = 0;
    if (out.converged) out.converged[i] = 1;
    return;
  }
  const double B = 0.5 * (b - a);
  // thin 0, q2 1, erfcx 2, dawson 3: the tests of exact_piece, in its order
  const int not_thin = T > kThinDepth;
  const int not_q2 = !(std::fabs(B) <= kQ2Relative * a * a);
  const int dawson = !(B > 0.0);
  GroupColumns& col = s.group[not_thin * (1 + not_q2 * (1 + dawson))];
  const std::size_t k = col.size++;
  col.a[k] = a;
  col.b[k] = b;
  col.ke[k] = kappa_exit;
  col.kf[k] = kappa_far;
  col.index[k] = i;
}

// 2. evaluate each group on its contiguous columns, padded to whole vectors with copies of the
// group's first piece; 3. scatter the results back to the pieces' places.
void evaluate_groups(Scratch& s, const OpticsColumns& out) {
  const std::size_t L = lanes();
  for (int g = 0; g < kGroups; ++g) {
    GroupColumns& col = s.group[g];
    const std::size_t m = col.size;
    if (m == 0) continue;
    col.size = 0;
    const std::size_t padded = (m + L - 1) / L * L;
    for (std::size_t k = m; k < padded; ++k) {
      col.a[k] = col.a[0];
      col.b[k] = col.b[0];
      col.ke[k] = col.ke[0];
      col.kf[k] = col.kf[0];
    }
    HWY_DYNAMIC_DISPATCH(GroupKernel)(g, col.a.data(), col.b.data(), col.ke.data(), col.kf.data(), padded,
                                      col.tr.data(), col.em.data(), col.terms.data());
    for (std::size_t k = 0; k < m; ++k) {
      const std::size_t i = col.index[k];
      out.transmittance[i] = col.tr[k];
      out.emission[i] = col.em[k];
    }
    if (out.branch || out.terms || out.converged) {
      for (std::size_t k = 0; k < m; ++k) {
        const std::size_t i = col.index[k];
        if (out.branch) out.branch[i] = kGroupBranch[g];
        if (out.terms) out.terms[i] = static_cast<std::int32_t>(col.terms[k]);
        if (out.converged) out.converged[i] = col.terms[k] <= kSeriesBudget ? 1 : 0;
      }
    }
  }
}

}  // namespace

const char* exact_batch_target() { return HWY_DYNAMIC_DISPATCH(TargetName)(); }

void exact_batch(const PieceColumns& in, const OpticsColumns& out) {
  thread_local Scratch s;
  for (std::size_t begin = 0; begin < in.size; begin += kChunk) {
    const std::size_t end = std::min(in.size, begin + kChunk);
    for (std::size_t i = begin; i < end; ++i)
      classify(s, out, i, in.length[i], in.rho_far[i], in.rho_exit[i], in.kappa_far[i], in.kappa_exit[i]);
    evaluate_groups(s, out);
  }
}

void exact_batch(const Piece* pieces, std::size_t n, const OpticsColumns& out) {
  thread_local Scratch s;
  constexpr std::size_t kChunkPieces = kChunk / kChannels;
  for (std::size_t begin = 0; begin < n; begin += kChunkPieces) {
    const std::size_t end = std::min(n, begin + kChunkPieces);
    for (std::size_t p = begin; p < end; ++p) {
      const Piece& piece = pieces[p];
      for (std::size_t c = 0; c < kChannels; ++c)
        classify(s, out, kChannels * p + c, piece.length, piece.rho_far[c], piece.rho_exit[c],
                 piece.kappa_far[c], piece.kappa_exit[c]);
    }
    evaluate_groups(s, out);
  }
}

}  // namespace rayint
#endif  // HWY_ONCE
