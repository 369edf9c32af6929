// `rayint render SCENE.json -o image.npy --loss-target TARGET --grad-out GRAD.npy`: for a scene
// whose medium is a voxel grid (effects absorption [+ emission], method exact), the image, the loss
// sum over pixels and channels of (I - target)^2 and its exact gradient with respect to every grid
// point value, in the grid's own interpolation (trilinear, or Kuhn where the scene says
// "interpolation": "kuhn"), as NPY float64 of shape (nz, ny, nx): C order, so element [k, j, i]
// is point (i, j, k) and the flat order is the grid's own `values` order (x fastest).
// scene/grid_loss_gradient.hpp computes; this file reads and writes.
#include <cstdio>
#include <stdexcept>
#include <string>

#include "commands.hpp"
#include "render_kinds.hpp"
#include "rayint/core/atomic_file.hpp"
#include "rayint/core/error.hpp"
#include "rayint/core/format.hpp"
#include "rayint/input/json_source.hpp"
#include "rayint/render/float_image.hpp"
#include "rayint/render/npy_array.hpp"
#include "rayint/scene/grid_loss_gradient.hpp"

namespace rayint::cli {

void render_scene_gradient_file(const nlohmann::json& root, const RenderOptions& options) {
  const std::string& target_path = options.loss_target;
  if (image_format_of(target_path) == ImageFormat::png)
    throw InputError(target_path + ": --loss-target: a float image is needed (.npy, .pfm, .exr), not 8-bit PNG");
  if (!options.grad_positions_out.empty())
    throw InputError(options.input + ": medium: --grad-positions-out is for mesh cases (grid point positions "
                     "are fixed by origin and spacing and not differentiated)");
  const Scene scene = read_render_scene(root, options);
  const std::unique_ptr<ScenePipeline> pipeline = make_render_pipeline(scene, options);
  const std::string refusal = grid_gradient_refusal(scene, *pipeline);
  if (!refusal.empty()) throw InputError(options.input + ": " + refusal);
  const Image target = read_image(target_path);
  const int width = scene.camera ? scene.camera->width : static_cast<int>(scene.rays.size());
  const int height = scene.camera ? scene.camera->height : 1;
  if (target.width != width || target.height != height)
    throw InputError(target_path + ": --loss-target: the image is " + std::to_string(target.width) + " x " +
                     std::to_string(target.height) + ", the scene renders " + std::to_string(width) + " x " +
                     std::to_string(height));
  GridLossGradient g;
  try {
    g = grid_image_loss_gradient(*pipeline, target, options.threads);
  } catch (const std::invalid_argument& e) {  // the Kuhn gradient refuses a transfer function
    throw InputError(options.input + ": transfer: " + json_source::one_line(e.what()));
  }
  if (g.pixels_failed > 0) {  // nothing is written: a failed gradient is never shown as numbers
    std::fprintf(stderr,
                 "rayint render: %ld pixels failed (non-finite intensity or derivative; first %s); no gradient "
                 "written\n",
                 g.pixels_failed, g.first_failure.c_str());
    throw ChecksFailed{};
  }
  const auto nx = static_cast<std::size_t>(g.dims[0]), ny = static_cast<std::size_t>(g.dims[1]),
             nz = static_cast<std::size_t>(g.dims[2]);
  const std::string npy = encode_npy_array(g.d_value, {nz, ny, nx});  // before anything is written
  write_image(options.output, g.image);
  write_file_atomically(options.grad_out, npy);
  // The loss is a result, not progress: printed with -q too.
  std::fprintf(stderr,
               "rayint render: loss %s over %d x %d pixels; d loss / d grid point value (%s interpolation) -> %s "
               "(shape (nz, ny, nx) = (%zu, %zu, %zu), x fastest as the grid's values)\n",
               format_number(g.loss).c_str(), g.image.width, g.image.height, interpolation_name(g.interpolation),
               options.grad_out.c_str(), nz, ny, nx);
}

}  // namespace rayint::cli
