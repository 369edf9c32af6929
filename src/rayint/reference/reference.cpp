// The independent high-precision reference for the emission-absorption ray integral of
// Williams & Max (1992).
//
// What it computes. On one piece, with s the distance from the exit (eye side) in [0, L],
//   rho(s)   = rho_exit   + (rho_far   - rho_exit)   s / L,
//   kappa(s) = kappa_exit + (kappa_far - kappa_exit) s / L,
//   tau(s)   = rho_exit s + (rho_far - rho_exit) s^2 / (2 L)      (optical depth to the exit),
//   T = tau(L) = L (rho_far + rho_exit) / 2,   transmittance = exp(-T),
//   emission = integral_0^L kappa(s) rho(s) exp(-tau(s)) ds       (Williams & Max Eq. 4),
//   intensity = incoming exp(-T) + emission.
// A ray is split at the transfer-function breakpoints (Sec. 3.3) and composited far -> near,
// I <- I exp(-T_k) + emission_k, from the background, per channel.
//
// It never calls the closed-form code (integrators/exact.*) nor the double-precision splitting
// (model/pieces.*): everything below is done in cpp_bin_float_50 (168-bit significand,
// eps = 5.3e-51) from the exact double inputs.
//
// Methods, by region:
//   - L = 0, rho = 0 everywhere or kappa = 0 everywhere: emission exactly 0, no quadrature.
//   - Otherwise Eq. 4 by non-adaptive Gauss-Kronrod quadrature (Boost.Math nodes and weights,
//     15- to 61-point rules) on n equal subintervals of [0, s_cut]. Error estimate: the sum
//     over subintervals of |Kronrod - Gauss|, i.e. the Gauss error, which for this entire
//     integrand exceeds the Kronrod error by many orders (measured: estimate ~1e-38..1e-47,
//     true error ~1e-50).
//       * Rule and n: the cheapest (measured cost) that keeps every subinterval within the
//         rule's calibrated limits on the optical-depth increment 2 rho(c) h and the curvature
//         term |a| h^2 (kRules). Thin pieces (T < 0.5) take 15 to 31 points on one or two
//         subintervals, T ~ 1-10 one subinterval of 31-61 points, thick pieces 61 points on
//         8 (rho constant: ceil(140 / 18)) to 16 (rho rising from 0) subintervals.
//       * Thick pieces (T > 140): integration stops at tau(s_cut) = tau_cut = 140; the rest is
//         bounded by max kappa on [s_cut, L] times exp(-tau_cut) and added to the error;
//         tau_cut is raised when that bound exceeds kTargetRelative (1e-36) of the emission
//         (kappa vanishing at the exit of a piece with T > ~1e24).
//       * If the estimate misses kTargetRelative the subintervals are doubled (budget 4; in a
//         scan of 3000 random pieces from T = 1e-6 to 1e3 this happened once). The detailed
//         result reports `converged`; the error bound is honest either way.
//     Node values: on a subinterval with centre c and half-width h, tau(c + h y) =
//     tau(c) + rho(c) h y + a h^2 y^2 (a = rho' / 2), so exp(-tau) at the pair c -+ h y is
//     exp(-tau(c)) exp(-a h^2 y^2) exp(+- rho(c) h y): two Taylor series with argument halving
//     (exp_series, ~2-3x faster than Boost's exp for these arguments) and a reciprocal per
//     pair, instead of two exps; the factors move from one subinterval to the next by a
//     multiplication by exp(-+ 4 a h^2 y). exp(-tau(c)) and exp(-T) use Boost's exp.
//     Cost per piece and channel (CPU time, busy 2-core machine): 27-63 us for T <= 0.01,
//     64-153 us for T = 0.3-5, 140-290 us at T = 30, 305-510 us for T >= 500; 4-15x less than
//     the 61-point rule with Boost's exp at every node.
// Error bound: quadrature estimate + truncation bound + rounding (series, recurrences, sums,
// cancellation in kappa and rho near a zero end, input rounding in the ray) + |x - (hi + lo)|
// of the returned double-double, propagated through compositing.
//
// Accuracy (tests/test_reference.cpp, against Eqs. 5 and 6, a hand-derived linear-kappa
// integral, a both-linear erfc form and hand-composited rays, all in 50 digits, T = 1e-30 to
// 1e30): the 50-digit emission is within 3e-49 relative (the 1e-40 test bound), the returned
// hi + lo within the double-double's resolution (<= 5e-33 relative measured, the 1e-30 claim),
// and the error bound is never below the true error.
#include "rayint/reference/reference.hpp"

