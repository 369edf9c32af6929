#include "rayint/report/volume_comparison_json.hpp"

#include <filesystem>

#include "rayint/render/image.hpp"

namespace rayint {
namespace {

Image grey(const std::vector<double>& v, int w, int h) {
  Image img(w, h);
  for (std::size_t i = 0; i < v.size(); ++i) img.pixels[i] = {v[i], v[i], v[i]};
  return img;
}

nlohmann::json error_json(const ImageError& e) {
  return {{"mean_abs", e.mean_abs}, {"rms", e.rms}, {"max_abs", e.max_abs},
          {"mean_rel_brightness", e.mean_rel_brightness}};
}

nlohmann::json monte_carlo_json(const EstimateImage& e) {
  return nlohmann::json{{"seconds", e.stats.seconds}, {"paths", e.stats.paths},
                        {"paths_per_second", static_cast<double>(e.stats.paths) / e.stats.seconds},
                        {"real_collisions", e.stats.real_collisions},
                        {"tentative_collisions", e.stats.tentative_collisions},
                        {"shadow_rays", e.stats.shadow_rays}};
}

}  // namespace

nlohmann::json volume_comparison_json(const std::string& scene, int points, const ScatteringVolume& v,
                                      const ComparisonOptions& o, const VolumeComparison& c) {
  nlohmann::json runs = nlohmann::json::array();
  for (const auto& r : c.runs)
    runs.push_back({{"method", r.method}, {"grid", r.grid}, {"bins", r.bins},
                    {"iterations", r.iterations}, {"converged", r.converged},
                    {"setup_seconds", r.setup_seconds}, {"gather_seconds", r.gather_seconds},
                    {"error", error_json(r.error)}});
  return {
      {"scene", scene}, {"width", c.width}, {"height", c.height}, {"points", points},
      {"albedo", v.albedo}, {"phase", v.phase.name()}, {"phase_g", v.phase.g()},
      {"reference", {{"spp", o.reference.samples_per_pixel}, {"seed", o.reference.seed},
                     {"every_order", monte_carlo_json(c.reference_all)},
                     {"single_scattering_with_shadows", monte_carlo_json(c.reference_single)},
                     {"mean_pixel_std_error", c.mean_reference_se}}},
      {"brightness", {{"multiple", c.brightness_all}, {"single_with_shadows", c.brightness_single},
                      {"ratio", c.brightness_single > 0 ? c.brightness_all / c.brightness_single : 0.0}}},
      {"runs", runs}};
}

void write_volume_comparison_images(const VolumeComparison& c, const std::string& dir, double exposure) {
  std::filesystem::create_directories(dir);
  PngOptions po;
  po.exposure = exposure;
  write_png(dir + "/monte_carlo_multiple.png", grey(c.reference_all.mean, c.width, c.height), po);
  write_png(dir + "/monte_carlo_single_shadows.png", grey(c.reference_single.mean, c.width, c.height), po);
  for (const auto& r : c.runs)
    write_png(dir + "/" + r.method + "_grid" + std::to_string(r.grid) +
                  (r.bins ? "_bins" + std::to_string(r.bins) : std::string()) + ".png",
              grey(r.image, c.width, c.height), po);
}

}  // namespace rayint
