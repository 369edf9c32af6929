#pragma once
// The report of `rayint scene-sweep`: per method configuration, its time and each effect's work
// and error against the reference (scene/scene_sweep.hpp).
#include <nlohmann/json.hpp>

#include "rayint/scene/scene_sweep.hpp"

namespace rayint {

nlohmann::json scene_sweep_json(const Scene& scene, const SceneSweepResult& result);

}  // namespace rayint