#include <algorithm>
#include <array>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "rayint/core/parallel.hpp"
#include "rayint/model/poly_ray.hpp"
#include "rayint/reference/poly_reference.hpp"
#include "rayint/reference/reference_detail.hpp"

namespace rayint {
namespace reference_detail {
namespace {

// ---- constants, each with where it came from ------------------------------------------------

// Unit roundoff of Real: 2^(1 - 168).
double eps() { return std::ldexp(1.0, 1 - std::numeric_limits<Real>::digits); }

// Internal target for each of the quadrature estimate and the truncation bound, relative to
// the emission: 1e-36 leaves six digits to the 30-digit claim and four to the double-double.
// (|Kronrod - Gauss| is the Gauss error; the Kronrod result is far more accurate.)
constexpr double kTargetRelative = 1e-36;

// First truncation depth: exp(-140) = 1.6e-61, so the tail bound meets kTargetRelative while
// max kappa / emission < 6e24 (tau_cut is raised otherwise).
constexpr double kTauCut = 140.0;

constexpr int kMaxRefinements = 4;       // doublings of the subintervals
constexpr int kMaxTruncationPasses = 4;  // raises of tau_cut

// Gauss-Kronrod rules with the largest optical-depth increment (2 rho(c) h) and curvature
// term (|a| h^2) per subinterval for which |Kronrod - Gauss| stayed below 1e-38 relative in
// the calibration (kappa rising, falling, constant; rho constant for the increment, rising or
// falling from 0 for the curvature). Measured maxima: increment 0.027, 0.32, 2.2, 6.5, 13, 23;
// curvature 6.1e-6, 1.0e-3, 0.045, 0.27, 0.76, 1.6. The table keeps ~20% margin.
struct RuleLimit {
  int points;
  double max_increment;
  double max_curvature;
};
constexpr std::array<RuleLimit, 6> kRules{{{15, 0.022, 4.8e-6},
                                           {21, 0.25, 8.0e-4},
                                           {31, 1.8, 0.036},
                                           {41, 5.2, 0.21},
                                           {51, 10.5, 0.6},
                                           {61, 18.0, 1.25}}};

// Measured cost in microseconds (this machine; only the ratios matter): per node pair, the
// exp_series for P (2.5) and, with varying rho, for F (1.7) and for the recurrence factor G
// (2.0, only with several subintervals); per subinterval, one Boost exp plus the node loop.
double method_cost(int points, int n_sub, bool varying_rho) {
  const double pairs = (points - 1) / 2;
  const double per_pair = 2.5 + (varying_rho ? 1.7 : 0.0) + (varying_rho && n_sub > 1 ? 2.0 : 0.0);
  return pairs * per_pair + n_sub * (7.0 + 0.28 * points);
}

// exp_series: Taylor series on |u| <= 1/32 after halving; the series stops when the first
// omitted term is <= 2^-180 (then the tail is < 1.1 * 2^-180 relative).
constexpr double kSeriesRadius = 1.0 / 32.0;
constexpr int kMaxSeriesTerms = 40;  // 23 terms reach 2^-180 at the radius
double series_tail() { return std::ldexp(1.0, -180); }

// ---- tables, initialised once (function-local statics are thread-safe) ----------------------

const std::array<Real, kMaxSeriesTerms>& inverse_factorials() {
  static const std::array<Real, kMaxSeriesTerms> table = [] {
    std::array<Real, kMaxSeriesTerms> t;
    t[0] = 1;
    for (int k = 1; k < kMaxSeriesTerms; ++k) t[k] = t[k - 1] / k;
    return t;
  }();
  return table;
}

template <unsigned N>
struct GaussKronrodTable {
  static constexpr std::size_t kSize = (N + 1) / 2;  // x[0] = 0 < x[1] < ... < x[kSize - 1]
  std::array<Real, kSize> x;
  std::array<Real, kSize> kronrod;
  std::array<Real, kSize> gauss;  // 0 where x is a Kronrod-only node
};

template <unsigned N>
const GaussKronrodTable<N>& gauss_kronrod_table() {
  // Initialised once under the C++11 static-initialisation guard, which also serialises the
  // first use of Boost's own function-local tables.
  static const GaussKronrodTable<N> table = [] {
    using boost::math::quadrature::gauss;
    using boost::math::quadrature::gauss_kronrod;
    GaussKronrodTable<N> t;
    const auto& xs = gauss_kronrod<Real, N>::abscissa();
    const auto& wk = gauss_kronrod<Real, N>::weights();
    const auto& wg = gauss<Real, (N - 1) / 2>::weights();
    if (xs.size() != t.kSize || wk.size() != t.kSize)
      throw std::logic_error("reference: unexpected Gauss-Kronrod table size");
    // Boost's layout (gauss_kronrod::integrate_non_adaptive_m1_1): the Gauss nodes are the
    // even-indexed abscissae when the Gauss order (N - 1) / 2 is odd, else the odd-indexed
    // ones, with Gauss weight index i / 2.
    const std::size_t first_gauss = ((N - 1) / 2) % 2 == 1 ? 0 : 1;
    for (std::size_t i = 0; i < t.kSize; ++i) {
      t.x[i] = xs[i];
      t.kronrod[i] = wk[i];
      t.gauss[i] = (i % 2 == first_gauss) ? Real(wg[i / 2]) : Real(0);
    }
    return t;
  }();
  return table;
}

// ---- the quadrature ------------------------------------------------------------------------

// rho(s) = rho0 + 2 a s, kappa(s) = kappa0 + kappa1 s, tau(s) = s (rho0 + a s).
struct Coefficients {
  Real rho0, a, kappa0, kappa1;
};

struct QuadratureSum {
  Real kronrod;             // the emission over [0, s_cut]
  Real estimate;            // sum of h |K - G|
  Real cancellation;        // sum of h * max kappa * max rho * (Kronrod sum of exp(-tau))
  double exp_relative = 0;  // largest relative error bound of a node exponential factor
};

template <unsigned N>
QuadratureSum gauss_kronrod_sum(const Coefficients& co, const Real& s_cut, int n_sub) {
  using Table = GaussKronrodTable<N>;
  const Table& t = gauss_kronrod_table<N>();
  constexpr std::size_t M = Table::kSize;
  QuadratureSum out;

  const Real h = s_cut / (2 * n_sub);
  const Real ah2 = co.a * h * h;
  const bool varying_rho = co.a != 0;
  const bool recur = varying_rho && n_sub > 1;
  const Real rho_first = co.rho0 + 2 * co.a * h;  // rho at the first centre, c = h

  // Node factors: F = exp(-a h^2 y^2) (the same in every subinterval), P = exp(-+ rho(c) h y)
  // for the first subinterval, and G = exp(-+ 4 a h^2 y) that moves P to the next one.
  std::array<Real, M> F, P_far, P_exit, G_far, G_exit;
  double err = 0.0, e = 0.0;
  for (std::size_t j = 1; j < M; ++j) {
    const Real& y = t.x[j];
    F[j] = varying_rho ? exp_series(-(ah2 * y * y), &e) : Real(1);
    err = std::max(err, varying_rho ? e : 0.0);
    P_exit[j] = exp_series(rho_first * h * y, &e);  // node c - h y, nearer the exit
    err = std::max(err, e + eps());
    P_far[j] = 1 / P_exit[j];  // node c + h y
    if (recur) {
      G_exit[j] = exp_series(4 * ah2 * y, &e);
      err = std::max(err, e + eps());
      G_far[j] = 1 / G_exit[j];
    }
  }
  out.exp_relative = err;

  for (int m = 0; m < n_sub; ++m) {
    const Real c = h * (2 * m + 1);
    const Real C = exp(-(c * (co.rho0 + co.a * c)));  // exp(-tau(c))
    const Real rho_c = co.rho0 + 2 * co.a * c, rho_d = 2 * co.a * h;
    const Real kappa_c = co.kappa0 + co.kappa1 * c, kappa_d = co.kappa1 * h;
    const Real f0 = kappa_c * rho_c * C;
    Real K = t.kronrod[0] * f0;
    Real G = t.gauss[0] * f0;
    Real E = t.kronrod[0] * C;  // the rule applied to exp(-tau) alone
    for (std::size_t j = 1; j < M; ++j) {
      const Real& y = t.x[j];
      const Real ry = rho_d * y, ky = kappa_d * y;
      const Real CF = C * F[j];
      const Real e_far = CF * P_far[j], e_exit = CF * P_exit[j];
      const Real pair =
          (kappa_c + ky) * (rho_c + ry) * e_far + (kappa_c - ky) * (rho_c - ry) * e_exit;
      K += t.kronrod[j] * pair;
      E += t.kronrod[j] * (e_far + e_exit);
      if (t.gauss[j] != 0) G += t.gauss[j] * pair;
      if (recur) {
        P_far[j] *= G_far[j];
        P_exit[j] *= G_exit[j];
      }
    }
    out.kronrod += h * K;
    out.estimate += h * abs(K - G);
    // kappa(c +- h y) and rho(c +- h y) may cancel near a zero end: their absolute error is a
    // few ulps of kappa_c + |kappa_d| and rho_c + |rho_d|, the maxima on the subinterval.
    out.cancellation += h * (kappa_c + abs(kappa_d)) * (rho_c + abs(rho_d)) * E;
  }
  return out;
}

// The Gauss-Kronrod rules the reference holds tables for, by number of points.
using RulePoints = std::integer_sequence<unsigned, 15, 21, 31, 41, 51, 61>;

// f(std::integral_constant<unsigned, N>{}) for the rule with N == `points` among the listed
// ones (with_rule below: among RulePoints); throws std::invalid_argument for any other number.
template <class F, unsigned N, unsigned... Rest>
auto with_rule(int points, const F& f, std::integer_sequence<unsigned, N, Rest...>) {
  if (points == static_cast<int>(N)) return f(std::integral_constant<unsigned, N>{});
  if constexpr (sizeof...(Rest) > 0) {
    return with_rule(points, f, std::integer_sequence<unsigned, Rest...>{});
  } else {
    throw std::invalid_argument("reference: no Gauss-Kronrod rule with " +
                                std::to_string(points) + " points");
  }
}
template <class F>
auto with_rule(int points, const F& f) {
  return with_rule(points, f, RulePoints{});
}

QuadratureSum run_rule(int rule, const Coefficients& co, const Real& s_cut, int n_sub) {
  return with_rule(rule, [&](auto points) {
    return gauss_kronrod_sum<decltype(points)::value>(co, s_cut, n_sub);
  });
}

struct Method {
  int rule;
  int subintervals;
};

// The cheapest rule and number of equal subintervals of [0, s_cut] that keep every
// subinterval within the rule's limits. With linear rho >= 0, n equal subintervals have
// increments <= increment / n, where increment = s_cut * max rho, and curvature terms
// curvature / n^2, where curvature = |a| (s_cut / 2)^2.
Method choose_method(double increment, double curvature, bool varying_rho) {
  Method best{0, 0};
  double best_cost = std::numeric_limits<double>::infinity();
  for (const RuleLimit& r : kRules) {
    const double n = std::max({1.0, std::ceil(increment / r.max_increment),
                               std::ceil(std::sqrt(curvature / r.max_curvature))});
    if (!(n < 1e6)) continue;
    const int n_sub = static_cast<int>(n);
    const double cost = method_cost(r.points, n_sub, varying_rho);
    if (cost < best_cost) {
      best = {r.points, n_sub};
      best_cost = cost;
    }
  }
  if (best.rule == 0) throw std::logic_error("reference: optical depth increment out of range");
  return best;
}

struct Forced {
  Method method;
  double tau_cut;
};

PieceQuadrature integrate(const PieceData& p, const Forced* forced) {
  for (const Real* v : {&p.length, &p.rho_far, &p.rho_exit, &p.kappa_far, &p.kappa_exit})
    if (!(boost::multiprecision::isfinite(*v) && *v >= 0))
      throw std::invalid_argument("reference: piece length, rho and kappa must be finite and >= 0");

  PieceQuadrature q;
  const Real T = p.length * (p.rho_far + p.rho_exit) / 2;
  q.optical_depth = T;
  q.tau_cut = T;
  q.transmittance = exp(-T);
  // T carries <= 3 roundings, so its absolute error is <= 3 eps T; Boost's exp adds a few ulps.
  q.transmittance_error = q.transmittance * ((4 * T + 8) * eps());
  if (p.length == 0 || T == 0 || (p.kappa_far == 0 && p.kappa_exit == 0)) return q;

  Coefficients co;
  co.rho0 = p.rho_exit;
  co.a = (p.rho_far - p.rho_exit) / (2 * p.length);
  co.kappa0 = p.kappa_exit;
  co.kappa1 = (p.kappa_far - p.kappa_exit) / p.length;

  Real tau_cut = forced ? Real(forced->tau_cut) : Real(kTauCut);
  QuadratureSum sum;
  Method method{0, 0};
  for (int pass = 1;; ++pass) {
    q.truncation_passes = pass - 1;
    q.truncated = T > tau_cut;
    Real s_cut = p.length;
    if (q.truncated) {
      // tau(s_cut) = tau_cut, the root of a s^2 + rho0 s - tau_cut in the stable form; the
      // discriminant is >= rho_far^2 because tau_cut < T.
      s_cut = 2 * tau_cut / (co.rho0 + sqrt(co.rho0 * co.rho0 + 4 * co.a * tau_cut));
      s_cut = std::min(s_cut, p.length);
    }
    q.tau_cut = q.truncated ? tau_cut : T;
    const Real rho_max = std::max(co.rho0, co.rho0 + 2 * co.a * s_cut);
    const Real half = s_cut / 2;
    method = forced ? forced->method
                    : choose_method(static_cast<double>(s_cut * rho_max),
                                    static_cast<double>(abs(co.a) * half * half), co.a != 0);

    for (q.refinements = 0;; ++q.refinements) {
      sum = run_rule(method.rule, co, s_cut, method.subintervals);
      if (forced || sum.estimate <= kTargetRelative * sum.kronrod ||
          q.refinements == kMaxRefinements)
        break;
      method.subintervals *= 2;
    }

    q.truncation_error = 0;
    if (q.truncated) {
      // Beyond s_cut: integral kappa rho exp(-tau) <= max kappa * (exp(-tau_cut) - exp(-T)).
      const Real kappa_tail = std::max(co.kappa0 + co.kappa1 * s_cut, p.kappa_far);
      q.truncation_error = kappa_tail * exp(-tau_cut);
      if (!forced && q.truncation_error > kTargetRelative * sum.kronrod &&
          pass < kMaxTruncationPasses) {
        // Raise tau_cut until kappa_tail exp(-tau_cut) <= kTargetRelative * emission / e.
        tau_cut += log(q.truncation_error / (kTargetRelative * sum.kronrod)) + 1;
        continue;
      }
    }
    break;
  }

  q.rule = method.rule;
  q.subintervals = method.subintervals;
  q.emission = sum.kronrod;
  q.quadrature_error = sum.estimate;
  // Rounding, relative to each node value: the products (<= 8 ulps), exp(-tau(c)) with
  // tau(c) <= tau_cut (4 tau_cut + 8 ulps), the node factors F * P (recurrence: one factor
  // error per subinterval), the weights and the sum (rule size ulps); plus the cancellation
  // in kappa and rho near a zero end (<= 8 ulps of the subinterval maxima, summed).
  const double node_ulps = 8 + 4 * static_cast<double>(q.tau_cut) + 8 + method.rule +
                           (method.subintervals + 2) * sum.exp_relative / eps();
  q.rounding_error = sum.kronrod * (node_ulps * eps()) + sum.cancellation * (8 * eps());
  q.emission_error = q.quadrature_error + q.truncation_error + q.rounding_error;
  q.converged = forced || (q.quadrature_error <= kTargetRelative * q.emission &&
                           q.truncation_error <= kTargetRelative * q.emission);
  return q;
}

double round_up_to_double(const Real& x) {
  double d = static_cast<double>(x);
  if (Real(d) < x) d = std::nextafter(d, std::numeric_limits<double>::infinity());
  return d;
}

bool even_significand(double d) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &d, sizeof bits);
  return (bits & 1u) == 0;
}

// Nearest double, ties to even; Boost's conversion is checked against both neighbours.
double nearest_double(const Real& x) {
  const double d = static_cast<double>(x);
  if (!std::isfinite(d)) return d;
  double best = d;
  Real best_distance = abs(x - Real(d));
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (const double candidate : {std::nextafter(d, -inf), std::nextafter(d, inf)}) {
    if (!std::isfinite(candidate)) continue;
    const Real distance = abs(x - Real(candidate));
    if (distance < best_distance ||
        (distance == best_distance && even_significand(candidate) && !even_significand(best))) {
      best = candidate;
      best_distance = distance;
    }
  }
  return best;
}

void check_function(const PiecewiseLinear& f) {
  bool ok = !f.scalar.empty() && f.scalar.size() == f.value.size();
  for (std::size_t i = 0; ok && i < f.scalar.size(); ++i)
    ok = std::isfinite(f.scalar[i]) && std::isfinite(f.value[i]) && f.value[i] >= 0 &&
         (i == 0 || f.scalar[i - 1] <= f.scalar[i]) && (i < 2 || f.scalar[i - 2] < f.scalar[i]);
  if (!ok)
    throw std::invalid_argument(
        "reference: a transfer function needs matching, non-empty point lists with "
        "non-decreasing finite scalars (at most two equal: a jump) and finite values >= 0");
}

}  // namespace

