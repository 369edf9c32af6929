// The emission integrand at a batch of nodes (emission_nodes.hpp), compiled once per Highway
// target (hwy/foreach_target.h) and dispatched at run time (HWY_DYNAMIC_DISPATCH).
#include "rayint/cells/emission_nodes.hpp"

#include <cmath>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "rayint/cells/emission_nodes.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>
#include <hwy/contrib/math/math-inl.h>

HWY_BEFORE_NAMESPACE();
namespace rayint {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// sum_k a[k] T_k(x), as the scalar clenshaw of cell_integral.cpp (same operations, same order;
// the compiler may fuse multiply-adds on FMA targets).
template <class D, class V>
HWY_INLINE V Clenshaw(D d, const double* a, std::size_t n, V x) {
  V b1 = hn::Zero(d), b2 = hn::Zero(d);
  const V two_x = hn::Mul(hn::Set(d, 2.0), x);
  for (std::size_t k = n; k-- > 1;) {
    const V b0 = hn::Add(hn::Sub(hn::Mul(two_x, b1), b2), hn::Set(d, a[k]));
    b2 = b1;
    b1 = b0;
  }
  return hn::Add(hn::Sub(hn::Mul(x, b1), b2), hn::Set(d, n == 0 ? 0.0 : a[0]));
}

void EmissionAtNodes(const EmissionPiece& p, double centre, double half, const double* u, std::size_t n, double* out) {
  const hn::ScalableTag<double> d;
  using V = hn::Vec<decltype(d)>;
  constexpr std::size_t kMaxLanes = HWY_MAX_BYTES / sizeof(double);
  const std::size_t L = hn::Lanes(d);
  HWY_ALIGN double w[kChannels][kMaxLanes], arg[kChannels][kMaxLanes], g[kChannels][kMaxLanes];
  const V lo = hn::Set(d, -700.0), hi = hn::Set(d, 700.0);
  for (std::size_t i = 0; i < n; i += L) {
    const std::size_t m = n - i < L ? n - i : L;
    const V xv = hn::Add(hn::Set(d, centre), hn::Mul(hn::Set(d, half), hn::LoadU(d, u + i)));
    const V f = Clenshaw(d, p.c, p.nc, xv);
    const V dx = hn::Sub(xv, hn::Set(d, p.x0));
    const V dP = hn::Sub(Clenshaw(d, p.P, p.nP, xv), hn::Set(d, p.P0));
    bool in_range = true;
    for (std::size_t c = 0; c < kChannels; ++c) {
      const EmissionLinear &r = p.rho[c], &q = p.kappa[c];
      const V rho = hn::Add(hn::Set(d, r.v0), hn::Mul(hn::Set(d, r.beta), hn::Sub(f, hn::Set(d, r.s0))));
      const V kappa = hn::Add(hn::Set(d, q.v0), hn::Mul(hn::Set(d, q.beta), hn::Sub(f, hn::Set(d, q.s0))));
      const V weight = hn::Mul(kappa, rho);
      const V tau = hn::Mul(hn::Set(d, p.h),
                            hn::Add(hn::Mul(hn::Set(d, r.v0), dx),
                                    hn::Mul(hn::Set(d, r.beta), hn::Sub(dP, hn::Mul(hn::Set(d, r.s0), dx)))));
      const V a = hn::Neg(tau);
      in_range = in_range && hn::AllTrue(d, hn::And(hn::Ge(a, lo), hn::Le(a, hi)));
      const V value = hn::IfThenZeroElse(hn::Eq(weight, hn::Zero(d)), hn::Mul(weight, hn::Exp(d, a)));
      hn::Store(value, d, g[c]);
      hn::Store(weight, d, w[c]);
      hn::Store(a, d, arg[c]);
    }
    for (std::size_t k = 0; k < m; ++k)
      for (std::size_t c = 0; c < kChannels; ++c) {
        double v = g[c][k];
        if (!in_range && !(arg[c][k] >= -700.0 && arg[c][k] <= 700.0)) v = w[c][k] == 0.0 ? 0.0 : w[c][k] * std::exp(arg[c][k]);
        out[kChannels * (i + k) + c] = v;
      }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace rayint
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace rayint {

HWY_EXPORT(EmissionAtNodes);

void emission_at_nodes(const EmissionPiece& piece, double centre, double half, const double* u, std::size_t n,
                       double* out) {
  HWY_DYNAMIC_DISPATCH(EmissionAtNodes)(piece, centre, half, u, n, out);
}

}  // namespace rayint
#endif  // HWY_ONCE
