// Placeholder until the mesh renderer lands: refuses clearly instead of drawing anything.
#include <stdexcept>

#include "render_kinds.hpp"

namespace rayint::cli {

void render_mesh_file(const nlohmann::json&, const RenderOptions& options) {
  throw std::invalid_argument(options.input + ": rendering mesh files is not implemented yet");
}

}  // namespace rayint::cli
