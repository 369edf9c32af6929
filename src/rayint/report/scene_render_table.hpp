#pragma once
// The table `rayint render SCENE` prints on stderr: per effect, method, time, work and error.
#include <string>

#include "rayint/scene/pipeline.hpp"

namespace rayint {

std::string scene_render_table(const SceneRenderResult& result);

}  // namespace rayint
