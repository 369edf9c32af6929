// The ray integral through one linear cell in its own interpolation (see cell_integral.hpp for
// the paths, thresholds and error estimate).
#include "rayint/cells/cell_integral.hpp"

#include <algorithm>
#include <array>
#include <boost/container/small_vector.hpp>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/tools/roots.hpp>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <stdexcept>

#include "rayint/cells/chord_scalar.hpp"
#include "rayint/cells/emission_nodes.hpp"
#include "rayint/integrators/exact.hpp"

namespace rayint {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kMaxDegree = 64;
constexpr int kMaxSubintervals = 256;
constexpr int kTrustedDegree = 16;

using Channels = std::array<double, kChannels>;
// Chebyshev coefficients of f on one interpolant (and of its antiderivative and derivative), and
// the knots of a chord: on the stack up to an affine cell's cubic (4, its antiderivative 5) and a
// few more, so the polynomial path allocates nothing per chord (heap allocations were ~5 % of
// `rayint bench` box12); longer series (up to degree kMaxDegree + 1) spill to the heap.
using Coefficients = boost::container::small_vector<double, 10>;
using Knots = boost::container::small_vector<double, 8>;

// 15-point Gauss-Kronrod on [a, b] with the embedded 7-point Gauss rule (Boost.Math's nodes),
// all channels at once (they share the scalar at every node).
struct RuleSums {
  double a = 0.0, b = 0.0;
  Channels kronrod{}, error{}, l1{};
};

using GK15 = boost::math::quadrature::gauss_kronrod<double, 15>;
using G7 = boost::math::quadrature::gauss<double, 7>;

// The integrand at the 15 Gauss-Kronrod nodes c, c -+ h x[j] (x: 0 and the 7 positive nodes;
// the embedded 7-point Gauss rule's nodes at even indices), filled Gauss nodes first.
// Integrands are evaluated in batches, f(c, h, u, n, values) at the n <= kMaxBatch nodes
// c + h u[j] (u: signed unit nodes, read up to kMaxEmissionNodes), so that the emission is
// evaluated vectorised over a rule's nodes (emission_nodes.hpp); c + h (-x) is the scalar rules'
// c - h x (to its rounding where the target fuses the multiply-add).
constexpr std::size_t kMaxBatch = 15;
static_assert(kMaxBatch <= kMaxEmissionNodes, "emission_at_nodes takes the largest batch");
using UnitNodes = std::array<double, kMaxEmissionNodes>;  // padded with zeros
struct KronrodValues {
  Channels centre;  // not zeroed: every slot used is written first (index 0 and the unused
  std::array<Channels, 8> minus, plus;  // half of each array are never read)
};

// The batches' unit nodes: the 7-point Gauss rule's (0, -+ x[2], -+ x[4], -+ x[6] of GK15),
// the Kronrod ones (-+ x[1], -+ x[3], ...), and the even N-point Gauss rule's (-+ x[0], ...).
// GK15's abscissae x[first], x[first + 2], ... as -+ pairs at v[j - 1], v[j] (v[0] stays the
// centre, 0, for first = 2).
UnitNodes gk15_units(std::size_t first) {
  const auto& x = GK15::abscissa();
  UnitNodes v{};
  for (std::size_t j = first; j < x.size(); j += 2) v[j - 1] = -x[j], v[j] = x[j];
  return v;
}
const UnitNodes& gauss_7_units() {
  static const UnitNodes u = gk15_units(2);
  return u;
}
const UnitNodes& kronrod_8_units() {
  static const UnitNodes u = gk15_units(1);
  return u;
}
template <int N>
const UnitNodes& gauss_units() {
  static const UnitNodes u = [] {
    const auto& x = boost::math::quadrature::gauss<double, N>::abscissa();
    UnitNodes v{};
    for (std::size_t j = 0; j < x.size(); ++j) v[2 * j] = -x[j], v[2 * j + 1] = x[j];
    return v;
  }();
  return u;
}

template <class F>
void gauss_7_nodes(F& f, double a, double b, KronrodValues& v) {
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  std::array<Channels, 7> fx;
  f(c, h, gauss_7_units().data(), fx.size(), fx.data());
  v.centre = fx[0];
  for (std::size_t j = 2; j < 8; j += 2) v.minus[j] = fx[j - 1], v.plus[j] = fx[j];
}

// The 7-point Gauss rule from those nodes, and the integral of |f| by it.
void gauss_7_sums(const KronrodValues& v, double a, double b, Channels& value, Channels& l1) {
  static const auto& wg = G7::weights();
  const double h = 0.5 * (b - a);
  for (std::size_t ch = 0; ch < kChannels; ++ch) {
    double sum = wg[0] * v.centre[ch], abs_sum = wg[0] * std::abs(v.centre[ch]);
    for (std::size_t j = 2; j < 8; j += 2) {
      sum += wg[j / 2] * (v.minus[j][ch] + v.plus[j][ch]);
      abs_sum += wg[j / 2] * (std::abs(v.minus[j][ch]) + std::abs(v.plus[j][ch]));
    }
    value[ch] = h * sum, l1[ch] = h * abs_sum;
  }
}

// `gauss`: the Gauss nodes' values already computed (gauss_7_nodes on the same [a, b]).
template <class F>
RuleSums gauss_kronrod_15(F& f, double a, double b, const KronrodValues* gauss = nullptr) {
  static const auto& x = GK15::abscissa();
  static const auto& wk = GK15::weights();
  static const auto& wg = G7::weights();
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  KronrodValues v;
  if (gauss != nullptr) {
    v = *gauss;
  } else {
    gauss_7_nodes(f, a, b, v);
  }
  {  // the Kronrod nodes (odd indices)
    std::array<Channels, 8> fx;
    f(c, h, kronrod_8_units().data(), fx.size(), fx.data());
    for (std::size_t j = 1; j < x.size(); j += 2) v.minus[j] = fx[j - 1], v.plus[j] = fx[j];
  }
  Channels K{}, Gs{}, L1{};
  for (std::size_t ch = 0; ch < kChannels; ++ch) {
    K[ch] = wk[0] * v.centre[ch], Gs[ch] = wg[0] * v.centre[ch], L1[ch] = wk[0] * std::abs(v.centre[ch]);
  }
  for (std::size_t j = 1; j < x.size(); ++j) {
    const Channels &fm = v.minus[j], &fp = v.plus[j];
    for (std::size_t ch = 0; ch < kChannels; ++ch) {
      K[ch] += wk[j] * (fm[ch] + fp[ch]);
      L1[ch] += wk[j] * (std::abs(fm[ch]) + std::abs(fp[ch]));
      if (j % 2 == 0) Gs[ch] += wg[j / 2] * (fm[ch] + fp[ch]);
    }
  }
  RuleSums r;
  r.a = a, r.b = b;
  for (std::size_t ch = 0; ch < kChannels; ++ch) {
    r.kronrod[ch] = h * K[ch], r.error[ch] = std::abs(h * (K[ch] - Gs[ch])), r.l1[ch] = h * L1[ch];
  }
  return r;
}

// Globally adaptive: the subinterval with the largest |K - G| relative to its channel's
// tolerance is halved until, in every channel, the sum of the estimates is below tol * L1 (or 8
// ulps of L1: the rounding floor of the sums) or below `floor` (the channel's rounding noise,
// see integrate_curved), at most kMaxSubintervals. Returns false when the budget ran out first.
template <class F>
bool adaptive_integral(F& f, double a, double b, double tol, const Channels& floor, Channels& value,
                       Channels& error, const KronrodValues* gauss = nullptr) {
  std::vector<RuleSums> parts{gauss_kronrod_15(f, a, b, gauss)};
  const double rel = std::max(tol, 8 * std::numeric_limits<double>::epsilon());
  for (;;) {
    Channels K{}, E{}, L1{};
    for (const RuleSums& p : parts)
      for (std::size_t ch = 0; ch < kChannels; ++ch) K[ch] += p.kronrod[ch], E[ch] += p.error[ch], L1[ch] += p.l1[ch];
    value = K;
    error = E;
    bool done = true;
    for (std::size_t ch = 0; ch < kChannels; ++ch) {
      if (!std::isfinite(K[ch])) return false;
      done = done && E[ch] <= std::max(rel * L1[ch], floor[ch]);
    }
    if (done) return true;
    if (static_cast<int>(parts.size()) >= kMaxSubintervals) return false;
    std::size_t worst = 0;
    double worst_ratio = -1.0;
    for (std::size_t k = 0; k < parts.size(); ++k)
      for (std::size_t ch = 0; ch < kChannels; ++ch) {
        const double ratio = parts[k].error[ch] / std::max({rel * L1[ch], floor[ch], std::numeric_limits<double>::min()});
        if (ratio > worst_ratio) worst_ratio = ratio, worst = k;
      }
    const RuleSums w = parts[worst];
    const double m = 0.5 * (w.a + w.b);
    parts[worst] = gauss_kronrod_15(f, w.a, m);
    parts.push_back(gauss_kronrod_15(f, m, w.b));
  }
}

// N-point Gauss-Legendre rule (Boost.Math's nodes, N even) on [a, b], all channels, with the
// integral of |f| (the tolerance's scale) from the same nodes.
template <int N, class F>
void gauss_rule(F& f, double a, double b, Channels& value, Channels& l1) {
  static_assert(N % 2 == 0 && N <= static_cast<int>(kMaxBatch), "odd rules: gauss_7_nodes");
  using G = boost::math::quadrature::gauss<double, N>;
  static const auto& w = G::weights();
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  std::array<Channels, N> fx;
  f(c, h, gauss_units<N>().data(), fx.size(), fx.data());
  value = Channels{};
  l1 = Channels{};
  for (std::size_t j = 0; j < w.size(); ++j) {
    const Channels &fm = fx[2 * j], &fp = fx[2 * j + 1];
    for (std::size_t ch = 0; ch < kChannels; ++ch) {
      value[ch] += w[j] * (fm[ch] + fp[ch]);
      l1[ch] += w[j] * (std::abs(fm[ch]) + std::abs(fp[ch]));
    }
  }
  for (std::size_t ch = 0; ch < kChannels; ++ch) value[ch] *= h, l1[ch] *= h;
}

// sum_k |c_k| R^k: a bound of |sum_k c_k T_k(z)| on the Bernstein ellipse E_R of [-1, 1]
// (|T_k| <= (R^k + R^-k) / 2 <= R^k there), so on every complex z with |z| <= (R - 1/R) / 2.
double ellipse_bound(const Coefficients& c, double R) {
  double sum = 0.0, Rk = 1.0;
  for (const double ck : c) {
    sum += std::abs(ck) * Rk;
    Rk *= R;
  }
  return sum;
}

// Chebyshev series sum_k c[k] T_k(x) on x in [-1, 1].
double clenshaw(const Coefficients& c, double x) {
  double b1 = 0.0, b2 = 0.0;
  for (std::size_t k = c.size(); k-- > 1;) {
    const double b0 = 2.0 * x * b1 - b2 + c[k];
    b2 = b1;
    b1 = b0;
  }
  return x * b1 - b2 + (c.empty() ? 0.0 : c[0]);
}

// clenshaw(c, x) and clenshaw(e, y) at once: the two recurrences interleaved (each is a chain of
// dependent operations, so alone it waits on latency), each with clenshaw's operations in its
// order: bit for bit clenshaw's two values. A series shorter than the other enters with zero
// coefficients above its length, which leave its recurrence at +0 until its own top term.
void clenshaw_pair(const Coefficients& c, double x, const Coefficients& e, double y, double& fc, double& fe) {
  double b1 = 0.0, b2 = 0.0, d1 = 0.0, d2 = 0.0;
  for (std::size_t k = std::max(c.size(), e.size()); k-- > 1;) {
    const double b0 = 2.0 * x * b1 - b2 + (k < c.size() ? c[k] : 0.0);
    const double d0 = 2.0 * y * d1 - d2 + (k < e.size() ? e[k] : 0.0);
    b2 = b1, b1 = b0, d2 = d1, d1 = d0;
  }
  fc = x * b1 - b2 + (c.empty() ? 0.0 : c[0]);
  fe = y * d1 - d2 + (e.empty() ? 0.0 : e[0]);
}

// cos(pi m / n) for m = 0 .. 2n - 1 and the degrees used (n = 8 .. kMaxDegree, powers of 2),
// computed once: the DCT and the Chebyshev points read them instead of calling cos.
const double* cosine_table(int n) {
  struct Tables {
    std::array<std::vector<double>, 8> by_log2;
    Tables() {
      for (int l = 0; l < 8; ++l) {
        const int m = 1 << l;
        by_log2[static_cast<std::size_t>(l)].resize(2 * static_cast<std::size_t>(m));
        for (int j = 0; j < 2 * m; ++j) by_log2[static_cast<std::size_t>(l)][static_cast<std::size_t>(j)] = std::cos(kPi * j / m);
      }
    }
  };
  static const Tables tables;
  int l = 0;
  while ((1 << l) < n) ++l;
  if ((1 << l) != n || l >= 8) throw std::logic_error("cosine_table: degree not a power of two <= 128");
  return tables.by_log2[static_cast<std::size_t>(l)].data();
}

// Coefficients from values v[j] at x_j = cos(pi j / n), j = 0..n (DCT-I).
void chebyshev_coefficients(const std::vector<double>& v, int n, Coefficients& c) {
  c.assign(static_cast<std::size_t>(n) + 1, 0.0);
  const double* cosine = cosine_table(n);
  for (int k = 0; k <= n; ++k) {
    double sum = 0.5 * (v[0] + ((k % 2 == 0) ? 1.0 : -1.0) * v[static_cast<std::size_t>(n)]);
    int index = 0;  // (j k) mod 2n, stepped (an integer division per term cost more than the sum)
    for (int j = 1; j < n; ++j) {
      index += k;
      if (index >= 2 * n) index -= 2 * n;
      sum += v[static_cast<std::size_t>(j)] * cosine[index];
    }
    c[static_cast<std::size_t>(k)] = 2.0 * sum / n;
  }
  c[0] *= 0.5;
  c[static_cast<std::size_t>(n)] *= 0.5;
}

void derivative(const Coefficients& c, Coefficients& d) {  // into d (no small_vector return)
  const std::size_t n = c.size() - 1;
  if (n == 0) {
    d.assign(1, 0.0);
    return;
  }
  d.assign(n + 2, 0.0);
  for (std::size_t k = n; k >= 1; --k) d[k - 1] = d[k + 1] + 2.0 * static_cast<double>(k) * c[k];
  d[0] *= 0.5;
  d.resize(n);
}

Coefficients antiderivative(const Coefficients& c) {
  const std::size_t n = c.size() - 1;
  Coefficients C(n + 2, 0.0);
  auto at = [&](std::size_t k) { return k <= n ? c[k] : 0.0; };
  C[1] = c[0] - 0.5 * at(2);
  for (std::size_t k = 2; k <= n + 1; ++k) C[k] = (at(k - 1) - at(k + 1)) / (2.0 * static_cast<double>(k));
  return C;
}

struct LinearPart {  // v0 + beta (f - s0) on the transfer function's interval holding f_mid
  double v0 = 0.0, beta = 0.0, s0 = 0.0, max_value = 0.0;
};

LinearPart linear_part(const PiecewiseLinear& f, double f_mid) {
  const std::size_t n = f.scalar.size();
  if (n == 1 || f_mid <= f.scalar.front()) return {f.value.front(), 0.0, 0.0, f.value.front()};
  if (f_mid >= f.scalar.back()) return {f.value.back(), 0.0, 0.0, f.value.back()};
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(f.scalar.begin(), f.scalar.end(), f_mid) - f.scalar.begin());
  const double s0 = f.scalar[k - 1], s1 = f.scalar[k], v0 = f.value[k - 1], v1 = f.value[k];
  return {v0, (v1 - v0) / (s1 - s0), s0, std::max(v0, v1)};
}

