// exact_batch.cpp -- the exact piece integral of exact.cpp (Williams & Max 1992, Eq. 4 with rho and
// kappa linear, Sec. 3.3) on structure-of-arrays batches, vectorised with Google Highway.
//
// The formulas, regions and thresholds are exactly those of exact.cpp (kThinDepth, kQ2Relative,
// the same series and closed forms); what differs is how they are evaluated:
//   1. a scalar pass computes a = rho_exit L, b = rho_far L, T, B, and sorts the piece indices into
//      the four branches (transparent pieces are written at once: transmittance 1, emission 0);
//   2. each branch's pieces are copied into contiguous columns (padded to whole vectors with a
//      copy of the group's first piece) and evaluated lane-parallel:
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
constexpr std::size_t kPad = 16;    // columns are padded to a multiple of this (>= any lane count)
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

}  // namespace HWY_NAMESPACE
}  // namespace rayint
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace rayint {
HWY_EXPORT(GroupKernel);
HWY_EXPORT(TargetName);

namespace {
using namespace exact_batch_detail;

struct Scratch {
  std::vector<std::size_t> index[kGroups];
  std::vector<double> a, b, ke, kf, tr, em, terms;
};

constexpr ExactBranch kGroupBranch[kGroups] = {ExactBranch::thin_series, ExactBranch::q2_series,
                                               ExactBranch::erfcx, ExactBranch::dawson};

}  // namespace

const char* exact_batch_target() { return HWY_DYNAMIC_DISPATCH(TargetName)(); }

void exact_batch(const PieceColumns& in, const OpticsColumns& out) {
  thread_local Scratch s;
  for (auto& v : s.index) v.clear();
  // 1. classify, as exact_piece does
  for (std::size_t i = 0; i < in.size; ++i) {
    const double a = in.rho_exit[i] * in.length[i];
    const double b = in.rho_far[i] * in.length[i];
    const double T = 0.5 * (a + b);
    if (!(T > 0.0)) {
      out.transmittance[i] = 1.0;
      out.emission[i] = 0.0;
      if (out.branch) out.branch[i] = ExactBranch::transparent;
      if (out.terms) out.terms[i] = 0;
      if (out.converged) out.converged[i] = 1;
      continue;
    }
    const double B = 0.5 * (b - a);
    Group g;
    if (T <= kThinDepth) g = kThin;
    else if (std::fabs(B) <= kQ2Relative * a * a) g = kQ2;
    else if (B > 0.0) g = kErfcx;
    else g = kDawson;
    s.index[g].push_back(i);
  }
  // 2. evaluate each group on contiguous, padded columns; 3. scatter back
  for (int g = 0; g < kGroups; ++g) {
    const std::vector<std::size_t>& idx = s.index[g];
    const std::size_t m = idx.size();
    if (m == 0) continue;
    const std::size_t padded = (m + kPad - 1) / kPad * kPad;
    for (auto* col : {&s.a, &s.b, &s.ke, &s.kf, &s.tr, &s.em, &s.terms})
      if (col->size() < padded) col->resize(padded);
    for (std::size_t k = 0; k < padded; ++k) {
      const std::size_t i = idx[k < m ? k : 0];
      s.a[k] = in.rho_exit[i] * in.length[i];
      s.b[k] = in.rho_far[i] * in.length[i];
      s.ke[k] = in.kappa_exit[i];
      s.kf[k] = in.kappa_far[i];
    }
    HWY_DYNAMIC_DISPATCH(GroupKernel)(g, s.a.data(), s.b.data(), s.ke.data(), s.kf.data(), padded,
                                      s.tr.data(), s.em.data(), s.terms.data());
    for (std::size_t k = 0; k < m; ++k) {
      const std::size_t i = idx[k];
      out.transmittance[i] = s.tr[k];
      out.emission[i] = s.em[k];
      if (out.branch) out.branch[i] = kGroupBranch[g];
      if (out.terms) out.terms[i] = static_cast<std::int32_t>(s.terms[k]);
      if (out.converged) out.converged[i] = s.terms[k] <= kSeriesBudget ? 1 : 0;
    }
  }
}

}  // namespace rayint
#endif  // HWY_ONCE