Real exp_series(const Real& z, double* relative_error) {
  const double z_abs = std::fabs(static_cast<double>(z));
  if (!(z_abs < 1e4)) throw std::invalid_argument("reference: exp_series argument out of range");
  int k = 0;  // halvings
  double u_abs = z_abs;
  while (u_abs > kSeriesRadius) {
    u_abs *= 0.5;
    ++k;
  }
  const Real u = ldexp(z, -k);
  int n = 0;  // terms u^0 .. u^(n-1) are summed; u^n / n! <= 2^-180
  for (double term = 1.0; term > series_tail();) {
    ++n;
    term *= u_abs / n;
  }
  if (n > kMaxSeriesTerms) throw std::logic_error("reference: exp_series needs too many terms");
  const auto& c = inverse_factorials();
  Real r = c[n - 1];
  for (int j = n - 2; j >= 0; --j) {
    r *= u;
    r += c[j];
  }
  for (int i = 0; i < k; ++i) r *= r;
  if (relative_error) {
    // Horner with coefficients good to j ulps: <= (3n + 4) eps * exp(2|u|) relative, plus the
    // tail; each squaring doubles the relative error and adds one rounding.
    const double series = (3.0 * n + 4.0) * eps() * std::exp(2 * kSeriesRadius) +
                          1.1 * series_tail() / std::exp(-kSeriesRadius);
    *relative_error = std::ldexp(series + eps(), k) * 1.01;
  }
  return r;
}

