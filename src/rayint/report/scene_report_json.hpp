#pragma once
// The JSON form of a scene render (`rayint render SCENE --stats`): per effect, the method, the
// time and work, and the error against the reference when it was measured. Format: docs/scenes.md.
#include <nlohmann/json.hpp>

#include "rayint/scene/pipeline.hpp"

namespace rayint {

nlohmann::json term_error_json(const TermError& e);
nlohmann::json scene_report_json(const Scene& scene, const SceneRenderResult& result);

}  // namespace rayint
