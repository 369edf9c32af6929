// exact.cpp -- the exact ray integral of Williams & Max (1992), Eq. 4 on one piece on which the
// density rho and chromaticity kappa are both linear (Sec. 3.3), in stable forms.
//
// Notation. s is the distance from the piece's exit (eye side), u = s/L in [0, 1].
//   a = rho_exit * L,  b = rho_far * L  (both >= 0),  A = a,  B = (b - a)/2,
//   tau(u) = A u + B u^2   (optical depth from the point to the exit),  T = tau(1) = (a + b)/2.
// Since rho = d tau/ds, integrating kappa * rho * exp(-tau) by parts with kappa linear gives
//   emission = kappa_exit * w_exit + kappa_far * w_far,
//   w_exit = 1 - e0 >= 0,  w_far = e0 - exp(-T) >= 0,  e0 = int_0^1 exp(-tau(u)) du,
// and w_exit + w_far = 1 - exp(-T). The paper's q2 (d rho/dt, t toward the eye) is
// q2 = -2B/L^2: q2 < 0 means B > 0.
//
// Methods by region:
//   - T == 0: transparent, weights 0.
//   - T <= kThinDepth = 1 (thin): Taylor series of exp(-tau) about the midpoint u = 1/2, where
//     tau'(1/2) = T, so terms decay like (T/2)^n/n! (see thin_weights); the weights are formed
//     from expm1 and the small series remainder, with no difference of nearly equal quantities.
//   - T > 1 and |B| <= kQ2Relative * A^2 (q2 -> 0, includes q2 == 0): series in B,
//     e0 = sum_k (-B)^k/k! m_{2k}(A), m_n(A) = int_0^1 u^n e^{-A u} du, three terms; the next
//     is below 120 (B/A^2)^3 < 1e-21 relative. kQ2Relative = 2^-26 keeps it that small.
//   - T > 1, B > 0: e0 = sqrt(pi)/(2 beta) [erfcx(z0) - exp(-T) erfcx(z1)], beta = sqrt(B),
//     z0 = A/(2 beta), z1 = z0 + beta; all erfcx arguments >= 0, no overflow for T up to 1e308.
//   - T > 1, B < 0: e0 = (1/gamma) [D(|y0|) - exp(-T) D(|y1|)], gamma = sqrt(-B),
//     |y0| = A/(2 gamma), |y1| = b/(2 gamma), D = Dawson's integral.
//   For T > 1 the two weights are formed from e0 with a cancellation factor below 4
//   (1 - e0 >= 1 - int exp(-u^2) > 0.25, e0 - e^{-T} > 0.17 at T = 1), and the bracket above
//   loses at most 1/(1 - e^{-1}) = 1.6.
// Accuracy (against the 50-digit reference): max relative error 8.05e-14, median 0.41 ulp over
// 1,008,738 pieces of all stress regimes (`rayint stress --count 1000000 --seed 1`,
// reports/stress-exact.json); tests/test_exact.cpp asserts <= 1e-13 in every regime and a
// median <= 2 ulp, and the CTest gate re-checks 100,000 pieces on every CI run.
#include "rayint/integrators/exact.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "rayint/integrators/exact_batch.hpp"
#include "rayint/special/special_functions.hpp"