PieceQuadrature integrate_piece(const PieceData& piece) { return integrate(piece, nullptr); }

namespace {
template <unsigned N>
GaussKronrodRule rule_view() {
  const GaussKronrodTable<N>& t = gauss_kronrod_table<N>();
  return {static_cast<int>(N), GaussKronrodTable<N>::kSize, t.x.data(), t.kronrod.data(),
          t.gauss.data()};
}
}  // namespace

GaussKronrodRule gauss_kronrod_rule(int points) {
  return with_rule(points, [](auto n) { return rule_view<decltype(n)::value>(); });
}

double unit_roundoff() { return eps(); }

double rounded_up(const Real& x) { return round_up_to_double(x); }

void check_transfer_functions(const TransferFunctions& tf) {
  for (const auto* group : {&tf.density, &tf.color})
    for (const PiecewiseLinear& f : *group) check_function(f);
}

PieceQuadrature integrate_piece_forced(const PieceData& piece, int rule, int subintervals,
                                       double tau_cut) {
  if (subintervals < 1) throw std::invalid_argument("reference: subintervals must be >= 1");
  const Forced forced{{rule, subintervals}, tau_cut};
  return integrate(piece, &forced);
}

Real interpolate(const PiecewiseLinear& f, double s, bool from_above) {
  // A scalar stored twice is a jump: its first point is the limit from below, its second the
  // limit from above (also at an end point: the end value holds beyond it).
  if (s < f.scalar.front() || (s == f.scalar.front() && !from_above)) return Real(f.value.front());
  if (s > f.scalar.back() || (s == f.scalar.back() && from_above)) return Real(f.value.back());
  // k: the first point above s (from above) or at or above s (from below); a point at s is then
  // k - 1 (its last copy) or k (its first copy).
  const auto it = from_above ? std::upper_bound(f.scalar.begin(), f.scalar.end(), s)
                             : std::lower_bound(f.scalar.begin(), f.scalar.end(), s);
  const auto k = static_cast<std::size_t>(it - f.scalar.begin());
  if (from_above && s == f.scalar[k - 1]) return Real(f.value[k - 1]);
  if (!from_above && s == f.scalar[k]) return Real(f.value[k]);
  const Real s0 = f.scalar[k - 1], s1 = f.scalar[k], x = s;  // s0 < s < s1
  return (Real(f.value[k - 1]) * (s1 - x) + Real(f.value[k]) * (x - s0)) / (s1 - s0);
}

