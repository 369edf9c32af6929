// The exact closed forms against the 50-digit reference, regime by regime, and against the
// analytic limits of Williams & Max (Eq. 5, Eq. 6, rho = 0).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "rayint/metrics/error_metrics.hpp"
#include "rayint/generators/regimes.hpp"
#include "rayint/integrators/exact.hpp"
#include "rayint/integrators/paper.hpp"
#include "rayint/reference/reference.hpp"
#include "tolerances.hpp"
#include "transfer_builders.hpp"

using namespace rayint;
using namespace rayint::test;  // Tolerances and the transfer-function builders

namespace {

// Passes if relative error <= rel, or absolute error <= Tolerances::exact_abs_underflow where
// the reference value is itself below the underflow threshold.
bool within(double x, const ExtendedValue& ref, double rel) {
  if (!std::isfinite(x)) return false;
  if (relative_error(x, ref) <= rel) return true;
  return std::fabs(ref.hi) < 1e-290 && absolute_error(x, ref) <= Tolerances::exact_abs_underflow;
}

void require_ray_matches_reference(const TransferFunctions& tf, const Ray& ray, double rel) {
  const ReferenceRay ref = reference_ray(tf, ray);
  ExactIntegrator exact(tf);
  Diagnostics diag;
  const RayResult r = exact.integrate(ray, &diag);
  for (int c = 0; c < kChannels; ++c) {
    INFO("channel " << c << " exact " << r.intensity[c] << " reference " << ref.intensity[c].hi
                    << " rel " << relative_error(r.intensity[c], ref.intensity[c]));
    CHECK(within(r.intensity[c], ref.intensity[c], rel));
    CHECK(within(r.transmittance[c], ref.transmittance[c], rel));
  }
}

}  // namespace

TEST_CASE("Figure 2 worked example: a=5, b=-3, f=8.5, g=-5.1, h=0", "[exact][paper]") {
  // rho_r(s) = 5 - 3 s and kappa_r rho_r = 8.5 - 5.1 s, so kappa_r = 1.7 on the interval and
  // Eq. 5 is the exact answer: I = kappa (1 - e^{-T}) + I0 e^{-T}.
  const TransferFunctions tf = uniform_tf(line(0.0, 5.0, 1.0, 2.0), constant(1.7));
  Ray ray;
  ray.background = {0.3, 0.3, 0.3};
  ray.segments = {{1.0, 0.1, 0.9}};
  const double T = 1.0 * (4.7 + 2.3) / 2;  // rho(0.1) = 4.7, rho(0.9) = 2.3
  const double expected = 1.7 * -std::expm1(-T) + 0.3 * std::exp(-T);

  const RayResult exact = ExactIntegrator(tf).integrate(ray, nullptr);
  const RayResult paper = PaperIntegrator(tf).integrate(ray, nullptr);
  const ReferenceRay ref = reference_ray(tf, ray);
  CHECK(relative_error(exact.intensity[0], expected) <= Tolerances::analytic_limit_rel);
  CHECK(relative_error(ref.intensity[0].hi, expected) <= Tolerances::analytic_limit_rel);
  CHECK(relative_error(paper.intensity[0], expected) <= Tolerances::paper_benign_rel);

  // The paper's own coefficients for this interval, fed to its printed q2 != 0 formula.
  // S(t) = v + w t with v = 0.1, w = 0.8: q1 = a + b v, q2 = b w, q3 = f + g v, q4 = g w, q5 = 0.
  const double v = 0.1, w = 0.8;
  const PaperInterval iv{5 - 3 * v, -3 * w, 8.5 - 5.1 * v, -5.1 * w, 0.0, 0.0, 1.0};
  const double em = paper_emission(iv);
  CHECK(relative_error(em, 1.7 * -std::expm1(-T)) <= Tolerances::paper_benign_rel);
  CHECK(relative_error(paper_transmittance(iv), std::exp(-T)) <= Tolerances::analytic_limit_rel);
}

