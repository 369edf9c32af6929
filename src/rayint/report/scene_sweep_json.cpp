#include "rayint/report/scene_sweep_json.hpp"

#include "rayint/report/scene_report_json.hpp"

namespace rayint {

nlohmann::json scene_sweep_json(const Scene& scene, const SceneSweepResult& r) {
  nlohmann::json j;
  j["scene"] = scene.name;
  j["source"] = scene.source;
  j["width"] = scene.camera ? scene.camera->width : static_cast<int>(scene.rays.size());
  j["height"] = scene.camera ? scene.camera->height : 1;
  j["error_grid"] = r.error_grid;
  j["threads"] = r.threads;
  j["reference_seconds"] = r.reference_seconds;
  j["points"] = nlohmann::json::array();
  for (const SweepPoint& p : r.points) {
    nlohmann::json x;
    for (const auto& kv : p.methods) x["methods"][kv.first] = kv.second.label();
    x["render_seconds"] = p.render_seconds;
    x["setup_seconds"] = p.setup_seconds;
    x["render_cpu_seconds"] = p.render_cpu_seconds;
    x["setup_cpu_seconds"] = p.setup_cpu_seconds;
    x["total_error"] = term_error_json(p.total_error);
    for (const EffectReport& e : p.effects) {
      nlohmann::json ej = {{"effect", e.effect}, {"method", e.method}, {"seconds", e.work.seconds}, {"cpu_seconds", e.work.cpu_seconds},
                           {"setup_seconds", e.work.setup_seconds}, {"samples", e.work.samples},
                           {"shadow_rays", e.work.shadow_rays}, {"shadow_samples", e.work.shadow_samples},
                           {"light_grid_lookups", e.work.lookups}};
      if (e.has_error) ej["error"] = term_error_json(e.error);
      x["effects"].push_back(ej);
    }
    j["points"].push_back(x);
  }
  return j;
}

}  // namespace rayint
