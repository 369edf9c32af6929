// core/math.hpp: the step weight (1 - e^{-x})/x and the attenuated length int_0^s e^{-sigma t} dt
// against their 50-digit values (Boost.Multiprecision cpp_bin_float_50), region by region, and
// their limits at x = 0 and x = inf.
#include <algorithm>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>

#include "rayint/core/math.hpp"
#include "tolerances.hpp"

using namespace rayint;
using rayint::test::Tolerances;

namespace {

using Real = boost::multiprecision::cpp_bin_float_50;

Real step_weight_50(const Real& x) {
  return x == 0 ? Real(1) : Real(-boost::multiprecision::expm1(Real(-x)) / x);
}

// |got - ref| / |ref| in units of epsilon = 2^-52.
double eps_error(double got, const Real& ref) {
  return static_cast<double>(abs(Real(got) - ref) / abs(ref)) /
         std::numeric_limits<double>::epsilon();
}

}  // namespace

TEST_CASE("step weight and attenuated length: error against 50 digits by region", "[math]") {
  std::mt19937_64 rng(13);
  // Regions of core/math.hpp: series below kStepWeightSeriesDepth, expm1 above.
  struct Region {
    const char* name;
    double log10_lo, log10_hi;
  };
  const Region regions[] = {{"series", -300.0, std::log10(kStepWeightSeriesDepth)},
                            {"expm1", std::log10(kStepWeightSeriesDepth), 3.0}};
  for (const Region& region : regions) {
    std::uniform_real_distribution<double> log_x(region.log10_lo, region.log10_hi);
    std::uniform_real_distribution<double> log_s(-3.0, 3.0);
    double worst_weight = 0.0, worst_length = 0.0;
    for (int i = 0; i < 100000; ++i) {
      const double x = std::pow(10.0, log_x(rng));
      if (!(x > 0.0) || x >= 1e3) continue;
      worst_weight = std::max(worst_weight, eps_error(step_weight(x), step_weight_50(Real(x))));
      const double s = std::pow(10.0, log_s(rng));
      const double sigma = x / s;
      const Real s50(s), sigma50(sigma);
      const Real length50 = s50 * step_weight_50(sigma50 * s50);
      worst_length = std::max(worst_length, eps_error(attenuated_length(sigma, s), length50));
    }
    WARN("region " << region.name << ": step_weight <= " << worst_weight
                   << " eps, attenuated_length <= " << worst_length << " eps");
    CHECK(worst_weight <= Tolerances::step_weight_eps);
    CHECK(worst_length <= Tolerances::attenuated_length_eps);
  }
}

TEST_CASE("step weight and attenuated length: limits", "[math]") {
  const double inf = std::numeric_limits<double>::infinity();
  CHECK(step_weight(0.0) == 1.0);
  CHECK(step_weight(inf) == 0.0);
  CHECK(attenuated_length(0.0, 2.5) == 2.5);
  CHECK(attenuated_length(2.0, 0.0) == 0.0);
  CHECK(attenuated_length(inf, 1.0) == 0.0);
  CHECK(std::fabs(kPi - std::acos(-1.0)) == 0.0);
}
