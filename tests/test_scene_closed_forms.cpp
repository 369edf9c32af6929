// Closed forms that the scene path must reproduce (issue 6). Every expected value is derived
// here, in the test, from the physics, never from the code under test:
//  - homogeneous transmittance T = exp(-sigma L);
//  - emission only I = B + eps L (eps = kappa sigma);
//  - emission plus absorption with a constant source I = B e^{-sigma L} + kappa (1 - e^{-sigma L});
//  - single scattering from a homogeneous slab of optical thickness tau0, albedo a, lit by a
//    beam of irradiance F (perpendicular to the beam) at cosine mu0, seen at cosine mu. With
//    tau measured from the lit (top) face and ds = dtau / (sigma mu) along the viewing ray:
//      reflected   I_R = a p F mu0/(mu0 + mu) (1 - exp(-tau0 (1/mu0 + 1/mu)))
//      transmitted I_T = a p F mu0/(mu0 - mu) (exp(-tau0/mu0) - exp(-tau0/mu)),  mu != mu0
//                  I_T = a p F tau0/mu0 exp(-tau0/mu0),                          mu == mu0
//      without shadows (T_L = 1) reflected I_R = a p F (1 - exp(-tau0/mu));
//  - Henyey-Greenstein normalisation and mean cosine, integrated over the sphere of viewing
//    directions from inside a box.
#include <boost/math/quadrature/gauss.hpp>
#include <catch2/catch.hpp>
#include <cmath>

#include "rayint/core/math.hpp"
#include "scene_builders.hpp"

using namespace rayint;
using namespace rayint::test;
using nlohmann::json;

namespace {

double hg(double g, double cos_theta) {
  return (1 - g * g) / (4 * kPi * std::pow(1 + g * g - 2 * g * cos_theta, 1.5));
}

double rel(double got, double want) { return std::abs(got - want) / std::abs(want); }

json box_scene(double sigma, const json& effects, const json& rays) {
  return {{"medium", {{"type", "homogeneous"}, {"shape", "box"}, {"density", 1.0},
                      {"lower", {-1, -1, -1}}, {"upper", {1, 1, 1}}}},
          {"transfer", {{"extinction", {{0, 0}, {1, sigma}}}, {"emission", {{0, 0.8}}}}},
          {"background", {{"color", {0.5, 1.0, 2.0}}}},
          {"effects", effects},
          {"rays", rays}};
}

// Two rays through the box [-1,1]^3: along -z (L = 2) and oblique (L = 2/|d_z|, staying inside
// the side faces: |x|, |y| < 1 at both faces).
json two_rays() {
  return json::array({ray_json(Vec3(0.2, -0.1, 5), Vec3(0, 0, -1)),
                      ray_json(Vec3(0.3, -0.2, 5), Vec3(0.03, 0.02, -1).normalized())});
}
double length_of(int i) { return i == 0 ? 2.0 : 2.0 / Vec3(0.03, 0.02, -1).normalized().z() * -1.0; }

}  // namespace

TEST_CASE("scene: homogeneous transmittance exp(-sigma L), every method and the reference", "[scene]") {
  const double sigma = 1.7;
  for (const char* method : {"exact", "riemann:n=7"}) {
    json j = box_scene(sigma, {"absorption"}, two_rays());
    j["methods"] = {{"absorption", method}};
    const SceneRenderResult r = render_rays(scene_from(j), true);
    for (int i = 0; i < 2; ++i) {
      const Rgb t = term_of(r, "absorption", static_cast<std::size_t>(i));
      const double T = std::exp(-sigma * length_of(i));
      CHECK(rel(t[0], 0.5 * T) < 1e-14);
      CHECK(rel(t[2], 2.0 * T) < 1e-14);
    }
    // the reference agrees with the closed form too: the error it reports is the method's
    CHECK(report_of(r, "absorption").error.max_abs < 1e-14);
  }
}

TEST_CASE("scene: emission only I = B + eps L", "[scene]") {
  const double sigma = 1.7, kappa = 0.8;
  for (const char* method : {"exact", "riemann:n=5"}) {
    json j = box_scene(sigma, {"emission"}, two_rays());
    j["methods"] = {{"emission", method}};
    const SceneRenderResult r = render_rays(scene_from(j), true);
    for (int i = 0; i < 2; ++i) {
      const double L = length_of(i);
      const Rgb px = r.image.pixels[static_cast<std::size_t>(i)];
      CHECK(rel(px[0], 0.5 + kappa * sigma * L) < 1e-14);
      CHECK(rel(px[2], 2.0 + kappa * sigma * L) < 1e-14);
    }
    CHECK(report_of(r, "emission").error.max_rel_to_peak < 1e-12);
  }
}

