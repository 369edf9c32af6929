// The NeRF quadratures (integrators/nerf): pl_nerf is exact where its model holds (density linear
// between samples, constant colour), against the 50-digit reference; nerf and pl_nerf converge at
// their orders on a smooth ray (against `exact`, which test_exact.cpp and the first test here
// verify against the reference to 1e-13); NeRF 2020's last sample hides the background; the
// explicit-sample functions the Python module calls give the method's numbers; spec checking.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "rayint/integrators/exact.hpp"
#include "rayint/integrators/exact_batch.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/integrators/nerf.hpp"
#include "rayint/metrics/error_metrics.hpp"
#include "rayint/reference/reference.hpp"
#include "tolerances.hpp"
#include "smooth_ray.hpp"
#include "transfer_builders.hpp"

using namespace rayint;
using rayint::test::constant;
using rayint::test::line;
using rayint::test::max_rel;
using rayint::test::SmoothCase;
using rayint::test::Tolerances;

namespace {

// The tolerances of this file, with where they come from (kept beside the tests rather than in
// tolerances.hpp so that adding them does not rebuild every test).
struct NerfTolerances {
  // pl_nerf where its model holds (linear rho, constant kappa) against the 50-digit reference:
  // exact but for the rounding of up to 3 x 64 compounded steps; measured <= 5.1e-16 (intensity)
  // and 9.1e-16 (transmittance).
  static constexpr double pl_nerf_exact_rel = 1e-13;
  // Orders from n to 2n, n = 8..64, on the smooth ray: measured nerf 1.9993..2.0000 (mid),
  // 0.945..0.986 (near), pl_nerf 1.9993..2.0000 (mid colour), 1.0009..1.0034 (near colour); 0.1
  // as MethodTolerances::riemann_order_band.
  static constexpr double order_band = 0.1;
  // The explicit-sample functions against the methods on the same samples: the same operations
  // in the same order; measured 0 (bitwise equal).
  static constexpr double same_sum_rel = 1e-15;
  // nerf at=mid against pl_nerf where rho and kappa are linear over every interval: the midpoint
  // value times h is the trapezoid, so the two sums agree up to rounding of ~64 steps per segment.
  static constexpr double mid_vs_linear_rel = 1e-13;
};

RayResult run(const std::string& spec, const TransferFunctions& tf, const Ray& ray) {
  return make_integrator(parse_method_spec(spec), tf)->integrate(ray, nullptr);
}

// Orders from the errors at n and 2n, n = 8 .. 64.
std::vector<double> doubling_orders(const std::string& prefix) {
  const SmoothCase sc;
  const RayResult exact = ExactIntegrator(sc.tf).integrate(sc.ray, nullptr);
  std::vector<double> errors, orders;
  for (int n = 8; n <= 64; n *= 2) {
    errors.push_back(max_rel(run(prefix + std::to_string(n), sc.tf, sc.ray), exact));
    if (errors.size() > 1) orders.push_back(std::log2(errors[errors.size() - 2] / errors.back()));
  }
  return orders;
}

}  // namespace

TEST_CASE("pl_nerf is exact for linear density and constant colour", "[nerf]") {
  // Density linear over the whole scalar range (no breakpoint inside a segment), colour constant
  // per channel: PL-NeRF's model holds, so its only error is rounding, whatever n.
  TransferFunctions tf;
  tf.density = {line(0, 0.2, 1, 3.0), line(0, 2.0, 1, 0.1), line(0, 0.0, 1, 1.0)};
  tf.color = {constant(0.7), constant(1.3), constant(0.25)};
  Ray ray;
  ray.background = {0.3, 0.1, 0.6};
  ray.segments = {{1.5, 0.05, 0.9}, {0.6, 0.9, 0.4}, {2.0, 0.4, 0.0}};
  const ReferenceRay ref = reference_ray(tf, ray);
  for (const char* spec : {"pl_nerf:n=1", "pl_nerf:n=7", "pl_nerf:n=64", "pl_nerf:n=3:color=near"}) {
    const RayResult r = run(spec, tf, ray);
    for (int c = 0; c < kChannels; ++c) {
      INFO(spec << " channel " << c);
      CHECK(relative_error(r.intensity[c], ref.intensity[c]) <= NerfTolerances::pl_nerf_exact_rel);
      CHECK(relative_error(r.transmittance[c], ref.transmittance[c]) <=
            NerfTolerances::pl_nerf_exact_rel);
    }
  }
}

TEST_CASE("nerf and pl_nerf converge at their orders on a smooth ray", "[nerf][convergence]") {
  const SmoothCase sc;
  // The independent check of the comparison value itself.
  const ReferenceRay ref = reference_ray(sc.tf, sc.ray);
  const RayResult exact = ExactIntegrator(sc.tf).integrate(sc.ray, nullptr);
  for (int c = 0; c < kChannels; ++c)
    REQUIRE(relative_error(exact.intensity[c], ref.intensity[c]) <= Tolerances::exact_rel);
  struct Expect {
    const char* prefix;
    double order;
  };
  for (const Expect& e : {Expect{"nerf:n=", 2.0}, Expect{"nerf:at=near:n=", 1.0},
                          Expect{"pl_nerf:n=", 2.0}, Expect{"pl_nerf:color=near:n=", 1.0}}) {
    for (const double p : doubling_orders(e.prefix)) {
      INFO(e.prefix << " order " << p);
      CHECK(std::fabs(p - e.order) <= NerfTolerances::order_band);
    }
  }
}

