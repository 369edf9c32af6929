// `rayint render FILE.json -o image.png`: a mesh case (issue: meshes) or a scene (issue: scenes).
// The file's top-level keys decide which: a scene names its "effects"; a mesh case has a "mesh"
// or "mesh_file". Each kind has its own file (render_mesh.cpp, render_scene.cpp).
#include <string>

#include "commands.hpp"
#include "options.hpp"
#include "render_kinds.hpp"
#include "rayint/input/case_reader.hpp"
#include "rayint/input/json_source.hpp"
#include "rayint/render/float_image.hpp"

namespace rayint::cli {

// A slab scene (input/slab_scene_reader.hpp) has "medium": {"type": "slab", ...}.
bool is_slab_scene(const nlohmann::json& root) {
  if (!root.is_object() || !root.contains("medium")) return false;
  const nlohmann::json& m = root["medium"];
  return m.is_object() && m.contains("type") && m["type"].is_string() && m["type"] == "slab";
}

void set_render_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("render", "Render a mesh case or a scene to an image (PNG preview; PFM, EXR, NPY floats)");
  auto opts = std::make_shared<RenderOptions>();
  cmd->add_option("file", opts->input, "mesh case or scene JSON")->required();
  cmd->add_option("-o,--output", opts->output, "image to write, format by extension: .png (8-bit sRGB preview), "
                  ".pfm, .exr (float32), .npy (float64)")->required();
  cmd->add_option("--compare", opts->compare,
                  "method to compare against the exact/reference image (error heat map)");
  cmd->add_option("--stats", opts->stats_path, "write statistics / per-effect costs as JSON here");
  cmd->add_option("--exposure", opts->exposure, "radiance multiplier before 8-bit encoding")
      ->check(CLI::PositiveNumber);
  add_threads_option(cmd, opts->threads, "worker threads (0: all cores)");
  add_quiet_flag(cmd, opts->quiet);
  add_strict_mesh_flag(cmd, opts->strict_mesh);
  add_cells_option(cmd, opts->split_cells);
  cmd->add_option("--method", opts->methods,
                  "scenes: EFFECT=METHOD, overrides the scene's methods (repeatable), e.g. "
                  "shadows=two_pass:grid=64");
  cmd->add_option("--shard", opts->shard,
                  "I/N: render band I of N of the rows (a scene of explicit rays: of the rays) and "
                  "write a shard file to -o; `rayint merge` joins the bands into the image and statistics");
  cmd->add_flag("--fit", opts->fit,
                "mesh cases: frame the whole mesh, keeping the camera's direction, up, projection and "
                "size (without a camera: 256 x 256, looking down -z); the camera used is printed on stderr");
  cmd->add_option("--errors", opts->error_grid,
                  "scenes: measure each term against its reference on K x K pixels (all explicit rays)")
      ->check(CLI::Range(0, 4096));
  cmd->add_option("--loss-target", opts->loss_target,
                  "mesh cases and voxel-grid scenes: float image (.npy, .pfm, .exr) for the loss sum "
                  "(I - target)^2; with --grad-out");
  cmd->add_option("--grad-out", opts->grad_out,
                  "write the exact d loss / d scalar here (.npy float64); needs --loss-target. Mesh cases: "
                  "per vertex, shape (points,) (per tet for cell data). Voxel-grid scenes (effects absorption "
                  "[+ emission], method exact): per grid point, in the grid's interpolation (trilinear, or "
                  "kuhn), shape (nz, ny, nx): [k, j, i] is point (i, j, k), x fastest as the grid's values");
  cmd->add_option("--grad-positions-out", opts->grad_positions_out,
                  "mesh cases: with --grad-out, also d loss / d vertex position (.npy, points x 3)");
  cmd->callback([opts] {
    const bool gradient = !opts->grad_out.empty() || !opts->loss_target.empty() || !opts->grad_positions_out.empty();
    if (gradient && (opts->grad_out.empty() || opts->loss_target.empty()))
      throw std::invalid_argument("--grad-out and --loss-target go together (--grad-positions-out needs both)");
    if (gradient && (!opts->compare.empty() || !opts->shard.empty() || !opts->stats_path.empty() || opts->fit ||
                     opts->error_grid > 0))
      throw std::invalid_argument("--grad-out: not with --compare, --shard, --stats, --fit or --errors");
    // --compare is one method spec, checked before anything is read or rendered.
    if (!opts->compare.empty() && parse_methods_option(opts->compare, "--compare").size() != 1)
      throw std::invalid_argument("--compare " + opts->compare + ": one method, not a list");
    const nlohmann::json root =
        json_source::parse(json_source::read_text_file(opts->input), opts->input);
    if (opts->shard.empty())  // a shard writes a shard file; `rayint merge -o` names the image
      image_format_of(opts->output);  // an unknown extension is refused before the render
    if (is_slab_scene(root))
      throw InputError(opts->input +
                       ": medium.type: \"slab\" is a plane-parallel slab with detectors, not an "
                       "image; solve it with `rayint slab --scene " + opts->input + "`");
    if (root.is_object() && (root.contains("effects") || root.contains("medium")))
      gradient ? render_scene_gradient_file(root, *opts) : render_scene_file(root, *opts);
    else if (root.is_object() && (root.contains("mesh") || root.contains("mesh_file")))
      gradient ? render_mesh_gradient_file(root, *opts) : render_mesh_file(root, *opts);
    else
      throw InputError(opts->input +
                       ": (root): not a renderable file (a scene has \"effects\", a mesh case has "
                       "\"mesh\" or \"mesh_file\")");
  });
}

}  // namespace rayint::cli