TEST_CASE("scene: emission plus absorption with a constant source", "[scene]") {
  const double sigma = 1.7, kappa = 0.8;
  for (const char* method : {"exact", "riemann:n=3"}) {
    json j = box_scene(sigma, {"absorption", "emission"}, two_rays());
    j["methods"] = {{"absorption", method}, {"emission", method}};
    const SceneRenderResult r = render_rays(scene_from(j), true);
    for (int i = 0; i < 2; ++i) {
      const double T = std::exp(-sigma * length_of(i));
      const Rgb px = r.image.pixels[static_cast<std::size_t>(i)];
      CHECK(rel(px[0], 0.5 * T + kappa * (1 - T)) < 1e-14);
      CHECK(rel(px[2], 2.0 * T + kappa * (1 - T)) < 1e-14);
    }
    CHECK(r.total_error.max_rel_to_peak < 1e-12);
  }
}

namespace {

struct SlabSetup {
  double sigma = 2.0, H = 0.4, albedo = 0.7, F = 2.0, g = 0.5, mu0 = 0.6;
  double tau0() const { return sigma * H; }
  Vec3 light_dir() const { return Vec3(std::sqrt(1 - mu0 * mu0), 0, -mu0); }
  // A viewing ray seeing light that leaves the slab at cosine mu (upward when reflected,
  // downward when transmitted) at azimuth phi.
  ViewRay view(double mu, double phi, bool reflected) const {
    const double s = std::sqrt(1 - mu * mu);
    const Vec3 w_eye(s * std::cos(phi), s * std::sin(phi), reflected ? mu : -mu);
    return {Vec3(0.1, 0.2, reflected ? H + 3 : -3) + w_eye * 0.0, -w_eye};
  }
  json scene(const json& effects, const json& rays, const json& methods) const {
    return {{"medium", {{"type", "homogeneous"}, {"shape", "slab"}, {"density", 1.0}, {"z", {0.0, H}}}},
            {"transfer", {{"extinction", {{0, 0}, {1, sigma}}}, {"albedo", {{0, albedo}}}}},
            {"lights", {{{"type", "directional"}, {"direction", {light_dir().x(), 0, light_dir().z()}}, {"intensity", F}}}},
            {"phase", {{"type", "henyey_greenstein"}, {"g", g}}},
            {"effects", effects},
            {"methods", methods},
            {"reference", {{"rtol", 1e-11}}},
            {"rays", rays}};
  }
};

}  // namespace

TEST_CASE("scene: single scattering from a homogeneous slab, reflected and transmitted", "[scene]") {
  const SlabSetup s;
  const double mus[] = {0.3, 0.6, 0.9};  // 0.6 == mu0
  const double phis[] = {0.0, 1.0};
  json rays = json::array();
  std::vector<double> expected, expected_unshadowed;
  for (bool reflected : {true, false})
    for (double mu : mus)
      for (double phi : phis) {
        const ViewRay v = s.view(mu, phi, reflected);
        rays.push_back(ray_json(v.origin, v.direction));
        const double p = hg(s.g, s.light_dir().dot(-v.direction));
        const double a = s.albedo, F = s.F, t0 = s.tau0(), m0 = s.mu0;
        if (reflected) {
          expected.push_back(a * p * F * m0 / (m0 + mu) * (1 - std::exp(-t0 * (1 / m0 + 1 / mu))));
          expected_unshadowed.push_back(a * p * F * (1 - std::exp(-t0 / mu)));
        } else {
          expected.push_back(mu == m0 ? a * p * F * t0 / m0 * std::exp(-t0 / m0)
                                      : a * p * F * m0 / (m0 - mu) * (std::exp(-t0 / m0) - std::exp(-t0 / mu)));
          expected_unshadowed.push_back(std::nan(""));
        }
      }
  // The reference (nested adaptive quadrature) against the closed forms.
  const Scene shadowed = scene_from(s.scene({"absorption", "single_scattering", "shadows"}, rays,
                                            {{"single_scattering", "riemann:n=64"}, {"shadows", "shadow_rays:n=4"}}));
  ScenePipeline pipe(shadowed, 1);
  const Effect& ss = *pipe.effects().at(1);
  REQUIRE(ss.name() == "single_scattering");
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const ReferenceValue ref = ss.reference(pipe.ray(static_cast<long long>(i)));
    INFO("ray " << i << " expected " << expected[i] << " reference " << ref.value[0]);
    CHECK(ref.converged);
    CHECK(rel(ref.value[0], expected[i]) < 1e-9);
  }
  // Riemann sums with shadow rays converge to it at second order (midpoint rule): the error
  // falls by ~4 when n doubles.
  auto max_err = [&](int n) {
    const Scene sc = scene_from(s.scene({"absorption", "single_scattering", "shadows"}, rays,
                                        {{"single_scattering", "riemann:n=" + std::to_string(n)},
                                         {"shadows", "shadow_rays:n=1"}}));
    const SceneRenderResult r = render_rays(sc);
    double e = 0;
    for (std::size_t i = 0; i < expected.size(); ++i)
      e = std::max(e, rel(term_of(r, "single_scattering", i)[0], expected[i]));
    return e;
  };
  const double e32 = max_err(32), e64 = max_err(64);
  CHECK(e64 < 1e-3);
  CHECK(e32 / e64 > 3.5);
  CHECK(e32 / e64 < 4.5);
  // Without shadows the reflected light is a p F (1 - exp(-tau0/mu)).
  const Scene unshadowed = scene_from(s.scene({"absorption", "single_scattering"}, rays, json::object()));
  ScenePipeline pipe2(unshadowed, 1);
  for (std::size_t i = 0; i < expected.size(); ++i) {
    if (std::isnan(expected_unshadowed[i])) continue;
    const ReferenceValue ref = pipe2.effects().at(1)->reference(pipe2.ray(static_cast<long long>(i)));
    CHECK(rel(ref.value[0], expected_unshadowed[i]) < 1e-9);
  }
}