LinearPart linear_part(const PiecewiseLinear& f, const Real& f_mid) {
  const std::size_t n = f.scalar.size();
  if (n == 1 || f_mid <= f.scalar.front()) return {Real(f.value.front()), 0, 0, Real(f.value.front())};
  if (f_mid >= f.scalar.back()) return {Real(f.value.back()), 0, 0, Real(f.value.back())};
  std::size_t k = 1;
  while (Real(f.scalar[k]) <= f_mid) ++k;  // scalar[k-1] <= f_mid < scalar[k]
  const Real s0 = f.scalar[k - 1], s1 = f.scalar[k], v0 = f.value[k - 1], v1 = f.value[k];
  return {v0, (v1 - v0) / (s1 - s0), s0, std::max(v0, v1)};
}

ExtendedValue to_extended(const Real& x) {
  ExtendedValue v;
  v.hi = nearest_double(x);
  if (std::isfinite(v.hi)) v.lo = nearest_double(x - Real(v.hi));
  if (v.lo == 0.0) v.lo = 0.0;  // no negative zero
  return v;
}

Real representation_error(const Real& x, const ExtendedValue& v) {
  return abs(x - Real(v.hi) - Real(v.lo));
}

RaySums::RaySums(const Rgb& background, const char* message) {
  for (int c = 0; c < kChannels; ++c) {
    if (!std::isfinite(background[c])) throw std::invalid_argument(message);
    intensity[c] = background[c];
    transmittance[c] = 1;
    error[c] = 0;
  }
}

