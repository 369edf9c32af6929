#pragma once
// Scenes for the [scene] tests, built as JSON and read through the scene reader, so that every
// test goes through the same path as `rayint render`.
#include <nlohmann/json.hpp>
#include <string>

#include "rayint/input/scene_reader.hpp"
#include "rayint/scene/pipeline.hpp"

namespace rayint::test {

inline Scene scene_from(const nlohmann::json& j) { return parse_scene(j, "test-scene.json", "."); }

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
