// The scalar of a linear cell along a ray: multilinear form, Taylor predictor, Newton (see
// chord_scalar.hpp for the method, the acceptance test and the thresholds).
#include "rayint/cells/chord_scalar.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

namespace rayint {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

struct Monomials {
  double r, s, t, rs, rt, st, rst;
  explicit Monomials(const Vec3& p)
      : r(p[0]), s(p[1]), t(p[2]), rs(p[0] * p[1]), rt(p[0] * p[2]), st(p[1] * p[2]), rst(p[0] * p[1] * p[2]) {}
};

Vec3 position(const MultilinearCell& m, const Monomials& q) {
  return m.x[0] + q.r * m.x[1] + q.s * m.x[2] + q.t * m.x[3] + q.rs * m.x[4] + q.rt * m.x[5] + q.st * m.x[6] +
         q.rst * m.x[7];
}

Eigen::Matrix3d jacobian(const MultilinearCell& m, const Monomials& q) {
  Eigen::Matrix3d J;
  J.col(0) = m.x[1] + q.s * m.x[4] + q.t * m.x[5] + q.st * m.x[7];
  J.col(1) = m.x[2] + q.r * m.x[4] + q.t * m.x[6] + q.rt * m.x[7];
  J.col(2) = m.x[3] + q.r * m.x[5] + q.s * m.x[6] + q.rs * m.x[7];
  return J;
}

}  // namespace

namespace {

// The coefficients of a per-node quantity (positions, scalars) in the monomials 1, r, s, t, rs,
// rt, st, rst: its values at the corners q of the unit cube (bit 0: r, bit 1: s, bit 2: t) from
// the nodal form, then Moebius inversion (the coefficient of the monomial with exponent bits m
// is the alternating sum over the corners q contained in m). A hexahedron's or voxel's corners
// are its nodes (the shape functions are exactly 0 and 1 there, so reading the node is the
// same value bit for bit); a wedge's, pyramid's or tetra's corners outside the domain come
// from the shape functions, which are polynomials.
template <class V>
std::array<V, 8> monomial_coefficients(LinearCellType type, const V* node, const V& zero) {
  constexpr int kHexCorner[8] = {0, 1, 3, 2, 4, 5, 7, 6};  // node at corner q
  const int n = linear_node_count(type);
  std::array<V, 8> corner;
  double N[kMaxLinearNodes];
  for (int q = 0; q < 8; ++q) {
    const auto Q = static_cast<std::size_t>(q);
    if (type == LinearCellType::hexahedron) {
      corner[Q] = node[kHexCorner[q]];
    } else if (type == LinearCellType::voxel) {
      corner[Q] = node[q];
    } else {
      linear_shape_functions(type, Vec3((q & 1) ? 1.0 : 0.0, (q & 2) ? 1.0 : 0.0, (q & 4) ? 1.0 : 0.0), N);
      V v = zero;
      for (int i = 0; i < n; ++i) v += N[i] * node[i];
      corner[Q] = v;
    }
  }
  constexpr int kBits[8] = {0, 1, 2, 4, 3, 5, 6, 7};  // slots 1, r, s, t, rs, rt, st, rst
  std::array<V, 8> out;
  for (int slot = 0; slot < 8; ++slot) {
    const int bits = kBits[slot];
    V v = zero;
    for (int q = 0; q < 8; ++q) {
      if ((q & ~bits) != 0) continue;
      const int parity = __builtin_popcount(static_cast<unsigned>(bits ^ q)) % 2;
      v += (parity == 0 ? 1.0 : -1.0) * corner[static_cast<std::size_t>(q)];
    }
    out[static_cast<std::size_t>(slot)] = v;
  }
  return out;
}

}  // namespace

