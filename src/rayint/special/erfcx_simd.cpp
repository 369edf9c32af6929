// Array forms of the vector special functions (erfcx_simd.hpp), compiled once per Highway target
// (hwy/foreach_target.h) and dispatched at run time (HWY_DYNAMIC_DISPATCH).
#include "rayint/special/erfcx_simd.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "rayint/special/erfcx_simd.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>
#include <hwy/contrib/math/math-inl.h>

#include "rayint/special/erfcx_simd-inl.hpp"

#ifndef RAYINT_ERFCX_SIMD_SHARED
#define RAYINT_ERFCX_SIMD_SHARED
#include <cmath>
namespace rayint::special::detail {
// 2^(j/32), j = 0..31, as hi + lo: hi the double nearest, lo the rest, from exp2l (64-bit
// significand on x86-64; hi + lo within ~2^-63 relative, 1/1000 of a double's ulp).
struct Exp2Table {
  alignas(64) double hi[32];
  alignas(64) double lo[32];
  Exp2Table() {
    for (int j = 0; j < 32; ++j) {
      const long double v = std::exp2l(static_cast<long double>(j) / 32.0L);
      hi[j] = static_cast<double>(v);
      lo[j] = static_cast<double>(v - static_cast<long double>(hi[j]));
    }
  }
};
inline const Exp2Table& exp2_table() {
  static const Exp2Table table;
  return table;
}
}  // namespace rayint::special::detail
#endif