TEST_CASE("Analytic limits: constant kappa is Eq. 5, constant kappa and rho is Eq. 6",
          "[exact][limits]") {
  std::mt19937_64 rng(20261122);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 2000; ++i) {
    ChannelPiece p;
    p.length = std::exp(u(rng) * 10 - 5);
    const double T = std::exp(u(rng) * 30 - 25);  // 1e-11 .. 150
    const double share = u(rng);
    p.rho_exit = 2 * T / p.length * share;
    p.rho_far = 2 * T / p.length * (1 - share);
    p.kappa_exit = p.kappa_far = std::exp(u(rng) * 6 - 3);
    const PieceOptics o = exact_piece(p);
    const double T_computed = 0.5 * (p.rho_exit + p.rho_far) * p.length;
    INFO("T " << T << " share " << share << " branch " << branch_name(o.branch));
    // Eq. 5: I = kappa (1 - e^{-int rho}) for constant kappa.
    CHECK(relative_error(o.emission, p.kappa_exit * -std::expm1(-T_computed)) <=
          Tolerances::analytic_limit_rel);
    // Eq. 6: constant rho as well.
    p.rho_far = p.rho_exit;
    const PieceOptics o6 = exact_piece(p);
    CHECK(relative_error(o6.emission, p.kappa_exit * -std::expm1(-p.rho_exit * p.length)) <=
          Tolerances::analytic_limit_rel);
    CHECK(relative_error(o6.transmittance, std::exp(-p.rho_exit * p.length)) <=
          Tolerances::analytic_limit_rel);
  }
}

TEST_CASE("rho = 0 transmits the background unchanged", "[exact][limits]") {
  const TransferFunctions tf = uniform_tf(constant(0.0), line(0.0, 3.0, 1.0, 7.0));
  Ray ray;
  ray.background = {0.25, 1.5, 1e-200};
  ray.segments = {{2.0, 0.0, 1.0}, {0.5, 1.0, 0.2}};
  Diagnostics diag;
  const RayResult r = ExactIntegrator(tf).integrate(ray, &diag);
  for (int c = 0; c < kChannels; ++c) {
    CHECK(r.intensity[c] == ray.background[c]);
    CHECK(r.transmittance[c] == 1.0);
  }
  CHECK(diag.branches["transparent"] > 0);
}

TEST_CASE("exact against the reference, regime by regime", "[exact][regimes]") {
  // 150 pieces per regime here (the 100,000-piece figure in the README comes from
  // `rayint stress`); every branch must be taken and none may be non-finite.
  std::mt19937_64 rng(7);
  std::vector<double> ulps;
  std::map<std::string, long> branches;
  for (const Regime regime : all_regimes()) {
    double worst = 0.0;
    for (int i = 0; i < 150; ++i) {
      const RegimeSample s = sample_piece(regime, rng);
      const PieceOptics o = exact_piece(s.piece);
      const ReferencePiece ref = reference_piece(s.piece, s.incoming);
      const double intensity = s.incoming * o.transmittance + o.emission;
      branches[branch_name(o.branch)]++;
      INFO("regime " << regime_name(regime) << " branch " << branch_name(o.branch) << " terms "
                     << o.terms << " L " << s.piece.length << " rho_exit " << s.piece.rho_exit
                     << " rho_far " << s.piece.rho_far << " kappa " << s.piece.kappa_exit << ","
                     << s.piece.kappa_far << " incoming " << s.incoming << " exact "
                     << intensity << " ref " << ref.intensity.hi);
      REQUIRE(std::isfinite(intensity));
      CHECK(o.converged);
      CHECK(within(intensity, ref.intensity, Tolerances::exact_rel));
      CHECK(within(o.emission, ref.emission, Tolerances::exact_rel));
      CHECK(within(o.transmittance, ref.transmittance, Tolerances::exact_rel));
      worst = std::max(worst, relative_error(o.emission, ref.emission));
      if (std::fabs(ref.emission.hi) > 1e-290) ulps.push_back(ulp_error(o.emission, ref.emission));
    }
    INFO("regime " << regime_name(regime) << " worst emission rel error " << worst);
    CHECK(worst <= Tolerances::exact_rel);
  }
  for (const char* b : {"transparent", "thin_series", "q2_series", "erfcx", "dawson"}) {
    INFO("branch " << b);
    CHECK(branches[b] > 0);
  }
  std::nth_element(ulps.begin(), ulps.begin() + static_cast<long>(ulps.size() / 2), ulps.end());
  CHECK(ulps[ulps.size() / 2] <= Tolerances::exact_median_ulp);
}