double affine_chord_chebyshev(const LinearCell& cell, const ViewRay& ray, double a, double b, std::array<double, 4>& c) {
  const double m = 0.5 * (a + b), h = 0.5 * (b - a);
  const Vec3 pc = cell.affine_inverse * (ray.origin + m * ray.direction - cell.affine_origin);
  const Vec3 ph = cell.affine_inverse * (h * ray.direction);
  // Polynomials in x as coefficient arrays; a linear factor (u0 + u1 x).
  using Poly = std::array<double, 4>;
  const auto times = [](const Poly& p, const Poly& u) {
    return Poly{p[0] * u[0], p[0] * u[1] + p[1] * u[0], p[1] * u[1] + p[2] * u[0], p[2] * u[1] + p[3] * u[0]};
  };
  const auto abs_poly = [](const Poly& p) { return Poly{std::abs(p[0]), std::abs(p[1]), std::abs(p[2]), std::abs(p[3])}; };
  // The nodal form (wedges; hexahedra and voxels factorised, below): each N_i a product of linear factors in x,
  // nonnegative on the chord (a partition of unity), so the sum is as well conditioned as one
  // nodal evaluation.
  Poly lo[3], hi[3];  // 1 - p_k and p_k
  for (int k = 0; k < 3; ++k) hi[k] = {pc[k], ph[k], 0.0, 0.0}, lo[k] = {1.0 - pc[k], -ph[k], 0.0, 0.0};
  // f = f_ref + sum_i N_i (f_i - f_ref) (sum_i N_i = 1): the products' rounding then scales
  // with the node values' spread, not their size (f_ref the midrange, added to c_0 last).
  const int n = linear_node_count(cell.type);
  double f_lo = cell.value[0], f_hi = cell.value[0];
  for (int i = 1; i < n; ++i)
    f_lo = std::min(f_lo, cell.value[static_cast<std::size_t>(i)]), f_hi = std::max(f_hi, cell.value[static_cast<std::size_t>(i)]);
  const double f_ref = 0.5 * (f_lo + f_hi);
  Poly g{}, g_abs{};
  if (cell.type == LinearCellType::wedge) {
    const Poly w{1.0 - pc[0] - pc[1], -ph[0] - ph[1], 0.0, 0.0};
    const Poly tri[3] = {w, hi[0], hi[1]};
    for (int i = 0; i < n; ++i) {
      const Poly p = times(tri[i % 3], i < 3 ? lo[2] : hi[2]);
      const Poly pa = abs_poly(p);
      const double f = cell.value[static_cast<std::size_t>(i)] - f_ref;
      for (std::size_t j = 0; j < 4; ++j) g[j] += f * p[j], g_abs[j] += std::abs(f) * pa[j];
    }
  } else {
    // Voxel (node bits: r, s, t) or hexahedron (VTK's order around each layer), factorised as
    // the trilinear form is: along r, then s, then t (7 products of a polynomial by a linear
    // factor instead of 16; every factor is nonnegative on the chord, so each stage is a convex
    // combination, as well conditioned as the nodal sum). g_abs: the same with absolute values
    // everywhere, >= the nodal form's sum of |f_i - f_ref| |N_i| (measured ~15 % of `rayint
    // bench` box12's affine_chord_chebyshev time before, 2026-12-05).
    constexpr int kHexBits[8] = {0, 1, 3, 2, 4, 5, 7, 6};  // hexahedron node -> corner bits
    std::array<double, 8> fv{};
    for (int i = 0; i < 8; ++i)
      fv[static_cast<std::size_t>(cell.type == LinearCellType::voxel ? i : kHexBits[i])] = cell.value[static_cast<std::size_t>(i)] - f_ref;
    const auto combine = [&](const Poly& p0, const Poly& p1, int axis) {  // p0 (1 - r_k) + p1 r_k
      const Poly a0 = times(p0, lo[axis]), a1 = times(p1, hi[axis]);
      return Poly{a0[0] + a1[0], a0[1] + a1[1], a0[2] + a1[2], a0[3] + a1[3]};
    };
    Poly lo_abs[3], hi_abs[3];
    for (int k = 0; k < 3; ++k) lo_abs[k] = abs_poly(lo[k]), hi_abs[k] = abs_poly(hi[k]);
    const auto combine_abs = [&](const Poly& p0, const Poly& p1, int axis) {
      const Poly a0 = times(p0, lo_abs[axis]), a1 = times(p1, hi_abs[axis]);
      return Poly{a0[0] + a1[0], a0[1] + a1[1], a0[2] + a1[2], a0[3] + a1[3]};
    };
    Poly A[4], A_abs[4];
    for (std::size_t st = 0; st < 4; ++st) {
      const double f0 = fv[2 * st], f1 = fv[2 * st + 1];
      A[st] = combine(Poly{f0, 0.0, 0.0, 0.0}, Poly{f1, 0.0, 0.0, 0.0}, 0);
      A_abs[st] = combine_abs(Poly{std::abs(f0), 0.0, 0.0, 0.0}, Poly{std::abs(f1), 0.0, 0.0, 0.0}, 0);
    }
    const Poly B0 = combine(A[0], A[1], 1), B1 = combine(A[2], A[3], 1);
    const Poly B0_abs = combine_abs(A_abs[0], A_abs[1], 1), B1_abs = combine_abs(A_abs[2], A_abs[3], 1);
    g = combine(B0, B1, 2);
    g_abs = combine_abs(B0_abs, B1_abs, 2);
  }
  // x^2 = (T0 + T2) / 2, x^3 = (3 T1 + T3) / 4.
  c = {f_ref + (g[0] + 0.5 * g[2]), g[1] + 0.75 * g[3], 0.5 * g[2], 0.25 * g[3]};
  return 8 * kEps * (g_abs[0] + g_abs[1] + g_abs[2] + g_abs[3]) + kEps * std::abs(f_ref);
}

