// The 50-digit reference (reference.cpp) against values computed here, in cpp_bin_float_50,
// independently of both the reference and the closed form (integrators/exact.*):
//   Eq. 6 (rho, kappa constant), Eq. 5 (kappa constant, rho linear), rho = 0, thick pieces,
//   kappa linear with rho constant (integral of s exp(-rho s) by hand), kappa and rho both
//   linear via erfc (Gaussian integral by hand), and rays composited by hand from such pieces.
// Every case also checks that the reported error bound is not below the true error. Then the
// internals: the exp series, double-double rounding, interpolation, the error estimate on
// deliberately coarse rules and truncations, and concurrent use.
#include <array>
#include <boost/math/special_functions/erf.hpp>
#include <boost/math/special_functions/expm1.hpp>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include "rayint/reference/reference.hpp"
#include "rayint/reference/reference_detail.hpp"
#include "tolerances.hpp"

using namespace rayint;
using rayint::reference_detail::Real;
using rayint::test::Tolerances;

namespace {

// Tolerances of this file, with where they come from (the shared claim is
// Tolerances::reference_rel = 1e-30).
struct ReferenceTolerances {
  // The 50-digit emission before rounding to hi + lo: measured <= 1e-46 relative on these cases
  // (quadrature, 168-bit rounding); 1e-40 is the internal target with room to spare.
  static constexpr double internal_rel = 1e-40;
  // hi + lo resolves a value to half an ulp of lo: <= 2^-106 relative (1.2e-32), away from
  // underflow.
  static constexpr double double_double_rel = 1.3e-32;
  // exp_series against Boost's exp: both within a few hundred ulps of 5.3e-51.
  static constexpr double exp_series_rel = 1e-46;
  // A coarse forced rule must really be coarse for the honesty test to mean something.
  static constexpr double coarse_rule_min_error = 1e-25;
};

Real value(const ExtendedValue& v) { return Real(v.hi) + Real(v.lo); }

// |x - exact| / |exact|; 0 when both are 0, +inf for a nonzero x against an exact 0.
double rel_error(const Real& x, const Real& exact) {
  if (x == exact) return 0.0;
  if (exact == 0) return std::numeric_limits<double>::infinity();
  return static_cast<double>(abs(x - exact) / abs(exact));
}

// 1 - exp(-x) without cancellation.
Real one_minus_exp(const Real& x) { return -boost::math::expm1(Real(-x)); }

// 1 - exp(-x) (1 + x) = sum_{k>=2} (-1)^k (k - 1) x^k / k!, by its series for small x.
Real one_minus_exp_one_plus(const Real& x) {
  if (x > 0.5) return 1 - exp(-x) * (1 + x);
  Real sum = 0;
  Real term_k = x;  // x^k / k!
  for (int k = 2; k < 200; ++k) {
    term_k *= x / k;
    const Real add = (k % 2 == 0 ? 1 : -1) * (k - 1) * term_k;
    sum += add;
    if (abs(add) < sum * 1e-60) break;
  }
  return sum;
}

// ---- the analytic pieces ----------------------------------------------------------------------
// All with s = distance from the exit; the reference is given the same doubles.

// Eq. 6 and its kappa-linear extension (rho constant):
//   integral_0^L (k0 + k1 s) rho exp(-rho s) ds = k0 (1 - e^-T) + k1 (1 - e^-T (1 + T)) / rho.
Real emission_rho_constant(const Real& L, const Real& rho, const Real& kappa_exit,
                           const Real& kappa_far) {
  const Real T = rho * L;
  if (T == 0) return 0;
  const Real k1 = (kappa_far - kappa_exit) / L;
  return kappa_exit * one_minus_exp(T) + k1 * one_minus_exp_one_plus(T) / rho;
}

// Eq. 5 (kappa constant, rho linear): kappa (1 - e^-T).
Real emission_kappa_constant(const Real& L, const Real& rho_far, const Real& rho_exit,
                             const Real& kappa) {
  return kappa * one_minus_exp(L * (rho_far + rho_exit) / 2);
}

// Both linear with rho rising away from the exit (a = (rho_far - rho_exit) / 2L > 0): by parts,
//   E = kappa(0) - kappa(L) e^-T + kappa' integral_0^L exp(-tau(s)) ds,
// and with x = sqrt(a) (s + rho_exit / 2a) the integral is
//   sqrt(pi) / (2 sqrt a) e^(x0^2) [erfc(x0) - erfc(x1)].
Real emission_both_linear(const Real& L, const Real& rho_far, const Real& rho_exit,
                          const Real& kappa_far, const Real& kappa_exit) {
  const Real a = (rho_far - rho_exit) / (2 * L);
  const Real T = L * (rho_far + rho_exit) / 2;
  const Real x0 = rho_exit / (2 * sqrt(a));
  const Real x1 = sqrt(a) * L + x0;
  const Real pi = boost::math::constants::pi<Real>();
  const Real gauss =
      sqrt(pi) / (2 * sqrt(a)) * exp(x0 * x0) * (boost::math::erfc(x0) - boost::math::erfc(x1));
  return kappa_exit - kappa_far * exp(-T) + (kappa_far - kappa_exit) / L * gauss;
}

struct AnalyticCase {
  std::string description;
  ChannelPiece piece;
  double incoming;
  Real emission;       // exact
  Real transmittance;  // exact
  bool moderate;       // error bound must also be <= reference_rel relative
};

AnalyticCase rho_constant(std::string what, double L, double rho, double k_exit, double k_far,
                          double incoming, bool moderate = true) {
  return {std::move(what),
          {L, rho, rho, k_far, k_exit},
          incoming,
          emission_rho_constant(L, rho, k_exit, k_far),
          exp(-Real(rho) * L),
          moderate};
}

AnalyticCase kappa_constant(std::string what, double L, double rho_far, double rho_exit,
                            double kappa, double incoming, bool moderate = true) {
  return {std::move(what),
          {L, rho_far, rho_exit, kappa, kappa},
          incoming,
          emission_kappa_constant(L, rho_far, rho_exit, kappa),
          exp(-Real(L) * (Real(rho_far) + Real(rho_exit)) / 2),
          moderate};
}

AnalyticCase both_linear(std::string what, double L, double rho_far, double rho_exit, double k_far,
                         double k_exit, double incoming) {
  return {std::move(what),
          {L, rho_far, rho_exit, k_far, k_exit},
          incoming,
          emission_both_linear(L, rho_far, rho_exit, k_far, k_exit),
          exp(-Real(L) * (Real(rho_far) + Real(rho_exit)) / 2),
          true};
}

std::vector<AnalyticCase> analytic_cases() {
  return {
      // (1) Eq. 6: rho and kappa constant.
      rho_constant("Eq. 6, T = 1", 1.0, 1.0, 0.7, 0.7, 0.3),
      rho_constant("Eq. 6, T = 0.75, kappa 2.5", 0.3, 2.5, 2.5, 2.5, 1.0),
      rho_constant("Eq. 6, T = 15", 2.0, 7.5, 0.4, 0.4, 5.0),
      rho_constant("Eq. 6, short thick piece, T = 1", 1e-3, 1e3, 1.3, 1.3, 0.0),
      rho_constant("Eq. 6, T = 3e-9", 0.3, 1e-8, 0.9, 0.9, 2.0),
      rho_constant("Eq. 6, T = 1e-30", 1e-15, 1e-15, 0.6, 0.6, 0.25),
      rho_constant("Eq. 6, long thin piece, T = 0.2", 1e6, 2e-7, 0.5, 0.5, 1.0),
      // (2) Eq. 5: kappa constant, rho linear.
      kappa_constant("Eq. 5, rho 0 -> 3", 1.0, 3.0, 0.0, 0.8, 0.5),
      kappa_constant("Eq. 5, rho 3 -> 0", 1.0, 0.0, 3.0, 0.8, 0.5),
      kappa_constant("Eq. 5, rho 5 (far) -> 0.2 (exit)", 0.7, 5.0, 0.2, 1.1, 0.0),
      kappa_constant("Eq. 5, rho 0.01 -> 9, T ~ 45", 10.0, 9.0, 0.01, 0.3, 2.0),
      kappa_constant("Eq. 5, thin, T = 5e-7", 1.0, 1e-6, 0.0, 0.4, 1.0),
      kappa_constant("Eq. 5, T = 80", 20.0, 0.5, 7.5, 1.0, 1.0),
      // (4) thick pieces.
      kappa_constant("Eq. 5, thick, T = 500, rho 0 -> 1000", 1.0, 1000.0, 0.0, 0.6, 3.0),
      kappa_constant("Eq. 5, thick, T = 500, rho 1000 -> 0", 1.0, 0.0, 1000.0, 0.6, 3.0),
      kappa_constant("Eq. 5, thick, T = 1e6, rho 0 -> 2e6", 1.0, 2e6, 0.0, 0.9, 1.0),
      rho_constant("Eq. 6, thick, T = 1e6", 1.0, 1e6, 0.5, 0.5, 1.0),
      rho_constant("Eq. 6, thick, T = 500", 5.0, 100.0, 0.5, 0.5, 1.0),
      // (5) kappa linear, rho constant.
      rho_constant("kappa 0.2 -> 1.4, rho 1.5, T = 3", 2.0, 1.5, 0.2, 1.4, 0.5),
      rho_constant("kappa 1.4 -> 0, rho 0.8, T = 0.4", 0.5, 0.8, 1.4, 0.0, 0.5),
      rho_constant("kappa 0 -> 2, rho 4, T = 12", 3.0, 4.0, 0.0, 2.0, 0.0),
      rho_constant("kappa 0.3 -> 0.9, thin, T = 2e-6", 1.0, 2e-6, 0.3, 0.9, 1.0),
      rho_constant("kappa 0 (exit) -> 1, thick, T = 1e6", 1.0, 1e6, 0.0, 1.0, 0.0, false),
      rho_constant("kappa 0 (exit) -> 1, T = 1e30 (tau_cut raised)", 1.0, 1e30, 0.0, 1.0, 0.0,
                   false),
      // Both linear (rho rising away from the exit), by erfc.
      both_linear("rho 0.5 -> 3, kappa 2 (exit) -> 0.25 (far), T = 2.3", 1.3, 3.0, 0.5, 0.25, 2.0,
                  0.7),
      both_linear("rho 0 -> 6, kappa 0 (exit) -> 1, T = 3", 1.0, 6.0, 0.0, 1.0, 0.0, 0.0),
  };
}

void check_case(const AnalyticCase& c, const ReferencePiece& r) {
  INFO(c.description << ": subintervals " << r.subintervals << ", error bound " << r.error_bound);
  const Real exact_intensity = Real(c.incoming) * c.transmittance + c.emission;
  const double e_rel = rel_error(value(r.emission), c.emission);
  const double t_rel = rel_error(value(r.transmittance), c.transmittance);
  const double i_rel = rel_error(value(r.intensity), exact_intensity);
  INFO("relative errors: emission " << e_rel << ", transmittance " << t_rel << ", intensity "
                                    << i_rel);
  CHECK(std::isfinite(r.intensity.hi));
  CHECK(e_rel <= Tolerances::reference_rel);
  CHECK(i_rel <= Tolerances::reference_rel);
  // The transmittance of a thick piece underflows in double; it is then 0 + 0.
  if (c.transmittance > Real(1e-290)) {
    CHECK(t_rel <= Tolerances::reference_rel);
  } else {
    CHECK(r.transmittance.hi == 0.0);
  }
  // (7) The bound is honest, and tight enough for moderate cases.
  const Real actual = abs(value(r.intensity) - exact_intensity);
  INFO("actual intensity error " << static_cast<double>(actual));
  CHECK(Real(r.error_bound) >= actual);
  if (c.moderate) {
    CHECK(r.error_bound <= Tolerances::reference_rel * std::fabs(r.intensity.hi));
  }
}

}  // namespace

