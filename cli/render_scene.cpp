// `rayint render SCENE.json -o image.png`: renders a scene (docs/scenes.md) with the effects it
// names, and reports each effect's time, work and (with --errors K) error against its reference.
#include <iostream>
#include <stdexcept>

#include "commands.hpp"
#include "progress.hpp"
#include "render_kinds.hpp"
#include "shard.hpp"
#include "rayint/input/shard_reader.hpp"
#include "rayint/report/shard_json.hpp"
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

void apply_method_overrides(Scene& scene, const std::vector<std::string>& overrides) {
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

Scene read_render_scene(const nlohmann::json& root, const RenderOptions& options) {
  Scene scene = parse_scene(root, options.input, dir_of(options.input));
  if (scene.camera) check_camera_memory(*scene.camera, 1, false, options.input + ": camera");
  apply_method_overrides(scene, options.methods);
  return scene;
}

std::unique_ptr<ScenePipeline> make_render_pipeline(const Scene& scene, const RenderOptions& options) {
  try {
    return std::make_unique<ScenePipeline>(scene, options.threads);
  } catch (const std::invalid_argument& e) {
    throw InputError(options.input + ": (root): " + json_source::one_line(e.what()));
  }
}

void render_scene_file(const nlohmann::json& root, const RenderOptions& options) {
  if (!options.compare.empty())
    throw InputError(options.input + ": --compare applies to mesh cases; for scenes use --errors K");
  if (!options.shard.empty() && options.error_grid > 0)
    throw InputError("--errors: not with --shard (the reference comparison samples the whole image; "
                     "run --errors K unsharded)");
  const json_source::InputFileLog read;  // the grid and preset files the scene names: shard inputs
  const Scene scene = read_render_scene(root, options);
  const std::unique_ptr<ScenePipeline> pipeline = make_render_pipeline(scene, options);
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
  // --shard I/N: render the shard's lines (rows, or explicit rays) and write them as a shard
  // file (-o); merging: the image and figures assembled from the shards' lines, as a single run.
  const bool in_shard = !options.shard.empty();
  const ShardSpec shard = begin_shard(options.shard, options.output);
  const std::vector<std::string> inputs = run_inputs({options.input}, read);
  if (in_shard) {
    const SceneRenderPart part = pipeline->render_part(ro, shard);
    if (!options.quiet) progress_line.finish();
    write_shard(options.output, "render", shard, inputs, to_json(part));
    return;
  }
  SceneRenderResult result;
  if (merging()) {
    const std::vector<SceneRenderPart> parts = merged_parts(
        "render", inputs, scene_render_part_from_json, [](std::size_t i, const SceneRenderPart& part) {
          check_shard_band(i, static_cast<std::size_t>(part.lines), part.line_begin, part.line_end, "data.line_begin");
        });
    try {
      result = pipeline->assemble(parts);
    } catch (const std::invalid_argument& e) {
      throw InputError("merge: " + options.input + ": " + e.what());
    }
  } else {
    result = pipeline->render(ro);
  }
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