MultilinearCell multilinear_form(const LinearCell& cell) {
  MultilinearCell m;
  m.type = cell.type;
  const int n = linear_node_count(cell.type);
  for (int i = 0; i < n; ++i) m.magnitude = std::max(m.magnitude, cell.x[static_cast<std::size_t>(i)].cwiseAbs().maxCoeff());
  m.x = monomial_coefficients<Vec3>(cell.type, cell.x.data(), Vec3::Zero());
  return m;
}

ChordScalar::ChordScalar(const LinearCell& cell, const ViewRay& ray, const Vec3* start)
    : m_(multilinear_form(cell)), cell_(&cell), o_(ray.origin), d_(ray.direction),
      start_(linear_reference_centre(cell.type)) {
  if (start != nullptr && start->allFinite() && inside_reference(cell.type, *start, 0.25)) start_ = *start;
  // f's monomial coefficients, as x's: used only for taylor_tail's bound, never for a value of f.
  F_ = monomial_coefficients<double>(cell.type, cell.value.data(), 0.0);
}

double ChordScalar::taylor_tail(int n) const {
  // Hexahedra and voxels only: on wedges the degree-8 start and the bound's chop moved
  // tools/cell_accuracy's worst wedge errors up at the rounding level (2.42e-14 -> 2.58e-14
  // relative, 7.33e-15 -> 7.44e-15 absolute, wedge_gmsh), so wedges and pyramids keep degree 16.
  const bool hex = m_.type == LinearCellType::hexahedron || m_.type == LinearCellType::voxel;
  if (!converged_ || !hex) return std::numeric_limits<double>::infinity();
  // The series' truncation: every |P_k| h^k beyond order_ taken as kTaylorNegligible, times f's
  // linear coefficients, and 4x for the products and the rest of the (geometric) tail.
  double sum = 4 * kTaylorNegligible * (std::abs(F_[1]) + std::abs(F_[2]) + std::abs(F_[3]) + std::abs(F_[4]) +
                                        std::abs(F_[5]) + std::abs(F_[6]) + std::abs(F_[7]));
  for (int k = n + 1; k <= order_; ++k) sum += std::abs(f_series_[static_cast<std::size_t>(k)]);
  return sum;
}

// linear_cells.cpp's inverse_map on the multilinear form: the same tolerances and budget.
// With `step_first` the residual test is skipped before the first step: a point that passes it
// by a hair (a Taylor prediction) still takes one step, and near a singular Jacobian (a
// pyramid's apex) the residual bound alone leaves the point off by |J^-1| 8 eps |x|.
bool ChordScalar::newton(const Vec3& target, Vec3& p, bool step_first) {
  const double residual_tolerance = 8 * kEps * std::max(m_.magnitude, target.cwiseAbs().maxCoeff());
  for (int it = 0; it < kNewtonMaxIterations; ++it) {
    const Monomials q(p);
    const Vec3 residual = target - position(m_, q);
    if (!(step_first && it == 0) && residual.cwiseAbs().maxCoeff() <= residual_tolerance) return true;
    Vec3 step = jacobian(m_, q).inverse() * residual;
    ++newton_steps;
    if (!step.allFinite()) return false;
    const double size = step.cwiseAbs().maxCoeff();
    if (size > kNewtonMaxStep) step *= kNewtonMaxStep / size;
    p += step;
    if (size <= kNewtonStepTolerance) return true;
  }
  return false;
}

