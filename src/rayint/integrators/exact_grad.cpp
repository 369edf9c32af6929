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
//   - dawson (B < 0): for T <= 50 the series in |B| about the exit end,
//     M_n = sum_k |B|^k/k! m_{n+2k}(A), all terms positive (the midpoint series, whose
//     S + S_P lost ~A/2 ulps: 1.07e-14 measured at A = 75, is not used here; see
//     dawson_exit_series). For T > 50 (then y0 = A/(2 sqrt(-B)) > 7), the
//     e^{-T} terms drop and M1 = d1(y0)/gamma^2, M2 = d2(y0)/gamma^3 with the Laplace series
//     d_n(y) = int_0^y x^n e^{-2yx + x^2} dx ~ sum_k (n+2k)!/(k! (2y)^{n+2k+1}), whose
//     smallest term (~e^{-y^2}) and neglected endpoint (~y^n e^{-y^2}) are below 1e-17.
// Batched (exact_pieces_grad, what exact_ray_gradient uses): exact_batch forms the optics of all
// pieces and, for thin_series lanes, the moments above with the same recurrence and stop in its
// vector kernel (OpticsColumns::m1); the other branches' moments come from closed_form_moments
// below, the same functions exact_piece_grad calls; exp(-T) from special::exp_neg_array (std::exp's
// accuracy class, in vectors: the batch's Exp's extra ulp doubled a saturated ray's worst length
// entry). Against exact_piece_grad:
// GradTolerances::batch_vs_scalar_rel (tests/test_grad_batch.cpp, every regime and SIMD target).
// Measured accuracy against the 50-digit reference gradient (reference/reference_grad.hpp):
// see docs/gradients.md and tests/test_grad.cpp ([grad]).
#include "rayint/integrators/exact_grad.hpp"
#include "rayint/integrators/ray_gradient_chain.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "rayint/integrators/exact_batch.hpp"
#include "rayint/special/erfcx_simd.hpp"
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

// 1/(n+1), as exact.cpp's table (the same constant expressions, so the same doubles).
struct Reciprocals {
  double r[kMidpointBudget + 4];
  constexpr Reciprocals() : r() {
    for (int n = 0; n < kMidpointBudget + 4; ++n) r[n] = 1.0 / (n + 1);
  }
};
constexpr Reciprocals kRecip;

// The midpoint series of exact.cpp's thin_weights (same recurrence e_{n+1} = (P e_n +
// 2 Q e_{n-1})/(n+1), P = -T/2, Q = -B/4, same arithmetic and stop), with the sums of its
// derivatives in P and Q: S = 1 + s_minus_1, S_P = sum_{n odd} e_n/(n+2), S_Q = sum_{n even}
// e_n/(n+3). The loop ends when two successive coefficients are below stop_abs + stop_rel * S.
struct MidpointSums {
  double s_minus_1 = 0.0, S_P = 0.0, S_Q = 0.0;
  int terms = 0;
  bool converged = true;
};
MidpointSums midpoint_sums(double a, double b, double T, double stop_abs, double stop_rel, int budget) {
  MidpointSums m;
  const double P = -0.5 * T;
  const double Q = -0.125 * (b - a);
  double e_prev = 1.0;  // e_0
  double e = P;         // e_1
  m.S_P = P * kRecip.r[2];
  m.S_Q = kRecip.r[2];
  int n = 1;
  for (; n < budget; ++n) {
    const double e_next = (P * e + 2.0 * Q * e_prev) * kRecip.r[n];  // e_{n+1}
    if ((n & 1) == 1) {  // n + 1 even
      m.s_minus_1 += e_next * kRecip.r[n + 1];
      m.S_Q += e_next * kRecip.r[n + 3];
    } else {
      m.S_P += e_next * kRecip.r[n + 2];
    }
    e_prev = e;
    e = e_next;
    if (std::fabs(e) + std::fabs(e_prev) <= stop_abs + stop_rel * (1.0 + m.s_minus_1)) break;
  }
  m.terms = n + 1;
  m.converged = n < budget;
  return m;
}