TEST_CASE("reference: analytic pieces to 30 digits with an honest bound", "[reference]") {
  for (const AnalyticCase& c : analytic_cases())
    check_case(c, reference_piece(c.piece, c.incoming));
}

TEST_CASE("reference: 50-digit emission before rounding is far beyond 30 digits", "[reference]") {
  for (const AnalyticCase& c : analytic_cases()) {
    const reference_detail::PieceQuadrature q = reference_detail::integrate_piece(
        {Real(c.piece.length), Real(c.piece.rho_far), Real(c.piece.rho_exit),
         Real(c.piece.kappa_far), Real(c.piece.kappa_exit)});
    INFO(c.description << ": rule " << q.rule << " x " << q.subintervals << ", refinements "
                       << q.refinements << ", truncated " << q.truncated << " at tau "
                       << static_cast<double>(q.tau_cut) << " (passes " << q.truncation_passes
                       << ")");
    const double rel = rel_error(q.emission, c.emission);
    INFO("relative error " << rel << ", bound " << static_cast<double>(q.emission_error));
    CHECK(q.converged);
    CHECK(rel <= ReferenceTolerances::internal_rel);
    CHECK(q.emission_error >= abs(q.emission - c.emission));
    CHECK(rel_error(q.transmittance, c.transmittance) <= ReferenceTolerances::internal_rel);
    CHECK(q.transmittance_error >= abs(q.transmittance - c.transmittance));
  }
}

