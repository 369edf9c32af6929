// The vector erfcx, Dawson, Exp and Expm1 of special/erfcx_simd* (Google Highway) against the
// 50-digit reference (reference/special_reference.*) and against libcerf, over their regions.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <vector>

#include "rayint/metrics/error_metrics.hpp"
#include "rayint/reference/special_reference.hpp"
#include "rayint/special/erfcx_simd.hpp"
#include "rayint/special/simd_tables.hpp"
#include "rayint/special/special_functions.hpp"
#include "simd_targets.hpp"
#include "tolerances.hpp"

using namespace rayint;
using rayint::test::SimdTolerances;

namespace {

// x >= 0 covering both regions: linear steps on [0, 24] (the table and the start of the
// asymptotic region), each table interval's ends and the 16 boundary to the ulp, and
// log-spaced points from 1e-300 to 1e6.
std::vector<double> arguments() {
  std::vector<double> x{0.0, 5e-324, 1e-300, 1e-20, 1e-8};
  for (int i = 0; i <= 1500; ++i) x.push_back(24.0 * i / 1500 + 1e-3 * (i % 7));
  for (int i = 0; i <= special::kSimdTableIntervals; ++i) {
    const double edge = i * special::kSimdTableStep;
    x.push_back(edge);
    x.push_back(std::nextafter(edge, 0.0));
    x.push_back(std::nextafter(edge, 100.0));
  }
  for (int i = 0; i <= 600; ++i) x.push_back(std::pow(10.0, -300.0 + 306.0 * i / 600));
  return x;
}

struct Measured {
  double max_ref = 0.0, at_ref = 0.0;    // against 50 digits
  double max_cerf = 0.0, at_cerf = 0.0;  // against libcerf
};

template <class Vec, class Ref, class Cerf>
Measured measure(Vec vec, Ref ref, Cerf cerf) {
  const std::vector<double> x = arguments();
  std::vector<double> y(x.size());
  vec(x.data(), y.data(), x.size());
  Measured m;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const ExtendedValue r = ref(x[i]);
    const double e = r.hi == 0.0 ? std::fabs(y[i]) : relative_error(y[i], r);
    if (!(e <= m.max_ref)) m.max_ref = e, m.at_ref = x[i];
    const double c = cerf(x[i]);
    const double ec = c == 0.0 ? std::fabs(y[i]) : std::fabs(y[i] - c) / std::fabs(c);
    if (!(ec <= m.max_cerf)) m.max_cerf = ec, m.at_cerf = x[i];
  }
  return m;
}

// One vector function's measurement against its bound `ref_rel` (50 digits) and libcerf's, then
// reported as `name`_simd with the target it ran on.
void check_measured(const char* name, const Measured& m, double ref_rel) {
  INFO("target " << special::simd_target_name() << ": max rel vs 50 digits " << m.max_ref << " at x = "
                 << m.at_ref << ", vs libcerf " << m.max_cerf << " at x = " << m.at_cerf);
  CHECK(m.max_ref <= ref_rel);
  CHECK(m.max_cerf <= SimdTolerances::vs_libcerf_rel);
  WARN(name << "_simd (" << special::simd_target_name() << "): max rel " << m.max_ref << " at " << m.at_ref
            << "; vs libcerf " << m.max_cerf << " at " << m.at_cerf);
}

}  // namespace

TEST_CASE("vector erfcx against 50 digits and libcerf", "[special_simd]") {
  check_measured("erfcx", measure(special::erfcx_array, erfcx_reference, special::erfcx), SimdTolerances::erfcx_rel);
}

TEST_CASE("vector erfcx and Dawson on every SIMD target this CPU runs", "[special_simd][simd_targets]") {
  rayint::test::for_each_simd_target([] {
    const Measured e = measure(special::erfcx_array, erfcx_reference, special::erfcx);
    const Measured w = measure(special::dawson_array, dawson_reference, special::dawson);
    INFO("target " << special::simd_target_name() << ": erfcx max rel " << e.max_ref << " at x = " << e.at_ref
                   << ", Dawson " << w.max_ref << " at x = " << w.at_ref);
    CHECK(e.max_ref <= SimdTolerances::erfcx_rel);
    CHECK(w.max_ref <= SimdTolerances::dawson_rel);
    CHECK(e.max_cerf <= SimdTolerances::vs_libcerf_rel);
    CHECK(w.max_cerf <= SimdTolerances::vs_libcerf_rel);
  });
}

TEST_CASE("vector Dawson against 50 digits and libcerf", "[special_simd]") {
  check_measured("dawson", measure(special::dawson_array, dawson_reference, special::dawson), SimdTolerances::dawson_rel);
}

TEST_CASE("vector erfcx and Dawson: limits and special values", "[special_simd]") {
  const double x[] = {0.0, 1e300, INFINITY, NAN};
  double e[4], dw[4];
  special::erfcx_array(x, e, 4);
  special::dawson_array(x, dw, 4);
  CHECK(e[0] == 1.0);
  CHECK(dw[0] == 0.0);
  CHECK(relative_error(e[1], 1.0 / (1e300 * std::sqrt(M_PI))) <= 4e-16);
  CHECK(relative_error(dw[1], 0.5e-300) <= 4e-16);
  CHECK(e[2] == 0.0);
  CHECK(dw[2] == 0.0);
  CHECK(std::isnan(e[3]));
  CHECK(std::isnan(dw[3]));
}

