// The pipeline evaluates exactly the named effects (issue 6): no shadow ray without `shadows`,
// and adding a term effect never changes another effect's term.
//
// Why bitwise: each term is integrated by its own Effect on its own samples, whose positions
// depend only on the ray and that effect's method, and the view attenuation and shadowing it
// uses depend only on whether `absorption` / `shadows` are named. So for a fixed pair of those
// attenuations, every term must be identical to the last bit whatever else is named; any
// difference would mean that effects share state. Adding `shadows` changes exactly the terms it
// shadows (single_scattering, shading) and leaves the others bitwise unchanged.
#include <catch2/catch.hpp>
#include <cstring>

#include "rayint/scene/cloud.hpp"
#include "scene_builders.hpp"

using namespace rayint;
using namespace rayint::test;
using nlohmann::json;

namespace {

json cloud_scene(const json& effects) {
  json rays = json::array();
  for (int i = 0; i < 24; ++i) {
    const double x = -1.2 + 2.4 * i / 23.0;
    rays.push_back(ray_json(Vec3(x, 0.1 * (i % 5) - 0.2, 4), Vec3(-0.05 * x, 0.01, -1).normalized()));
  }
  json methods = json::object();
  for (const auto& e : effects)
    if (e == "single_scattering" || e == "shading") methods[e.get<std::string>()] = "riemann:n=24";
  return {{"medium", {{"type", "cloud"}, {"preset", "max1995"}, {"seed", 3}}},
          {"transfer", {{"extinction", {{0, 0}, {1, 8}}}, {"albedo", {{0, 0.9}}}, {"emission", {{0, 0.2}, {1, 0.5}}}}},
          {"lights", {{{"type", "directional"}, {"direction", {0.4, -1, -0.2}}, {"intensity", 2}},
                      {{"type", "point"}, {"position", {2, 2, 2}}, {"intensity", 5}}}},
          {"phase", {{"type", "henyey_greenstein"}, {"g", 0.6}}},
          {"background", {{"color", {0.2, 0.3, 0.5}}}},
          {"effects", effects},
          {"methods", methods},
          {"rays", rays}};
}

bool same_bits(const Rgb& a, const Rgb& b) {
  return std::memcmp(a.data(), b.data(), sizeof(Rgb)) == 0;
}

}  // namespace

TEST_CASE("scene pipeline: no shadow ray is cast unless shadows is named", "[scene]") {
  const SceneRenderResult r = render_rays(scene_from(cloud_scene({"absorption", "emission", "single_scattering", "shading"})));
  for (const EffectReport& e : r.effects) {
    CHECK(e.effect != "shadows");
    CHECK(e.work.shadow_rays == 0);
    CHECK(e.work.shadow_samples == 0);
    CHECK(e.work.lookups == 0);
  }
  CHECK(report_of(r, "single_scattering").work.samples == 24 * 24);

  // With shadows: one shadow ray per light per sample that scatters (single_scattering) or is
  // lit from the front (shading), counted under "shadows".
  const SceneRenderResult s = render_rays(scene_from(cloud_scene({"absorption", "single_scattering", "shadows"})));
  const EffectReport& sh = report_of(s, "shadows");
  CHECK(sh.work.shadow_rays > 0);
  CHECK(sh.work.shadow_rays <= 2 * 24 * 24);
  CHECK(sh.work.shadow_samples == 24 * sh.work.shadow_rays);  // shadow_rays:n defaults to the ss n
}

