// The shared pieces of meshes and scenes: camera rays, PNG round trips, phase functions.
#include <catch2/catch.hpp>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <random>

#include "cli_harness.hpp"
#include "rayint/input/json_schema.hpp"
#include "rayint/input/json_source.hpp"
#include "rayint/optics/phase.hpp"
#include "rayint/geometry/camera.hpp"
#include "rayint/render/image.hpp"

using rayint::Camera;
using rayint::PhaseFunction;
using rayint::Vec3;
using rayint::test::TempDir;

TEST_CASE("camera: centre ray looks at look_at, corners span the field of view", "[camera]") {
  Camera cam;
  cam.position = Vec3(1, 2, 3);
  cam.look_at = Vec3(1, 2, -7);
  cam.width = 4;
  cam.height = 2;
  cam.fov_deg = 90.0;
  const auto centre = cam.ray_at(2.0, 1.0);
  CHECK((centre.direction - Vec3(0, 0, -1)).norm() < 1e-15);
  CHECK((centre.origin - cam.position).norm() == 0.0);
  // Top edge at tan(45 deg) = 1 above the axis; the left edge at aspect 2 on the left.
  const auto top = cam.ray_at(2.0, 0.0);
  CHECK(std::abs(top.direction.y() / -top.direction.z() - 1.0) < 1e-15);
  const auto left = cam.ray_at(0.0, 1.0);
  CHECK(std::abs(left.direction.x() / -left.direction.z() + 2.0) < 1e-15);

  cam.projection = Camera::Projection::orthographic;
  cam.ortho_height = 2.0;
  const auto corner = cam.ray_at(0.0, 0.0);
  CHECK((corner.direction - Vec3(0, 0, -1)).norm() < 1e-15);
  CHECK((corner.origin - Vec3(1 - 2, 2 + 1, 3)).norm() < 1e-15);
}

TEST_CASE("camera: JSON form is validated field by field", "[camera]") {
  const rayint::JsonSchema schema("cam.json");
  auto parse = [&](const char* text) {
    return schema.camera(rayint::json_source::parse(text, "cam.json"), "camera");
  };
  CHECK(parse(R"({"position":[0,0,5],"look_at":[0,0,0],"fov_deg":30,"width":8,"height":4})").width == 8);
  CHECK_THROWS_WITH(parse(R"({"position":[0,0,5],"look_at":[0,0,5],"fov_deg":30,"width":8,"height":4})"),
                    Catch::Contains("cam.json: camera: look_at must differ"));
  CHECK_THROWS_WITH(parse(R"({"position":[0,0,5],"look_at":[0,0,0],"width":8,"height":4})"),
                    Catch::Contains("exactly one of fov_deg"));
  CHECK_THROWS_WITH(parse(R"({"position":[0,0,5],"look_at":[0,0,0],"fov_deg":30,"width":0,"height":4})"),
                    Catch::Contains("camera.width"));
  CHECK_THROWS_WITH(parse(R"({"position":[0,0,5],"look_at":[0,0,0],"fov_deg":30,"width":8,"height":4,"zoom":1})"),
                    Catch::Contains("camera.zoom: unknown field"));
}