TEST_CASE("Highway Exp and Expm1 on the ranges exact_batch uses, against 50 digits",
          "[special_simd]") {
  using reference_detail::Real;
  // exp(-T), T in [0, 745] (below, 0); expm1(-t), t in [0, 1] (thin pieces) and [1, 50] (q2).
  std::vector<double> xe, xm;
  for (int i = 0; i <= 3000; ++i) xe.push_back(-745.0 * i / 3000 - 1e-3 * (i % 5));
  for (int i = 0; i <= 2000; ++i) xm.push_back(-1.0 * i / 2000);
  for (int i = 0; i <= 300; ++i) xm.push_back(-std::pow(10.0, -300.0 + 300.0 * i / 300));
  for (int i = 0; i <= 1000; ++i) xm.push_back(-1.0 - 49.0 * i / 1000);
  std::vector<double> ye(xe.size()), ym(xm.size());
  special::exp_array(xe.data(), ye.data(), xe.size());
  special::expm1_array(xm.data(), ym.data(), xm.size());
  double max_exp = 0.0, max_expm1 = 0.0, at_exp = 0.0, at_expm1 = 0.0;
  for (std::size_t i = 0; i < xe.size(); ++i) {
    const ExtendedValue r = reference_detail::to_extended(exp(Real(xe[i])));
    if (underflowed(r)) continue;
    const double u = ulp_error(ye[i], r);
    if (u > max_exp) max_exp = u, at_exp = xe[i];
  }
  for (std::size_t i = 0; i < xm.size(); ++i) {
    const ExtendedValue r = reference_detail::to_extended(expm1(Real(xm[i])));
    const double u = ulp_error(ym[i], r);
    if (u > max_expm1) max_expm1 = u, at_expm1 = xm[i];
  }
  WARN("Highway Exp max " << max_exp << " ulp at " << at_exp << ", Expm1 max " << max_expm1
                          << " ulp at " << at_expm1);
  CHECK(max_exp <= SimdTolerances::exp_ulp);
  CHECK(max_expm1 <= SimdTolerances::expm1_ulp);
  const double big[] = {-1000.0, -1e300};
  double out[2];
  special::exp_array(big, out, 2);
  CHECK(out[0] == 0.0);
  CHECK(out[1] == 0.0);
}

TEST_CASE("exp_neg_array (the gradient's transmittance) against 50 digits, on every SIMD target",
          "[special_simd][simd_targets]") {
  using reference_detail::Real;
  // x in [0, 745]: uniform, log-spaced from 1e-300, each table step's ends (k ln2/32) and their
  // neighbours, and the vector range's end 700 with what lies beyond (std::exp there).
  std::vector<double> x{0.0, 5e-324, 1e-300, 700.0, 700.5, 708.0, 745.0, 746.0};
  for (int i = 0; i <= 4000; ++i) x.push_back(690.0 * i / 4000 + 1e-4 * (i % 7));
  for (int i = 0; i <= 100; ++i) x.push_back(690.0 + 60.0 * i / 100);
  for (int i = 0; i <= 600; ++i) x.push_back(std::pow(10.0, -300.0 + 302.8 * i / 600));
  for (int k = 0; k <= 1000; ++k) {
    const double e = k * 0.6931471805599453 / 32;
    for (const double v : {e, std::nextafter(e, 0.0), std::nextafter(e, 1e9), e + 0.6931471805599453 / 64})
      x.push_back(v);
  }
  std::vector<Real> ref(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) ref[i] = exp(-Real(x[i]));
  rayint::test::for_each_simd_target([&] {
    std::vector<double> y(x.size());
    special::exp_neg_array(x.data(), y.data(), x.size());
    double max_ulp = 0.0, at = 0.0, max_std = 0.0;
    std::size_t differ = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const ExtendedValue r = reference_detail::to_extended(ref[i]);
      if (x[i] > 700.0) {  // std::exp's lanes
        CHECK(y[i] == std::exp(-x[i]));
        continue;
      }
      const double u = ulp_error(y[i], r);
      if (u > max_ulp) max_ulp = u, at = x[i];
      max_std = std::max(max_std, ulp_error(std::exp(-x[i]), r));
      differ += y[i] != std::exp(-x[i]);
    }
    WARN("target " << special::simd_target_name() << ": exp_neg_array max " << max_ulp << " ulp at x = " << at
                   << "; " << differ << " of " << x.size() << " differ from std::exp (its max " << max_std << " ulp)");
    CHECK(max_ulp <= SimdTolerances::exp_neg_ulp);
  });
}

TEST_CASE("the dispatch names its target", "[special_simd]") {
  const char* name = special::simd_target_name();
  REQUIRE(name != nullptr);
  CHECK(std::strlen(name) > 0);
}