bool ChordScalar::expand(double a, double b) {
  order_ = -1;
  converged_ = false;
  t_c_ = 0.5 * (a + b);
  const double h = 0.5 * (b - a);
  Vec3 p0 = start_;
  if (!newton(o_ + t_c_ * d_, p0, false)) {
    p0 = linear_reference_centre(cell_->type);
    if (!newton(o_ + t_c_ * d_, p0, false)) return false;
  }
  start_ = p0;
  P_[0] = p0;
  const Monomials q0(p0);
  const Eigen::Matrix3d Jinv = jacobian(m_, q0).inverse();
  if (!Jinv.allFinite()) return false;
  // Series of the products: U = rs, V = rt, W = st (full coefficients once P_k is known).
  std::array<double, kTaylorMaxOrder + 1> U{}, V{}, W{};
  U[0] = q0.rs, V[0] = q0.rt, W[0] = q0.st;
  const double r0 = p0[0], s0 = p0[1], t0 = p0[2];
  int small = 0;
  double hk = 1.0;
  order_ = 0;
  for (int k = 1; k <= kTaylorMaxOrder; ++k) {
    const auto K = static_cast<std::size_t>(k);
    double Uk = 0.0, Vk = 0.0, Wk = 0.0, Xk = 0.0;  // the parts without order-k unknowns
    for (std::size_t i = 1; i < K; ++i) {
      const Vec3& a_i = P_[i];
      const Vec3& b_j = P_[K - i];
      Uk += a_i[0] * b_j[1];
      Vk += a_i[0] * b_j[2];
      Wk += a_i[1] * b_j[2];
      Xk += U[i] * P_[K - i][2];
    }
    Xk += Uk * t0;
    const Vec3 Q = Uk * m_.x[4] + Vk * m_.x[5] + Wk * m_.x[6] + Xk * m_.x[7];
    const Vec3 rhs = (k == 1 ? d_ : Vec3::Zero()) - Q;
    const Vec3 Pk = Jinv * rhs;
    if (!Pk.allFinite()) break;
    P_[K] = Pk;
    U[K] = Uk + r0 * Pk[1] + Pk[0] * s0;
    V[K] = Vk + r0 * Pk[2] + Pk[0] * t0;
    W[K] = Wk + s0 * Pk[2] + Pk[1] * t0;
    const double X = Xk + q0.rs * Pk[2] + (r0 * Pk[1] + Pk[0] * s0) * t0;  // rst's coefficient
    order_ = k;
    hk *= h;
    f_series_[K] = hk * (F_[1] * Pk[0] + F_[2] * Pk[1] + F_[3] * Pk[2] + F_[4] * U[K] + F_[5] * V[K] + F_[6] * W[K] + F_[7] * X);
    small = (Pk.cwiseAbs().maxCoeff() * hk <= kTaylorNegligible) ? small + 1 : 0;
    if (small >= 2) {
      converged_ = true;
      break;
    }
  }
  return true;
}

bool ChordScalar::sample(double t, double& f) {
  ++samples;
  const Vec3 target = o_ + t * d_;
  Vec3 p = start_;
  bool from_prediction = false;
  if (order_ >= 0) {
    const double tau = t - t_c_;
    Vec3 pred = P_[static_cast<std::size_t>(order_)];
    for (int k = order_ - 1; k >= 0; --k) pred = pred * tau + P_[static_cast<std::size_t>(k)];
    if (pred.allFinite() && inside_reference(cell_->type, pred, 0.25)) {
      p = pred;
      from_prediction = true;
    }
  }
  const int steps_before = newton_steps;
  bool ok = newton(target, p, from_prediction);
  if (ok && from_prediction && newton_steps == steps_before + 1) ++predicted;
  if (!ok && from_prediction) {
    p = start_;
    ok = newton(target, p, false);
  }
  if (!ok) {
    p = linear_reference_centre(cell_->type);
    ok = newton(target, p, false);
  }
  if (!ok) return false;
  start_ = p;
  // The scalar from the nodal form (sum N_i f_i, as cell_scalar): the monomial coefficients are
  // alternating sums of up to eight node values, whose rounding (~8 eps max|f_i|) would bias f;
  // measured on 200 warped pyramids: one chord's error above its estimate with the monomial f.
  f = cell_scalar(*cell_, p);
  return true;
}

}  // namespace rayint