// Moments from the sums: e0 = e^{-tau_m} S, M1 = e^{-tau_m} (S + S_P)/2,
// M2 = e^{-tau_m} (S + 2 S_P + S_Q)/4 (u = (1 + x)/2).
Moments midpoint_moments(double decay_mid, const MidpointSums& m) {
  Moments mo;
  mo.method = MomentMethod::midpoint_series;
  mo.terms = m.terms;
  mo.converged = m.converged;
  const double S = 1.0 + m.s_minus_1;
  mo.e0 = decay_mid * S;
  mo.m1 = 0.5 * decay_mid * (S + m.S_P);
  mo.m2 = 0.25 * decay_mid * (S + 2.0 * m.S_P + m.S_Q);
  return mo;
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

// Dawson branch, T <= kMomentAsymptoticDepth: the series in |B| about the exit end,
//   M_n = sum_k |B|^k/k! m_{n+2k}(A),  m_j(A) = int_0^1 u^j e^{-A u} du,
// all of whose terms are positive (no cancellation). Here A <= 2T <= 100 and |B| <= A/2 <= 50;
// after K = 4|B| + 40 terms the next is below (e/4)^K < 2^-70 of the sum. m_j: upward
// m_j = (j m_{j-1} - e^{-A})/A for j <= A (errors shrink by j/A), downward
// m_{j-1} = (A m_j + e^{-A})/j above (all terms positive), started 60 steps above the largest
// index needed from m ~ e^{-A}/(j + 1 - A), whose error shrinks by A/j < 1/2 per step.
Moments dawson_exit_series(double A, double B) {
  Moments mo;
  mo.method = MomentMethod::exit_series;
  const double g2 = -B;
  const int K = static_cast<int>(std::ceil(4.0 * g2 + 40.0));
  const int J = 2 * K + 2;
  const double eA = std::exp(-A);
  const int up_to = std::min(J, static_cast<int>(std::floor(A)));
  // m[0..J], every entry written below. The recurrences multiply by 1/A and 1/j (formed off
  // their dependency chain) instead of dividing: a rounding more per step, in recurrences that
  // shrink every error (the divisions' latency was most of this function's time).
  thread_local std::vector<double> m;
  const int top = std::max(J, static_cast<int>(std::ceil(2.0 * A))) + 60;
  if (m.size() < static_cast<std::size_t>(J) + 1) m.resize(static_cast<std::size_t>(J) + 1);
  m[0] = -std::expm1(-A) / A;
  const double inv_A = 1.0 / A;
  for (int j = 1; j <= up_to; ++j)
    m[static_cast<std::size_t>(j)] = (j * m[static_cast<std::size_t>(j) - 1] - eA) * inv_A;
  if (up_to < J) {
    double mj = eA / (top + 1 - A);
    for (int j = top; j > up_to + 1; --j) {
      mj = (A * mj + eA) * (1.0 / j);  // m_{j-1}
      if (j - 1 <= J) m[static_cast<std::size_t>(j) - 1] = mj;
    }
  }
  double t = 1.0, m1 = 0.0, m2 = 0.0;
  int k = 0;
  for (; k <= K; ++k) {
    if (k > 0) t *= g2 / k;
    const double d1 = t * m[static_cast<std::size_t>(2 * k + 1)], d2 = t * m[static_cast<std::size_t>(2 * k + 2)];
    m1 += d1;
    m2 += d2;
    if (k > g2 && d1 <= 0x1p-60 * m1 && d2 <= 0x1p-60 * m2) break;
  }
  mo.terms = k + 1;
  mo.converged = k <= K;
  mo.m1 = m1;
  mo.m2 = m2;
  return mo;
}

Moments dawson_moments(double A, double B, double T) {
  if (T <= kMomentAsymptoticDepth) return dawson_exit_series(A, B);
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

// The entries that depend on kappa: d emission / d (length, rho_far, rho_exit), from the moments
// and transmittance already in g.
struct KappaTerms {
  double de_length, de_rho_far, de_rho_exit;
};
KappaTerms kappa_terms(double m1, double m2, double t, const ChannelPiece& p, double dkappa) {
  const double de0_da = -m1 + 0.5 * m2;
  const double de0_db = -0.5 * m2;
  const double de_da = dkappa * de0_da + 0.5 * p.kappa_far * t;
  const double de_db = dkappa * de0_db + 0.5 * p.kappa_far * t;
  return {p.rho_exit * de_da + p.rho_far * de_db, p.length * de_db, p.length * de_da};
}
void set_kappa_terms(PieceOpticsGrad& g, const ChannelPiece& p, double dkappa) {
  const KappaTerms k = kappa_terms(g.m1, g.m2, g.optics.transmittance, p, dkappa);
  g.de_rho_exit = k.de_rho_exit;
  g.de_rho_far = k.de_rho_far;
  g.de_length = k.de_length;
}

// exact_piece's branch from a = rho_exit L and b = rho_far L (its tests, in its arithmetic; the
// batch's classification forms the same).
ExactBranch branch_of(double a, double b) {
  const double T = 0.5 * (a + b);
  if (!(T > 0.0)) return ExactBranch::transparent;
  if (T <= kThinDepth) return ExactBranch::thin_series;
  const double B = 0.5 * (b - a);
  if (std::fabs(B) <= kQ2Relative * a * a) return ExactBranch::q2_series;
  return B > 0.0 ? ExactBranch::erfcx : ExactBranch::dawson;
}

// The moments of a piece on the q2_series, erfcx or dawson branch, from its optics (exact_piece's
// or exact_batch's): the one place both the scalar and the batch gradient form them.
Moments closed_form_moments(const PieceOptics& o, double A, double B, double T) {
  const double t = o.transmittance;
  switch (o.branch) {
    case ExactBranch::q2_series:
      return q2_moments(A, B);
    case ExactBranch::erfcx:
      return erfcx_moments(A, B, T, t, o.weight_far + t, o.weight_far);
    case ExactBranch::dawson: {
      Moments mo = dawson_moments(A, B, T);
      mo.e0 = o.weight_far + t;
      return mo;
    }
    case ExactBranch::transparent:
    case ExactBranch::thin_series:
      break;
  }
  return Moments{};
}

// Every entry of g from its optics and moments.
void set_derivatives(PieceOpticsGrad& g, const Moments& mo, const ChannelPiece& p, double dkappa) {
  const PieceOptics& o = g.optics;
  const double t = o.transmittance;
  g.e0 = mo.e0;
  g.m1 = mo.m1;
  g.m2 = mo.m2;
  g.method = mo.method;
  g.terms = mo.terms;
  g.converged = mo.converged;
  g.de_kappa_exit = o.weight_exit;
  g.de_kappa_far = o.weight_far;
  g.dt_rho_exit = g.dt_rho_far = -0.5 * t * p.length;
  g.dt_length = -0.5 * t * (p.rho_exit + p.rho_far);
  set_kappa_terms(g, p, dkappa);
}

}  // namespace

const char* moment_method_name(MomentMethod m) {
  switch (m) {
    case MomentMethod::transparent: return "transparent";
    case MomentMethod::midpoint_series: return "midpoint_series";
    case MomentMethod::q2_series: return "q2_series";
    case MomentMethod::identity: return "identity";
    case MomentMethod::continued_fraction: return "continued_fraction";
    case MomentMethod::exit_series: return "exit_series";
    case MomentMethod::asymptotic: return "asymptotic";
  }
  return "?";
}

PieceOpticsGrad exact_piece_grad(const ChannelPiece& p) {
  return exact_piece_grad(p, p.kappa_far - p.kappa_exit);
}

PieceOpticsGrad exact_piece_grad(const ChannelPiece& p, double dkappa) {
  PieceOpticsGrad g;
  const double a = p.rho_exit * p.length;
  const double b = p.rho_far * p.length;
  const double T = 0.5 * (a + b);
  const double A = a, B = 0.5 * (b - a);
  Moments mo;
  if (T > 0.0 && T <= kThinDepth) {
    // exact_piece's thin branch (thin_weights), the same arithmetic in one loop with the
    // derivative sums: its weights bit for bit (tests/test_grad.cpp).
    PieceOptics& o = g.optics;
    o.branch = ExactBranch::thin_series;
    o.transmittance = std::exp(-T);
    const MidpointSums sums = midpoint_sums(a, b, T, 0x1p-56 * 0.25 * T, 0.0, 100);
    o.terms = sums.terms;
    o.converged = sums.converged;
    const double tau_m = 0.125 * (3.0 * a + b);
    const double em1_mid = std::expm1(-tau_m);
    const double em1_rest = std::expm1(-0.125 * (a + 3.0 * b));
    const double decay_mid = 1.0 + em1_mid;
    o.weight_exit = -em1_mid - decay_mid * sums.s_minus_1;
    o.weight_far = decay_mid * (sums.s_minus_1 - em1_rest);
    o.emission = p.kappa_exit * o.weight_exit + p.kappa_far * o.weight_far;
    mo = midpoint_moments(decay_mid, sums);
  } else {
    g.optics = exact_piece(p);
  }
  if (g.optics.branch != ExactBranch::transparent && g.optics.branch != ExactBranch::thin_series)
    mo = closed_form_moments(g.optics, A, B, T);
  set_derivatives(g, mo, p, dkappa);
  return g;
}

namespace {

// What exact_pieces_grad forms before the derivatives: per batch entry j (piece j s, s the
// stride) its transmittance, emission weights and moments M1, M2; per piece its emission.
struct MomentColumns {
  double* transmittance = nullptr;
  double* weight_exit = nullptr;
  double* weight_far = nullptr;
  double* m1 = nullptr;
  double* m2 = nullptr;
  double* emission = nullptr;  // in.size entries
};

// Storage for pieces_moments' columns, reused (a thread's): `entries` batch entries and
// `piece_channels` emissions; columns() points at them.
struct MomentStore {
  std::vector<double> transmittance, weight_exit, weight_far, m1, m2, emission;
  void reserve(std::size_t entries, std::size_t piece_channels) {
    if (transmittance.size() < entries)
      for (auto* v : {&transmittance, &weight_exit, &weight_far, &m1, &m2}) v->resize(entries);
    if (emission.size() < piece_channels) emission.resize(piece_channels);
  }
  MomentColumns columns() {
    return MomentColumns{transmittance.data(), weight_exit.data(), weight_far.data(), m1.data(), m2.data(),
                         emission.data()};
  }
};

void pieces_moments(const PieceColumns& in, const MomentColumns& out, std::size_t stride) {
  struct Columns {
    std::vector<double> length, rho_far, rho_exit, kappa_far, kappa_exit, emission, e0, depth;
  };
  thread_local Columns col;
  const std::size_t n = in.size;
  // With a stride s > 1 only every s-th piece (the first channel of a grey medium's piece) goes
  // through the batch; the others reuse its depth below.
  const std::size_t m = (n + stride - 1) / stride;
  if (col.e0.size() < m)
    for (auto* v : {&col.emission, &col.e0, &col.depth}) v->resize(m);
  PieceColumns batch_in = in;
  if (stride > 1) {  // every s-th piece, gathered
    if (col.length.size() < m)
      for (auto* v : {&col.length, &col.rho_far, &col.rho_exit, &col.kappa_far, &col.kappa_exit}) v->resize(m);
    for (std::size_t j = 0; j < m; ++j) {
      col.length[j] = in.length[j * stride];
      col.rho_far[j] = in.rho_far[j * stride];
      col.rho_exit[j] = in.rho_exit[j * stride];
      col.kappa_far[j] = in.kappa_far[j * stride];
      col.kappa_exit[j] = in.kappa_exit[j * stride];
    }
    batch_in = PieceColumns{col.length.data(), col.rho_far.data(), col.rho_exit.data(), col.kappa_far.data(),
                            col.kappa_exit.data(), m};
  }
  OpticsColumns oc{out.transmittance, stride > 1 ? col.emission.data() : out.emission};
  oc.weight_exit = out.weight_exit;
  oc.weight_far = out.weight_far;
  oc.m1 = out.m1;
  oc.m2 = out.m2;
  oc.e0 = col.e0.data();
  exact_batch(batch_in, oc);
  // The depth of every batch entry, then its transmittance exp(-T) through exp_neg_array
  // (special/erfcx_simd.hpp: at most ~0.52 ulp, std::exp's class, in vectors). exact_batch's
  // own Exp (1 ulp) doubled the worst error of a saturated ray's length entry (out_of_range:
  // 1.1e-13 of the channel's largest entry against 5.7e-14, tests/test_grad.cpp), which amplifies
  // the transmittance's rounding; std::exp per piece was ~6% of a long ray's gradient.
  for (std::size_t j = 0; j < m; ++j) {
    const double a = batch_in.rho_exit[j] * batch_in.length[j], b = batch_in.rho_far[j] * batch_in.length[j];
    col.depth[j] = 0.5 * (a + b);
  }
  special::exp_neg_array(col.depth.data(), out.transmittance, m);
  for (std::size_t j = 0; j < m; ++j) {
    const double T = col.depth[j];
    if (!(T > 0.0)) out.transmittance[j] = 1.0;  // transparent
    // The batch formed the moments of thin_series and transparent lanes; the others are NaN.
    if (std::isnan(out.m1[j])) {
      const double a = batch_in.rho_exit[j] * batch_in.length[j], b = batch_in.rho_far[j] * batch_in.length[j];
      PieceOptics o;
      o.transmittance = out.transmittance[j];
      o.weight_exit = out.weight_exit[j];
      o.weight_far = out.weight_far[j];
      o.branch = branch_of(a, b);
      const Moments mo = closed_form_moments(o, a, 0.5 * (b - a), T);
      out.m1[j] = mo.m1;
      out.m2[j] = mo.m2;
    }
  }
  if (stride == 1) return;
  // Piece i = j s + r: r = 0 is the batch entry j itself, r > 0 the same depth (a grey medium's
  // other channels: exact_piece_grad's same_depth overload; a transparent piece keeps its 0).
  for (std::size_t j = 0; j < m; ++j) {
    const double w_exit = out.weight_exit[j], w_far = out.weight_far[j];
    const bool transparent = !(col.depth[j] > 0.0);
    const std::size_t i0 = j * stride, i1 = std::min(n, i0 + stride);
    out.emission[i0] = col.emission[j];
    for (std::size_t i = i0 + 1; i < i1; ++i)
      out.emission[i] = transparent ? 0.0 : in.kappa_exit[i] * w_exit + in.kappa_far[i] * w_far;
  }
}

// A piece-channel's derivatives (exact_piece_grad's entries) from its batch entry's
// transmittance, weights and moments (shared by a grey medium's channels), its inputs and
// kappa_far - kappa_exit. The emission is left 0 (pieces_moments writes it).
inline PieceDerivatives piece_derivatives(double t, double w_exit, double w_far, double m1, double m2,
                                          const ChannelPiece& p, double dkappa) {
  PieceDerivatives g;
  g.transmittance = t;
  g.de_kappa_exit = w_exit;
  g.de_kappa_far = w_far;
  g.dt_rho = -0.5 * t * p.length;
  g.dt_length = -0.5 * t * (p.rho_exit + p.rho_far);
  const KappaTerms k = kappa_terms(m1, m2, t, p, dkappa);
  g.de_length = k.de_length;
  g.de_rho_far = k.de_rho_far;
  g.de_rho_exit = k.de_rho_exit;
  return g;
}

// chain_ray_gradient's PieceSource for the exact pieces: pieces_moments' columns kept for the
// whole ray (per piece for a grey medium, per piece-channel otherwise), the derivatives formed
// from them where the reverse pass uses them (piece_derivatives): no PieceDerivatives record is
// written per piece-channel and read back.
class ExactPieceSource {
 public:
  void start(std::size_t piece_channels, bool grey) {
    thread_local MomentStore store;
    grey_ = grey;
    store.reserve(grey ? piece_channels / kChannels : piece_channels, piece_channels);
    at_ = store.columns();  // the reverse pass reads through these pointers (no reload per piece)
  }
  void evaluate(const PieceColumns& in, std::size_t first) {
    const std::size_t j0 = grey_ ? first / kChannels : first;
    pieces_moments(in,
                   MomentColumns{at_.transmittance + j0, at_.weight_exit + j0, at_.weight_far + j0, at_.m1 + j0,
                                 at_.m2 + j0, at_.emission + first},
                   grey_ ? kChannels : 1);
  }
  double transmittance(std::size_t k, int c) const { return at_.transmittance[entry(k, c)]; }
  double emission(std::size_t k, int c) const { return at_.emission[kChannels * k + static_cast<std::size_t>(c)]; }
  PieceDerivatives derivatives(std::size_t k, int c, const ChannelPiece& p, double dkappa) const {
    const std::size_t j = entry(k, c);
    return piece_derivatives(at_.transmittance[j], at_.weight_exit[j], at_.weight_far[j], at_.m1[j], at_.m2[j], p,
                             dkappa);
  }

 private:
  std::size_t entry(std::size_t k, int c) const { return grey_ ? k : kChannels * k + static_cast<std::size_t>(c); }
  bool grey_ = false;
  MomentColumns at_;  // the thread's MomentStore, from entry 0
};

}  // namespace

void exact_pieces_grad(const PieceColumns& in, const double* kappa_far_minus_exit, PieceDerivatives* out,
                       int same_depth_stride) {
  thread_local MomentStore col;
  const std::size_t n = in.size;
  const std::size_t stride = same_depth_stride > 1 ? static_cast<std::size_t>(same_depth_stride) : 1;
  col.reserve((n + stride - 1) / stride, n);
  pieces_moments(in, col.columns(), stride);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = i / stride;
    const ChannelPiece p{in.length[i], in.rho_far[i], in.rho_exit[i], in.kappa_far[i], in.kappa_exit[i]};
    out[i] = piece_derivatives(col.transmittance[j], col.weight_exit[j], col.weight_far[j], col.m1[j], col.m2[j], p,
                               kappa_far_minus_exit[i]);
    out[i].emission = col.emission[i];
  }
}

