// The scene references must not be fooled by features that fall between quadrature nodes.
//
// A global adaptive Gauss-Kronrod integral started from one panel stops at once when all 15
// nodes of that panel miss a feature: the K15 - G7 estimate is then zero. A ray clipping the
// edge of Max's cloud did exactly that (reference T = 1, true T = 0.88 at pixel (24, 24) of the
// 64 x 64 shadowed figure), and the "error" of every approximation on that pixel was the
// reference's. The references now start from panels no longer than the medium's
// feature_length(); these tests fail without that.
#include <catch2/catch.hpp>
#include <cmath>

#include "rayint/scene/term_references.hpp"
#include "scene_builders.hpp"

using namespace rayint;
using namespace rayint::test;
using nlohmann::json;

TEST_CASE("scene references: a bump between the nodes of one panel is found with short panels", "[scene]") {
  // A Gaussian bump of width 1e-3 at 0.5123 on [0, 1]: far from every node of GK15 on [0, 1].
  const auto f = [](double t) -> Rgb {
    const double v = std::exp(-std::pow((t - 0.5123) / 1e-3, 2));
    return {v, v, v};
  };
  const double truth = 1e-3 * std::sqrt(std::acos(-1.0));
  QuadratureOptions one;  // panel_length infinite: one starting panel
  const QuadratureResult fooled = integrate_adaptive(f, 0.0, 1.0, one);
  CHECK(fooled.value[0] < 1e-3 * truth);  // documents the failure the panels guard against
  QuadratureOptions panels;
  panels.panel_length = 1e-3;
  const QuadratureResult found = integrate_adaptive(f, 0.0, 1.0, panels);
  CHECK(found.converged);
  CHECK(found.value[0] == Approx(truth).epsilon(1e-9));
}

TEST_CASE("scene references: the cloud's transmittance on rays clipping its edge matches brute force", "[scene]") {
  const json camera = {{"position", {0, 0.15, 4.2}}, {"look_at", {0, 0.15, 0}}, {"fov_deg", 30}, {"width", 64}, {"height", 64}};
  const Scene scene = scene_from({{"medium", {{"type", "cloud"}, {"preset", "max1995"}, {"seed", 7}}},
                                  {"transfer", {{"extinction", {{0, 0}, {1, 10}}}, {"albedo", {{0, 0.9}}}}},
                                  {"camera", camera},
                                  {"effects", {"absorption"}}});
  REQUIRE(scene.camera);
  REQUIRE(scene.medium.field().feature_length() < 0.05);
  // Pixels whose rays graze the cloud (the first two were fooled) and one through its middle.
  for (const auto& [x, y] : {std::pair{24, 24}, std::pair{8, 24}, std::pair{40, 24}}) {
    INFO("pixel " << x << ", " << y);
    const ViewRay ray = scene.camera->ray_for_pixel(x, y);
    const RaySpan span = scene.medium.bounds().clip(ray);
    REQUIRE(span.hit);
    // Brute force: 400,000 midpoint samples, error O(h^2) on a Lipschitz density.
    const long n = 400000;
    const double h = (span.t_exit - span.t_enter) / n;
    double tau = 0.0;
    for (long m = 0; m < n; ++m)
      tau += scene.medium.extinction(ray.origin + ray.direction * (span.t_enter + (static_cast<double>(m) + 0.5) * h))[0] * h;
    const ReferenceValue ref = reference_transmittance(scene, ray);
    CHECK(ref.converged);
    CHECK(ref.value[0] == Approx(std::exp(-tau)).epsilon(1e-6));
    CHECK(std::exp(-tau) < 0.999);  // the ray does cross some cloud
  }
}
