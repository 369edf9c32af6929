// `rayint render SCENE.json -o image.png`: renders a scene (docs/scenes.md) with the effects it
// names, and reports each effect's time, work and (with --errors K) error against its reference.
#include <iostream>
#include <stdexcept>

#include "commands.hpp"
#include "progress.hpp"
#include "render_kinds.hpp"
#include "rayint/input/case_reader.hpp"
#include "rayint/input/json_source.hpp"
#include "rayint/input/scene_reader.hpp"
#include "rayint/report/scene_render_table.hpp"
#include "rayint/report/scene_report_json.hpp"
#include "rayint/render/float_image.hpp"
#include "rayint/render/image.hpp"
#include "rayint/scene/effect.hpp"
#include "rayint/scene/pipeline.hpp"

namespace rayint::cli {
namespace {

std::string dir_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

void apply_overrides(Scene& scene, const std::vector<std::string>& overrides) {
  for (const std::string& o : overrides) {
    try {
      auto [effect, spec] = parse_effect_assignment(scene, o);
      scene.methods[effect] = spec;
    } catch (const EffectMethodError& e) {
      if (e.kind == EffectMethodError::Kind::syntax)
        throw InputError("--method " + o + ": expected EFFECT=METHOD, e.g. single_scattering=riemann:n=64");
      throw InputError("--method " + o + ": " + e.what());
    }
  }
}

}  // namespace

void render_scene_file(const nlohmann::json& root, const RenderOptions& options) {
  if (!options.shard.empty())
    throw InputError(options.input + ": --shard applies to mesh cases (rows); scenes are not sharded yet");
  if (!options.compare.empty())
    throw InputError(options.input + ": --compare applies to mesh cases; for scenes use --errors K");
  Scene scene = parse_scene(root, options.input, dir_of(options.input));
  if (scene.camera) check_camera_memory(*scene.camera, 1, false, options.input + ": camera");
  apply_overrides(scene, options.methods);
  std::unique_ptr<ScenePipeline> pipeline;
  try {
    pipeline = std::make_unique<ScenePipeline>(scene, options.threads);
  } catch (const std::invalid_argument& e) {
    throw InputError(options.input + ": (root): " + json_source::one_line(e.what()));
  }
  SceneRenderOptions ro;
  ro.threads = options.threads;
  ro.error_grid = options.error_grid;
  ProgressLine progress_line;
  if (!options.quiet)
    ro.progress = [&progress_line](double f) {
      progress_line.update("rendering " + std::to_string(static_cast<int>(f * 100.0)) + "%", f);
    };
  ProgressLine error_line;
  if (!options.quiet && options.error_grid > 0)
    ro.error_progress = [&progress_line, &error_line](double f) {
      progress_line.finish();  // the rendering line is complete when the error phase starts
      error_line.update("errors against the references " + std::to_string(static_cast<int>(f * 100.0)) + "%", f);
    };
  const SceneRenderResult result = pipeline->render(ro);
  if (!options.quiet) {
    progress_line.finish();
    error_line.finish();
  }
  PngOptions png;
  png.exposure = options.exposure;
  write_image(options.output, result.image, png);
  if (!options.stats_path.empty()) emit(scene_report_json(scene, result).dump(2) + "\n", options.stats_path);
  if (!options.quiet) std::cerr << scene_render_table(result);
}

}  // namespace rayint::cli