void exact_pieces_grad(const ChannelPiece* pieces, const double* kappa_far_minus_exit, std::size_t n,
                       PieceDerivatives* out, int same_depth_stride) {
  thread_local PieceColumnStore columns;
  exact_pieces_grad(columns.assign(pieces, n), kappa_far_minus_exit, out, same_depth_stride);
}

PieceOpticsGrad exact_piece_grad(const ChannelPiece& p, double dkappa, const PieceOpticsGrad& same_depth) {
  PieceOpticsGrad g = same_depth;
  // exact_piece's emission, in its arithmetic (a transparent piece keeps its 0).
  if (g.optics.branch != ExactBranch::transparent)
    g.optics.emission = p.kappa_exit * g.optics.weight_exit + p.kappa_far * g.optics.weight_far;
  set_kappa_terms(g, p, dkappa);
  return g;
}

namespace {

// The exact pieces' derivatives as chain_ray_gradient asks for them.
void exact_ray_chain(const detail::GradientPreparation& prep, const Ray& ray, RayGradient& grad,
                     GradientBlocks blocks) {
  ExactPieceSource source;
  detail::chain_ray_gradient(prep, ray, grad, source, detail::PieceEnds::fixed_along_segment, blocks);
}

}  // namespace

ExactRayGradient::ExactRayGradient(const TransferFunctions& tf)
    : prep_(std::make_shared<const detail::GradientPreparation>(tf)) {}

RayGradient ExactRayGradient::operator()(const Ray& ray) const {
  RayGradient grad;
  (*this)(ray, grad);
  return grad;
}

void ExactRayGradient::operator()(const Ray& ray, RayGradient& grad, GradientBlocks blocks) const {
  exact_ray_chain(*prep_, ray, grad, blocks);
}

RayGradient exact_ray_gradient(const TransferFunctions& tf, const Ray& ray) {
  RayGradient grad;
  exact_ray_gradient(tf, ray, grad);
  return grad;
}

void exact_ray_gradient(const TransferFunctions& tf, const Ray& ray, RayGradient& grad, GradientBlocks blocks) {
  exact_ray_chain(detail::thread_preparation(tf), ray, grad, blocks);
}

}  // namespace rayint