// A-priori error bounds of the 7- and 10-point Gauss rules for the emission integrand
// g(x) = kappa(f(x)) rho(f(x)) exp(-tau(x)) on a piece [x0, x1] of an interpolant (c, its
// antiderivative P, P0 = P(x0), h world length per unit x). g is entire (f and P are
// polynomials, each transfer function is its linear part on the piece), so with y = (x - m) / r
// (m, r the piece's centre and half-length) and M = max |g| on the Bernstein ellipse E_rho of y:
// |I - G_N| <= r (64/15) M rho^(-2N) / (rho^2 - 1) (Trefethen, Approximation Theory and
// Approximation Practice, Thm 19.3). On E_rho, |x| <= A = |m| + r (rho + 1/rho) / 2, so x lies in
// the ellipse E_R of [-1, 1] with R = A + sqrt(A^2 + 1) (semi-minor axis A): |f| <= ellipse_bound(c,
// R), |P| likewise, |x - x0| <= A + |x0|, and |exp(-tau)| <= exp(|tau|) (exp_upper). Per
// channel the smallest bound over the rho visited in kGaussEllipses (2^2 .. 2^11): from rho = 32
// up while a larger ellipse lowers some channel's bound, else down likewise, stopping as soon as
// the 7- or the 10-point bound is within `enough` in every channel (the caller's rounding floor:
// a smaller bound would change nothing; measured on the bench's box12: 94 % of the pieces stop
// at the first ellipse, 6 % after three; 1.1 visits per piece, 4 before); infinite when nothing
// is finite. (Every ellipse's bound is a bound: the walk only decides how small it gets.
// On the bench meshes the best rho of this family was 16 for 28 % of the pieces, 32 for 29 %, and
// above 32 for 44 % (up to 2048); until 2026-12-05 only 4 .. 32 were tried, each with libm's exp.)
struct GaussBounds {
  Channels n7{}, n10{};
};
struct GaussEllipse {
  double rho, scale7, scale10;  // (64/15) rho^-2N / (rho^2 - 1) for N = 7, 10
};
constexpr GaussEllipse gauss_ellipse(double rho) {
  double p7 = 1.0, p10 = 1.0;
  for (int k = 0; k < 14; ++k) p7 /= rho;
  for (int k = 0; k < 20; ++k) p10 /= rho;
  return {rho, (64.0 / 15.0) * p7 / (rho * rho - 1.0), (64.0 / 15.0) * p10 / (rho * rho - 1.0)};
}
constexpr std::array<GaussEllipse, 10> kGaussEllipses = {
    gauss_ellipse(4.0),   gauss_ellipse(8.0),   gauss_ellipse(16.0),   gauss_ellipse(32.0),   gauss_ellipse(64.0),
    gauss_ellipse(128.0), gauss_ellipse(256.0), gauss_ellipse(512.0), gauss_ellipse(1024.0), gauss_ellipse(2048.0)};