TEST_CASE("reference: the 1e30 piece raised its truncation depth", "[reference]") {
  const reference_detail::PieceQuadrature q =
      reference_detail::integrate_piece({Real(1), Real(1e30), Real(1e30), Real(1), Real(0)});
  CHECK(q.truncated);
  CHECK(q.truncation_passes >= 1);
  CHECK(q.tau_cut > 140);
  CHECK(q.converged);
}

TEST_CASE("reference: rho = 0 and L = 0 emit nothing and transmit everything", "[reference]") {
  for (const ChannelPiece& p : {ChannelPiece{2.0, 0.0, 0.0, 0.8, 0.3},     // rho = 0
                                ChannelPiece{0.0, 5.0, 2.0, 0.8, 0.3},     // L = 0
                                ChannelPiece{1.0, 3.0, 1.0, 0.0, 0.0}}) {  // kappa = 0
    const ReferencePiece r = reference_piece(p, 0.625);
    const bool transparent = p.length == 0.0 || (p.rho_far == 0.0 && p.rho_exit == 0.0);
    CHECK(r.emission.hi == 0.0);
    CHECK(r.emission.lo == 0.0);
    CHECK(r.subintervals == 0);
    if (transparent) {
      CHECK(r.transmittance.hi == 1.0);
      CHECK(r.transmittance.lo == 0.0);
      CHECK(r.intensity.hi == 0.625);
      CHECK(r.intensity.lo == 0.0);
    }
    CHECK(r.error_bound <= Tolerances::reference_rel * 0.625);
  }
}

