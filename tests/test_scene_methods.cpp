// The scene methods against their references: exact on a voxel-grid medium (piecewise linear
// along rays, so integrators/exact applies) against the 50-digit reference, and the two-pass
// light grid (Kajiya-Von Herzen) converging to the nested reference as the grid is refined.
#include <catch2/catch.hpp>
#include <cmath>

#include "scene_builders.hpp"

using namespace rayint;
using namespace rayint::test;
using nlohmann::json;

namespace {

json small_grid() { return sine_grid(4, 0.2, 0.8, 1.3, 2.1, 0.7); }

json grid_rays() {
  json rays = json::array();
  for (int i = 0; i < 12; ++i)
    rays.push_back(ray_json(Vec3(-0.9 + 0.15 * i, 0.37 - 0.05 * i, 4), Vec3(0.02 * i - 0.1, 0.03, -1).normalized()));
  return rays;
}

}  // namespace

TEST_CASE("scene: exact on a voxel grid matches the 50-digit reference, Riemann converges to it", "[scene]") {
  for (bool absorption : {true, false}) {
    json effects = absorption ? json{"absorption", "emission"} : json{"emission"};
    json j = {{"medium", {{"type", "grid"}, {"grid", small_grid()}}},
              {"transfer", {{"extinction", {{0, 0}, {0.5, 1.5}, {1, 2.5}}}, {"emission", {{0, 0.2}, {1, 0.9}}}}},
              {"background", {{"color", {0.3, 0.6, 0.9}}}},
              {"effects", effects},
              {"reference", {{"rtol", 1e-12}}},
              {"rays", grid_rays()}};
    const SceneRenderResult exact = render_rays(scene_from(j), true);
    INFO("absorption " << absorption);
    for (const EffectReport& e : exact.effects) {
      CHECK(e.method == "exact");
      // 50-digit reference with absorption; adaptive double quadrature (rtol 1e-12) without
      CHECK(e.error.max_rel_to_peak < (absorption ? 1e-13 : 1e-11));
      CHECK(e.error.peak_reference > 0.1);
    }
    j["methods"] = absorption ? json{{"absorption", "riemann:n=2000"}, {"emission", "riemann:n=2000"}}
                              : json{{"emission", "riemann:n=2000"}};
    const SceneRenderResult riemann = render_rays(scene_from(j), true);
    for (const EffectReport& e : riemann.effects) {
      CHECK(e.error.max_rel_to_peak < 1e-5);
      CHECK(e.error.max_rel_to_peak > 1e-12);  // it is an approximation, and the test can see it
    }
  }
}

TEST_CASE("scene: two-pass light grid converges to the nested reference", "[scene]") {
  // Homogeneous box lit by a directional light, straight down and oblique. Straight down, the
  // grid carries T_L exactly at the vertices (constant medium: the trapezoid step is exact) and
  // the trilinear lookup of exp(-sigma depth) errs by O(h^2): halving the spacing must cut the
  // max error by more than 3.5 (measured 3.84 and 3.96). Oblique, T_L has a kink where the light's
  // entry face changes from the top to a side, and interpolating across a kink is first order in
  // the max norm: the factor must exceed 1.8 (measured 2.66 and 2.21).
  const std::pair<json, double> cases[] = {{json{0, 0, -1}, 3.5}, {json{0.5, 0.3, -0.8}, 1.8}};
  for (const auto& [dir, factor] : cases) {
    auto max_err = [&](int grid) {
      json rays = json::array();
      for (int i = 0; i < 10; ++i)
        rays.push_back(ray_json(Vec3(-0.8 + 0.17 * i, 0.1 * i - 0.4, 5), Vec3(0.01 * i, -0.02, -1).normalized()));
      const json j = {{"medium", {{"type", "homogeneous"}, {"shape", "box"}, {"density", 1.0},
                                  {"lower", {-1, -1, -1}}, {"upper", {1, 1, 1}}}},
                      {"transfer", {{"extinction", {{0, 0}, {1, 1.5}}}, {"albedo", {{0, 0.8}}}}},
                      {"lights", {{{"type", "directional"}, {"direction", dir}, {"intensity", 3}}}},
                      {"effects", {"absorption", "single_scattering", "shadows"}},
                      {"methods", {{"single_scattering", "riemann:n=400"}, {"shadows", "two_pass:grid=" + std::to_string(grid)}}},
                      {"rays", rays}};
      const SceneRenderResult r = render_rays(scene_from(j), true);
      const EffectReport& ss = report_of(r, "single_scattering");
      CHECK(ss.error.reference_converged);
      CHECK(report_of(r, "shadows").work.lookups > 0);
      CHECK(report_of(r, "shadows").work.shadow_rays == 0);
      return ss.error.max_rel_to_peak;
    };
    const double e5 = max_err(5), e9 = max_err(9), e17 = max_err(17);
    INFO("direction " << dir.dump() << " errors " << e5 << " " << e9 << " " << e17);
    CHECK(e9 < e5);
    CHECK(e5 / e9 > factor);
    CHECK(e9 / e17 > factor);
  }
}

TEST_CASE("scene: a grid is trilinear by default, kuhn on request, each exact against its own reference",
          "[scene][trilinear]") {
  json j = {{"medium", {{"type", "grid"}, {"grid", small_grid()}}},
            {"transfer", {{"extinction", {{0, 0}, {0.5, 1.5}, {1, 2.5}}}, {"emission", {{0, 0.2}, {1, 0.9}}}}},
            {"background", {{"color", {0.3, 0.6, 0.9}}}},
            {"effects", {"absorption", "emission"}},
            {"rays", grid_rays()}};
  const Scene trilinear = scene_from(j);
  CHECK(trilinear.medium.field().kind() == "voxel grid (trilinear)");
  j["medium"]["interpolation"] = "kuhn";
  const Scene kuhn = scene_from(j);
  CHECK(kuhn.medium.field().kind() == "voxel grid (kuhn)");
  const SceneRenderResult a = render_rays(trilinear, true), b = render_rays(kuhn, true);
  for (const auto* r : {&a, &b})
    for (const EffectReport& e : r->effects) {
      CHECK(e.method == "exact");
      CHECK(e.error.max_rel_to_peak < 1e-13);
    }
  // The two interpolants are different fields: on this coarse grid the emission term differs by
  // more than the references' error, on some ray (measured 0.14 of the peak).
  double diff = 0.0, peak = 0.0;
  for (std::size_t i = 0; i < grid_rays().size(); ++i)
    for (int c = 0; c < kChannels; ++c) {
      diff = std::max(diff, std::abs(term_of(a, "emission", i)[c] - term_of(b, "emission", i)[c]));
      peak = std::max(peak, std::abs(term_of(a, "emission", i)[c]));
    }
  WARN("trilinear vs kuhn on the 4^3 grid: max emission difference " << diff / peak << " of the peak");
  CHECK(diff / peak > 1e-3);
  j["medium"]["interpolation"] = "cubic";
  CHECK_THROWS_WITH(scene_from(j), Catch::Contains("medium.interpolation") && Catch::Contains("\"trilinear\" or \"kuhn\""));
}
