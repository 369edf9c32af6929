// rayint scatter -- multiple scattering on a scene's medium: the Monte Carlo reference (every
// order, and single scattering with shadows), Max's discrete ordinates over grid sizes and bin
// counts, and the zonal method, each against the reference with its cost
// (src/rayint/scattering/volume_comparison.hpp). JSON report and PNG images.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "rayint/input/scene_reader.hpp"
#include "rayint/render/image.hpp"
#include "rayint/scattering/volume_comparison.hpp"

namespace rayint::cli {
namespace {

struct ScatterOptions {
  std::string scene;
  int width = 64, height = 64, points = 64, spp = 256, threads = 0;
  unsigned long long seed = 1;
  std::vector<int> grids{8, 16, 24, 32}, bins{1, 2, 3, 4}, zonal{6, 8, 10};
  std::string output, images;
  double exposure = 1.0;
  bool quiet = false;
};

Image grey(const std::vector<double>& v, int w, int h) {
  Image img(w, h);
  for (std::size_t i = 0; i < v.size(); ++i) img.pixels[i] = {v[i], v[i], v[i]};
  return img;
}

nlohmann::json error_json(const ImageError& e) {
  return {{"mean_abs", e.mean_abs}, {"rms", e.rms}, {"max_abs", e.max_abs},
          {"mean_rel_brightness", e.mean_rel_brightness}};
}

}  // namespace

void set_scatter_command(CLI::App& app) {
  auto s = std::make_shared<ScatterOptions>();
  CLI::App* cmd = app.add_subcommand(
      "scatter", "Multiple scattering on a scene's medium: discrete ordinates and zonal method against Monte Carlo");
  cmd->add_option("scene", s->scene, "scene file (docs/scenes.md): medium, one directional light, phase, camera")->required();
  cmd->add_option("--width", s->width, "image width (default 64)");
  cmd->add_option("--height", s->height, "image height (default 64)");
  cmd->add_option("--points", s->points, "medium resampled on points^3 grid points (default 64)");
  cmd->add_option("--spp", s->spp, "Monte Carlo paths per pixel (default 256)");
  cmd->add_option("--seed", s->seed, "Monte Carlo seed (default 1)");
  cmd->add_option("--threads", s->threads, "threads (default all cores); results do not depend on it")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--grids", s->grids, "discrete-ordinates cells per axis (default 8,16,24,32)")->delimiter(',');
  cmd->add_option("--bins", s->bins, "bins per cube-face edge, 6 b^2 bins (default 1,2,3,4)")->delimiter(',');
  cmd->add_option("--zonal-grids", s->zonal, "zonal cells per axis (default 6,8,10; isotropic only)")->delimiter(',');
  cmd->add_option("--images", s->images, "write PNGs of every image into this folder");
  cmd->add_option("--exposure", s->exposure, "PNG exposure (default 1)");
  cmd->add_option("-o,--output", s->output, "JSON report here (atomically) instead of stdout");
  cmd->add_flag("--quiet", s->quiet, "no progress on stderr");
  cmd->callback([s]() {
    if (s->width < 1 || s->height < 1 || s->width > 4096 || s->height > 4096)
      throw std::invalid_argument("--width/--height: must be in [1, 4096]");
    if (s->spp < 1) throw std::invalid_argument("--spp: must be >= 1");
    if (s->points < 2 || s->points > 512) throw std::invalid_argument("--points: must be in [2, 512]");
    for (int g : s->grids)
      if (g < 2 || g > 128) throw std::invalid_argument("--grids: each must be in [2, 128]");
    for (int b : s->bins)
      if (b < 1 || b > 8) throw std::invalid_argument("--bins: each must be in [1, 8]");
    for (int g : s->zonal)
      if (g < 2 || g > 20) throw std::invalid_argument("--zonal-grids: each must be in [2, 20]");
    const Scene scene = read_scene_file(s->scene);
    if (!scene.camera) throw std::invalid_argument(s->scene + ": rayint scatter needs a camera");
    if (!is_grey(scene.medium, scene.lights))
      throw std::invalid_argument(s->scene + ": rayint scatter needs the same extinction, albedo and light in r, g, b");
    Camera cam = *scene.camera;
    cam.width = s->width;
    cam.height = s->height;
    ScatteringVolume v = volume_from_medium(scene.medium, scene.lights, scene.phase, 0, s->points);
    v.background = 0.0;
    ComparisonOptions o;
    o.reference.samples_per_pixel = s->spp;
    o.reference.seed = s->seed;
    o.reference.threads = s->threads;
    o.threads = s->threads;
    o.do_grids = s->grids;
    o.do_bins = s->bins;
    o.zonal_grids = s->zonal;
    const bool quiet = s->quiet;
    const VolumeComparison c = compare_volume_methods(v, cam, o, [quiet](const std::string& m) {
      if (!quiet) std::cerr << "rayint scatter: " << m << "\n";
    });
    nlohmann::json runs = nlohmann::json::array();
    for (const auto& r : c.runs)
      runs.push_back({{"method", r.method}, {"grid", r.grid}, {"bins", r.bins},
                      {"iterations", r.iterations}, {"converged", r.converged},
                      {"setup_seconds", r.setup_seconds}, {"gather_seconds", r.gather_seconds},
                      {"error", error_json(r.error)}});
    auto mc_json = [](const EstimateImage& e) {
      return nlohmann::json{{"seconds", e.stats.seconds}, {"paths", e.stats.paths},
                            {"paths_per_second", static_cast<double>(e.stats.paths) / e.stats.seconds},
                            {"real_collisions", e.stats.real_collisions},
                            {"tentative_collisions", e.stats.tentative_collisions},
                            {"shadow_rays", e.stats.shadow_rays}};
    };
    const nlohmann::json j = {
        {"scene", s->scene}, {"width", c.width}, {"height", c.height}, {"points", s->points},
        {"albedo", v.albedo}, {"phase", v.phase.name()}, {"phase_g", v.phase.g()},
        {"reference", {{"spp", s->spp}, {"seed", s->seed}, {"every_order", mc_json(c.reference_all)},
                       {"single_scattering_with_shadows", mc_json(c.reference_single)},
                       {"mean_pixel_std_error", c.mean_reference_se}}},
        {"brightness", {{"multiple", c.brightness_all}, {"single_with_shadows", c.brightness_single},
                        {"ratio", c.brightness_single > 0 ? c.brightness_all / c.brightness_single : 0.0}}},
        {"runs", runs}};
    if (!s->images.empty()) {
      std::filesystem::create_directories(s->images);
      PngOptions po;
      po.exposure = s->exposure;
      write_png(s->images + "/monte_carlo_multiple.png", grey(c.reference_all.mean, c.width, c.height), po);
      write_png(s->images + "/monte_carlo_single_shadows.png", grey(c.reference_single.mean, c.width, c.height), po);
      for (const auto& r : c.runs)
        write_png(s->images + "/" + r.method + "_grid" + std::to_string(r.grid) +
                      (r.bins ? "_bins" + std::to_string(r.bins) : std::string()) + ".png",
                  grey(r.image, c.width, c.height), po);
    }
    emit(j.dump(2), s->output);
  });
}

}  // namespace rayint::cli