TEST_CASE("nerf at midpoints and pl_nerf coincide where the transfer functions are linear",
          "[nerf]") {
  // On an interval where rho and kappa are linear, rho(mid) h = (rho_0 + rho_1) h / 2 and
  // kappa(mid) = (kappa_0 + kappa_1) / 2: the two quadratures are the same sum. They differ only
  // on intervals with a transfer-function breakpoint inside (and on NeRF's explicit samples,
  // where nerf's sample sits at an interval's end).
  const SmoothCase sc;  // no breakpoint inside any segment
  for (const int n : {1, 5, 64}) {
    const RayResult mid = run("nerf:n=" + std::to_string(n), sc.tf, sc.ray);
    const RayResult lin = run("pl_nerf:n=" + std::to_string(n), sc.tf, sc.ray);
    INFO("n " << n);
    CHECK(max_rel(mid, lin) <= NerfTolerances::mid_vs_linear_rel);
  }
}

TEST_CASE("nerf with last=inf: NeRF 2020's last sample hides the background", "[nerf]") {
  const SmoothCase sc;  // density > 0 at the far end of the ray in every channel
  Ray black = sc.ray, white = sc.ray;
  black.background = {0.0, 0.0, 0.0};
  white.background = {1.0, 1.0, 1.0};
  const RayResult a = run("nerf:n=16:at=near:last=inf", sc.tf, black);
  const RayResult b = run("nerf:n=16:at=near:last=inf", sc.tf, white);
  const RayResult open = run("nerf:n=16:at=near", sc.tf, white);
  for (int c = 0; c < kChannels; ++c) {
    CHECK(a.transmittance[c] == 0.0);
    CHECK(a.intensity[c] == b.intensity[c]);
    CHECK(open.transmittance[c] > 0.05);  // without it the background shows
  }
}

TEST_CASE("the explicit-sample functions give the methods' numbers", "[nerf]") {
  // One segment, constant scalar gradient: the samples the method takes, handed over explicitly
  // (what the Python module's nerf_composite / pl_nerf_composite do), must give the same sums.
  const SmoothCase sc;
  Ray ray;
  ray.segments = {{1.3, 0.9, 0.2}};
  const int n = 10;
  const double h = 1.3 / n;
  std::vector<double> sigma, colour, delta(n + 1, h);
  for (int c = 0; c < kChannels; ++c) {
    sigma.clear();
    colour.clear();
    for (int k = 0; k < n; ++k) {  // midpoints, from the eye outward
      const double s = 0.2 + ((k + 0.5) / n) * (0.9 - 0.2);
      sigma.push_back(sc.tf.density[c](s));
      colour.push_back(sc.tf.color[c](s));
    }
    const CompositeResult mid = nerf_composite(sigma.data(), colour.data(), delta.data(), n);
    const RayResult m = run("nerf:n=10", sc.tf, ray);
    CHECK(relative_error(mid.emission, m.intensity[c]) <= NerfTolerances::same_sum_rel);
    CHECK(relative_error(mid.transmittance, m.transmittance[c]) <= NerfTolerances::same_sum_rel);
    sigma.clear();
    colour.clear();
    for (int k = 0; k <= n; ++k) {  // interval ends, from the eye outward
      const double s = k == n ? 0.9 : 0.2 + (static_cast<double>(k) / n) * (0.9 - 0.2);
      sigma.push_back(sc.tf.density[c](s));
      colour.push_back(sc.tf.color[c](s));
    }
    const CompositeResult pl = pl_nerf_composite(sigma.data(), colour.data(), delta.data(), n, true);
    const RayResult p = run("pl_nerf:n=10", sc.tf, ray);
    CHECK(relative_error(pl.emission, p.intensity[c]) <= NerfTolerances::same_sum_rel);
    CHECK(relative_error(pl.transmittance, p.transmittance[c]) <= NerfTolerances::same_sum_rel);
  }
}

TEST_CASE("nerf and pl_nerf specs are checked", "[nerf]") {
  const SmoothCase sc;
  for (const char* bad : {"nerf:n=0", "nerf:n=2.5", "nerf:at=far", "nerf:last=1e10",
                          "pl_nerf:color=left", "pl_nerf:at=mid"}) {
    INFO(bad);
    CHECK_THROWS_AS(make_integrator(parse_method_spec(bad), sc.tf), std::invalid_argument);
  }
  Ray huge = sc.ray;
  huge.segments.assign(4, {1.0, 0.1, 0.9});
  CHECK_THROWS_AS(run("nerf:n=20000000", sc.tf, huge), std::runtime_error);
}