// ---- (6) rays ---------------------------------------------------------------------------------

namespace {

// Transfer functions built so that on every piece each channel has rho or kappa constant:
//   r: rho 1 up to s = 0.5 then rising to 3 at s = 1; kappa rising 0.2 -> 0.8 up to 0.5, then 0.8
//   g: rho 2 up to 0.25, falling to 0.5 at 0.75, then 0.5; kappa 0.5 (one point at 0.1)
//   b: rho 0 up to 0.6, rising to 4 at 0.9, then 4; kappa 1 -> 0.4 on [0, 0.3], then 0.4
// Breakpoints: 0, 0.1, 0.25, 0.3, 0.5, 0.6, 0.75, 0.9, 1.
TransferFunctions hand_tf() {
  TransferFunctions tf;
  tf.density[0] = {{0.0, 0.5, 1.0}, {1.0, 1.0, 3.0}};
  tf.color[0] = {{0.0, 0.5, 1.0}, {0.2, 0.8, 0.8}};
  tf.density[1] = {{0.25, 0.75}, {2.0, 0.5}};
  tf.color[1] = {{0.1}, {0.5}};
  tf.density[2] = {{0.0, 0.6, 0.9}, {0.0, 0.0, 4.0}};
  tf.color[2] = {{0.0, 0.3, 1.0}, {1.0, 0.4, 0.4}};
  return tf;
}

// The same functions written out by hand, in 50 digits.
Real hand_rho(int c, const Real& s) {
  switch (c) {
    case 0:
      return s <= 0.5 ? Real(1) : s >= 1 ? Real(3) : 1 + 4 * (s - 0.5);
    case 1:
      return s <= 0.25 ? Real(2) : s >= 0.75 ? Real(0.5) : 2 - 3 * (s - 0.25);
    default:
      return s <= 0.6 ? Real(0) : s >= 0.9 ? Real(4) : (s - 0.6) * 4 / (Real(0.9) - 0.6);
  }
}
Real hand_kappa(int c, const Real& s) {
  switch (c) {
    case 0:
      return s >= 0.5 ? Real(0.8) : 0.2 + (s - 0) * (Real(0.8) - 0.2) / 0.5;
    case 1:
      return Real(0.5);
    default:
      return s >= 0.3 ? Real(0.4) : 1 + s * (Real(0.4) - 1) / 0.3;
  }
}

struct HandSegment {
  double length, scalar_far, scalar_exit;
  std::vector<double> ends;  // far -> near, including both segment ends
};

// The ray, with the piece ends of each segment listed by hand.
std::vector<HandSegment> hand_segments() {
  return {
      {2.0, 0.05, 0.8, {0.05, 0.1, 0.25, 0.3, 0.5, 0.6, 0.75, 0.8}},     // rising across 6 points
      {0.5, 0.95, 0.95, {0.95, 0.95}},                                   // constant scalar
      {0.0, 0.2, 0.7, {}},                                               // zero length: skipped
      {1.5, 1.2, 0.2, {1.2, 1.0, 0.9, 0.75, 0.6, 0.5, 0.3, 0.25, 0.2}},  // falling, from beyond 1
      {0.25, 0.55, 0.45, {0.55, 0.5, 0.45}},                             // short, across 0.5
  };
}

// A piece of one channel from the analytic formulas: rho constant (Eq. 6 and its kappa-linear
// extension) or kappa constant (Eq. 5); the functions above never give both linear.
Real hand_emission(const Real& L, const Real& rho_far, const Real& rho_exit, const Real& k_far,
                   const Real& k_exit) {
  if (rho_far == rho_exit) return emission_rho_constant(L, rho_far, k_exit, k_far);
  REQUIRE(k_far == k_exit);
  return emission_kappa_constant(L, rho_far, rho_exit, k_far);
}

}  // namespace