namespace rayint {
namespace {

constexpr int kSeriesBudget = 100;
constexpr double kSqrtPi = 1.7724538509055160273;

// 1/(n+1) for the series, so the loop has no division.
struct Reciprocals {
  double r[kSeriesBudget + 2];
  constexpr Reciprocals() : r() {
    for (int n = 0; n < kSeriesBudget + 2; ++n) r[n] = 1.0 / (n + 1);
  }
};
constexpr Reciprocals kRecip;

// Thin pieces, expanded about the midpoint u = 1/2 with x = 2u - 1 in [-1, 1]:
//   tau(u) = tau_m + (T/2) x + (B/4) x^2,  tau_m = tau(1/2) = (3a + b)/8,
// because tau'(1/2) = A + B = T. With exp(-(T/2) x - (B/4) x^2) = sum e_n x^n,
//   (n+1) e_{n+1} = P e_n + 2 Q e_{n-1},  P = -T/2, Q = -B/4,
// and e0 = e^{-tau_m} S, S = sum_{n even} e_n/(n+1). The weights follow without cancellation:
//   w_exit = -expm1(-tau_m) - e^{-tau_m} (S - 1),
//   w_far  =  e^{-tau_m} (-expm1(-(T - tau_m)) + (S - 1)),  T - tau_m = (a + 3b)/8 >= 0,
// where |S - 1| <= T^2/12 + ... is small beside both first terms (each >= T/4 - O(T^2)).
// Terms decay like (T/2)^n/n!: 20 terms at T = 1, 6 at T = 1e-3. The loop stops when two
// successive coefficients are below 2^-56 * T/4 (the absolute accuracy the weights need).
void thin_weights(double a, double b, double T, PieceOptics& out) {
  const double P = -0.5 * T;
  const double Q = -0.125 * (b - a);  // -B/4 with B = (b - a)/2
  double e_prev = 1.0;                // e_0
  double e = P;                       // e_1
  double s_minus_1 = 0.0;
  const double stop = 0x1p-56 * 0.25 * T;
  int n = 1;
  for (; n < kSeriesBudget; ++n) {
    const double e_next = (P * e + 2.0 * Q * e_prev) * kRecip.r[n];  // e_{n+1}
    if ((n & 1) == 1) s_minus_1 += e_next * kRecip.r[n + 1];        // n+1 even
    e_prev = e;
    e = e_next;
    if (std::fabs(e) + std::fabs(e_prev) <= stop) break;
  }
  out.terms = n + 1;
  out.converged = n < kSeriesBudget;
  const double tau_m = 0.125 * (3.0 * a + b);
  const double em1_mid = std::expm1(-tau_m);          // e^{-tau_m} - 1
  const double em1_rest = std::expm1(-0.125 * (a + 3.0 * b));
  const double decay_mid = 1.0 + em1_mid;
  out.weight_exit = -em1_mid - decay_mid * s_minus_1;
  out.weight_far = decay_mid * (s_minus_1 - em1_rest);
}

// e0 for |B| <= kQ2Relative A^2, A >= 1 (T > 1 implies it here): series in B,
//   e0 = m_0 - B m_2 + B^2/2 m_4,  m_n(A) = int_0^1 u^n e^{-A u} du
//      = n!/A^{n+1} (1 - e^{-A} sum_{j<=n} A^j/j!).
// m_2, m_4 lose up to 2.5 digits to cancellation at A = 1, but enter multiplied by
// |B| <= 1.5e-8 A^2, so their error is below 1e-22 relative to e0.
double q2_series_e0(double A, double B, double em1_A) {
  const double m0 = -em1_A / A;
  if (B == 0.0) return m0;
  const double eA = 1.0 + em1_A;
  const double A2 = A * A;
  const double p2 = 1.0 + A + 0.5 * A2;
  const double p4 = p2 + A2 * A / 6.0 + A2 * A2 / 24.0;
  if (!std::isfinite(A2 * A2 * A)) {
    // A > ~1e61 (T up to 1e308): A^5 overflows and e^{-A} = 0, so m_n = n!/A^{n+1}; with
    // r = B/A^2 (|r| <= kQ2Relative) the series is (1 - 2r + 12 r^2)/A, with no inf * 0.
    // (The general form below gave NaN here; found by tests/test_exact_batch.cpp.)
    const double r = B / A / A;
    return (1.0 - 2.0 * r + 12.0 * r * r) / A;
  }
  const double m2 = 2.0 / (A2 * A) * (1.0 - eA * p2);
  const double m4 = 24.0 / (A2 * A2 * A) * (1.0 - eA * p4);
  return m0 - B * m2 + 0.5 * B * B * m4;
}

// The grey batch's compositing, far -> near: ray i's pieces are [ends[i-1], ends[i]) (from 0 for
// the first), each composited as intensity = intensity t + emission per channel and
// transmittance *= t, from RayResult::of_background. `optics` holds the columns transmittance,
// emission r, g, b, one after the other, `stride` apart. Each ray's pieces are a chain of
// dependent multiplies and adds (a multiply and an add of latency per piece, one ray at a
// time), so kInterleave rays advance in turn, one piece each, as far as the shortest of them
// reaches (a tile's neighbouring rays have similar piece counts); the rest of each ray, and the
// rays past the last whole group, alone. Every ray gets the same operations in the same order
// as alone, so the results are the same bit for bit. The transmittance is one product kept
// once: every channel's starts at 1 and is multiplied by the same t. (Issue 33, round 20: the
// compositing's perf samples in a 1-thread 105k-tet 512^2 render ~100 -> ~50-75.)
void composite_grey(const Ray* rays, std::size_t n_rays, const std::size_t* ends, const double* optics,
                    std::size_t stride, RayResult* results) {
  static_assert(kChannels == 3, "a transmittance and three emission columns");
  constexpr std::size_t kInterleave = 4;
  const std::size_t s1 = stride, s2 = 2 * stride, s3 = 3 * stride;
  // one piece (its transmittance at `at`, its emissions a stride apart) onto one ray's sums
  const auto composite = [&](const double* at, double& i_r, double& i_g, double& i_b, double& tr) {
    const double t = at[0];
    i_r = i_r * t + at[s1];
    i_g = i_g * t + at[s2];
    i_b = i_b * t + at[s3];
    tr *= t;
  };
  // one ray's pieces from q (its transmittance) for `count` pieces
  const auto alone = [&](const double* q, std::size_t count, double i_r, double i_g, double i_b, double tr,
                         RayResult& result) {
    for (const double* end = q + count; q != end; ++q) composite(q, i_r, i_g, i_b, tr);
    result.intensity = {i_r, i_g, i_b};
    result.transmittance = {tr, tr, tr};
  };
  std::size_t i = 0, begin = 0;
  for (; i + kInterleave <= n_rays; i += kInterleave) {
    const double* q[kInterleave];
    std::size_t count[kInterleave];
    double i_r[kInterleave], i_g[kInterleave], i_b[kInterleave], tr[kInterleave];
    std::size_t shortest = static_cast<std::size_t>(-1);
    for (std::size_t j = 0; j < kInterleave; ++j) {
      const std::size_t first = j == 0 ? begin : ends[i + j - 1];
      q[j] = optics + first;
      count[j] = ends[i + j] - first;
      shortest = std::min(shortest, count[j]);
      const RayResult r = RayResult::of_background(rays[i + j].background);
      i_r[j] = r.intensity[0];
      i_g[j] = r.intensity[1];
      i_b[j] = r.intensity[2];
      tr[j] = r.transmittance[0];
    }
    for (std::size_t step = 0; step < shortest; ++step)
      for (std::size_t j = 0; j < kInterleave; ++j) composite(q[j] + step, i_r[j], i_g[j], i_b[j], tr[j]);
    for (std::size_t j = 0; j < kInterleave; ++j)
      alone(q[j] + shortest, count[j] - shortest, i_r[j], i_g[j], i_b[j], tr[j], results[i + j]);
    begin = ends[i + kInterleave - 1];
  }
  for (; i < n_rays; ++i) {
    const RayResult r = RayResult::of_background(rays[i].background);
    alone(optics + begin, ends[i] - begin, r.intensity[0], r.intensity[1], r.intensity[2], r.transmittance[0],
          results[i]);
    begin = ends[i];
  }
}

}  // namespace

const char* branch_name(ExactBranch b) {
  switch (b) {
    case ExactBranch::transparent: return "transparent";
    case ExactBranch::thin_series: return "thin_series";
    case ExactBranch::q2_series: return "q2_series";
    case ExactBranch::erfcx: return "erfcx";
    case ExactBranch::dawson: return "dawson";
  }
  return "?";
}

PieceOptics exact_piece(const ChannelPiece& p) {
  PieceOptics out;
  const double a = p.rho_exit * p.length;
  const double b = p.rho_far * p.length;
  const double T = 0.5 * (a + b);
  if (!(T > 0.0)) {
    out.branch = ExactBranch::transparent;
    return out;
  }
  const double A = a;
  const double B = 0.5 * (b - a);
  out.transmittance = std::exp(-T);
  if (T <= kThinDepth) {
    out.branch = ExactBranch::thin_series;
    thin_weights(a, b, T, out);
  } else {
    double e0;
    if (std::fabs(B) <= kQ2Relative * A * A) {
      out.branch = ExactBranch::q2_series;
      e0 = q2_series_e0(A, B, std::expm1(-A));
    } else if (B > 0.0) {
      out.branch = ExactBranch::erfcx;
      const double beta = std::sqrt(B);
      const double z0 = A / (2.0 * beta);
      const double z1 = z0 + beta;
      e0 = kSqrtPi / (2.0 * beta) *
           (special::erfcx(z0) - out.transmittance * special::erfcx(z1));
    } else {
      out.branch = ExactBranch::dawson;
      const double gamma = std::sqrt(-B);
      const double y0 = A / (2.0 * gamma);
      const double y1 = b / (2.0 * gamma);
      e0 = (special::dawson(y0) - out.transmittance * special::dawson(y1)) / gamma;
    }
    out.weight_exit = 1.0 - e0;
    out.weight_far = e0 - out.transmittance;
  }
  out.emission = p.kappa_exit * out.weight_exit + p.kappa_far * out.weight_far;
  return out;
}

RayResult ExactIntegrator::integrate_segments(const Ray& ray, Diagnostics* diag) const {
  if (path_ == Path::scalar) return integrate_scalar(ray, diag);
  if (splitter_.grey() && !diag) {
    RayResult r;
    integrate_grey(&ray, 1, &r);
    return r;
  }
  // Every piece of the ray (far -> near), then one batch over all its piece-channels, results
  // piece-major (index 3 k + c).
  struct Columns {
    PieceChannelColumns pieces;  // written by the splitter in the batch's layout
    std::vector<double> transmittance, emission;
    std::vector<ExactBranch> branch;
    std::vector<std::int32_t> terms;
    std::vector<unsigned char> converged;
  };
  thread_local Columns col;
  col.pieces.clear();
  splitter_.append(ray.segments, col.pieces);
  const std::size_t n = col.pieces.size();
  if (col.transmittance.size() < n) {
    col.transmittance.resize(n);
    col.emission.resize(n);
  }
  OpticsColumns out{col.transmittance.data(), col.emission.data()};
  if (diag) {
    col.branch.resize(n);
    col.terms.resize(n);
    col.converged.resize(n);
    out.branch = col.branch.data();
    out.terms = col.terms.data();
    out.converged = col.converged.data();
  }
  const PieceChannelColumns& p = col.pieces;
  exact_batch(PieceColumns{p.length.data(), p.rho_far.data(), p.rho_exit.data(), p.kappa_far.data(),
                           p.kappa_exit.data(), n},
              out);
  RayResult r = RayResult::of_background(ray.background);
  for (std::size_t k = 0; k < n; k += kChannels) {
    for (int c = 0; c < kChannels; ++c) {
      const double t = col.transmittance[k + static_cast<std::size_t>(c)];
      r.intensity[c] = r.intensity[c] * t + col.emission[k + static_cast<std::size_t>(c)];
      r.transmittance[c] *= t;
    }
  }
  if (diag) {
    int max_terms = 0;
    for (std::size_t i = 0; i < n; ++i) {
      diag->count(branch_name(col.branch[i]));
      if (!col.converged[i]) diag->count("series_not_converged");
      if (col.terms[i] > max_terms) max_terms = col.terms[i];
    }
    diag->max_stat("max_series_terms", max_terms);
  }
  return r;
}

bool ExactIntegrator::integrate_many_segments(const Ray* rays, std::size_t n, RayResult* out, long* pieces) const {
  if (path_ == Path::batch && splitter_.grey()) {
    const long count = integrate_grey(rays, n, out);
    if (pieces) *pieces += count;
    return true;
  }
  return RayIntegrator::integrate_many_segments(rays, n, out, pieces);  // one at a time
}

long ExactIntegrator::integrate_grey(const Ray* rays, std::size_t n_rays, RayResult* results) const {
  struct Columns {
    GreyPieceColumns pieces;
    std::vector<std::size_t> ends;  // ray i's pieces end at ends[i]
    // the transmittance and the kChannels emission columns, each `stride` long, in one block
    std::vector<double> optics;
    std::size_t stride = 0;
  };
  thread_local Columns col;
  col.pieces.clear();
  col.ends.resize(n_rays);
  long count = 0;
  for (std::size_t i = 0; i < n_rays; ++i) {
    count += splitter_.append(rays[i].segments, col.pieces);
    col.ends[i] = col.pieces.size();
  }
  const GreyPieceColumns& p = col.pieces;
  const std::size_t n = p.size();
  if (col.stride < n) {
    col.stride = n;
    col.optics.resize((1 + kChannels) * n);
  }
  GreyPieceView in{p.length.data(), p.rho_far.data(), p.rho_exit.data(), {}, {}, n};
  GreyOpticsColumns out{col.optics.data(), {}};
  for (std::size_t c = 0; c < kChannels; ++c) {
    in.kappa_far[c] = p.kappa_far[c].data();
    in.kappa_exit[c] = p.kappa_exit[c].data();
    out.emission[c] = col.optics.data() + (1 + c) * col.stride;
  }
  exact_batch(in, out);
  composite_grey(rays, n_rays, col.ends.data(), col.optics.data(), col.stride, results);
  return count;
}

RayResult ExactIntegrator::integrate_scalar(const Ray& ray, Diagnostics* diag) const {
  RayResult r = RayResult::of_background(ray.background);
  int max_terms = 0;
  for (const auto& seg : ray.segments) {
    const std::vector<Piece>& pieces = splitter_.pieces(seg);
    for (const auto& piece : pieces) {
      for (int c = 0; c < kChannels; ++c) {
        const PieceOptics o = exact_piece(piece.channel(c));
        r.intensity[c] = r.intensity[c] * o.transmittance + o.emission;
        r.transmittance[c] *= o.transmittance;
        if (diag) {
          diag->count(branch_name(o.branch));
          if (!o.converged) diag->count("series_not_converged");
          if (o.terms > max_terms) max_terms = o.terms;
        }
      }
    }
  }
  if (diag) diag->max_stat("max_series_terms", max_terms);
  return r;
}

}  // namespace rayint