constexpr std::size_t kFirstEllipse = 3;  // rho = 32

// An upper bound of exp(x) for 0 <= x <= 700 (above: infinity; NaN stays NaN), within 1e-11
// relative of exp(x): x = k ln 2 + y, 2^k exact, e^y <= 1 + y + y^2/2 + 0.36 y^3 for
// 0 <= y <= ln 2 + 1e-12 (Taylor's remainder y^3 e^xi / 6 with e^xi <= 2.0001 < 6 x 0.36), y taken
// >= 0 (e^y is increasing); the factor 1 + 1e-11 covers the rounding of y (<= ~1e-13 absolute
// for x <= 700, so e^(1e-13)) and of the polynomial (a few ulps). A libm exp per ellipse was a
// third of gauss_bounds' time.
double exp_upper(double x) {
  if (!(x <= 700.0)) return x > 700.0 ? std::numeric_limits<double>::infinity() : x;
  constexpr double kLn2 = 0.6931471805599453, kLog2e = 1.4426950408889634;
  const double k = std::floor(std::max(x, 0.0) * kLog2e);
  const double y = std::max(x - k * kLn2, 0.0);
  const double poly = 1.0 + y * (1.0 + y * (0.5 + y * 0.36));
  // 2^k built from its exponent bits (0 <= k <= 1010; std::ldexp was a library call)
  const std::uint64_t bits = static_cast<std::uint64_t>(static_cast<int>(k) + 1023) << 52;
  double two_k;
  std::memcpy(&two_k, &bits, sizeof two_k);
  return poly * (1.0 + 1e-11) * two_k;
}