void RaySums::round_into(ReferenceRay& out) const {
  for (int c = 0; c < kChannels; ++c) {
    out.intensity[c] = to_extended(intensity[c]);
    out.transmittance[c] = to_extended(transmittance[c]);
    out.error_bound[c] =
        round_up_to_double(error[c] + representation_error(intensity[c], out.intensity[c]));
  }
}

}  // namespace reference_detail

using reference_detail::Real;

ReferencePiece reference_piece(const ChannelPiece& piece, double incoming) {
  if (!std::isfinite(incoming))
    throw std::invalid_argument("reference: incoming intensity must be finite");
  const reference_detail::PieceData data{Real(piece.length), Real(piece.rho_far),
                                         Real(piece.rho_exit), Real(piece.kappa_far),
                                         Real(piece.kappa_exit)};
  const reference_detail::PieceQuadrature q = reference_detail::integrate_piece(data);
  const Real in = incoming;
  const Real intensity = in * q.transmittance + q.emission;
  ReferencePiece out;
  out.transmittance = reference_detail::to_extended(q.transmittance);
  out.emission = reference_detail::to_extended(q.emission);
  out.intensity = reference_detail::to_extended(intensity);
  const Real error = q.emission_error + abs(in) * q.transmittance_error +
                     abs(intensity) * (2 * reference_detail::eps()) +
                     reference_detail::representation_error(intensity, out.intensity);
  out.error_bound = reference_detail::round_up_to_double(error);
  out.subintervals = q.subintervals;
  return out;
}