TEST_CASE("reference: a ray composited by hand from analytic pieces", "[reference]") {
  const TransferFunctions tf = hand_tf();
  Ray ray;
  ray.background = {0.3, 0.0, 1.5};
  int pieces = 0;
  std::array<Real, kChannels> I, T;
  for (int c = 0; c < kChannels; ++c) {
    I[c] = ray.background[c];
    T[c] = 1;
  }
  for (const HandSegment& seg : hand_segments()) {
    ray.segments.push_back({seg.length, seg.scalar_far, seg.scalar_exit});
    for (std::size_t k = 0; k + 1 < seg.ends.size(); ++k) {
      const Real s_far = seg.ends[k], s_exit = seg.ends[k + 1];
      const Real L = seg.scalar_far == seg.scalar_exit
                         ? Real(seg.length)
                         : seg.length * (s_exit - s_far) / (Real(seg.scalar_exit) - seg.scalar_far);
      for (int c = 0; c < kChannels; ++c) {
        const Real rho_far = hand_rho(c, s_far), rho_exit = hand_rho(c, s_exit);
        const Real e =
            hand_emission(L, rho_far, rho_exit, hand_kappa(c, s_far), hand_kappa(c, s_exit));
        const Real t = exp(-L * (rho_far + rho_exit) / 2);
        I[c] = I[c] * t + e;
        T[c] *= t;
      }
      ++pieces;
    }
  }

  const ReferenceRay r = reference_ray(tf, ray);
  CHECK(r.pieces == pieces);
  CHECK(r.subintervals > 0);
  for (int c = 0; c < kChannels; ++c) {
    INFO("channel " << c << ": error bound " << r.error_bound[c]);
    const double i_rel = rel_error(value(r.intensity[c]), I[c]);
    const double t_rel = rel_error(value(r.transmittance[c]), T[c]);
    INFO("relative error: intensity " << i_rel << ", transmittance " << t_rel);
    CHECK(i_rel <= Tolerances::reference_rel);
    CHECK(t_rel <= Tolerances::reference_rel);
    CHECK(Real(r.error_bound[c]) >= abs(value(r.intensity[c]) - I[c]));
    CHECK(r.error_bound[c] <= Tolerances::reference_rel * r.intensity[c].hi);
  }
}