GaussBounds gauss_bounds(const Coefficients& c, const Coefficients& P, double P0, double x0, double x1,
                         double h, const std::array<LinearPart, kChannels>& rho,
                         const std::array<LinearPart, kChannels>& kappa, const Channels& enough) {
  GaussBounds out;
  out.n7.fill(std::numeric_limits<double>::infinity());
  out.n10.fill(std::numeric_limits<double>::infinity());
  const double m = 0.5 * (x0 + x1), r = 0.5 * (x1 - x0);
  // The bounds on ellipse e; true when it lowered some channel's bound.
  const auto visit = [&](const GaussEllipse& e) {
    const double A = std::abs(m) + r * 0.5 * (e.rho + 1.0 / e.rho);
    const double R = A + std::sqrt(A * A + 1.0);
    const double f_bound = ellipse_bound(c, R), P_bound = ellipse_bound(P, R) + std::abs(P0);
    const double dx_bound = A + std::abs(x0);
    // |exp(-tau)| <= exp(max over channels of the bound of |tau|): one exp_upper per ellipse.
    double tau_bound = 0.0;
    Channels weight{};
    for (std::size_t ch = 0; ch < kChannels; ++ch) {
      const LinearPart &p = rho[ch], &k = kappa[ch];
      weight[ch] = (std::abs(k.v0) + std::abs(k.beta) * (f_bound + std::abs(k.s0))) *
                   (std::abs(p.v0) + std::abs(p.beta) * (f_bound + std::abs(p.s0)));
      tau_bound = std::max(tau_bound, h * (std::abs(p.v0) * dx_bound + std::abs(p.beta) * (P_bound + std::abs(p.s0) * dx_bound)));
    }
    const double growth = r * exp_upper(tau_bound);
    bool smaller = false;
    for (std::size_t ch = 0; ch < kChannels; ++ch) {
      const double M = growth * weight[ch];
      if (!std::isfinite(M)) continue;
      smaller = smaller || e.scale7 * M < out.n7[ch] || e.scale10 * M < out.n10[ch];
      out.n7[ch] = std::min(out.n7[ch], e.scale7 * M);
      out.n10[ch] = std::min(out.n10[ch], e.scale10 * M);
    }
    return smaller;
  };
  const auto settled = [&] {
    bool n7 = true, n10 = true;
    for (std::size_t ch = 0; ch < kChannels; ++ch) {
      n7 = n7 && out.n7[ch] <= enough[ch];
      n10 = n10 && out.n10[ch] <= enough[ch];
    }
    return n7 || n10;
  };
  // The bound falls with rho (rho^-2N) until the integrand's growth on the larger ellipse wins.
  visit(kGaussEllipses[kFirstEllipse]);
  std::size_t up = kFirstEllipse + 1;
  while (!settled() && up < kGaussEllipses.size() && visit(kGaussEllipses[up])) ++up;
  if (up == kFirstEllipse + 1)
    for (std::size_t down = kFirstEllipse; !settled() && down-- > 0 && visit(kGaussEllipses[down]);) {
    }
  return out;
}

// One Chebyshev interpolant of f on [a, b] (t), with its tail.
struct Interpolant {
  double a = 0.0, b = 0.0;
  Coefficients c;
  double tail = 0.0;
};
using Interpolants = boost::container::small_vector<Interpolant, 2>;