TEST_CASE("scene pipeline: adding an effect never changes another effect's term", "[scene]") {
  const std::vector<std::vector<std::string>> sets = {
      {"absorption", "emission"},
      {"absorption", "emission", "single_scattering"},
      {"absorption", "single_scattering", "shading"},
      {"absorption", "emission", "single_scattering", "shading"},
      {"emission"},
      {"emission", "single_scattering"},
      {"emission", "single_scattering", "shading"},
  };
  std::vector<SceneRenderResult> results;
  for (const auto& set : sets) results.push_back(render_rays(scene_from(cloud_scene(set))));
  auto has = [](const std::vector<std::string>& s, const std::string& e) {
    return std::find(s.begin(), s.end(), e) != s.end();
  };
  int compared = 0;
  for (std::size_t a = 0; a < sets.size(); ++a)
    for (std::size_t b = 0; b < sets.size(); ++b) {
      if (a == b || has(sets[a], "absorption") != has(sets[b], "absorption")) continue;
      for (const std::string& e : sets[a]) {
        if (!has(sets[b], e)) continue;
        for (std::size_t i = 0; i < 24; ++i) {
          INFO("effect " << e << " set " << a << " vs " << b << " ray " << i);
          CHECK(same_bits(term_of(results[a], e, i), term_of(results[b], e, i)));
          ++compared;
        }
      }
    }
  CHECK(compared > 500);

  // shadows modifies single_scattering only; absorption and emission stay bitwise the same.
  const SceneRenderResult no = render_rays(scene_from(cloud_scene({"absorption", "emission", "single_scattering"})));
  const SceneRenderResult yes = render_rays(scene_from(cloud_scene({"absorption", "emission", "single_scattering", "shadows"})));
  bool ss_changed = false;
  for (std::size_t i = 0; i < 24; ++i) {
    CHECK(same_bits(term_of(no, "absorption", i), term_of(yes, "absorption", i)));
    CHECK(same_bits(term_of(no, "emission", i), term_of(yes, "emission", i)));
    ss_changed = ss_changed || !same_bits(term_of(no, "single_scattering", i), term_of(yes, "single_scattering", i));
  }
  CHECK(ss_changed);
}

TEST_CASE("scene pipeline: results do not depend on the number of threads", "[scene]") {
  const Scene scene = scene_from(cloud_scene({"absorption", "emission", "single_scattering", "shadows"}));
  const SceneRenderResult one = render_rays(scene, false, 1);
  const SceneRenderResult two = render_rays(scene, false, 2);
  for (std::size_t i = 0; i < 24; ++i) CHECK(same_bits(one.image.pixels[i], two.image.pixels[i]));
  CHECK(report_of(one, "shadows").work.shadow_rays == report_of(two, "shadows").work.shadow_rays);
}

TEST_CASE("scene pipeline: means and errors of a camera render do not depend on the number of threads",
          "[scene]") {
  // Rows go to whichever worker is free; the means are summed per row and the error
  // accumulators per sampled pixel, then reduced in order, so every figure is bit for bit the
  // same for any thread count (they used to be summed per worker).
  json j = cloud_scene({"absorption", "emission", "single_scattering"});
  j.erase("rays");
  j["camera"] = {{"position", {0, 0.15, 4.2}}, {"look_at", {0, 0.15, 0}}, {"fov_deg", 30},
                 {"width", 12}, {"height", 10}};
  const Scene scene = scene_from(j);
  auto render = [&](unsigned threads) {
    ScenePipeline pipeline(scene, threads);
    SceneRenderOptions o;
    o.threads = threads;
    o.error_grid = 4;
    return pipeline.render(o);
  };
  const SceneRenderResult one = render(1);
  for (const unsigned threads : {2u, 3u, 7u}) {
    const SceneRenderResult many = render(threads);
    CHECK(same_bits(one.image_mean, many.image_mean));
    REQUIRE(one.effects.size() == many.effects.size());
    for (std::size_t e = 0; e < one.effects.size(); ++e) {
      CHECK(same_bits(one.effects[e].mean_term, many.effects[e].mean_term));
      REQUIRE(one.effects[e].has_error);
      CHECK(one.effects[e].error.mean_abs == many.effects[e].error.mean_abs);
      CHECK(one.effects[e].error.max_abs == many.effects[e].error.max_abs);
    }
    CHECK(one.total_error.mean_abs == many.total_error.mean_abs);
  }
}

