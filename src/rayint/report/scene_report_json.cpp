#include "rayint/report/scene_report_json.hpp"

#include <cmath>

#include "rayint/report/json_number.hpp"
#include "rayint/scene/grid_field.hpp"

namespace rayint {

nlohmann::json term_error_json(const TermError& e) {
  return {{"rays", e.rays},
          {"max_abs", number_or_null(e.max_abs)},
          {"mean_abs", number_or_null(e.mean_abs)},
          {"peak_reference", number_or_null(e.peak_reference)},
          {"max_rel_to_peak", number_or_null(e.max_rel_to_peak)},
          {"reference_error_estimate", number_or_null(e.max_reference_error)},
          {"reference_converged", e.reference_converged},
          {"reference_seconds", number_or_null(e.reference_seconds)}};
}

nlohmann::json scene_report_json(const Scene& scene, const SceneRenderResult& r) {
  nlohmann::json j;
  j["scene"] = scene.name;
  j["source"] = scene.source;
  j["medium"] = scene.medium.field().kind();
  // A voxel grid's interpolant (scene/grid_field.hpp): "trilinear" (default) or "kuhn".
  if (const auto* grid = dynamic_cast<const GridField*>(&scene.medium.field()))
    j["interpolation"] = interpolation_name(grid->interpolation());
  j["effects_named"] = scene.effects;
  j["width"] = r.image.width;
  j["height"] = r.image.height;
  j["threads"] = r.threads;
  j["render_seconds"] = r.render_seconds;
  j["render_cpu_seconds"] = r.render_cpu_seconds;
  j["setup_cpu_seconds"] = r.setup_cpu_seconds;
  j["setup_seconds"] = r.setup_seconds;
  j["error_seconds"] = r.error_seconds;
  j["image_mean"] = rgb_json(r.image_mean);
  nlohmann::json effects = nlohmann::json::array();
  for (const EffectReport& e : r.effects) {
    nlohmann::json x = {{"effect", e.effect},
                        {"method", e.method},
                        {"role", e.role},
                        {"seconds", e.work.seconds},
                        {"cpu_seconds", e.work.cpu_seconds},
                        {"setup_seconds", e.work.setup_seconds},
                        {"setup_cpu_seconds", e.work.setup_cpu_seconds},
                        {"rays", e.work.rays},
                        {"samples", e.work.samples},
                        {"shadow_rays", e.work.shadow_rays},
                        {"shadow_samples", e.work.shadow_samples},
                        {"light_grid_lookups", e.work.lookups},
                        {"mean_term", rgb_json(e.mean_term)}};
    if (e.has_error) x["error"] = term_error_json(e.error);
    effects.push_back(x);
  }
  j["effects"] = effects;
  if (r.has_total_error) j["total_error"] = term_error_json(r.total_error);
  if (!r.ray_terms.empty()) {
    nlohmann::json rays = nlohmann::json::array();
    for (std::size_t i = 0; i < r.ray_terms.size(); ++i) {
      nlohmann::json terms = nlohmann::json::object();
      std::size_t e = 0;
      for (const EffectReport& rep : r.effects)
        if (rep.role != "modifier" && e < r.ray_terms[i].size()) terms[rep.effect] = rgb_json(r.ray_terms[i][e++]);
      rays.push_back({{"pixel", rgb_json(r.image.pixels[i])}, {"terms", terms}});
    }
    j["rays"] = rays;
  }
  return j;
}

}  // namespace rayint