struct Sampler {
  // (A constructor, not aggregate initialisation: that zeroed the optional's 1.2 kB per chord.)
  Sampler(const LinearCell* cell_, const ViewRay* ray_, bool use_newton_) : cell(cell_), ray(ray_), use_newton(use_newton_) {}
  const LinearCell* cell;
  const ViewRay* ray;
  bool use_newton;
  std::optional<ChordScalar> scalar;  // the isoparametric samples (chord_scalar.hpp), if use_newton
  // An affine linear cell: p(t) is linear and every shape function multilinear, so f(t) is a
  // polynomial of degree <= 3 (voxel, hexahedron; 2 for a wedge): interpolate() takes the
  // coefficients above it as rounding (its tail), not as a truncation to test.
  int exact_degree = -1;
  int samples = 0;
  bool ok = true;
  // Before the samples of one interpolant on [a, b]: the Taylor predictor about its centre.
  void begin(double a, double b) {
    if (use_newton) scalar->expand(a, b);
  }
  // A bound of f's Chebyshev coefficients above degree n on the last begin()'s interval (the
  // Taylor series' tail, chord_scalar.hpp); 0 on the polynomial path (exact_degree decides).
  double tail_bound(int n) const { return use_newton ? scalar->taylor_tail(n) : 0.0; }
  // An affine cell: f's coefficients on [a, b] multiplied out (affine_chord_chebyshev), with
  // their rounding as the tail; false on the Newton path.
  // On the Newton path (hexahedra, voxels): f's own Taylor series about the centre of [a, b],
  // when it converged and a degree meets `chop` (ChordScalar::series_chebyshev: no samples, no
  // DCT), with its error bound as the tail; else false (the samples follow, from the same
  // expansion).
  double chop = 0.0;
  bool exact(double a, double b, Coefficients& c, double& rounding) {
    if (use_newton) {
      std::array<double, kTaylorMaxOrder + 1> series;
      int degree = 0;
      if (!scalar->expand(a, b) || !scalar->series_chebyshev(chop, series, degree, rounding)) return false;
      c.assign(series.begin(), series.begin() + degree + 1);
      return true;
    }
    std::array<double, 4> c4{};
    rounding = affine_chord_chebyshev(*cell, *ray, a, b, c4);
    c.assign(c4.begin(), c4.end());
    return true;
  }
  double operator()(double t) {
    ++samples;
    const Vec3 x = ray->origin + t * ray->direction;
    if (!use_newton) return cell_scalar(*cell, cell->affine_inverse * (x - cell->affine_origin));
    double f = 0.0;
    if (!scalar->sample(t, f)) {
      ok = false;
      return 0.0;
    }
    return f;
  }
};

// Interpolants covering [a, b]; false on a Newton failure or a missed tail after the budget.
template <class F>
bool interpolate(F& f, double a, double b, int depth, int n0, double tail_target,
                 Interpolants& out, int& max_degree) {
  {
    Interpolant I{a, b, {}, 0.0};
    if (f.exact(a, b, I.c, I.tail) && I.tail <= tail_target) {
      max_degree = std::max(max_degree, static_cast<int>(I.c.size()) - 1);
      out.push_back(std::move(I));
      return true;
    }
  }
  std::vector<double> v(static_cast<std::size_t>(n0) + 1);
  auto node = [&](int j, int n) { return 0.5 * (a + b) + 0.5 * (b - a) * cosine_table(n)[j]; };
  f.begin(a, b);
  for (int j = 0; j <= n0; ++j) v[static_cast<std::size_t>(j)] = f(node(j, n0));
  if (!f.ok) return false;
  Interpolant I{a, b, {}, 0.0};
  for (int n = n0;; n *= 2) {
    chebyshev_coefficients(v, n, I.c);
    if (f.exact_degree >= 0 && f.exact_degree < n) {  // a polynomial of known degree: the rest is rounding
      I.tail = 0.0;
      for (int k = f.exact_degree + 1; k <= n; ++k) I.tail += std::abs(I.c[static_cast<std::size_t>(k)]);
    } else {
      I.tail = std::abs(I.c[static_cast<std::size_t>(n) - 1]) + std::abs(I.c[static_cast<std::size_t>(n)]);
    }
    // Below kTrustedDegree the two-coefficient tail test alone is not trusted: the rest must be
    // bounded a priori too (Sampler::tail_bound), and twice that bound joins the tail.
    double bound = 0.0;
    if (I.tail <= tail_target && n < kTrustedDegree && f.exact_degree < 0) {
      bound = f.tail_bound(n);
      if (!(bound <= 0.5 * tail_target)) I.tail = std::numeric_limits<double>::infinity();  // not accepted at n
    }
    if (I.tail <= tail_target) {
      I.tail += 2 * bound;
      max_degree = std::max(max_degree, n);
      // Chop: trailing coefficients whose absolute sum is <= kChopFraction of the tail target
      // are dropped and their sum added to the tail (|T_k| <= 1, so the bound stays a bound);
      // a nearly cubic scalar then costs a short Clenshaw sum at every quadrature node.
      double dropped = 0.0;
      std::size_t keep = I.c.size();
      while (keep > 2 && dropped + std::abs(I.c[keep - 1]) <= kChopFraction * tail_target) dropped += std::abs(I.c[--keep]);
      // With an a-priori bound of f's coefficients above degree m (the Taylor series) below the
      // same kChopFraction of the target, the coefficients above m are the samples' rounding
      // (the DCT spreads ~eps |f| into every one), not f: dropped too, and the bound (not their
      // sum) joins the tail, since f_true - f_kept = (f's part above m) + (the interpolation
      // error of the kept part, in the tail already).
      for (std::size_t m = 1; m + 1 < keep; ++m) {
        const double above = f.tail_bound(static_cast<int>(m));
        if (f.exact_degree < 0 && above > 0.0 && above <= kChopFraction * tail_target) {
          keep = m + 1;
          dropped = above;
          break;
        }
      }
      if (f.exact_degree >= 0 && static_cast<std::size_t>(f.exact_degree) + 1 < keep) {
        keep = static_cast<std::size_t>(f.exact_degree) + 1;  // the rest is rounding, in the tail already
        dropped = 0.0;
      }
      I.c.resize(keep);
      I.tail += dropped;
      out.push_back(std::move(I));
      return true;
    }
    if (2 * n > kMaxDegree) break;
    std::vector<double> w(2 * static_cast<std::size_t>(n) + 1);
    for (int j = 0; j <= 2 * n; ++j)
      w[static_cast<std::size_t>(j)] = (j % 2 == 0) ? v[static_cast<std::size_t>(j / 2)] : f(node(j, 2 * n));
    if (!f.ok) return false;
    v.swap(w);
  }
  if (depth >= kMaxBisections) return false;
  const double mid = 0.5 * (a + b);
  return interpolate(f, a, mid, depth + 1, n0, tail_target, out, max_degree) &&
         interpolate(f, mid, b, depth + 1, n0, tail_target, out, max_degree);
}

