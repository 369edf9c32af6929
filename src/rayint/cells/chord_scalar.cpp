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

ChordScalar::ChordScalar(const LinearCell& cell, const ViewRay& ray, const Vec3* start)
    : m_(&cell.multilinear), cell_(&cell), o_(ray.origin), d_(ray.direction), start_(linear_reference_centre(cell.type)) {
  if (start != nullptr && start->allFinite() && inside_reference(cell.type, *start, 0.25)) start_ = *start;
}

double ChordScalar::taylor_tail(int n) const {
  // Hexahedra and voxels only: on wedges the degree-8 start and the bound's chop moved
  // tools/cell_accuracy's worst wedge errors up at the rounding level (2.42e-14 -> 2.58e-14
  // relative, 7.33e-15 -> 7.44e-15 absolute, wedge_gmsh), so wedges and pyramids keep degree 16.
  const bool hex = cell_->type == LinearCellType::hexahedron || cell_->type == LinearCellType::voxel;
  if (!converged_ || !hex) return std::numeric_limits<double>::infinity();
  // The series' truncation: every |P_k| h^k beyond order_ taken as kTaylorNegligible, times f's
  // linear coefficients, and 4x for the products and the rest of the (geometric) tail.
  const std::array<double, 8>& F = m_->f;
  double sum = 4 * kTaylorNegligible * (std::abs(F[1]) + std::abs(F[2]) + std::abs(F[3]) + std::abs(F[4]) +
                                        std::abs(F[5]) + std::abs(F[6]) + std::abs(F[7]));
  for (int k = n + 1; k <= order_; ++k) sum += std::abs(f_series_[static_cast<std::size_t>(k)]);
  return sum;
}

bool ChordScalar::newton(const Vec3& target, Vec3& p, bool step_first) {
  return multilinear_newton(*m_, target, p, step_first, newton_steps);
}

bool ChordScalar::expand(double a, double b) {
  if (order_ >= 0 && a == a_ && b == b_) return expanded_;  // series_chebyshev's expansion, reused
  a_ = a, b_ = b;
  expanded_ = false;
  order_ = -1;
  converged_ = false;
  t_c_ = 0.5 * (a + b);
  const double h = 0.5 * (b - a);
  Vec3 p0 = start_;
  // At least one step (as every sample takes): P_0 is the series' a_0 in series_chebyshev.
  if (!newton(o_ + t_c_ * d_, p0, true)) {
    p0 = linear_reference_centre(cell_->type);
    if (!newton(o_ + t_c_ * d_, p0, false)) return false;
  }
  start_ = p0;
  P_[0] = p0;
  const Eigen::Matrix3d J0 = multilinear_jacobian(*m_, p0);
  const Eigen::Matrix3d Jinv = J0.inverse();
  if (!Jinv.allFinite()) return false;
  f_c_ = cell_scalar(*cell_, p0);
  condition_ = J0.cwiseAbs().rowwise().sum().maxCoeff() * Jinv.cwiseAbs().rowwise().sum().maxCoeff();
  // Series of the products: U = rs, V = rt, W = st (full coefficients once P_k is known).
  std::array<double, kTaylorMaxOrder + 1> U{}, V{}, W{};
  U[0] = p0[0] * p0[1], V[0] = p0[0] * p0[2], W[0] = p0[1] * p0[2];
  const double r0 = p0[0], s0 = p0[1], t0 = p0[2];
  const std::array<double, 8>& F = m_->f;
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
    const Vec3 Q = Uk * m_->x[4] + Vk * m_->x[5] + Wk * m_->x[6] + Xk * m_->x[7];
    const Vec3 rhs = (k == 1 ? d_ : Vec3::Zero()) - Q;
    const Vec3 Pk = Jinv * rhs;
    if (!Pk.allFinite()) break;
    P_[K] = Pk;
    U[K] = Uk + r0 * Pk[1] + Pk[0] * s0;
    V[K] = Vk + r0 * Pk[2] + Pk[0] * t0;
    W[K] = Wk + s0 * Pk[2] + Pk[1] * t0;
    const double X = Xk + U[0] * Pk[2] + (r0 * Pk[1] + Pk[0] * s0) * t0;  // rst's coefficient
    order_ = k;
    hk *= h;
    f_series_[K] = hk * (F[1] * Pk[0] + F[2] * Pk[1] + F[3] * Pk[2] + F[4] * U[K] + F[5] * V[K] + F[6] * W[K] + F[7] * X);
    // The same sums over absolute values (series_chebyshev's rounding bound).
    const double mono[7] = {std::abs(Pk[0]), std::abs(Pk[1]), std::abs(Pk[2]), std::abs(U[K]),
                            std::abs(V[K]),  std::abs(W[K]),  std::abs(X)};
    double f_abs = 0.0, mono_abs = 0.0;
    for (std::size_t j = 0; j < 7; ++j) f_abs += std::abs(F[j + 1]) * mono[j], mono_abs += mono[j];
    f_abs_[K] = hk * f_abs, mono_abs_[K] = hk * mono_abs;
    small = (Pk.cwiseAbs().maxCoeff() * hk <= kTaylorNegligible) ? small + 1 : 0;
    if (small >= 2) {
      converged_ = true;
      break;
    }
  }
  expanded_ = true;
  return true;
}

