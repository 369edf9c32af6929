// rayint scatter -- multiple scattering on a scene's medium: the Monte Carlo reference (every
// order, and single scattering with shadows), Max's discrete ordinates over grid sizes and bin
// counts, and the zonal method, each against the reference with its cost
// (src/rayint/scattering/volume_comparison.hpp). JSON report and PNG images.
#include <iostream>
#include <utility>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "options.hpp"
#include "shard.hpp"
#include "rayint/input/scene_reader.hpp"
#include "rayint/input/shard_reader.hpp"
#include "rayint/report/shard_json.hpp"
#include "rayint/report/volume_comparison_json.hpp"
#include "rayint/effects/scene_volume_comparison.hpp"

namespace rayint::cli {
namespace {

struct ScatterOptions {
  std::string scene;
  int width = 64, height = 64, points = 64, threads = 0;
  ComparisonOptions comparison;  // grids, bins, zonal grids, Monte Carlo spp and seed
  std::string output, images;
  double exposure = 1.0;
  bool quiet = false;
  std::string shard;  // --shard I/N
};

}  // namespace

void set_scatter_command(CLI::App& app) {
  auto s = std::make_shared<ScatterOptions>();
  s->comparison.reference.samples_per_pixel = 256;
  CLI::App* cmd = app.add_subcommand(
      "scatter", "Multiple scattering on a scene's medium: discrete ordinates and zonal method against Monte Carlo");
  cmd->add_option("scene", s->scene, "scene file (docs/scenes.md): medium, one directional light, phase, camera")->required();
  cmd->add_option("--width", s->width, "image width (default 64)");
  cmd->add_option("--height", s->height, "image height (default 64)");
  cmd->add_option("--points", s->points, "medium resampled on points^3 grid points (default 64)");
  cmd->add_option("--spp", s->comparison.reference.samples_per_pixel, "Monte Carlo paths per pixel (default 256)");
  cmd->add_option("--seed", s->comparison.reference.seed, "Monte Carlo seed (default 1)");
  cmd->add_option("--threads", s->threads, "threads (default all cores); results do not depend on it")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--grids", s->comparison.do_grids, "discrete-ordinates cells per axis (default 8,16,24,32)")->delimiter(',');
  cmd->add_option("--bins", s->comparison.do_bins, "bins per cube-face edge, 6 b^2 bins (default 1,2,3,4)")->delimiter(',');
  cmd->add_option("--zonal-grids", s->comparison.zonal_grids, "zonal cells per axis (default 6,8,10; isotropic only)")->delimiter(',');
  cmd->add_option("--images", s->images, "write PNGs of every image into this folder");
  cmd->add_option("--exposure", s->exposure, "PNG exposure (default 1)")->check(CLI::PositiveNumber);
  add_output_option(cmd, s->output, "JSON report here (atomically) instead of stdout");
  add_quiet_flag(cmd, s->quiet);
  add_shard_option(cmd, s->shard);
  cmd->callback([s]() {
    if (s->width < 1 || s->height < 1 || s->width > 4096 || s->height > 4096)
      throw std::invalid_argument("--width/--height: must be in [1, 4096]");
    if (s->comparison.reference.samples_per_pixel < 1) throw std::invalid_argument("--spp: must be >= 1");
    if (s->points < 2 || s->points > 512) throw std::invalid_argument("--points: must be in [2, 512]");
    for (int g : s->comparison.do_grids)
      if (g < 2 || g > 128) throw std::invalid_argument("--grids: each must be in [2, 128]");
    for (int b : s->comparison.do_bins)
      if (b < 1 || b > 8) throw std::invalid_argument("--bins: each must be in [1, 8]");
    for (int g : s->comparison.zonal_grids)
      if (g < 2 || g > 20) throw std::invalid_argument("--zonal-grids: each must be in [2, 20]");
    const json_source::InputFileLog read;  // the scene and the grid/data files it names: shard inputs
    const Scene scene = read_scene_file(s->scene);
    const std::vector<std::string> inputs = run_inputs({s->scene}, read);
    ComparisonOptions o = s->comparison;
    o.reference.threads = o.threads = s->threads;
    const bool quiet = s->quiet;
    const auto progress = [quiet](const std::string& m) {
      if (!quiet) std::cerr << "rayint scatter: " << m << "\n";
    };
    // --shard: this shard's rows of the Monte Carlo references and its share of the method runs;
    // merge: the comparison from the shards' parts (README, "Shards and merge").
    const bool in_shard = !s->shard.empty();
    const ShardSpec shard = begin_shard(s->shard, s->output);
    SceneVolumeComparison r;
    if (in_shard || merging()) {
      SceneVolumeSetup setup = scene_volume_setup(scene, s->width, s->height, s->points);
      if (in_shard) {
        write_shard(s->output, "scatter", shard, inputs,
                    to_json(compare_volume_methods_part(setup.volume, setup.camera, o, shard, progress)));
        return;
      }
      r.volume = std::move(setup.volume);
      r.comparison =
          finish_volume_comparison(merged_parts("scatter", inputs, volume_comparison_part_from_json, check_row_band));
      if (r.comparison.width != s->width || r.comparison.height != s->height)
        throw std::invalid_argument("merge: the shards' images are not --width x --height");
    } else {
      r = compare_volume_methods_on_scene(scene, s->width, s->height, s->points, o, progress);
    }
    const VolumeComparison& c = r.comparison;
    const nlohmann::json j = volume_comparison_json(s->scene, s->points, r.volume, o, c);
    if (!s->images.empty()) write_volume_comparison_images(c, s->images, s->exposure);
    emit(j.dump(2), s->output);
  });
}

}  // namespace rayint::cli