ReferenceRay reference_ray(const TransferFunctions& tf, const Ray& ray) {
  return reference_ray(tf, ray, ReferenceRun{});
}

ReferenceRay reference_ray(const TransferFunctions& tf, const Ray& ray, const ReferenceRun& run) {
  // Quadratic chords (quadratic tetrahedra, model/ray.hpp): the polynomial reference
  // (poly_reference.hpp), one thread, the same ray as polynomials in 50 digits.
  if (has_quadratic_segments(ray)) {
    ReferenceRay out = reference_poly_ray(tf, to_poly_ray(ray));
    if (run.progress) run.progress(ray.segments.size(), ray.segments.size());
    return out;
  }
  using reference_detail::interpolate;
  std::vector<double> breakpoints;
  for (const auto* group : {&tf.density, &tf.color})
    for (const PiecewiseLinear& f : *group) {
      reference_detail::check_function(f);
      breakpoints.insert(breakpoints.end(), f.scalar.begin(), f.scalar.end());
    }
  std::sort(breakpoints.begin(), breakpoints.end());
  breakpoints.erase(std::unique(breakpoints.begin(), breakpoints.end()), breakpoints.end());

  ReferenceRay out;
  reference_detail::RaySums sums(ray.background, "reference: background must be finite");
  const double eps = reference_detail::eps();

  for (const Segment& seg : ray.segments)
    if (!(std::isfinite(seg.length) && seg.length >= 0 && std::isfinite(seg.scalar_far) &&
          std::isfinite(seg.scalar_exit)))
      throw std::invalid_argument(
          "reference: segment length must be finite and >= 0, scalars finite");

  // The quadratures of one segment's pieces, all channels: piece k, channel c at [k * 3 + c].
  // Computed in parallel a block at a time (ReferenceRun); buffers keep their capacity.
  constexpr std::size_t kBlock = 2048;  // segments: ~0.1-0.3 s of work, a few MB of quadratures
  std::vector<std::vector<reference_detail::PieceQuadrature>> block(kBlock);
  const auto quadratures = [&](const Segment& seg, std::vector<reference_detail::PieceQuadrature>& qs) {
    qs.clear();
    if (seg.length == 0) return;  // transmits everything, emits nothing
    std::vector<double> ends;
    const double s_far = seg.scalar_far, s_exit = seg.scalar_exit;
    // Piece ends in the direction of travel: s_far, the breakpoints strictly between, s_exit.
    ends.assign(1, s_far);
    if (s_far != s_exit) {
      const double lo = std::min(s_far, s_exit), hi = std::max(s_far, s_exit);
      const std::size_t first = ends.size();
      for (const double b : breakpoints)
        if (lo < b && b < hi) ends.push_back(b);
      if (s_far > s_exit)
        std::reverse(ends.begin() + static_cast<std::ptrdiff_t>(first), ends.end());
    }
    ends.push_back(s_exit);
    const Real length = seg.length;
    const Real span = Real(s_exit) - Real(s_far);

    for (std::size_t k = 0; k + 1 < ends.size(); ++k) {
      const double e_far = ends[k], e_exit = ends[k + 1];
      // Scalar varies linearly along the segment, so a piece's length is L times its share of
      // the scalar span (the whole segment when the scalar is constant).
      const Real piece_length =
          s_far == s_exit ? length : length * (Real(e_exit) - Real(e_far)) / span;
      // Each end takes the limit from inside the piece (at a jump: the left value below it, the
      // right value above it); a constant scalar takes the value at it, the left one at a jump.
      const bool up = e_far < e_exit, down = e_far > e_exit;
      for (int c = 0; c < kChannels; ++c) {
        const reference_detail::PieceData data{
            piece_length, interpolate(tf.density[c], e_far, up), interpolate(tf.density[c], e_exit, down),
            interpolate(tf.color[c], e_far, up), interpolate(tf.color[c], e_exit, down)};
        qs.push_back(reference_detail::integrate_piece(data));
      }
    }
  };

  const std::size_t n = ray.segments.size();
  for (std::size_t b0 = 0; b0 < n; b0 += kBlock) {
    const std::size_t count = std::min(kBlock, n - b0);
    parallel_for(static_cast<long long>(count), run.threads, [&](long long i) {
      const auto k = static_cast<std::size_t>(i);
      quadratures(ray.segments[b0 + k], block[k]);
    });
    for (std::size_t k = 0; k < count; ++k) {
      const std::vector<reference_detail::PieceQuadrature>& qs = block[k];
      for (std::size_t p = 0; p < qs.size(); p += kChannels) {
        for (int c = 0; c < kChannels; ++c) {
          const reference_detail::PieceQuadrature& q = qs[p + static_cast<std::size_t>(c)];
          // Propagate: the incoming error is attenuated, the piece adds its own; the piece data
          // (length, interpolated rho and kappa) carry <= 8 ulps, which move tau by <= 8 eps
          // tau, the emission by <= 8 eps (2 + tau_cut) and the transmitted part by <= 8 eps T.
          const Real incoming = sums.intensity[c];
          sums.add_piece(c, q, eps, q.emission * ((2 + q.tau_cut) * (8 * eps)),
                         abs(incoming) * q.transmittance * (q.optical_depth * (8 * eps)));
          out.subintervals += q.subintervals;
        }
        ++out.pieces;
      }
    }
    if (run.progress) run.progress(b0 + count, n);
  }

  sums.round_into(out);
  return out;
}

}  // namespace rayint