// The series' value bound. f's exact Taylor coefficients (in x) and the computed Chebyshev
// coefficients differ by (kEps = eps):
//   - truncation: taylor_tail(m) (with its allowance for the orders beyond the series);
//   - the rounding of f's monomial coefficients (MultilinearForm::f): each an alternating sum of
//     <= 8 values f_i - f_ref (7 additions, each off by <= eps x the sum of the |terms|, and the
//     subtractions of f_ref): <= 9 eps f_spread. As f - f(P_0) = sum_j F_j (mono_j(p) -
//     mono_j(P_0)), the series is off by <= 9 eps f_spread sum_k mono_abs_[k];
//   - arithmetic of the orders k >= 1: P_k = J^-1 (rhs) carries ~ eps cond(J) |P_k| (the
//     inverse's and the products' rounding), the 7-term dot products a few eps, the Chebyshev
//     conversion ~2 eps per order: (16 + 8 cond + 4 m) eps x sum_{k >= 1} |a_k| over absolute
//     values (that part's Chebyshev coefficients are bounded by sum_{k >= 1} |a_k|, |T_j| <= 1);
//   - a_0 = f(P_0) in the nodal form, added to c_0 last: N_i products of three factors (~4 eps
//     each), a sum of 8 nonnegative-weighted terms (7 eps max|f_i|), the final addition (1 eps):
//     16 eps max|f_i|; P_0 after a polishing Newton step (expand), off by rounding only (~eps |p|
//     times |grad f|, inside the same allowance).
// The constants are generous (rounding bounds of this shape are ~n eps); measured with
// tools/cell_accuracy and `rayint eval` (reports/cells/bench.md, "Hexahedra's chord scalar from
// its own Taylor series"): no chord's error above its estimate, worst errors main's.
bool ChordScalar::series_chebyshev(double chop, std::array<double, kTaylorMaxOrder + 1>& c, int& degree,
                                   double& error) const {
  const bool hex = cell_->type == LinearCellType::hexahedron || cell_->type == LinearCellType::voxel;
  if (!expanded_ || !converged_ || !hex) return false;
  // The smallest m >= 1 with taylor_tail(m) <= chop (the tail falls as m grows): from the top.
  double tail = taylor_tail(order_);
  if (!(tail <= chop) || order_ < 1) return false;
  int m = order_;
  while (m > 1 && tail + std::abs(f_series_[static_cast<std::size_t>(m)]) <= chop)
    tail += std::abs(f_series_[static_cast<std::size_t>(m--)]);
  double a_abs = 0.0, mono_abs = 0.0;
  for (int k = 1; k <= order_; ++k) {
    const auto K = static_cast<std::size_t>(k);
    if (k <= m) a_abs += f_abs_[K];
    mono_abs += mono_abs_[K];
  }
  double value_scale = 0.0;
  for (int i = 0; i < linear_node_count(cell_->type); ++i)
    value_scale = std::max(value_scale, std::abs(cell_->value[static_cast<std::size_t>(i)]));
  error = tail + 9 * kEps * m_->f_spread * mono_abs + (16 + 8 * condition_ + 4 * m) * kEps * a_abs +
          16 * kEps * value_scale;
  if (!std::isfinite(error)) return false;
  // c_j = sum_k a_k B_kj with x^k = sum_j B_kj T_j (a static table: dyadic rationals times
  // binomials, exact in double up to k = 24; sum_j |B_kj| = 1), a_0 = f(P_0) added last.
  static const auto B = [] {
    std::array<std::array<double, kTaylorMaxOrder + 2>, kTaylorMaxOrder + 1> t{};
    t[0][0] = 1.0;
    for (std::size_t k = 1; k <= kTaylorMaxOrder; ++k) {  // x T_0 = T_1, x T_j = (T_j+1 + T_j-1) / 2
      t[k][1] += t[k - 1][0];
      for (std::size_t j = 1; j < k; ++j)
        t[k][j + 1] += 0.5 * t[k - 1][j], t[k][j - 1] += 0.5 * t[k - 1][j];
    }
    return t;
  }();
  for (int j = 0; j <= m; ++j) {
    double sum = 0.0;
    for (int k = m - ((m - j) % 2); k >= std::max(j, 1); k -= 2)
      sum += f_series_[static_cast<std::size_t>(k)] * B[static_cast<std::size_t>(k)][static_cast<std::size_t>(j)];
    c[static_cast<std::size_t>(j)] = j == 0 ? f_c_ + sum : sum;
  }
  degree = m;
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
