// exact_grad.cpp -- exact derivatives of the exact ray integral (Williams & Max 1992, Eq. 4 on
// pieces where rho and kappa are linear, Sec. 3.3) with respect to every input of a ray.
//
// One piece (notation of exact.cpp: u = s/L from the exit, a = rho_exit L, b = rho_far L,
// A = a, B = (b - a)/2, tau(u) = A u + B u^2, T = (a + b)/2, e0 = int_0^1 e^{-tau} du,
// w_exit = 1 - e0, w_far = e0 - e^{-T}, emission = kappa_exit w_exit + kappa_far w_far):
//   d e0/dA = -M1,  d e0/dB = -M2,  M_n = int_0^1 u^n e^{-tau(u)} du, so
//   d e0/da = -M1 + M2/2,  d e0/db = -M2/2,  d e^{-T}/da = d e^{-T}/db = -e^{-T}/2,
//   d emission/da = (kappa_far - kappa_exit) d e0/da + kappa_far e^{-T}/2  (same for b),
//   d emission/d kappa_exit = w_exit,  d emission/d kappa_far = w_far,
// and a = rho_exit L, b = rho_far L carry them to L, rho_exit, rho_far.
// Everything reduces to the two moments M1, M2. The branch is exact_piece's own (the forward
// value comes from exact_piece, so the branch selection and its thresholds kThinDepth and
// kQ2Relative are literally shared); inside a branch the moments are the derivative of that
// branch's stable form:
//   - transparent (T == 0): M1 = 1/2, M2 = 1/3.
//   - thin_series (T <= 1): the midpoint series of exact.cpp's thin_weights, e0 = e^{-tau_m} S,
//     differentiated term by term: with S_P = sum_{n odd} e_n/(n+2), S_Q = sum_{n even} e_n/(n+3)
//     (dS/dP, dS/dQ), M1 = e^{-tau_m} (S + S_P)/2, M2 = e^{-tau_m} (S + 2 S_P + S_Q)/4. For
//     T <= 1, S ~ 1, |S_P| <= T/6, S_Q ~ 1/3: no cancellation.
//   - q2_series (|B| <= 2^-26 A^2): e0 = m0 - B m2 + B^2/2 m4 term by term,
//     M1 = m1 - B m3 + B^2/2 m5, M2 = m2 - B m4 + B^2/2 m6, with m_n(A) = int_0^1 u^n e^{-Au}
//     from the positive tail e^{-A} sum_{j>n} A^j/j! for A <= 8 (the closed form loses up to
//     12 ulps at A = 1 for m2), the closed form above, and n!/A^{n+1} where e^{-A} underflows.
//   - erfcx (B > 0): with beta = sqrt(B), z0 = A/(2 beta), z1 = z0 + beta and
//     g_n(z) = int_0^inf x^n e^{-2zx - x^2} dx (g0 = sqrt(pi)/2 erfcx),
//       M1 = [g1(z0) - e^{-T} (g1(z1) + beta g0(z1))] / B,
//       M2 = [g2(z0) - e^{-T} (g2(z1) + 2 beta g1(z1) + B g0(z1))] / (B beta),
//     brackets that lose less than a factor 3 (e^{-T} <= e^{-1}). g1 = (1/2)(1 - sqrt(pi) z
//     erfcx(z)) is the derivative of the erfcx form, d/dz erfcx = 2 z erfcx - 2/sqrt(pi), which
//     cancels like 2 z^2 for large z; so for z0 > kMomentCfFrom = 2 the ratios
//     r_n = g_n/g_{n-1} come from their continued fraction r_n = (n/2)/(z + r_{n+1}) (minimal
//     solution of g_{n+1} = (n/2) g_{n-1} - z g_n), run backward from depth
//     10 + 260/z^2 + 40/z, which meets 1e-17 at z = 2, 3, 4, 8, 30 (measured in 40 digits:
//     75, 41, 29, 15, 8 terms needed). For z0 <= 2 the integration-by-parts identities
//       2B M1 = (1 - e^{-T}) - A e0,  2B M2 = w_far - A M1
//     lose at most 1/g1(2) ~ 10 and 6 more ulps. The e^{-T} terms are dropped for
//     T > kMomentAsymptoticDepth = 50 (e^{-50} T^2 < 1e-18).
//   - dawson (B < 0): for T <= 50 the midpoint series above (Q = -B/4 > 0, so every
//     coefficient e_n has the sign of P^n and S, S_Q are sums of positive terms; S + S_P loses
//     about A/4, at most 25 ulps at T = 50). For T > 50 (then y0 = A/(2 sqrt(-B)) > 7), the
//     e^{-T} terms drop and M1 = d1(y0)/gamma^2, M2 = d2(y0)/gamma^3 with the Laplace series
//     d_n(y) = int_0^y x^n e^{-2yx + x^2} dx ~ sum_k (n+2k)!/(k! (2y)^{n+2k+1}), whose
//     smallest term (~e^{-y^2}) and neglected endpoint (~y^n e^{-y^2}) are below 1e-17.
// Measured accuracy against the 50-digit reference gradient (reference/reference_grad.hpp):
// see docs/gradients.md and tests/test_grad.cpp ([grad]).
#include "rayint/integrators/exact_grad.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "rayint/special/special_functions.hpp"

