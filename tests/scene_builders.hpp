#pragma once
// Scenes for the [scene] tests, built as JSON and read through the scene reader, so that every
// test goes through the same path as `rayint render`.
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "rayint/input/scene_reader.hpp"
#include "rayint/scene/pipeline.hpp"

namespace rayint::test {

inline Scene scene_from(const nlohmann::json& j) { return parse_scene(j, "test-scene.json", "."); }

// A grid medium's "grid" object: n^3 points on [-1, 1]^3, point (i, j, k) of value
// base + amp |sin(a i + b j - c k)| (x fastest): smooth, positive and nowhere constant.
inline nlohmann::json sine_grid(int n, double base, double amp, double a, double b, double c) {
  nlohmann::json values = nlohmann::json::array();
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) values.push_back(base + amp * std::fabs(std::sin(a * i + b * j - c * k)));
  const double h = 2.0 / (n - 1);
  return {{"dims", {n, n, n}}, {"origin", {-1, -1, -1}}, {"spacing", {h, h, h}}, {"values", values}};
}

// All explicit rays of `scene`, each term compared with its reference (error_grid > 0).
inline SceneRenderResult render_rays(const Scene& scene, bool errors = false, unsigned threads = 1) {
  ScenePipeline pipeline(scene, threads);
  SceneRenderOptions o;
  o.threads = threads;
  o.error_grid = errors ? 1 : 0;
  return pipeline.render(o);
}

// The term of `effect` on ray i (explicit-ray scenes).
inline Rgb term_of(const SceneRenderResult& r, const std::string& effect, std::size_t i) {
  std::size_t e = 0;
  for (const EffectReport& rep : r.effects) {
    if (rep.role == "modifier") continue;
    if (rep.effect == effect) return r.ray_terms.at(i).at(e);
    ++e;
  }
  throw std::runtime_error("no term " + effect);
}

inline const EffectReport& report_of(const SceneRenderResult& r, const std::string& effect) {
  for (const EffectReport& rep : r.effects)
    if (rep.effect == effect) return rep;
  throw std::runtime_error("no report " + effect);
}

inline nlohmann::json ray_json(const Vec3& o, const Vec3& d) {
  return {{"origin", {o.x(), o.y(), o.z()}}, {"direction", {d.x(), d.y(), d.z()}}};
}

}  // namespace rayint::test