TEST_CASE("image: the 8-bit sRGB code by table equals the pow formula's at every code bound", "[image]") {
  // The per-sample formula the table replaces (and the PNG writer used): lround(255 srgb_encode).
  const auto by_pow = [](double v) { return static_cast<int>(std::lround(rayint::srgb_encode(v) * 255.0)); };
  // Each code bound, found by scanning up from just below the IEC 61966-2-1 crossing computed in
  // long double (independent of the table's construction), and 200 ulps either side of it.
  int bounds = 0;
  for (int q = 0; q < 255; ++q) {
    const long double y = (q + 0.5L) / 255.0L;
    const long double x = y <= 0.04045L ? y / 12.92L : std::pow((y + 0.055L) / 1.055L, 2.4L);
    double v = static_cast<double>(x);
    for (int k = 0; k < 200; ++k) v = std::nextafter(v, 0.0);
    for (int k = 0; k < 400; ++k, v = std::nextafter(v, 2.0)) {
      if (static_cast<int>(rayint::srgb_encode_8bit(v)) != by_pow(v)) FAIL("code " << q << " at v = " << v);
      if (by_pow(v) == q + 1 && by_pow(std::nextafter(v, 0.0)) == q) ++bounds;
    }
  }
  CHECK(bounds == 255);  // every crossing was inside the scanned window
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> wide(-0.5, 1.5);
  int mismatches = 0;
  for (int i = 0; i < 1000000; ++i) {
    const double v = i % 2 ? unit(rng) : wide(rng);
    mismatches += static_cast<int>(rayint::srgb_encode_8bit(v)) != by_pow(v);
  }
  CHECK(mismatches == 0);
  CHECK(rayint::srgb_encode_8bit(std::nan("")) == 0);
  CHECK(rayint::srgb_encode_8bit(-1.0) == 0);
  CHECK(rayint::srgb_encode_8bit(0.0) == 0);
  CHECK(rayint::srgb_encode_8bit(1.0) == 255);
  CHECK(rayint::srgb_encode_8bit(7.0) == 255);
  CHECK(rayint::srgb_encode_8bit(0.5) == 188);  // 255 (1.055 0.5^(1/2.4) - 0.055) = 187.52
}

TEST_CASE("image: PNG round trip keeps 8-bit values, sRGB encode/decode invert", "[image]") {
  for (double x : {0.0, 0.001, 0.0031308, 0.2, 0.5, 1.0})
    CHECK(std::abs(rayint::srgb_decode(rayint::srgb_encode(x)) - x) < 1e-12);
  rayint::Image img(5, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) img.at(x, y) = {x / 4.0, y / 2.0, 0.25};
  TempDir dir;
  const std::string path = (dir.path / "img.png").string();
  rayint::write_png(path, img, {1.0, false});
  const rayint::Image back = rayint::read_png(path, false);
  REQUIRE(back.width == 5);
  REQUIRE(back.height == 3);
  for (std::size_t i = 0; i < img.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) CHECK(std::abs(back.pixels[i][c] - img.pixels[i][c]) <= 0.5 / 255 + 1e-12);
  CHECK_THROWS_WITH(rayint::read_png((dir.path / "missing.png").string()), Catch::Contains("missing.png: cannot read PNG"));
}

namespace {
// Integral over the sphere of p(cos theta) * f(cos theta), by Gauss-Kronrod in mu.
template <class F>
double sphere_integral(const PhaseFunction& p, F f) {
  auto integrand = [&](double mu) { return 2.0 * M_PI * p.eval(mu) * f(mu); };
  return boost::math::quadrature::gauss_kronrod<double, 61>::integrate(integrand, -1.0, 1.0, 15, 1e-13);
}
}  // namespace

TEST_CASE("phase functions: normalized, mean cosine as stated, sampling follows the density",
          "[phase]") {
  const PhaseFunction phases[] = {PhaseFunction::isotropic(), PhaseFunction::henyey_greenstein(0.75),
                                  PhaseFunction::henyey_greenstein(-0.3),
                                  PhaseFunction::henyey_greenstein(0.0),
                                  PhaseFunction::lambert_sphere()};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const auto& p : phases) {
    INFO(p.name() << " g=" << p.g());
    CHECK(std::abs(sphere_integral(p, [](double) { return 1.0; }) - 1.0) < 1e-10);
    CHECK(std::abs(sphere_integral(p, [](double mu) { return mu; }) - p.mean_cosine()) < 1e-10);
    // Monte Carlo mean of sampled cosines: 200k samples, standard error <= 0.6/sqrt(2e5) = 1.3e-3.
    const Vec3 w_in = Vec3(0.3, -0.5, 0.8).normalized();
    double sum = 0.0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
      const Vec3 w = p.sample(w_in, u(rng), u(rng));
      REQUIRE(std::abs(w.norm() - 1.0) < 1e-12);
      sum += w.dot(w_in);
    }
    CHECK(std::abs(sum / n - p.mean_cosine()) < 5 * 1.3e-3);
  }
  CHECK_THROWS(PhaseFunction::henyey_greenstein(1.0));
}