namespace rayint {
namespace {

constexpr double kSqrtPi = 1.7724538509055160273;
constexpr int kMidpointBudget = 400;
constexpr int kAsymptoticBudget = 200;

struct Moments {
  double e0 = 1.0, m1 = 0.5, m2 = 1.0 / 3.0;
  MomentMethod method = MomentMethod::transparent;
  int terms = 0;
  bool converged = true;
};

// The midpoint series of exact.cpp's thin_weights and its derivatives in P and Q.
Moments midpoint_moments(double a, double b, double T) {
  Moments m;
  m.method = MomentMethod::midpoint_series;
  const double P = -0.5 * T;
  const double Q = -0.125 * (b - a);
  double e_prev = 1.0;  // e_0
  double e = P;         // e_1
  double S = 1.0, S_P = P / 3.0, S_Q = 1.0 / 3.0;
  int n = 1;
  for (; n < kMidpointBudget; ++n) {
    const double e_next = (P * e + 2.0 * Q * e_prev) / (n + 1);  // e_{n+1}
    if ((n & 1) == 1) {  // n + 1 even
      S += e_next / (n + 2);
      S_Q += e_next / (n + 4);
    } else {
      S_P += e_next / (n + 3);
    }
    e_prev = e;
    e = e_next;
    if (std::fabs(e) + std::fabs(e_prev) <= 0x1p-60 * std::fabs(S)) break;
  }
  m.terms = n + 1;
  m.converged = n < kMidpointBudget;
  const double decay_mid = std::exp(-0.125 * (3.0 * a + b));
  m.e0 = decay_mid * S;
  m.m1 = 0.5 * decay_mid * (S + S_P);
  m.m2 = 0.25 * decay_mid * (S + 2.0 * S_P + S_Q);
  return m;
}

// m_n(A) = int_0^1 u^n e^{-A u} du for n = 0..6.
void unit_moments(double A, double m[7]) {
  const double fact[7] = {1, 1, 2, 6, 24, 120, 720};
  const double eA = std::exp(-A);
  if (A <= 8.0) {
    double q[7];
    q[0] = 1.0;
    for (int j = 1; j < 7; ++j) q[j] = q[j - 1] * A / j;
    double term = q[6], tail = 0.0;  // tail = sum_{j >= 7} A^j / j!
    for (int j = 7; j < 100; ++j) {
      term *= A / j;
      tail += term;
      if (term <= 0x1p-60 * tail) break;
    }
    double Apow = A;  // A^{n+1}
    double tails[7];
    tails[6] = tail;
    for (int n = 5; n >= 0; --n) tails[n] = tails[n + 1] + q[n + 1];
    for (int n = 0; n < 7; ++n) {
      m[n] = fact[n] / Apow * (eA * tails[n]);
      Apow *= A;
    }
    return;
  }
  double p = 0.0, q = 1.0, Apow = A;
  for (int n = 0; n < 7; ++n) {
    if (n > 0) q *= A / n;
    p += q;  // sum_{j <= n} A^j / j!
    m[n] = fact[n] / Apow * (1.0 - eA * p);
    Apow *= A;
  }
}

Moments q2_moments(double A, double B) {
  Moments mo;
  mo.method = MomentMethod::q2_series;
  mo.terms = 3;
  if (std::exp(-A) == 0.0) {
    // m_n = n!/A^{n+1}: M_k = A^{-(k+1)} sum_j (-r)^j (2j+k)!/j!, r = B/A^2 (no overflow of A^7).
    const double r = B / A / A;
    mo.e0 = (1.0 - 2.0 * r + 12.0 * r * r) / A;
    mo.m1 = (1.0 - 6.0 * r + 60.0 * r * r) / A / A;
    mo.m2 = (2.0 - 24.0 * r + 360.0 * r * r) / A / A / A;
    return mo;
  }
  double m[7];
  unit_moments(A, m);
  mo.e0 = m[0] - B * m[2] + 0.5 * B * B * m[4];
  mo.m1 = m[1] - B * m[3] + 0.5 * B * B * m[5];
  mo.m2 = m[2] - B * m[4] + 0.5 * B * B * m[6];
  return mo;
}

// g0, g1, g2 at z (erfcx branch). Returns the fraction terms used (0: recurrence).
int erfcx_g(double z, double g[3]) {
  g[0] = 0.5 * kSqrtPi * special::erfcx(z);
  if (z <= kMomentCfFrom) {
    g[1] = 0.5 - z * g[0];
    g[2] = 0.5 * g[0] - z * g[1];
    return 0;
  }
  const int depth = static_cast<int>(std::ceil(10.0 + 260.0 / (z * z) + 40.0 / z));
  double r = 0.0, r1 = 0.0, r2 = 0.0;
  for (int n = depth; n >= 1; --n) {
    r = (0.5 * n) / (z + r);
    if (n == 2) r2 = r;
    if (n == 1) r1 = r;
  }
  g[1] = g[0] * r1;
  g[2] = g[1] * r2;
  return depth;
}

Moments erfcx_moments(double A, double B, double T, double t, double e0, double w_far) {
  Moments mo;
  mo.e0 = e0;
  const double beta = std::sqrt(B);
  const double z0 = A / (2.0 * beta);
  if (z0 <= kMomentCfFrom) {
    mo.method = MomentMethod::identity;
    mo.m1 = (-std::expm1(-T) - A * e0) / (2.0 * B);
    mo.m2 = (w_far - A * mo.m1) / (2.0 * B);
    return mo;
  }
  mo.method = MomentMethod::continued_fraction;
  double g0[3], g1[3] = {0.0, 0.0, 0.0};
  mo.terms = erfcx_g(z0, g0);
  double far1 = 0.0, far2 = 0.0;
  if (T <= kMomentAsymptoticDepth) {
    mo.terms += erfcx_g(z0 + beta, g1);
    far1 = t * (g1[1] + beta * g1[0]);
    far2 = t * (g1[2] + 2.0 * beta * g1[1] + B * g1[0]);
  }
  mo.m1 = (g0[1] - far1) / B;
  mo.m2 = (g0[2] - far2) / (B * beta);
  return mo;
}

Moments dawson_moments(double a, double b, double A, double B, double T) {
  if (T <= kMomentAsymptoticDepth) return midpoint_moments(a, b, T);
  Moments mo;
  mo.method = MomentMethod::asymptotic;
  const double gamma = std::sqrt(-B);
  const double y = A / (2.0 * gamma);
  const double x = 1.0 / (2.0 * y);
  // d_n(y) = sum_k c_k, c_0 = n! x^{n+1}, c_{k+1} = c_k (n+2k+1)(n+2k+2) x^2 / (k+1).
  double d[3];
  int terms = 0;
  for (int n = 1; n <= 2; ++n) {
    double c = (n == 1 ? 1.0 : 2.0) * std::pow(x, n + 1);
    double sum = c;
    int k = 0;
    for (; k < kAsymptoticBudget; ++k) {
      const double next = c * (n + 2 * k + 1) * (n + 2 * k + 2) * x * x / (k + 1);
      if (next > c) {  // the asymptotic series turned before meeting the tolerance
        mo.converged = false;
        break;
      }
      c = next;
      sum += c;
      if (c <= 0x1p-60 * sum) break;
    }
    if (k == kAsymptoticBudget) mo.converged = false;
    terms += k + 1;
    d[n] = sum;
  }
  mo.terms = terms;
  mo.m1 = d[1] / (gamma * gamma);
  mo.m2 = d[2] / (gamma * gamma * gamma);
  mo.e0 = 0.0;  // set by the caller from the forward weights
  return mo;
}

}  // namespace

const char* moment_method_name(MomentMethod m) {
  switch (m) {
    case MomentMethod::transparent: return "transparent";
    case MomentMethod::midpoint_series: return "midpoint_series";
    case MomentMethod::q2_series: return "q2_series";
    case MomentMethod::identity: return "identity";
    case MomentMethod::continued_fraction: return "continued_fraction";
    case MomentMethod::asymptotic: return "asymptotic";
  }
  return "?";
}

PieceOpticsGrad exact_piece_grad(const ChannelPiece& p) {
  PieceOpticsGrad g;
  g.optics = exact_piece(p);
  const PieceOptics& o = g.optics;
  const double t = o.transmittance;
  const double a = p.rho_exit * p.length;
  const double b = p.rho_far * p.length;
  const double T = 0.5 * (a + b);
  const double A = a, B = 0.5 * (b - a);
  Moments mo;
  switch (o.branch) {
    case ExactBranch::transparent:
      break;
    case ExactBranch::thin_series:
      mo = midpoint_moments(a, b, T);
      break;
    case ExactBranch::q2_series:
      mo = q2_moments(A, B);
      break;
    case ExactBranch::erfcx:
      mo = erfcx_moments(A, B, T, t, o.weight_far + t, o.weight_far);
      break;
    case ExactBranch::dawson:
      mo = dawson_moments(a, b, A, B, T);
      if (mo.method == MomentMethod::asymptotic) mo.e0 = o.weight_far + t;
      break;
  }
  g.e0 = mo.e0;
  g.m1 = mo.m1;
  g.m2 = mo.m2;
  g.method = mo.method;
  g.terms = mo.terms;
  g.converged = mo.converged;

  const double de0_da = -mo.m1 + 0.5 * mo.m2;
  const double de0_db = -0.5 * mo.m2;
  const double dkappa = p.kappa_far - p.kappa_exit;
  const double de_da = dkappa * de0_da + 0.5 * p.kappa_far * t;
  const double de_db = dkappa * de0_db + 0.5 * p.kappa_far * t;
  g.de_kappa_exit = o.weight_exit;
  g.de_kappa_far = o.weight_far;
  g.de_rho_exit = p.length * de_da;
  g.de_rho_far = p.length * de_db;
  g.de_length = p.rho_exit * de_da + p.rho_far * de_db;
  g.dt_rho_exit = g.dt_rho_far = -0.5 * t * p.length;
  g.dt_length = -0.5 * t * (p.rho_exit + p.rho_far);
  return g;
}

namespace {

// A piece of a segment, as append_pieces makes it, with what the chain rule needs.
struct PieceRecord {
  std::size_t segment = 0;
  double s_far = 0.0, s_exit = 0.0;  // scalar at its ends
  double length = 0.0;
  double fraction = 1.0;             // length / segment length
  bool first = false, last = false;  // its far end is the segment's far end / exit is exit
  double sigma = 0.0;                // segment's scalar_exit - scalar_far
};

}  // namespace

RayGradient exact_ray_gradient(const TransferFunctions& tf, const Ray& ray) {
  for (int c = 0; c < kChannels; ++c)
    if (!std::isfinite(ray.background[c]))
      throw std::invalid_argument("exact gradient: background must be finite");
  const std::vector<double> breakpoints = tf.breakpoints();
  std::vector<PieceRecord> pieces;
  std::vector<double> ends;
  for (std::size_t j = 0; j < ray.segments.size(); ++j) {
    const Segment& seg = ray.segments[j];
    if (!(std::isfinite(seg.length) && std::isfinite(seg.scalar_far) && std::isfinite(seg.scalar_exit)))
      throw std::invalid_argument("exact gradient: segment " + std::to_string(j) +
                                  ": length and scalars must be finite");
    if (!(seg.length > 0.0)) continue;
    const double s0 = seg.scalar_far, s1 = seg.scalar_exit;
    if (s0 == s1) {
      pieces.push_back({j, s0, s1, seg.length, 1.0, true, true, 0.0});
      continue;
    }
    // append_pieces' ends: s0, the breakpoints strictly inside, s1, in the direction of travel.
    const double lo = std::min(s0, s1), hi = std::max(s0, s1);
    auto first = std::upper_bound(breakpoints.begin(), breakpoints.end(), lo);
    auto last = std::lower_bound(breakpoints.begin(), breakpoints.end(), hi);
    ends.assign(1, s0);
    if (s0 < s1)
      ends.insert(ends.end(), first, last);
    else
      ends.insert(ends.end(), std::make_reverse_iterator(last), std::make_reverse_iterator(first));
    ends.push_back(s1);
    const double span = s1 - s0;
    const std::size_t n_ends = ends.size();
    for (std::size_t k = 0; k + 1 < n_ends; ++k) {
      const double fraction = (ends[k + 1] - ends[k]) / span;
      const double len = seg.length * fraction;
      if (len > 0.0)
        pieces.push_back({j, ends[k], ends[k + 1], len, n_ends == 2 ? 1.0 : fraction, k == 0,
                          k + 2 == n_ends, span});
    }
  }

  RayGradient grad = RayGradient::zeros(tf, ray);
  const std::size_t n = pieces.size();
  // Forward: the optics of every piece-channel and the light entering it.
  std::vector<PieceOpticsGrad> optics(n * kChannels);
  std::vector<double> incoming(n * kChannels);
  Rgb intensity = ray.background;
  for (std::size_t k = 0; k < n; ++k) {
    const PieceRecord& pr = pieces[k];
    for (int c = 0; c < kChannels; ++c) {
      const ChannelPiece cp{pr.length, tf.density[c](pr.s_far), tf.density[c](pr.s_exit),
                            tf.color[c](pr.s_far), tf.color[c](pr.s_exit)};
      const std::size_t i = k * kChannels + static_cast<std::size_t>(c);
      optics[i] = exact_piece_grad(cp);
      incoming[i] = intensity[c];
      intensity[c] = intensity[c] * optics[i].optics.transmittance + optics[i].optics.emission;
    }
  }
  grad.intensity = intensity;

  // Reverse: adjoint = transmittance of everything nearer than the piece.
  Rgb adjoint{1.0, 1.0, 1.0};
  for (std::size_t k = n; k-- > 0;) {
    const PieceRecord& pr = pieces[k];
    const Segment& seg = ray.segments[pr.segment];
    const double lo = std::min(pr.s_far, pr.s_exit);
    for (int c = 0; c < kChannels; ++c) {
      const std::size_t i = k * kChannels + static_cast<std::size_t>(c);
      const PieceOpticsGrad& g = optics[i];
      const double e_bar = adjoint[c];
      const double t_bar = adjoint[c] * incoming[i];
      const double len_bar = e_bar * g.de_length + t_bar * g.dt_length;
      const double rho_far_bar = e_bar * g.de_rho_far + t_bar * g.dt_rho_far;
      const double rho_exit_bar = e_bar * g.de_rho_exit + t_bar * g.dt_rho_exit;
      const double kappa_far_bar = e_bar * g.de_kappa_far;
      const double kappa_exit_bar = e_bar * g.de_kappa_exit;
      // Length: len = L * (end - start) / sigma (or L for a one-piece segment).
      grad.length[pr.segment][c] += len_bar * pr.fraction;
      if (pr.sigma != 0.0 && pr.fraction != 1.0) {
        const double q = seg.length / pr.sigma;
        grad.scalar_far[pr.segment][c] += len_bar * q * (pr.fraction - (pr.first ? 1.0 : 0.0));
        grad.scalar_exit[pr.segment][c] += len_bar * q * ((pr.last ? 1.0 : 0.0) - pr.fraction);
      }
      // End values through the transfer functions.
      const auto through = [&](const PiecewiseLinear& f, std::vector<NodeDerivative>& nodes,
                               double s, double bar, bool is_seg_far, bool is_seg_exit) {
        if (bar == 0.0) return;
        const NodeWeights nw = node_weights(f, lo, s);
        for (int q = 0; q < nw.count; ++q) {
          nodes[nw.node[q]].value += bar * nw.w[q];
          nodes[nw.node[q]].position += bar * nw.dp[q];
        }
        if (is_seg_far) grad.scalar_far[pr.segment][c] += bar * nw.slope;
        if (is_seg_exit) grad.scalar_exit[pr.segment][c] += bar * nw.slope;
      };
      through(tf.density[c], grad.density[c], pr.s_far, rho_far_bar, pr.first, false);
      through(tf.density[c], grad.density[c], pr.s_exit, rho_exit_bar, false, pr.last);
      through(tf.color[c], grad.color[c], pr.s_far, kappa_far_bar, pr.first, false);
      through(tf.color[c], grad.color[c], pr.s_exit, kappa_exit_bar, false, pr.last);
      adjoint[c] *= g.optics.transmittance;
    }
  }
  grad.background = adjoint;
  return grad;
}

}  // namespace rayint
