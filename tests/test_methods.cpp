// The numerical methods (riemann, rk4, ode, eq5..eq8, particle): convergence at their known
// orders on a smooth ray, front-to-back = back-to-front, the analytic limits of Williams & Max
// (Eq. 5, Eq. 6, rho = 0) each within the method's own error estimate, the particle model's
// applicability, parameter checking and budgets. Reference: `exact`, which test_exact.cpp
// verifies against the 50-digit reference to 1e-13 (checked again here on the smooth ray); every
// error measured here is far above that.
// No Rosenbrock stepper is used (ode is the explicit Dormand-Prince pair), so the test against
// Boost 1.74's rosenbrock4 non-autonomous sign error does not apply.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "rayint/metrics/error_metrics.hpp"
#include "rayint/integrators/exact.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/reference/reference.hpp"
#include "tolerances.hpp"
#include "smooth_ray.hpp"
#include "transfer_builders.hpp"

using namespace rayint;
using rayint::test::MethodTolerances;
using rayint::test::Tolerances;

namespace {

using rayint::test::constant;
using rayint::test::constant_tf;
using rayint::test::line;
using rayint::test::max_rel;
using rayint::test::SmoothCase;

std::unique_ptr<RayIntegrator> make(const std::string& spec, const TransferFunctions& tf) {
  return make_integrator(parse_method_spec(spec), tf);
}

RayResult run(const std::string& spec, const TransferFunctions& tf, const Ray& ray) {
  return make(spec, tf)->integrate(ray, nullptr);
}

double max_rel_transmittance(const RayResult& r, const RayResult& ref) {
  double e = 0.0;
  for (int c = 0; c < kChannels; ++c)
    e = std::max(e, relative_error(r.transmittance[c], ref.transmittance[c]));
  return e;
}

const RayResult& smooth_exact() {
  static const SmoothCase sc;
  static const RayResult r = ExactIntegrator(sc.tf).integrate(sc.ray, nullptr);
  return r;
}

// A parameter value that parses back to the same double.
std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// Order fitted from the errors at n and 2n.
double order(double e_n, double e_2n) { return std::log2(e_n / e_2n); }

// Least-squares slope of log(error) against log(h): the order p in error ~ C h^p.
double fitted_order(const std::vector<double>& h, const std::vector<double>& e) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double m = static_cast<double>(h.size());
  for (std::size_t i = 0; i < h.size(); ++i) {
    const double x = std::log(h[i]), y = std::log(e[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return (m * sxy - sx * sy) / (m * sxx - sx * sx);
}

// The smooth case's intensity error against `exact` of spec(n), n = n_first, 2 n_first, ..,
// n_last; the order between consecutive n must lie within `band` of `expected`.
std::vector<double> check_doubling_orders(const std::function<std::string(int)>& spec, int n_first,
                                          int n_last, double expected, double band) {
  const SmoothCase sc;
  std::vector<double> errors;
  for (int n = n_first; n <= n_last; n *= 2) {
    const double e = max_rel(run(spec(n), sc.tf, sc.ray), smooth_exact());
    const double e_prev = errors.empty() ? 0.0 : errors.back();
    INFO(spec(n) << " error " << e << " previous " << e_prev);
    if (e_prev > 0.0) CHECK(std::fabs(order(e_prev, e) - expected) <= band);
    errors.push_back(e);
  }
  return errors;
}

}  // namespace

TEST_CASE("smooth case: the exact closed form agrees with the 50-digit reference", "[methods]") {
  const SmoothCase sc;
  const ReferenceRay ref = reference_ray(sc.tf, sc.ray);
  for (int c = 0; c < kChannels; ++c) {
    CHECK(relative_error(smooth_exact().intensity[c], ref.intensity[c]) <= Tolerances::exact_rel);
    CHECK(relative_error(smooth_exact().transmittance[c], ref.transmittance[c]) <=
          Tolerances::exact_rel);
  }
}

TEST_CASE("riemann with exact per-sample opacity is second order", "[methods][convergence]") {
  // Midpoint sampling with alpha = 1 - exp(-rho h) and colour kappa alpha: each sub-step is Eq. 6
  // with rho, kappa frozen at the midpoint, whose local error is O(h^3) -> second order.
  for (const std::string options : {"", ":order=ftb", ":correction=exp:ref_dt=0.01"}) {
    const std::vector<double> errors = check_doubling_orders(
        [&](int n) { return "riemann:n=" + std::to_string(n) + options; }, 8, 64, 2.0,
        MethodTolerances::riemann_order_band);
    // Cost/error figure quoted in riemann.cpp: n = 64 per segment.
    CHECK(errors.back() <= 1e-5);
  }
}

TEST_CASE("riemann with linearised opacity alpha = rho h is first order",
          "[methods][convergence]") {
  // alpha = rho h misses rho^2 h^2 / 2 per sample: O(h^2) locally, O(h) globally.
  check_doubling_orders([](int n) { return "riemann:correction=linear:n=" + std::to_string(n); },
                        8, 64, 1.0, MethodTolerances::riemann_order_band);
}

TEST_CASE("riemann with a fixed step dt along the ray is second order", "[methods][convergence]") {
  // Steps straddle the segment joins, where the scalar (so the integrand) has a kink: the step
  // holding a kink has an O(h^2) error whose constant depends on where the kink falls, so the
  // order between two step sizes zig-zags (measured 1.3 .. 2.7) around 2. The least-squares
  // slope over 8 halvings is the order.
  const SmoothCase sc;
  std::vector<double> hs, es;
  for (double dt = 1.0 / 8; dt >= 1.0 / 2048; dt /= 2) {
    const std::string spec = "riemann:dt=" + num(dt);
    hs.push_back(dt);
    es.push_back(max_rel(run(spec, sc.tf, sc.ray), smooth_exact()));
  }
  const double p = fitted_order(hs, es);
  INFO("fitted order " << p);
  CHECK(std::fabs(p - 2.0) <= MethodTolerances::riemann_dt_order_band);
}

TEST_CASE("riemann without opacity correction converges only at its reference step",
          "[methods][convergence]") {
  // Ray length 2.5 = 80/32, so dt = 1/32 tiles it exactly.
  const SmoothCase sc;
  const double ref_dt = 1.0 / 32;
  const std::string table = ":ref_dt=" + num(ref_dt);
  const RayResult at_ref =
      run("riemann:dt=" + num(ref_dt) + ":correction=none" + table, sc.tf, sc.ray);
  const RayResult exact_alpha = run("riemann:dt=" + num(ref_dt), sc.tf, sc.ray);
  // At dt == ref_dt the tabulated opacity is the right one.
  INFO("at ref_dt: tabulated vs exact opacity " << max_rel(at_ref, exact_alpha));
  CHECK(max_rel(at_ref, exact_alpha) <= MethodTolerances::riemann_same_sum_rel);
  const double e_at_ref = max_rel(at_ref, smooth_exact());
  // Refining the step without correcting the opacity makes the ray ever more opaque.
  double e_prev = e_at_ref;
  for (int k = 2; k <= 16; k *= 2) {
    const std::string dt = num(ref_dt / k);
    const double e_none = max_rel(
        run("riemann:dt=" + dt + ":correction=none" + table, sc.tf, sc.ray), smooth_exact());
    const double e_corrected =
        max_rel(run("riemann:dt=" + dt + ":correction=exp" + table, sc.tf, sc.ray), smooth_exact());
    INFO("dt = ref_dt/" << k << ": uncorrected " << e_none << " corrected " << e_corrected
                        << " at ref_dt " << e_at_ref);
    CHECK(e_none > e_prev);
    CHECK(e_none > 100 * e_at_ref);
    CHECK(e_corrected < e_at_ref);  // the correction restores convergence
    e_prev = e_none;
  }
}

TEST_CASE("riemann: front-to-back equals back-to-front to rounding", "[methods]") {
  const SmoothCase sc;
  for (const std::string sampling : {"n=7", "n=256", "dt=0.013", "dt=0.0009765625"}) {
    for (const std::string correction :
         {"", ":correction=linear", ":correction=none:ref_dt=0.02"}) {
      const std::string base = "riemann:" + sampling + correction;
      const RayResult btf = run(base + ":order=btf", sc.tf, sc.ray);
      const RayResult ftb = run(base + ":order=ftb", sc.tf, sc.ray);
      INFO(base << " btf-ftb " << max_rel(ftb, btf) << " transmittance "
                << max_rel_transmittance(ftb, btf));
      CHECK(max_rel(ftb, btf) <= MethodTolerances::ftb_btf_rel);
      CHECK(max_rel_transmittance(ftb, btf) <= MethodTolerances::ftb_btf_rel);
    }
  }
}

TEST_CASE("rk4 is fourth order on a smooth ray", "[methods][convergence]") {
  const std::vector<double> errors = check_doubling_orders(
      [](int n) { return "rk4:n=" + std::to_string(n); }, 8, 32, 4.0,
      MethodTolerances::rk4_order_band);
  CHECK(errors[1] <= 1e-7);  // n = 16: the figure quoted in rk4.cpp
}

TEST_CASE("ode: the error falls with rtol and stays below it", "[methods][convergence]") {
  const SmoothCase sc;
  double e_prev = 1.0, steps_prev = 0.0;
  for (double rtol = 1e-4; rtol >= 1e-10; rtol /= 100) {
    const std::string spec = "ode:rtol=" + num(rtol);
    Diagnostics diag;
    const RayResult r = make(spec, sc.tf)->integrate(sc.ray, &diag);
    const double e = max_rel(r, smooth_exact());
    INFO(spec << " error " << e << " steps " << diag.stats["steps"] << " rejected "
              << diag.stats["rejected_steps"]);
    CHECK(e < e_prev);
    CHECK(e <= MethodTolerances::ode_error_per_rtol * rtol);
    CHECK(diag.stats["steps"] > steps_prev);
    CHECK(diag.branches.count("step_budget_exhausted") == 0);
    e_prev = e;
    steps_prev = diag.stats["steps"];
  }
}

TEST_CASE("constant kappa and rho: every method against Eq. 6 within its own error estimate",
          "[methods][limits]") {
  // Per-channel constants, several cells, non-black background. Along the whole ray Eq. 6 holds:
  //   I = kappa (1 - e^{-rho L}) + I0 e^{-rho L}.
  const TransferFunctions tf = constant_tf({0.35, 1.4, 0.02}, {0.9, 0.25, 3.0});
  const Ray ray{{0.4, 1.2, 0.0},
                {{0.3, 0.1, 0.7}, {1.1, 0.7, 0.2}, {0.05, 0.2, 0.2}, {0.8, 0.2, 0.9}}};
  double L = 0.0;
  for (const auto& s : ray.segments) L += s.length;
  RayResult eq6;
  for (int c = 0; c < kChannels; ++c) {
    const double x = tf.density[c].value[0] * L;
    eq6.intensity[c] = tf.color[c].value[0] * -std::expm1(-x) + ray.background[c] * std::exp(-x);
    eq6.transmittance[c] = std::exp(-x);
  }
  // Exact per cell: eq5, eq6, eq7 (Eq. 6 itself) and riemann with exact per-sample opacity
  // (each sample is Eq. 6; only the rounding of up to 4 n compounded products remains).
  for (const std::string spec : {"exact", "eq5", "eq6", "eq7"}) {
    INFO(spec << " " << max_rel(run(spec, tf, ray), eq6));
    CHECK(max_rel(run(spec, tf, ray), eq6) <= Tolerances::analytic_limit_rel);
    CHECK(max_rel_transmittance(run(spec, tf, ray), eq6) <= Tolerances::analytic_limit_rel);
  }
  for (const std::string spec : {"riemann:n=64", "riemann:n=64:order=ftb", "riemann:dt=0.01"}) {
    INFO(spec << " " << max_rel(run(spec, tf, ray), eq6));
    CHECK(max_rel(run(spec, tf, ray), eq6) <= MethodTolerances::riemann_constant_rel);
  }
  // eq8: per cell alpha = x instead of 1 - e^{-x}, an error below x^2/2 in the opacity, which
  // moves I by at most x^2/2 |kappa - I_in| per cell; later cells only damp it.
  {
    const RayResult r = run("eq8", tf, ray);
    for (int c = 0; c < kChannels; ++c) {
      double bound = 0.0;
      for (const auto& s : ray.segments) {
        const double x = tf.density[c].value[0] * s.length;
        bound += 0.5 * x * x * std::max(tf.color[c].value[0], ray.background[c]);
      }
      INFO("eq8 channel " << c << " error " << std::fabs(r.intensity[c] - eq6.intensity[c])
                          << " bound " << bound);
      CHECK(std::fabs(r.intensity[c] - eq6.intensity[c]) <= bound);
    }
  }
  // rk4: per step I - kappa is multiplied by R(z) = 1 - z + z^2/2 - z^3/6 + z^4/24 instead of
  // e^{-z} (z = rho h <= 1, |R| <= 1), |R(z) - e^{-z}| <= z^5/120 (alternating series), times
  // |I - kappa| <= max(kappa, I0); N steps add up, plus 4 ulps of rounding per step.
  for (int n : {2, 8}) {
    const RayResult r = run("rk4:n=" + std::to_string(n), tf, ray);
    for (int c = 0; c < kChannels; ++c) {
      const double scale = std::max(tf.color[c].value[0], ray.background[c]);
      double bound = 0.0;
      for (const auto& s : ray.segments) {
        const double z = tf.density[c].value[0] * s.length / n;
        bound += n * (std::pow(z, 5) / 120 + 4 * 0x1p-52) * scale;
      }
      INFO("rk4 n=" << n << " channel " << c << " error "
                    << std::fabs(r.intensity[c] - eq6.intensity[c]) << " bound " << bound);
      CHECK(std::fabs(r.intensity[c] - eq6.intensity[c]) <= bound);
    }
  }
  // ode: its error estimate is its tolerance.
  for (double rtol : {1e-6, 1e-10}) {
    const std::string spec = "ode:rtol=" + num(rtol);
    INFO(spec << " " << max_rel(run(spec, tf, ray), eq6));
    CHECK(max_rel(run(spec, tf, ray), eq6) <= MethodTolerances::ode_error_per_rtol * rtol);
  }
}

TEST_CASE("constant kappa, linear rho with breakpoints inside cells: Eq. 5", "[methods][limits]") {
  // kappa constant: Eq. 5, I = kappa (1 - e^{-int rho}) + I0 e^{-int rho}, with int rho exact.
  // eq5 (kappa constant per piece, int rho exact) reproduces it across breakpoints; eq6 uses only
  // the cell's end values and must not.
  TransferFunctions tf;
  const PiecewiseLinear rho{{0.0, 0.3, 0.5, 0.8}, {0.2, 2.5, 0.1, 1.0}};
  tf.density = {rho, rho, rho};
  tf.color = {constant(0.7), constant(1.9), constant(0.05)};
  Ray ray;
  ray.background = {0.3, 0.0, 2.0};
  ray.segments = {{1.0, 0.0, 0.9}, {0.6, 0.9, 0.35}, {0.2, 0.35, 0.4}};
  const RayResult exact = ExactIntegrator(tf).integrate(ray, nullptr);
  for (const std::string spec : {"eq5", "particle"}) {
    INFO(spec << " " << max_rel(run(spec, tf, ray), exact));
    CHECK(max_rel(run(spec, tf, ray), exact) <= Tolerances::analytic_limit_rel);
    CHECK(max_rel_transmittance(run(spec, tf, ray), exact) <= Tolerances::analytic_limit_rel);
  }
  CHECK(max_rel(run("eq6", tf, ray), exact) > 1e-2);
}

TEST_CASE("eq7 keeps one opacity per cell: thick cells lose the background", "[methods][limits]") {
  // Eq. 7 is Eq. 6 written as an opacity; its transparency 1 - alpha cannot resolve e^{-x} below
  // half an ulp of 1, so for x = 50 it is exactly 0 where eq6 keeps e^{-50} (documented in
  // cell_approximations.cpp).
  const TransferFunctions tf = constant_tf({50.0, 50.0, 50.0}, {0.0, 0.0, 0.0});
  const Ray ray{{1.0, 1.0, 1.0}, {{1.0, 0.0, 1.0}}};
  CHECK(relative_error(run("eq6", tf, ray).intensity[0], std::exp(-50.0)) <=
        Tolerances::analytic_limit_rel);
  CHECK(run("eq7", tf, ray).intensity[0] == 0.0);
  CHECK(run("eq7", tf, ray).transmittance[0] == 0.0);
}

TEST_CASE("rho = 0: every method returns the background", "[methods][limits]") {
  const TransferFunctions tf = constant_tf({0.0, 0.0, 0.0}, {3.0, 0.5, 1e6});
  const Ray ray{{0.25, 1.5, 1e-200}, {{2.0, 0.0, 1.0}, {0.0, 1.0, 0.5}, {0.5, 1.0, 0.2}}};
  for (const std::string spec :
       {"riemann:n=5", "riemann:n=5:order=ftb", "riemann:dt=0.3", "riemann:correction=linear",
        "riemann:correction=none:ref_dt=0.1", "riemann:correction=exp:ref_dt=0.1", "rk4:n=3", "ode",
        "ode:rtol=1e-3", "eq5", "eq6", "eq7", "eq8", "particle"}) {
    const RayResult r = run(spec, tf, ray);
    for (int c = 0; c < kChannels; ++c) {
      INFO(spec << " channel " << c << " " << r.intensity[c]);
      CHECK(r.intensity[c] == ray.background[c]);
      CHECK(r.transmittance[c] == 1.0);
    }
  }
}

TEST_CASE("particle: one transfer function only, and then equal to exact", "[methods][particle]") {
  TransferFunctions single;
  const PiecewiseLinear rho{{0.0, 0.4, 1.0}, {0.5, 3.0, 0.2}};
  single.density = {rho, rho, rho};
  single.color = {constant(0.8), PiecewiseLinear{{0.0, 1.0}, {0.4, 0.4}}, constant(2.0)};
  Ray ray;
  ray.background = {0.1, 0.2, 0.0};
  ray.segments = {{0.6, 0.1, 0.9}, {1.5, 0.9, 0.3}, {0.0, 0.3, 0.3}, {0.25, 0.3, 0.3}};
  const RayResult exact = ExactIntegrator(single).integrate(ray, nullptr);
  Diagnostics diag;
  const RayResult particle = make("particle", single)->integrate(ray, &diag);
  INFO("particle vs exact " << max_rel(particle, exact));
  CHECK(max_rel(particle, exact) <= Tolerances::analytic_limit_rel);
  CHECK(max_rel_transmittance(particle, exact) <= Tolerances::analytic_limit_rel);
  CHECK(diag.stats["pieces"] > 0);

  auto refuses = [](const TransferFunctions& tf, const std::string& why) {
    try {
      make("particle", tf);
      FAIL("particle accepted a case with " << why);
    } catch (const std::invalid_argument& e) {
      const std::string msg = e.what();
      INFO(msg);
      CHECK(msg.rfind("particle: needs a single transfer function: ", 0) == 0);
      CHECK(msg.find(why) != std::string::npos);
    }
  };
  TransferFunctions two_densities = single;
  two_densities.density[2] = line(0.0, 0.5, 1.0, 0.2);
  refuses(two_densities, "density of channel b");
  TransferFunctions varying_colour = single;
  varying_colour.color[1] = line(0.0, 0.4, 1.0, 0.5);
  refuses(varying_colour, "colour of channel g");
}

TEST_CASE("method parameters are checked", "[methods][params]") {
  const SmoothCase sc;
  for (const std::string bad :
       {"riemann:n=0", "riemann:n=1.5", "riemann:n=8:dt=0.1", "riemann:dt=0", "riemann:dt=-1",
        "riemann:order=sideways", "riemann:correction=none", "riemann:correction=cubic",
        "riemann:correction=linear:ref_dt=0.1", "riemann:ref_dt=0", "rk4:n=0", "rk4:n=2.5",
        "ode:rtol=0", "ode:rtol=1e-20", "ode:rtol=2", "ode:atol=0", "ode:atol=-1", "eq5:n=3",
        "particle:n=3"}) {
    INFO(bad);
    CHECK_THROWS_AS(make(bad, sc.tf), std::invalid_argument);
  }
}

TEST_CASE("diagnostics count the work and change nothing", "[methods][diagnostics]") {
  const SmoothCase sc;
  const double segments = static_cast<double>(sc.ray.segments.size());
  struct Expect {
    std::string spec, stat;
    double value;  // < 0: only > 0 is required
  };
  for (const Expect& x : std::vector<Expect>{{"riemann:n=10", "samples", 10.0 * segments},
                                             {"riemann:n=10:order=ftb", "samples", 10.0 * segments},
                                             {"riemann:dt=0.125", "samples", 20.0},  // 2.5 / 0.125
                                             {"rk4:n=6", "steps", 6.0 * segments},
                                             {"ode", "steps", -1},
                                             {"eq5", "pieces", segments},
                                             {"eq6", "cells", segments},
                                             {"eq8", "cells", segments}}) {
    const auto m = make(x.spec, sc.tf);
    Diagnostics diag;
    const RayResult with = m->integrate(sc.ray, &diag);
    const RayResult without = m->integrate(sc.ray, nullptr);
    INFO(x.spec << " " << x.stat << " = " << diag.stats[x.stat]);
    if (x.value < 0) {
      CHECK(diag.stats[x.stat] > 0);
    } else {
      CHECK(diag.stats[x.stat] == x.value);
    }
    for (int c = 0; c < kChannels; ++c) {
      CHECK(with.intensity[c] == without.intensity[c]);
      CHECK(with.transmittance[c] == without.transmittance[c]);
    }
  }
}

TEST_CASE("budgets and non-finite results never crash", "[methods][budget]") {
  const TransferFunctions tf = constant_tf({1e7, 1e7, 1e7}, {0.5, 0.5, 0.5});
  const Ray ray{{1.0, 1.0, 1.0}, {{1.0, 0.0, 1.0}}};
  // ode: optical depth 1e7 needs ~3e6 explicit steps, over the budget -> NaN, and it says so.
  Diagnostics diag;
  const RayResult ode = make("ode", tf)->integrate(ray, &diag);
  CHECK(std::isnan(ode.intensity[0]));
  CHECK(diag.branches["step_budget_exhausted"] == 1);
  // rk4: rho h = 1e7 is far outside the stability region; it must return, whatever it returns.
  CHECK_NOTHROW(run("rk4:n=4", tf, ray));
  // riemann: exact per-sample opacity is unconditionally stable.
  const RayResult riemann = run("riemann:n=4", tf, ray);
  CHECK(relative_error(riemann.intensity[0], 0.5) <= Tolerances::analytic_limit_rel);
  // Fixed-step methods refuse a ray over their budget instead of running for minutes.
  CHECK_THROWS_AS(run("riemann:dt=1e-9", tf, ray), std::runtime_error);
  CHECK_THROWS_AS(run("riemann:n=100000000", tf, ray), std::runtime_error);
  CHECK_THROWS_AS(run("rk4:n=100000000", tf, ray), std::runtime_error);
}