double root(const Coefficients& c, double level, double lo, double hi, double f_lo, double f_hi) {
  boost::math::tools::eps_tolerance<double> tol(std::numeric_limits<double>::digits - 1);
  std::uintmax_t iterations = 200;
  const auto g = [&](double x) { return clenshaw(c, x) - level; };
  const auto r = boost::math::tools::toms748_solve(g, lo, hi, f_lo - level, f_hi - level, tol, iterations);
  return 0.5 * (r.first + r.second);
}

// Knots in x of one interpolant: -1, critical points, breakpoint crossings, 1.
Knots knots(const Interpolant& I, const std::vector<double>& breakpoints) {
  const int n = static_cast<int>(I.c.size()) - 1;
  // Monotone without search when |c_1| > sum_{k >= 2} k^2 |c_k| (|T_k'| <= k^2 on [-1, 1], so f'
  // keeps the sign of c_1): the usual case of a short chord in a mildly distorted cell.
  double bound = 0.0;
  for (int k = 2; k <= n; ++k) bound += static_cast<double>(k) * k * std::abs(I.c[static_cast<std::size_t>(k)]);
  const bool proven_monotone = n >= 1 && bound < std::abs(I.c[1]);
  Coefficients d;
  if (!proven_monotone) derivative(I.c, d);
  int M = 8;  // sign samples of f': a power of two >= 2n (the cosine table's degrees)
  while (M < 2 * n) M *= 2;
  if (proven_monotone) M = 0;
  Knots monotone{-1.0};
  double x_prev = -1.0, d_prev = proven_monotone ? 0.0 : clenshaw(d, -1.0);
  for (int m = M - 1; m >= 0; --m) {
    const double x = (m == 0) ? 1.0 : cosine_table(M)[m];
    const double dx = clenshaw(d, x);
    if (dx == 0.0 && m != 0) {
      monotone.push_back(x);
    } else if (d_prev != 0.0 && (dx < 0.0) != (d_prev < 0.0) && dx != 0.0) {
      monotone.push_back(root(d, 0.0, x_prev, x, d_prev, dx));
    }
    x_prev = x;
    d_prev = dx;
  }
  monotone.push_back(1.0);
  Knots out;
  for (std::size_t k = 0; k + 1 < monotone.size(); ++k) {
    const double lo = monotone[k], hi = monotone[k + 1];
    if (!(hi > lo)) continue;
    out.push_back(lo);
    double f_lo = 0.0, f_hi = 0.0;
    clenshaw_pair(I.c, lo, I.c, hi, f_lo, f_hi);
    const double f_min = std::min(f_lo, f_hi), f_max = std::max(f_lo, f_hi);
    for (double level : breakpoints)
      if (level > f_min && level < f_max) out.push_back(root(I.c, level, lo, hi, f_lo, f_hi));
  }
  out.push_back(1.0);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace

const char* cell_path_name(CellPath path) {
  switch (path) {
    case CellPath::linear_exact: return "linear_exact";
    case CellPath::polynomial: return "polynomial";
    case CellPath::isoparametric: return "isoparametric";
  }
  return "?";
}

CellPieceIntegral composite(const CellPieceIntegral& near, const CellPieceIntegral& far) {
  CellPieceIntegral out = near;
  for (std::size_t c = 0; c < kChannels; ++c) {
    out.emission[c] = near.emission[c] + std::exp(-near.optical_depth[c]) * far.emission[c];
    out.optical_depth[c] = near.optical_depth[c] + far.optical_depth[c];
  }
  out.error_estimate = near.error_estimate + far.error_estimate;
  out.pieces = near.pieces + far.pieces;
  out.samples = near.samples + far.samples;
  out.max_degree = std::max(near.max_degree, far.max_degree);
  out.converged = near.converged && far.converged;
  out.failure = !near.converged ? near.failure : far.failure;
  return out;
}

LinearCellIntegrator::LinearCellIntegrator(const TransferFunctions& tf)
    : tf_(&tf), breakpoints_(tf.breakpoints()), splitter_(tf) {}

CellPieceIntegral LinearCellIntegrator::integrate(const LinearCell& cell, const ViewRay& ray, double t_near,
                                            double t_far, const Vec3* start) const {
  if (cell.type != LinearCellType::tetra) return integrate_curved(cell, ray, t_near, t_far, !cell.affine, start);
  CellPieceIntegral out;
  out.path = CellPath::linear_exact;
  const Vec3 x_near = ray.origin + t_near * ray.direction, x_far = ray.origin + t_far * ray.direction;
  const double f_near = cell_scalar(cell, cell.affine_inverse * (x_near - cell.affine_origin));
  const double f_far = cell_scalar(cell, cell.affine_inverse * (x_far - cell.affine_origin));
  out.samples = 2;
  const Segment segment{(t_far - t_near) * ray.direction.norm(), f_far, f_near};
  Rgb intensity{0.0, 0.0, 0.0};
  for (const Piece& piece : splitter_.pieces(segment)) {  // far -> near
    for (int c = 0; c < kChannels; ++c) {
      const auto cc = static_cast<std::size_t>(c);
      const PieceOptics optics = exact_piece(piece.channel(c));
      if (!optics.converged) {
        out.converged = false;
        out.failure = "exact piece series missed its term budget";
      }
      intensity[cc] = intensity[cc] * optics.transmittance + optics.emission;
      out.optical_depth[cc] += piece.length * 0.5 * (piece.rho_far[cc] + piece.rho_exit[cc]);
    }
    ++out.pieces;
  }
  out.emission = intensity;
  // exact_piece's measured worst relative error (integrators/exact.cpp) is 8.05e-14.
  for (std::size_t c = 0; c < kChannels; ++c)
    out.error_estimate = std::max(out.error_estimate, 1e-13 * (out.emission[c] + out.optical_depth[c]));
  return out;
}

CellPieceIntegral LinearCellIntegrator::integrate_isoparametric(const LinearCell& cell, const ViewRay& ray,
                                                          double t_near, double t_far) const {
  return integrate_curved(cell, ray, t_near, t_far, true);
}

CellPieceIntegral LinearCellIntegrator::integrate_curved(const LinearCell& cell, const ViewRay& ray,
                                                   double t_near, double t_far, bool use_newton,
                                                   const Vec3* start) const {
  double value_scale = 0.0;
  const int nodes = linear_node_count(cell.type);
  for (int i = 0; i < nodes; ++i) value_scale = std::max(value_scale, std::abs(cell.value[static_cast<std::size_t>(i)]));
  Sampler sampler(&cell, &ray, use_newton);
  if (use_newton)
    sampler.scalar.emplace(cell, ray, start);
  else
    sampler.exact_degree = 3;
  // Degree 8 first where taylor_tail can accept it (hexahedra, voxels; affine cells: exact_degree).
  const bool hex = cell.type == LinearCellType::hexahedron || cell.type == LinearCellType::voxel;
  sampler.chop = kSeriesTruncation * std::max(kChebyshevTail * value_scale, std::numeric_limits<double>::min());
  return integrate_sampled(sampler, value_scale, ray, t_near, t_far, use_newton && !hex ? 16 : 8,
                           use_newton ? CellPath::isoparametric : CellPath::polynomial);
}

template <class F>
CellPieceIntegral LinearCellIntegrator::integrate_sampled(F& sampler, double value_scale, const ViewRay& ray,
                                                          double t_near, double t_far, int n0, CellPath path) const {
  CellPieceIntegral out;
  out.path = path;
  if (!(t_far >= t_near) || !std::isfinite(t_near) || !std::isfinite(t_far)) {
    out.converged = false;
    out.failure = "chord ends not finite or reversed";
    return out;
  }
  if (t_far == t_near) return out;
  const double tail_target = std::max(kChebyshevTail * value_scale, std::numeric_limits<double>::min());

  Interpolants parts;
  const bool ok = interpolate(sampler, t_near, t_far, 0, n0, tail_target, parts, out.max_degree);
  out.samples = sampler.samples;
  if (!ok) {
    out.converged = false;
    out.failure = sampler.ok ? "scalar interpolant missed its tail target" : "inverse map did not converge";
    return out;
  }
  const double speed = ray.direction.norm();
  Rgb depth{0.0, 0.0, 0.0}, emission{0.0, 0.0, 0.0}, error{0.0, 0.0, 0.0};
  for (const Interpolant& I : parts) {  // near -> far
    const double h = 0.5 * (I.b - I.a) * speed;  // world length per unit x
    const Knots xs = knots(I, breakpoints_);
    const Coefficients P = antiderivative(I.c);
    // P at a piece's far end is P at the next piece's near end (the same knot): kept, not summed
    // again; f at the piece's middle and P at its far end in one interleaved pass.
    double x_last = std::numeric_limits<double>::quiet_NaN(), P_last = 0.0;
    for (std::size_t k = 0; k + 1 < xs.size(); ++k) {
      const double x0 = xs[k], x1 = xs[k + 1];
      if (!(x1 > x0)) continue;
      double f_mid = 0.0, P1 = 0.0;
      clenshaw_pair(I.c, 0.5 * (x0 + x1), P, x1, f_mid, P1);
      const double length = h * (x1 - x0);
      const double P0 = x0 == x_last ? P_last : clenshaw(P, x0);
      x_last = x1, P_last = P1;
      ++out.pieces;
      std::array<LinearPart, kChannels> rho, kappa;
      bool emits = false;
      for (std::size_t c = 0; c < kChannels; ++c) {
        rho[c] = linear_part(tf_->density[c], f_mid);
        kappa[c] = linear_part(tf_->color[c], f_mid);
        emits = emits || (rho[c].max_value > 0.0 && kappa[c].max_value > 0.0);
      }
      // tau_c(x) = h int_x0^x (v0 + beta (f - s0)) = h (v0 dx + beta ((P(x) - P(x0)) - s0 dx)):
      // exact for the series (no quadrature error in the optical depth).
      const auto tau = [&](std::size_t c, double dx, double dP) {
        return h * (rho[c].v0 * dx + rho[c].beta * (dP - rho[c].s0 * dx));
      };
      const double dP1 = P1 - P0;
      Channels piece_emission{}, quadrature_error{};
      if (emits) {
        // At n nodes at once, vectorised over the nodes (emission_nodes.hpp: the same operations
        // as the scalar form, fused multiply-adds on FMA targets, exp Highway's, documented 1 ulp;
        // libm's, used before 2026-12-05, ~0.5 ulp; an exponent outside [-700, 700] or NaN goes
        // to std::exp).
        EmissionPiece emission_piece;
        emission_piece.c = I.c.data(), emission_piece.nc = I.c.size();
        emission_piece.P = P.data(), emission_piece.nP = P.size();
        emission_piece.x0 = x0, emission_piece.P0 = P0, emission_piece.h = h;
        for (std::size_t c = 0; c < kChannels; ++c) {
          emission_piece.rho[c] = {rho[c].v0, rho[c].beta, rho[c].s0};
          emission_piece.kappa[c] = {kappa[c].v0, kappa[c].beta, kappa[c].s0};
        }
        const auto integrand = [&](double centre, double half, const double* u, std::size_t n, Channels* v) {
          std::array<double, kChannels * kMaxEmissionNodes> g;
          emission_at_nodes(emission_piece, centre, half, u, n, g.data());
          for (std::size_t j = 0; j < n; ++j)
            for (std::size_t c = 0; c < kChannels; ++c) v[j][c] = g[kChannels * j + c];
        };
        // The integrand's rounding noise: rho = v0 + beta (f - s0) carries ~eps |beta| (|f| + |s0|)
        // absolutely (relative error unbounded where rho -> 0 at a breakpoint), kappa likewise;
        // the quadrature cannot resolve below kNoiseUlps = 64 ulps of that scale.
        Channels floor{};
        for (std::size_t c = 0; c < kChannels; ++c) {
          const double rho_noise = std::abs(rho[c].v0) + std::abs(rho[c].beta) * (value_scale + std::abs(rho[c].s0));
          const double kappa_noise = std::abs(kappa[c].v0) + std::abs(kappa[c].beta) * (value_scale + std::abs(kappa[c].s0));
          floor[c] = 64 * std::numeric_limits<double>::epsilon() * (x1 - x0) *
                     (kappa[c].max_value * rho_noise + rho[c].max_value * kappa_noise);
        }
        // First a 7-, then a 10-point Gauss rule, each accepted when its a-priori bound is within
        // the tolerance in every channel; otherwise the adaptive Gauss-Kronrod rule.
        const GaussBounds bounds = gauss_bounds(I.c, P, P0, x0, x1, h, rho, kappa, floor);
        const double rel = std::max(kQuadratureTolerance, 8 * std::numeric_limits<double>::epsilon());
        Channels l1{};
        const auto within = [&](const Channels& bound) {
          for (std::size_t c = 0; c < kChannels; ++c)
            if (!std::isfinite(piece_emission[c]) || !(bound[c] <= std::max(rel * l1[c], floor[c]))) return false;
          return true;
        };
        // No evaluation is wasted: the 10-point rule is used only where its bound is below the
        // rounding floor (known before evaluating: it passes unless a value is not finite) and
        // the 7-point one's is not; otherwise the 7-point rule's nodes are the Gauss-Kronrod
        // rule's Gauss nodes, which the adaptive rule reuses when the bound misses.
        bool done = false, floor7 = true, floor10 = true;
        for (std::size_t c = 0; c < kChannels; ++c) {
          floor7 = floor7 && bounds.n7[c] <= floor[c];
          floor10 = floor10 && bounds.n10[c] <= floor[c];
        }
        KronrodValues nodes;
        bool have_nodes = false;
        if (!floor7 && floor10) {
          gauss_rule<10>(integrand, x0, x1, piece_emission, l1);
          if (within(bounds.n10)) quadrature_error = bounds.n10, done = true;
        } else {
          gauss_7_nodes(integrand, x0, x1, nodes);
          have_nodes = true;
          gauss_7_sums(nodes, x0, x1, piece_emission, l1);
          if (within(bounds.n7)) quadrature_error = bounds.n7, done = true;
        }
        if (!done && !adaptive_integral(integrand, x0, x1, kQuadratureTolerance, floor, piece_emission, quadrature_error,
                                        have_nodes ? &nodes : nullptr)) {
          out.converged = false;
          out.failure = "emission quadrature missed its tolerance";
        }
      }
      const double e_f = I.tail;
      for (std::size_t c = 0; c < kChannels; ++c) {
        const double E = h * piece_emission[c];
        const double depth_error = std::abs(rho[c].beta) * e_f * length;
        // once (libm's exp is not merged: errno); the first piece's depth is 0
        const double transmittance = depth[c] == 0.0 ? 1.0 : std::exp(-depth[c]);
        error[c] += transmittance *
                        (h * quadrature_error[c] +
                         length * e_f * (std::abs(kappa[c].beta) * rho[c].max_value + kappa[c].max_value * std::abs(rho[c].beta)) +
                         E * depth_error) +
                    depth_error;
        emission[c] += transmittance * E;
        depth[c] += tau(c, x1 - x0, dP1);
      }
    }
  }
  out.emission = emission;
  out.optical_depth = depth;
  // Rounding: the inverse maps (residual 8 eps), Clenshaw sums and compositing, a few ulps of
  // the emission and depth each; kRoundingUlps = 32 is that with a margin (measured: see
  // reports/cells/accuracy.md, column est<err).
  constexpr double kRoundingUlps = 32 * std::numeric_limits<double>::epsilon();
  for (std::size_t c = 0; c < kChannels; ++c) error[c] += kRoundingUlps * (emission[c] + depth[c]);
  out.error_estimate = std::max({error[0], error[1], error[2]});
  return out;
}

// ---- Quadratic cells (cells/quadratic_isoparametric.hpp) ----------------------------------------

namespace {

// f(t) of a quadratic cell: the affine inverse, or Newton warm-started from the previous point.
struct QuadraticSampler {
  const QuadraticCell* cell;
  const ViewRay* ray;
  Vec3 start;
  int exact_degree;  // -1: f's degree along the ray is not used
  int samples = 0;
  bool ok = true;
  // The Newton start carries over from the previous sample (no predictor for quadratic maps).
  void begin(double, double) {}
  bool exact(double, double, Coefficients&, double&) const { return false; }
  // No bound: a degree below kTrustedDegree is accepted on the tail test alone only when affine
  // (n0 = 8: f is then a polynomial of degree <= 6 along the ray).
  double tail_bound(int) const { return 0.0; }
  double operator()(double t) {
    ++samples;
    const Vec3 x = ray->origin + t * ray->direction;
    if (cell->affine) return cell_scalar(*cell, cell->affine_inverse * (x - cell->affine_origin));
    InverseMap m = inverse_map(*cell, x, start);
    if (!m.converged) m = inverse_map(*cell, x);  // from the centre
    if (!m.converged) {
      ok = false;
      return 0.0;
    }
    start = m.p;
    return cell_scalar(*cell, m.p);
  }
};

}  // namespace

CellPieceIntegral LinearCellIntegrator::integrate(const QuadraticCell& cell, const ViewRay& ray, double t_near,
                                                  double t_far) const {
  double value_scale = 0.0;
  for (int i = 0; i < quadratic_node_count(cell.type); ++i)
    value_scale = std::max(value_scale, std::abs(cell.value[static_cast<std::size_t>(i)]));
  QuadraticSampler sampler{&cell, &ray, quadratic_reference_centre(cell.type), -1};
  return integrate_sampled(sampler, value_scale, ray, t_near, t_far, cell.affine ? 8 : 16,
                           cell.affine ? CellPath::polynomial : CellPath::isoparametric);
}

}  // namespace rayint