TEST_CASE("scene: phase functions integrate to 1 with mean cosine g over viewing directions", "[scene]") {
  // The eye at the centre of the box [-1,1]^3, no absorption, no shadows: the single-scattering
  // term along direction d is sigma_s E p(w_L . -d) l(d) with l(d) = 1/max|d_i| (constant medium:
  // one midpoint sample is exact). Dividing by sigma_s E l(d) and integrating over the sphere
  // with Gauss-Legendre in cos(theta) and the trapezoid rule in phi gives the normalisation and,
  // weighted by w_L . -d, the mean cosine.
  using GL = boost::math::quadrature::gauss<double, 40>;
  std::vector<double> x, w;
  for (std::size_t i = 0; i < GL::abscissa().size(); ++i) {
    x.push_back(GL::abscissa()[i]);
    w.push_back(GL::weights()[i]);
    if (GL::abscissa()[i] != 0.0) {
      x.push_back(-GL::abscissa()[i]);
      w.push_back(GL::weights()[i]);
    }
  }
  const int nphi = 160;
  const double sigma = 0.3, albedo = 0.8, E = 1.5;
  const Vec3 wl = Vec3(0.3, -0.5, -0.8).normalized();
  json rays = json::array();
  std::vector<double> weight, cosang, len;
  for (std::size_t i = 0; i < x.size(); ++i)
    for (int k = 0; k < nphi; ++k) {
      const double phi = 2 * kPi * k / nphi, st = std::sqrt(1 - x[i] * x[i]);
      const Vec3 d(st * std::cos(phi), st * std::sin(phi), x[i]);
      rays.push_back(ray_json(Vec3::Zero(), d));
      weight.push_back(w[i] * 2 * kPi / nphi);
      cosang.push_back(wl.dot(-d));
      len.push_back(1.0 / d.cwiseAbs().maxCoeff());
    }
  struct Expect { json phase; double mean; };
  const Expect cases[] = {{{{"type", "henyey_greenstein"}, {"g", 0.5}}, 0.5},
                          {{{"type", "henyey_greenstein"}, {"g", -0.3}}, -0.3},
                          {{{"type", "isotropic"}}, 0.0},
                          {{{"type", "lambert_sphere"}}, -4.0 / 9.0}};
  for (const Expect& c : cases) {
    const json j = {{"medium", {{"type", "homogeneous"}, {"shape", "box"}, {"density", 1.0},
                                {"lower", {-1, -1, -1}}, {"upper", {1, 1, 1}}}},
                    {"transfer", {{"extinction", {{0, sigma}}}, {"albedo", {{0, albedo}}}}},
                    {"lights", {{{"type", "directional"}, {"direction", {wl.x(), wl.y(), wl.z()}}, {"intensity", E}}}},
                    {"phase", c.phase},
                    {"effects", {"single_scattering"}},
                    {"methods", {{"single_scattering", "riemann:n=1"}}},
                    {"rays", rays}};
    const SceneRenderResult r = render_rays(scene_from(j), false, 2);
    double norm = 0, mean = 0;
    for (std::size_t i = 0; i < weight.size(); ++i) {
      const double p = term_of(r, "single_scattering", i)[1] / (sigma * albedo * E * len[i]);
      norm += weight[i] * p;
      mean += weight[i] * p * cosang[i];
    }
    INFO(c.phase.dump());
    CHECK(std::abs(norm - 1.0) < 1e-6);
    CHECK(std::abs(mean - c.mean) < 1e-6);
  }
}
