// Placeholder until the scene renderer lands: refuses clearly instead of drawing anything.
#include <stdexcept>

#include "render_kinds.hpp"

namespace rayint::cli {

void render_scene_file(const nlohmann::json&, const RenderOptions& options) {
  throw std::invalid_argument(options.input + ": rendering scene files is not implemented yet");
}

}  // namespace rayint::cli
