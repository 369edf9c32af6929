// test_vtk_methods.cpp -- the VTK peer methods (src/rayint/vtk/), built only with
// -DRAYINT_WITH_VTK=ON. Proves the translation of our transfer functions into VTK's (attenuation
// = rho, colour = kappa, near/far order, premultiplied RGBA + background) on cases where VTK's
// method is exact up to its float arithmetic, and that per-channel density is refused.
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "rayint/integrators/exact.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/vtk/vtk_integrators.hpp"
#include "../transfer_builders.hpp"

using namespace rayint;
using rayint::test::constant;
using rayint::test::line;
using rayint::test::uniform_tf;

namespace {

// VTK accumulates in float (24-bit mantissa) and evaluates Psi with Numerical Recipes' erfc fit
// (relative error <= 1.2e-7): a few float ulps per piece. The tolerance is 64 float epsilons.
constexpr double kFloatTol = 64.0 * 1.1920929e-7;

double max_rel(const RayResult& got, const RayResult& want) {
  double worst = 0.0;
  for (int c = 0; c < kChannels; ++c) {
    worst = std::max(worst, std::fabs(got.intensity[c] - want.intensity[c]) / std::fabs(want.intensity[c]));
    worst = std::max(worst, std::fabs(got.transmittance[c] - want.transmittance[c]) /
                                std::fabs(want.transmittance[c]));
  }
  return worst;
}

RayResult run(const std::string& method, const TransferFunctions& tf, const Ray& ray) {
  register_vtk_methods();
  return make_integrator(parse_method_spec(method), tf)->integrate(ray, nullptr);
}

}  // namespace

TEST_CASE("vtk_homogeneous equals exact on constant rho and kappa", "[vtk]") {
  TransferFunctions tf = uniform_tf(constant(0.7), constant(0.3));
  tf.color[1] = constant(0.6);  // per-channel colour is fine: VTK's colour is RGB
  tf.color[2] = constant(0.9);
  const Ray ray{{0.2, 0.4, 0.1}, {{1.0, 0.1, 0.9}, {0.5, 0.9, 0.4}, {2.0, 0.4, 0.4}}};
  const RayResult want = ExactIntegrator(tf).integrate(ray, nullptr);
  const double err = max_rel(run("vtk_homogeneous", tf, ray), want);
  INFO("max rel error " << err);
  CHECK(err < kFloatTol);
}

TEST_CASE("vtk_linear equals exact on transfer functions linear between breakpoints", "[vtk]") {
  TransferFunctions tf;
  for (int c = 0; c < kChannels; ++c) tf.density[c] = {{0.0, 0.3, 1.0}, {0.2, 1.5, 0.4}};
  tf.color[0] = {{0.0, 0.6, 1.0}, {1.0, 0.2, 0.5}};
  tf.color[1] = line(0.0, 0.1, 1.0, 0.9);
  tf.color[2] = {{0.0, 0.45, 1.0}, {0.3, 0.8, 0.0}};
  // Segments cross the breakpoints in both directions; the last leaves the range (clamped part).
  const Ray ray{{0.3, 0.2, 0.7},
                {{0.8, 0.0, 1.0}, {1.3, 0.9, 0.1}, {0.4, 0.2, 0.35}, {0.6, 0.5, 1.4}}};
  const RayResult want = ExactIntegrator(tf).integrate(ray, nullptr);
  const double err = max_rel(run("vtk_linear", tf, ray), want);
  INFO("max rel error " << err);
  CHECK(err < kFloatTol);
}

TEST_CASE("vtk methods: the segment order is near -> far", "[vtk]") {
  // A bright thin layer behind a dark absorber differs from the reverse by far more than float.
  const TransferFunctions tf = uniform_tf(line(0.0, 0.05, 1.0, 3.0), line(0.0, 1.0, 1.0, 0.0));
  const Ray ray{{0.0, 0.0, 0.0}, {{1.0, 0.0, 0.0}, {1.0, 1.0, 1.0}}};
  const RayResult want = ExactIntegrator(tf).integrate(ray, nullptr);
  const double err = max_rel(run("vtk_linear", tf, ray), want);
  INFO("max rel error " << err);
  CHECK(err < kFloatTol);
}

TEST_CASE("vtk methods refuse per-channel density as not applicable", "[vtk]") {
  register_vtk_methods();
  TransferFunctions tf = uniform_tf(constant(1.0), constant(0.5));
  tf.density[2] = constant(2.0);
  for (const char* m : {"vtk_linear", "vtk_partial_preint", "vtk_preint", "vtk_homogeneous"}) {
    INFO(m);
    try {
      make_integrator(parse_method_spec(m), tf);
      FAIL("accepted per-channel density");
    } catch (const std::invalid_argument& e) {
      CHECK(std::string(e.what()).find("not applicable") != std::string::npos);
    }
  }
}

TEST_CASE("vtk_preint: incremental and direct tables on one case", "[vtk]") {
  // The table methods are approximations; on a smooth case with a 128 x 128 x 256 table both
  // settings must land near exact (table spacing 1/127 in s, second-order in it). Measured:
  // the bound below is 10x the observed error, see the INFO line on failure.
  const TransferFunctions tf = uniform_tf(line(0.0, 0.5, 1.0, 1.5), line(0.0, 0.2, 1.0, 0.8));
  const Ray ray{{0.1, 0.1, 0.1}, {{0.5, 0.25, 0.75}}};
  const RayResult want = ExactIntegrator(tf).integrate(ray, nullptr);
  for (const char* m : {"vtk_preint:incremental=0", "vtk_preint:incremental=1"}) {
    const double err = max_rel(run(m, tf, ray), want);
    INFO(m << " max rel error " << err);
    CHECK(err < 1e-2);
  }
}

TEST_CASE("vtk methods: one integrator shared by two threads gives the sequential results bit for bit", "[vtk]") {
  // rayint render --compare vtk_* shares one integrator between its worker threads.
  register_vtk_methods();
  const TransferFunctions tf = uniform_tf(line(0.0, 0.2, 1.0, 3.0), line(0.0, 0.9, 1.0, 0.1));
  std::vector<Ray> rays;
  for (int i = 0; i < 400; ++i) {
    const double a = (i % 17) / 16.0, b = (i % 23) / 22.0;
    rays.push_back(Ray{{0.1, 0.2, 0.3}, {{0.5 + a, a, b}, {1.5 - b, b, 1.0 - a}}});
  }
  for (const char* method : {"vtk_linear", "vtk_partial_preint", "vtk_preint", "vtk_homogeneous"}) {
    INFO(method);
    const auto integrator = make_integrator(parse_method_spec(method), tf);
    std::vector<RayResult> sequential(rays.size()), parallel(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) sequential[i] = integrator->integrate(rays[i], nullptr);
    auto half = [&](std::size_t start) {
      for (std::size_t i = start; i < rays.size(); i += 2) parallel[i] = integrator->integrate(rays[i], nullptr);
    };
    std::thread t0(half, 0), t1(half, 1);
    t0.join();
    t1.join();
    bool same = true;
    for (std::size_t i = 0; i < rays.size(); ++i)
      for (int c = 0; c < kChannels; ++c)
        same = same && sequential[i].intensity[c] == parallel[i].intensity[c] &&
               sequential[i].transmittance[c] == parallel[i].transmittance[c];
    CHECK(same);
  }
}
