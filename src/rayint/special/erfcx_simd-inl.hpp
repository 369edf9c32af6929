// erfcx_simd-inl.hpp -- erfcx(x) = exp(x^2) erfc(x) and Dawson's integral
// D(x) = exp(-x^2) int_0^x exp(t^2) dt on vectors of x >= 0 (Google Highway, one copy per target;
// include it after hwy/highway.h inside a HWY_TARGET_INCLUDE file, see exact_batch.cpp).
//
// Methods by region (the scalar reference is libcerf, special_functions.hpp):
//   - 0 <= x < 16: piecewise polynomials of degree 17 on 16 intervals of width 1 (tables in
//     simd_tables.hpp/.cpp, Chebyshev interpolants generated in 50 digits by
//     tools/gen_special_simd_tables.cpp); erfcx directly, D as x * (D(x)/x) so the relative
//     accuracy holds down to x = 0 (D(0) = 0 exactly). Coefficients are looked up per lane
//     (AVX-512: a two-vector permute; other targets: a gather).
//   - x >= 16: the asymptotic series (A&S 7.1.23 and its Dawson companion) in w = 1/(2x^2),
//       erfcx(x) = 1/(sqrt(pi) x) sum_{n<=12} (-1)^n (2n-1)!! w^n,
//       D(x)     = 1/(2x)         sum_{n<=12}        (2n-1)!! w^n;
//     at x = 16 (w = 1/512) the first omitted term is below 1e-22 relative (at 12 it was 1e-19),
//     and it only falls from there on; 1/x and w underflow gracefully, so huge x (1e300) and +inf
//     give 1/x-like values and 0.
//   The table ends at 16 (not at 12, where 13 asymptotic terms already reach double accuracy)
//   so that it has 16 intervals, the permute's size.
// The sign convention x >= 0 is all exact_batch needs (every erfcx and Dawson argument of the
// closed forms is >= 0); negative x is outside the domain (lanes give unspecified values). NaN
// lanes give NaN.
// Accuracy (tests/test_special_simd.cpp, [special_simd]): max relative error against the 50-digit
// reference (reference/special_reference.*) over ~2,300 linearly and log-spaced x in [0, 1e6],
// every table interval's ends included: erfcx 2.19e-16, Dawson 2.62e-16 (AVX-512, 2026-12-02;
// the test asserts 4e-16); against libcerf 6.8e-16 and 1.8e-15 (libcerf's own error).
#if defined(RAYINT_SPECIAL_ERFCX_SIMD_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RAYINT_SPECIAL_ERFCX_SIMD_INL_H_
#undef RAYINT_SPECIAL_ERFCX_SIMD_INL_H_
#else
#define RAYINT_SPECIAL_ERFCX_SIMD_INL_H_
#endif

#include <hwy/highway.h>

#include "rayint/special/simd_tables.hpp"

HWY_BEFORE_NAMESPACE();
namespace rayint {
namespace special {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The table polynomial at x in [0, kSimdTableEnd) (lanes outside must be set to 0 by the caller).
// Each coefficient is looked up per lane: on AVX-512 (8 lanes, 16 intervals) with one two-vector
// permute, elsewhere with a gather.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V SimdTablePoly(D d, const double* HWY_RESTRICT table, V x) {
  const hn::RebindToSigned<D> di;
  const V scaled = hn::Mul(x, hn::Set(d, 1.0 / kSimdTableStep));  // exact: a power of 2
  const auto idx = hn::ConvertTo(di, scaled);                        // floor, x >= 0
  const V fi = hn::ConvertTo(d, idx);
  // t = 2 (x - x_i) / h - 1 = 2 scaled - (2 i + 1), exact
  const V t = hn::Sub(hn::Add(scaled, scaled), hn::MulAdd(fi, hn::Set(d, 2.0), hn::Set(d, 1.0)));
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX3
  static_assert(kSimdTableIntervals == 16, "the permute looks up 16 intervals in two vectors");
  const auto coefficient = [&](int k) {
    const double* row = table + k * kSimdTableIntervals;
    return V{_mm512_permutex2var_pd(hn::LoadU(d, row).raw, idx.raw, hn::LoadU(d, row + 8).raw)};
  };
#else
  const auto coefficient = [&](int k) { return hn::GatherIndex(d, table + k * kSimdTableIntervals, idx); };
#endif
  V p = coefficient(kSimdTableDegree);
  for (int k = kSimdTableDegree - 1; k >= 0; --k) p = hn::MulAdd(p, t, coefficient(k));
  return p;
}

// sum_{n=0}^{12} sign^n (2n-1)!! w^n by Horner's rule.
template <int kSign, class D, class V = hn::Vec<D>>
HWY_INLINE V SimdAsymptoticSum(D d, V w) {
  constexpr double c[13] = {1.0,      1.0,       3.0,         15.0,         105.0,
                            945.0,    10395.0,   135135.0,    2027025.0,    34459425.0,
                            654729075.0, 13749310575.0, 316234143225.0};
  V s = hn::Set(d, (12 % 2 == 1 && kSign < 0) ? -c[12] : c[12]);
  for (int n = 11; n >= 0; --n) s = hn::MulAdd(s, w, hn::Set(d, (n % 2 == 1 && kSign < 0) ? -c[n] : c[n]));
  return s;
}

template <class D, class V = hn::Vec<D>>
HWY_INLINE V ErfcxNonneg(D d, V x) {
  const auto in_table = hn::Lt(x, hn::Set(d, kSimdTableEnd));
  V table_part = hn::Zero(d), asymptotic_part = hn::Zero(d);
  if (!hn::AllFalse(d, in_table))
    table_part = SimdTablePoly(d, kErfcxTable, hn::IfThenElseZero(in_table, x));
  if (!hn::AllTrue(d, in_table)) {
    const V xa = hn::IfThenElse(in_table, hn::Set(d, kSimdTableEnd), x);
    const V half_inv = hn::Div(hn::Set(d, 0.5), xa);
    const V w = hn::Div(half_inv, xa);  // 1/(2 x^2) without forming x^2 (no overflow)
    const V s = SimdAsymptoticSum<-1>(d, w);
    asymptotic_part = hn::Div(hn::Mul(s, hn::Set(d, 0.56418958354775628695)), xa);  // 1/sqrt(pi)
  }
  return hn::IfThenElse(in_table, table_part, asymptotic_part);
}

template <class D, class V = hn::Vec<D>>
HWY_INLINE V DawsonNonneg(D d, V x) {
  const auto in_table = hn::Lt(x, hn::Set(d, kSimdTableEnd));
  V table_part = hn::Zero(d), asymptotic_part = hn::Zero(d);
  if (!hn::AllFalse(d, in_table)) {
    const V xt = hn::IfThenElseZero(in_table, x);
    table_part = hn::Mul(xt, SimdTablePoly(d, kDawsonTable, xt));
  }
  if (!hn::AllTrue(d, in_table)) {
    const V xa = hn::IfThenElse(in_table, hn::Set(d, kSimdTableEnd), x);
    const V half_inv = hn::Div(hn::Set(d, 0.5), xa);
    const V w = hn::Div(half_inv, xa);
    asymptotic_part = hn::Mul(SimdAsymptoticSum<+1>(d, w), half_inv);
  }
  return hn::IfThenElse(in_table, table_part, asymptotic_part);
}

}  // namespace HWY_NAMESPACE
}  // namespace special
}  // namespace rayint
HWY_AFTER_NAMESPACE();

#endif  // RAYINT_SPECIAL_ERFCX_SIMD_INL_H_ toggle