TEST_CASE("exact rays: w = 0, zero-length pieces, pulses 1e-12 wide, scalars out of range",
          "[exact][rays]") {
  SECTION("scalar constant along a segment (w = 0)") {
    const TransferFunctions tf = uniform_tf(line(0.0, 1.0, 1.0, 3.0), line(0.0, 2.0, 1.0, 0.5));
    Ray ray{{0.1, 0.2, 0.3}, {{1.5, 0.4, 0.4}, {0.7, 0.9, 0.9}}};
    require_ray_matches_reference(tf, ray, Tolerances::exact_rel);
  }
  SECTION("zero-length segments and pieces") {
    const TransferFunctions tf = uniform_tf(line(0.0, 1.0, 1.0, 3.0), line(0.0, 2.0, 1.0, 0.5));
    Ray ray{{0.1, 0.2, 0.3}, {{0.0, 0.1, 0.9}, {1.0, 0.0, 1.0}, {0.0, 0.5, 0.5}}};
    require_ray_matches_reference(tf, ray, Tolerances::exact_rel);
  }
  SECTION("a transfer-function pulse whose breakpoints are 1e-12 apart") {
    PiecewiseLinear pulse{{0.5, 0.5 + 1e-12, 0.5 + 2e-12}, {0.0, 1e9, 0.0}};
    const TransferFunctions tf = uniform_tf(pulse, line(0.0, 1.0, 1.0, 5.0));
    Ray ray{{0.0, 0.0, 0.0}, {{1.0, 0.0, 1.0}, {1.0, 1.0, 0.25}}};
    require_ray_matches_reference(tf, ray, Tolerances::exact_rel);
  }
  SECTION("scalars outside the transfer function's range") {
    const TransferFunctions tf = uniform_tf(line(0.2, 1.0, 0.8, 4.0), line(0.3, 2.0, 0.6, 0.5));
    Ray ray{{1.0, 1.0, 1.0}, {{2.0, -5.0, 0.1}, {1.0, 0.5, 7.0}, {1.0, 9.0, 10.0}}};
    require_ray_matches_reference(tf, ray, Tolerances::exact_rel);
  }
  SECTION("a segment whose scalar span is one denormal (found by rayint stress)") {
    // L / (s1 - s0) overflowed to inf and made the piece length inf.
    const TransferFunctions tf = uniform_tf(line(0.0, 0.5, 1.0, 3.0), line(0.0, 2.0, 1.0, 0.5));
    Ray ray{{0.1, 0.2, 0.3}, {{24.0, 0.0, 5e-324}, {1.0, 0.2, 0.9}}};
    require_ray_matches_reference(tf, ray, Tolerances::exact_rel);
  }
  SECTION("colour interpolated 4e-14 from its zero (found by rayint stress)") {
    // kappa = 82.8 (1 - f) with f = 1 - 6.9e-14 lost 13 digits when formed as 1 - f.
    const PiecewiseLinear kappa{{0.0, 0.6202816383715489, 1.0}, {82.79328637423598, 0.0, 1.0}};
    const TransferFunctions tf = uniform_tf(constant(5.76e10), kappa);
    Ray ray{{0.0, 0.0, 0.0}, {{0.13639106563747083, 0.6202816383715062, 0.6202816383715062}}};
    require_ray_matches_reference(tf, ray, Tolerances::exact_rel);
  }
  SECTION("very thick ray: background underflows") {
    const TransferFunctions tf = uniform_tf(line(0.0, 1e6, 1.0, 2e5), line(0.0, 1.0, 1.0, 2.0));
    Ray ray{{1.0, 1.0, 1.0}, {{1.0, 0.0, 1.0}, {3.0, 1.0, 0.0}}};
    require_ray_matches_reference(tf, ray, Tolerances::exact_rel);
  }
}

TEST_CASE("paper's literal formula overflows where the stable forms do not", "[paper]") {
  // Density increasing toward the eye (q2 > 0) over a thick piece: the printed formula multiplies
  // e^{-x^2} by Erfi(x) ~ e^{x^2}; each overflows for x^2 > 709.
  const TransferFunctions tf = uniform_tf(line(0.0, 1.0, 1.0, 2000.0), constant(1.0));
  Ray ray{{0.0, 0.0, 0.0}, {{1.0, 0.0, 1.0}}};
  const RayResult paper = PaperIntegrator(tf).integrate(ray, nullptr);
  const RayResult exact = ExactIntegrator(tf).integrate(ray, nullptr);
  CHECK_FALSE(std::isfinite(paper.intensity[0]));
  CHECK(std::isfinite(exact.intensity[0]));
  // And q2 == 0 with q1 == 0 divides 0 by 0 in the printed q2 = 0 branch.
  const PaperInterval zero{0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0};
  CHECK_FALSE(std::isfinite(paper_emission(zero)));
}