HWY_BEFORE_NAMESPACE();
namespace rayint {
namespace special {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

template <class F>
HWY_INLINE void apply(const double* x, double* y, std::size_t n, F f) {
  const hn::ScalableTag<double> d;
  const std::size_t L = hn::Lanes(d);
  std::size_t i = 0;
  for (; i + L <= n; i += L) hn::StoreU(f(d, hn::LoadU(d, x + i)), d, y + i);
  if (i < n) {  // the tail through a padded buffer
    HWY_ALIGN double buf[HWY_MAX_BYTES / sizeof(double)] = {};
    for (std::size_t k = 0; k < L; ++k) buf[k] = i + k < n ? x[i + k] : 1.0;
    hn::Store(f(d, hn::Load(d, buf)), d, buf);
    for (std::size_t k = 0; i + k < n; ++k) y[i + k] = buf[k];
  }
}

struct ErfcxOp {
  template <class D, class V> HWY_INLINE V operator()(D d, V v) const { return ErfcxNonneg(d, v); }
};
struct DawsonOp {
  template <class D, class V> HWY_INLINE V operator()(D d, V v) const { return DawsonNonneg(d, v); }
};
struct ExpOp {
  template <class D, class V> HWY_INLINE V operator()(D d, V v) const { return hn::Exp(d, v); }
};
struct Expm1Op {
  template <class D, class V> HWY_INLINE V operator()(D d, V v) const { return hn::Expm1(d, v); }
};

// exp(-x) for 0 <= x <= kExpNegVectorMax (exp_neg_array), table-driven (Tang's method): with
// k = round(-x 32/ln2), r = -x - k ln2/32 (|r| <= ln2/64; ln2/32 split in a 36-bit hi, so k hi
// is exact for |k| < 2^17, and a lo), e^-x = 2^(k >> 5) 2^((k & 31)/32) e^r with
// e^r = 1 + p, p the Taylor polynomial of degree 7 (next term < 5e-21; degree 6's, 3.4e-18, cost
// 0.03 ulp where the result is just below a power of two), and the table
// entry T = hi + lo (detail::Exp2Table): e^-x = 2^m (hi + (lo + hi p)). (The compiler may fuse a
// product and a sum on targets with FMA: the last bit can differ between targets, the bound not.)
// Errors: the final addition 0.5 ulp; hi p (|p| < 0.011) 0.006 ulp; r, p and
// lo together below 0.01 ulp: at most ~0.52 ulp; measured against 50 digits on 8715 arguments
// in [0, 700] (tests/test_special_simd.cpp): 0.514 ulp (AVX2, AVX-512), 0.516 (SSE4), std::exp
// 0.501 on the same points; 24-26 of them differ from std::exp (in the last bit). The result is
// normal (x <= 700), so the scaling is exact.
constexpr double kExpNegVectorMax = 700.0;
template <class D, class V>
HWY_INLINE V ExpNegAccurate(D d, V x, const detail::Exp2Table& table) {
  const hn::RebindToSigned<D> di;
  const V z = hn::Neg(x);
  const V kf = hn::Round(hn::Mul(z, hn::Set(d, 0x1.71547652b82fep+5)));  // 32/ln2
  const V ln2_32_hi = hn::Set(d, 0x1.62e42fefa0000p-6), ln2_32_lo = hn::Set(d, 0x1.cf79abc9e3b3ap-45);
  const V r = hn::Sub(hn::Sub(z, hn::Mul(kf, ln2_32_hi)), hn::Mul(kf, ln2_32_lo));
  V q = hn::Set(d, 1.0 / 5040);
  q = hn::Add(hn::Mul(q, r), hn::Set(d, 1.0 / 720));
  q = hn::Add(hn::Mul(q, r), hn::Set(d, 1.0 / 120));
  q = hn::Add(hn::Mul(q, r), hn::Set(d, 1.0 / 24));
  q = hn::Add(hn::Mul(q, r), hn::Set(d, 1.0 / 6));
  q = hn::Add(hn::Mul(q, r), hn::Set(d, 0.5));
  const V p = hn::Add(r, hn::Mul(hn::Mul(r, r), q));
  const auto k = hn::ConvertTo(di, kf);
  const auto j = hn::And(k, hn::Set(di, 31));
  const V hi = hn::GatherIndex(d, table.hi, j), lo = hn::GatherIndex(d, table.lo, j);
  const V s = hn::Add(hi, hn::Add(lo, hn::Mul(hi, p)));
  const auto m = hn::ShiftRight<5>(k);
  const V scale = hn::BitCast(d, hn::ShiftLeft<52>(hn::Add(m, hn::Set(di, 1023))));
  return hn::Mul(s, scale);
}
void ExpNegArray(const double* x, double* y, std::size_t n) {
  // Lanes outside [0, kExpNegVectorMax] (or NaN) are taken from std::exp after the vector pass.
  const hn::ScalableTag<double> d;
  const std::size_t L = hn::Lanes(d);
  const detail::Exp2Table& table = detail::exp2_table();  // once, not per vector
  std::size_t i = 0;
  bool outside = false;
  for (; i + L <= n; i += L) {
    const auto v = hn::LoadU(d, x + i);
    outside |= !hn::AllTrue(d, hn::And(hn::Ge(v, hn::Zero(d)), hn::Le(v, hn::Set(d, kExpNegVectorMax))));
    hn::StoreU(ExpNegAccurate(d, hn::Min(hn::Max(v, hn::Zero(d)), hn::Set(d, kExpNegVectorMax)), table), d, y + i);
  }
  for (; i < n; ++i) y[i] = std::exp(-x[i]);
  if (outside)
    for (std::size_t k = 0; k < n; ++k)
      if (!(x[k] >= 0.0 && x[k] <= kExpNegVectorMax)) y[k] = std::exp(-x[k]);
}

void ErfcxArray(const double* x, double* y, std::size_t n) { apply(x, y, n, ErfcxOp()); }
void DawsonArray(const double* x, double* y, std::size_t n) { apply(x, y, n, DawsonOp()); }
void ExpArray(const double* x, double* y, std::size_t n) { apply(x, y, n, ExpOp()); }
void Expm1Array(const double* x, double* y, std::size_t n) { apply(x, y, n, Expm1Op()); }
const char* TargetName() { return hwy::TargetName(HWY_TARGET); }

}  // namespace HWY_NAMESPACE
}  // namespace special
}  // namespace rayint
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace rayint::special {

HWY_EXPORT(ErfcxArray);
HWY_EXPORT(DawsonArray);
HWY_EXPORT(ExpArray);
HWY_EXPORT(Expm1Array);
HWY_EXPORT(TargetName);
HWY_EXPORT(ExpNegArray);

void erfcx_array(const double* x, double* y, std::size_t n) { HWY_DYNAMIC_DISPATCH(ErfcxArray)(x, y, n); }
void dawson_array(const double* x, double* y, std::size_t n) { HWY_DYNAMIC_DISPATCH(DawsonArray)(x, y, n); }
void exp_array(const double* x, double* y, std::size_t n) { HWY_DYNAMIC_DISPATCH(ExpArray)(x, y, n); }
void expm1_array(const double* x, double* y, std::size_t n) { HWY_DYNAMIC_DISPATCH(Expm1Array)(x, y, n); }
void exp_neg_array(const double* x, double* y, std::size_t n) { HWY_DYNAMIC_DISPATCH(ExpNegArray)(x, y, n); }
const char* simd_target_name() { return HWY_DYNAMIC_DISPATCH(TargetName)(); }

}  // namespace rayint::special
#endif  // HWY_ONCE
