// Array forms of the vector special functions (erfcx_simd.hpp), compiled once per Highway target
// (hwy/foreach_target.h) and dispatched at run time (HWY_DYNAMIC_DISPATCH).
#include "rayint/special/erfcx_simd.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "rayint/special/erfcx_simd.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>
#include <hwy/contrib/math/math-inl.h>

#include "rayint/special/erfcx_simd-inl.hpp"

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

void erfcx_array(const double* x, double* y, std::size_t n) { HWY_DYNAMIC_DISPATCH(ErfcxArray)(x, y, n); }
void dawson_array(const double* x, double* y, std::size_t n) { HWY_DYNAMIC_DISPATCH(DawsonArray)(x, y, n); }
void exp_array(const double* x, double* y, std::size_t n) { HWY_DYNAMIC_DISPATCH(ExpArray)(x, y, n); }
void expm1_array(const double* x, double* y, std::size_t n) { HWY_DYNAMIC_DISPATCH(Expm1Array)(x, y, n); }
const char* simd_target_name() { return HWY_DYNAMIC_DISPATCH(TargetName)(); }

}  // namespace rayint::special
#endif  // HWY_ONCE