TEST_CASE("reference: a constant-scalar ray is one piece and matches reference_piece",
          "[reference]") {
  TransferFunctions tf;
  for (int c = 0; c < kChannels; ++c) {
    tf.density[c] = {{0.0, 1.0}, {0.5 + c, 2.0}};
    tf.color[c] = {{0.0, 1.0}, {1.0, 0.25 * c}};
  }
  Ray ray;
  ray.background = {0.1, 0.2, 0.3};
  ray.segments = {{0.75, 0.5, 0.5}};
  const ReferenceRay r = reference_ray(tf, ray);
  CHECK(r.pieces == 1);
  for (int c = 0; c < kChannels; ++c) {
    // At s = 0.5 the interpolated values are exact in double.
    const double rho = (0.5 + c + 2.0) / 2, kappa = (1.0 + 0.25 * c) / 2;
    const ReferencePiece p = reference_piece({0.75, rho, rho, kappa, kappa}, ray.background[c]);
    CHECK(r.intensity[c].hi == p.intensity.hi);
    CHECK(std::fabs(r.intensity[c].lo - p.intensity.lo) <= 2 * r.error_bound[c]);
    CHECK(r.transmittance[c].hi == p.transmittance.hi);
  }
}

TEST_CASE("reference: invalid input is refused", "[reference]") {
  CHECK_THROWS_AS(reference_piece({1.0, -1.0, 1.0, 1.0, 1.0}, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(reference_piece({std::nan(""), 1.0, 1.0, 1.0, 1.0}, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(reference_piece({1.0, 1.0, 1.0, 1.0, 1.0}, INFINITY), std::invalid_argument);
  TransferFunctions tf = hand_tf();
  Ray ray;
  ray.segments = {{-1.0, 0.0, 1.0}};
  CHECK_THROWS_AS(reference_ray(tf, ray), std::invalid_argument);
  ray.segments = {{1.0, 0.0, 1.0}};
  tf.color[1].value.clear();
  CHECK_THROWS_AS(reference_ray(tf, ray), std::invalid_argument);
}

// ---- internals --------------------------------------------------------------------------------

TEST_CASE("reference: exp_series agrees with Boost's exp within its own bound", "[reference]") {
  for (double z = -24.0; z <= 24.0; z += 0.37) {
    for (const double scale : {1.0, 1e-3, 1e-9, 1e-40}) {
      const Real x = Real(z) * Real(scale) + Real(1) / 7 * scale;
      double bound = 0.0;
      const Real s = reference_detail::exp_series(x, &bound);
      const double rel = rel_error(s, exp(x));
      INFO("z = " << static_cast<double>(x) << ": relative error " << rel << ", bound " << bound);
      CHECK(rel <= ReferenceTolerances::exp_series_rel);
      CHECK(rel <= bound + 1e-49);  // Boost's own few-ulp error on top
    }
  }
  CHECK(reference_detail::exp_series(Real(0)) == 1);
}

TEST_CASE("reference: double-double rounding is to nearest", "[reference]") {
  const Real third = Real(1) / 3;
  for (const Real& x : {third, Real(2) / 3 * 1e-300, -third * 1e200, Real(0.1) + Real(1e-40),
                        Real(1e-320) / 3, Real(0)}) {
    const ExtendedValue v = reference_detail::to_extended(x);
    const Real hi = v.hi;
    for (const double neighbour : {std::nextafter(v.hi, -INFINITY), std::nextafter(v.hi, INFINITY)})
      CHECK(abs(x - hi) <= abs(x - Real(neighbour)));
    if (abs(x) > Real(1e-280)) {
      CHECK(reference_detail::representation_error(x, v) <=
            abs(x) * ReferenceTolerances::double_double_rel);
    }
  }
  // A tie goes to the even significand: 1 + 2^-53 lies halfway between 1 and 1 + 2^-52.
  const ExtendedValue tie = reference_detail::to_extended(1 + Real(std::ldexp(1.0, -53)));
  CHECK(tie.hi == 1.0);
  CHECK(tie.lo == std::ldexp(1.0, -53));
}

TEST_CASE("reference: interpolation in 50 digits", "[reference]") {
  const PiecewiseLinear f{{0.0, 0.1, 1.0}, {2.0, 0.0, 3.0}};
  CHECK(reference_detail::interpolate(f, -5.0, false) == 2);
  CHECK(reference_detail::interpolate(f, 7.0, false) == 3);
  CHECK(reference_detail::interpolate(f, 0.1, false) == 0);
  CHECK(reference_detail::interpolate(f, 1.0, false) == 3);
  // Between 0.1 and 1 the value is 3 (s - 0.1) / 0.9, with 0.1 the double nearest 1/10.
  const Real s0 = 0.1;
  for (const double s : {0.3, 0.55, 0.1 + 1e-15, 1.0 - 1e-12}) {
    const Real exact = 3 * (Real(s) - s0) / (1 - s0);
    CHECK(rel_error(reference_detail::interpolate(f, s, false), exact) <= 1e-48);
  }
  // Toward a zero value the relative accuracy holds (no cancellation).
  const Real near_zero = reference_detail::interpolate(f, std::nextafter(0.1, 0.0), false);
  const Real exact = 2 * (s0 - Real(std::nextafter(0.1, 0.0))) / s0;
  CHECK(rel_error(near_zero, exact) <= 1e-48);
}

TEST_CASE("reference: the error estimate covers the true error of coarse rules", "[reference]") {
  // Forced coarse rules and early truncation make the errors large enough to measure; the
  // estimate (|Kronrod - Gauss| + truncation + rounding) must still cover them.
  struct Forced {
    AnalyticCase c;
    int rule, subintervals;
    double tau_cut;
  };
  const std::vector<Forced> cases = {
      {rho_constant("Eq. 6, T = 10, GK15", 1.0, 10.0, 0.7, 0.7, 0.0), 15, 1, INFINITY},
      {kappa_constant("Eq. 5, rho 0 -> 6, GK15", 1.0, 6.0, 0.0, 0.8, 0.0), 15, 1, INFINITY},
      {kappa_constant("Eq. 5, rho 8 -> 0, GK21", 1.0, 0.0, 8.0, 0.8, 0.0), 21, 1, INFINITY},
      {rho_constant("kappa 0 -> 2, rho 4, T = 12, GK15 x 2", 3.0, 4.0, 0.0, 2.0, 0.0), 15, 2,
       INFINITY},
      {both_linear("both linear, T = 2.3, GK15", 1.3, 3.0, 0.5, 0.25, 2.0, 0.0), 15, 1, INFINITY},
      {kappa_constant("Eq. 5, T = 500, cut at 20", 1.0, 1000.0, 0.0, 0.6, 0.0), 61, 4, 20.0},
      {rho_constant("kappa 0 -> 1, T = 1e6, cut at 30", 1.0, 1e6, 0.0, 1.0, 0.0), 61, 2, 30.0},
  };
  for (const Forced& f : cases) {
    const ChannelPiece& p = f.c.piece;
    const reference_detail::PieceQuadrature q = reference_detail::integrate_piece_forced(
        {Real(p.length), Real(p.rho_far), Real(p.rho_exit), Real(p.kappa_far), Real(p.kappa_exit)},
        f.rule, f.subintervals, f.tau_cut);
    const Real actual = abs(q.emission - f.c.emission);
    INFO(f.c.description << ": actual " << static_cast<double>(actual) << ", estimate "
                         << static_cast<double>(q.emission_error) << " (quadrature "
                         << static_cast<double>(q.quadrature_error) << ", truncation "
                         << static_cast<double>(q.truncation_error) << ")");
    CHECK(actual >= ReferenceTolerances::coarse_rule_min_error * f.c.emission);
    CHECK(q.emission_error >= actual);
  }
}

TEST_CASE("reference: concurrent calls give the serial results", "[reference]") {
  const std::vector<AnalyticCase> cases = analytic_cases();
  std::vector<ReferencePiece> serial;
  for (const AnalyticCase& c : cases) serial.push_back(reference_piece(c.piece, c.incoming));
  const ReferenceRay serial_ray =
      reference_ray(hand_tf(), Ray{{0.3, 0.0, 1.5}, {{2.0, 0.05, 0.8}}});

  constexpr int kThreads = 4;
  std::vector<std::vector<ReferencePiece>> results(kThreads);
  std::vector<ReferenceRay> rays(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t)
    threads.emplace_back([&, t] {
      for (const AnalyticCase& c : cases)
        results[t].push_back(reference_piece(c.piece, c.incoming));
      rays[t] = reference_ray(hand_tf(), Ray{{0.3, 0.0, 1.5}, {{2.0, 0.05, 0.8}}});
    });
  for (std::thread& th : threads) th.join();
  for (int t = 0; t < kThreads; ++t) {
    REQUIRE(results[t].size() == serial.size());
    for (std::size_t i = 0; i < serial.size(); ++i) {
      CHECK(results[t][i].intensity.hi == serial[i].intensity.hi);
      CHECK(results[t][i].intensity.lo == serial[i].intensity.lo);
      CHECK(results[t][i].error_bound == serial[i].error_bound);
    }
    for (int c = 0; c < kChannels; ++c) {
      CHECK(rays[t].intensity[c].hi == serial_ray.intensity[c].hi);
      CHECK(rays[t].intensity[c].lo == serial_ray.intensity[c].lo);
    }
  }
}

TEST_CASE("reference: a long ray on several threads is bit-identical to one thread",
          "[reference]") {
  // 4500 segments (two full blocks of ReferenceRun and a partial one), the scalar crossing the
  // breakpoints of hand_tf back and forth, some segments of zero length.
  Ray ray;
  ray.background = {0.3, 0.0, 1.5};
  double s = 0.5;
  for (int k = 0; k < 4500; ++k) {
    const double next = 0.5 + 0.45 * std::sin(0.013 * (k + 1));
    ray.segments.push_back({k % 97 == 0 ? 0.0 : 1e-3 * (1 + k % 7), s, next});
    s = next;
  }
  const ReferenceRay serial = reference_ray(hand_tf(), ray);
  std::vector<std::size_t> done;
  ReferenceRun run;
  run.threads = 3;
  run.progress = [&](std::size_t d, std::size_t total) {
    CHECK(total == ray.segments.size());
    done.push_back(d);
  };
  const ReferenceRay parallel = reference_ray(hand_tf(), ray, run);
  CHECK(done == std::vector<std::size_t>{2048, 4096, 4500});
  CHECK(parallel.pieces == serial.pieces);
  CHECK(parallel.subintervals == serial.subintervals);
  CHECK(serial.pieces > 4500);  // breakpoints split segments
  for (int c = 0; c < kChannels; ++c) {
    CHECK(parallel.intensity[c].hi == serial.intensity[c].hi);
    CHECK(parallel.intensity[c].lo == serial.intensity[c].lo);
    CHECK(parallel.transmittance[c].hi == serial.transmittance[c].hi);
    CHECK(parallel.transmittance[c].lo == serial.transmittance[c].lo);
    CHECK(parallel.error_bound[c] == serial.error_bound[c]);
  }
}
