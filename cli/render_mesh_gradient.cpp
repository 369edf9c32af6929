// `rayint render MESHCASE.json -o image.npy --loss-target TARGET --grad-out GRAD.npy
//  [--grad-positions-out POS.npy]`: the exact image of a mesh case's camera, the loss
// sum over pixels and channels of (I - target)^2, and its exact gradient with respect to every
// vertex scalar (NPY float64, shape (points,); (tets,) for cell data) and, optionally, every
// vertex position (shape (points, 3)). render/mesh_gradient.hpp computes; this file reads and writes.
#include <cstdio>
#include <string>

#include "commands.hpp"
#include "render_kinds.hpp"
#include "rayint/core/atomic_file.hpp"
#include "rayint/core/error.hpp"
#include "rayint/core/format.hpp"
#include "rayint/input/mesh_case_reader.hpp"
#include "rayint/render/float_image.hpp"
#include "rayint/render/mesh_gradient.hpp"
#include "rayint/mesh/quadratic_tets.hpp"
#include "rayint/render/npy_array.hpp"

namespace rayint::cli {

void render_mesh_gradient_file(const nlohmann::json& root, const RenderOptions& options) {
  const std::string& target_path = options.loss_target;
  if (image_format_of(target_path) == ImageFormat::png)
    throw InputError(target_path + ": --loss-target: a float image is needed (.npy, .pfm, .exr), not 8-bit PNG");
  MeshCase mc = parse_mesh_case(root, options.input, MeshReadOptions{options.strict_mesh, options.split_cells});
  if (!mc.camera) throw InputError(options.input + ": camera: required to render a mesh case");
  if (mc.shading.enabled)
    throw InputError(options.input + ": shading: --grad-out differentiates the unshaded render only");
  const Image target = read_image(target_path);
  if (target.width != mc.camera->width || target.height != mc.camera->height)
    throw InputError(target_path + ": --loss-target: the image is " + std::to_string(target.width) + " x " +
                     std::to_string(target.height) + ", the camera renders " + std::to_string(mc.camera->width) +
                     " x " + std::to_string(mc.camera->height));
  refuse_quadratic_tets(mc.mesh, mc.mesh_source, "render --gradient");
  const TetTraversal mesh(mc.mesh, mc.neighbors, mc.mesh_source);
  const LossGradient g = image_loss_gradient(mc, mesh, target, options.threads, !options.grad_positions_out.empty());
  if (g.pixels_failed > 0) {  // nothing is written: a failed gradient is never shown as numbers
    std::fprintf(stderr, "rayint render: %ld pixels failed (non-finite intensity or gradient); no gradient written\n",
                 g.pixels_failed);
    throw ChecksFailed{};
  }
  write_image(options.output, g.image);
  write_file_atomically(options.grad_out, encode_npy_array(g.d_scalar, {g.d_scalar.size()}));
  if (!options.grad_positions_out.empty()) {
    std::vector<double> flat;
    flat.reserve(3 * g.d_position.size());
    for (const auto& d : g.d_position) flat.insert(flat.end(), d.begin(), d.end());
    write_file_atomically(options.grad_positions_out, encode_npy_array(flat, {g.d_position.size(), 3}));
  }
  // The loss is a result, not progress: printed with -q too.
  std::fprintf(stderr, "rayint render: loss %s over %d x %d pixels; d loss / d %s scalar -> %s (%zu values)%s\n",
               format_number(g.loss).c_str(), g.image.width, g.image.height, g.cell_scalars ? "cell" : "vertex",
               options.grad_out.c_str(), g.d_scalar.size(),
               options.grad_positions_out.empty() ? "" : ("; d loss / d position -> " + options.grad_positions_out).c_str());
  if (!options.grad_positions_out.empty() && g.ends_on_edges > 0)
    std::fprintf(stderr, "rayint render: warning: %ld ray ends lie on a mesh edge or vertex, where the position "
                 "gradient is one-sided (docs/gradients.md)\n", g.ends_on_edges);
}

}  // namespace rayint::cli