TEST_CASE("scene pipeline: the reported means are the means of the terms and of the pixels", "[scene]") {
  // Without absorption the background enters the pixel unattenuated but is no term: the image
  // mean is then the terms' means plus the background.
  for (const bool absorption : {true, false}) {
    json effects = absorption ? json{"absorption", "emission", "single_scattering"} : json{"emission", "single_scattering"};
    const SceneRenderResult r = render_rays(scene_from(cloud_scene(effects)));
    REQUIRE(r.ray_terms.size() == 24);
    Rgb pixel_mean{}, terms_total{};
    for (std::size_t i = 0; i < 24; ++i)
      for (int c = 0; c < 3; ++c) pixel_mean[c] += r.image.pixels[i][c] / 24.0;
    for (std::size_t e = 0; e < r.ray_terms[0].size(); ++e) {
      Rgb mean{};
      for (std::size_t i = 0; i < 24; ++i)
        for (int c = 0; c < 3; ++c) mean[c] += r.ray_terms[i][e][c] / 24.0;
      for (int c = 0; c < 3; ++c) {
        CHECK(r.effects[e].mean_term[c] == Approx(mean[c]).epsilon(1e-13).margin(1e-300));
        terms_total[c] += r.effects[e].mean_term[c];
      }
    }
    const Rgb background{0.2, 0.3, 0.5};
    for (int c = 0; c < 3; ++c) {
      CHECK(r.image_mean[c] == Approx(pixel_mean[c]).epsilon(1e-13));
      CHECK(r.image_mean[c] == Approx(terms_total[c] + (absorption ? 0.0 : background[c])).epsilon(1e-12));
    }
    CHECK(r.image_mean[0] > 0.0);
  }
}

TEST_CASE("scene: the cloud's Perlin noise stays within the bound used for its majorant", "[scene]") {
  // CloudField's max_density assumes |perlin| < 1.1; sample 200,000 points of three seeds.
  double worst = 0;
  for (std::uint64_t seed : {1u, 7u, 12345u}) {
    const PerlinNoise noise(seed);
    std::uint64_t state = seed * 2654435761u + 1;
    auto uniform = [&state] {
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      return static_cast<double>(state >> 11) / 9007199254740992.0;
    };
    for (int i = 0; i < 200000; ++i)
      worst = std::max(worst, std::abs(noise(Vec3(uniform(), uniform(), uniform()) * 40.0 - Vec3::Constant(20.0))));
  }
  CHECK(worst < 1.1);
  CHECK(worst > 0.5);  // it is noise, not zero
  // and the density never exceeds max_density
  const CloudField cloud(max_figure_cloud(7));
  double dmax = 0;
  for (int i = 0; i < 20000; ++i) {
    const double u = (i % 200) / 199.0, v = (i / 200) / 99.0;
    dmax = std::max(dmax, cloud.density(Vec3(-1.6 + 3.2 * u, -0.8 + 1.6 * v, 0.05)));
  }
  CHECK(dmax > 0.0);
  CHECK(dmax <= cloud.max_density());
}

TEST_CASE("scene effects: multiple_scattering is registered in its reserved place, last in the pipeline order",
          "[scene]") {
  // tests/main.cpp calls register_standard_effects() as cli/main.cpp does; the entry it replaces
  // was reserved (no factory) so that a program without the call is told to make it.
  const std::vector<EffectInfo>& effects = effect_registry();
  REQUIRE(!effects.empty());
  CHECK(effects.back().name == "multiple_scattering");
  const EffectInfo* ms = find_effect("multiple_scattering");
  REQUIRE(ms != nullptr);
  CHECK(ms->make != nullptr);
  CHECK(!ms->methods.empty());
  std::size_t named = 0;
  for (const EffectInfo& e : effects) named += e.name == "multiple_scattering" ? 1 : 0;
  CHECK(named == 1);
}
