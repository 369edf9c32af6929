#pragma once
// The two kinds of file `rayint render` draws; render_command.cpp dispatches between them.
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rayint/geometry/camera.hpp"
#include "rayint/mesh/mesh_case.hpp"
#include "rayint/scene/pipeline.hpp"
#include "rayint/scene/scene.hpp"

namespace rayint::cli {

struct RenderOptions {
  std::string input;
  std::string output;
  std::string compare;     // method name (+ knobs); empty: no comparison
  std::string stats_path;  // JSON statistics; empty: none
  double exposure = 1.0;
  unsigned threads = 0;
  bool quiet = false;
  bool strict_mesh = false;          // mesh cases: --strict-mesh
  bool split_cells = false;          // mesh cases: --cells split (mesh/cell_split.hpp)
  std::vector<std::string> methods;  // scenes: EFFECT=SPEC overrides of the scene's "methods"
  int error_grid = 0;                // scenes: reference errors on K x K pixels (0: none)
  std::string shard;                 // --shard I/N (rows; a scene of explicit rays: rays)
  bool fit = false;                  // mesh cases: --fit, frame the mesh (geometry/camera_fit.hpp)
  std::string loss_target;           // mesh cases: --loss-target, float image of the loss
  std::string grad_out;              // mesh cases: --grad-out, d loss / d vertex scalar (.npy)
  std::string grad_positions_out;    // mesh cases: --grad-positions-out, d loss / d position (.npy)
};

// A slab scene (medium.type "slab"): `rayint slab --scene`, not render or check --candidate-image.
bool is_slab_scene(const nlohmann::json& root);  // render_command.cpp
void render_mesh_file(const nlohmann::json& root, const RenderOptions& options);   // render_mesh.cpp
// --loss-target with --grad-out: render_mesh_gradient.cpp
void render_mesh_gradient_file(const nlohmann::json& root, const RenderOptions& options);
void render_scene_file(const nlohmann::json& root, const RenderOptions& options);  // render_scene.cpp
// --loss-target with --grad-out on a voxel-grid scene: render_scene_gradient.cpp
void render_scene_gradient_file(const nlohmann::json& root, const RenderOptions& options);
// The scene of `rayint render` (render_scene.cpp): read (grid and preset files relative to it),
// its camera's memory checked, --method overrides applied; and its pipeline (a scene the
// pipeline refuses is an InputError naming the file).
Scene read_render_scene(const nlohmann::json& root, const RenderOptions& options);
std::unique_ptr<ScenePipeline> make_render_pipeline(const Scene& scene, const RenderOptions& options);

// Refuses (InputError naming `where`) a render whose pixel memory exceeds core/limits.hpp
// kImageBytes: `images` RGB images of doubles, plus a double per pixel with `per_pixel_error`.
void check_camera_memory(const Camera& camera, int images, bool per_pixel_error, const std::string& where);
// Refuses a mesh case whose camera is so far from the mesh that a double's step along its rays
// exceeds the mesh's extent (every ray would silently miss).
void check_camera_reaches_mesh(const MeshCase& mesh_case, const std::string& where);

}  // namespace rayint::cli
