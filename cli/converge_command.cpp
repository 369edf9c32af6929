// `rayint converge SCENE.json --steps 0.2,0.1,0.05 (--methods riemann | --command TEMPLATE)`:
// a candidate renderer at a sequence of sample distances against the scene's exact image
// (method exact: trilinear grids through grid/trilinear_integral.hpp), the per-pixel error
// (median, p95, max over pixels of the largest channel error) against the step, the observed
// order of convergence, and whether the image is invariant to the step (studies/convergence.hpp).
// --expect-order P [--order-tolerance D]: exit 1 when the observed order is below P - D or any
// step failed (the JSON is written first). --methods riemann | nerf[:at=mid|near] (rayint's own
// quadratures, n = ceil(box diagonal / step)); --worst N lists each step's N worst pixels with
// their rays, --error-map-dir DIR writes each step's per-pixel error as DIR/step-<i>.npy. A command's template: {step} and {out} (a .pfm path
// rayint reads, or the extension given by --out-ext) are replaced; it must write a float image
// of the scene's camera size.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <unistd.h>
#include <sstream>

#include "commands.hpp"
#include "rayint/core/atomic_file.hpp"
#include "rayint/render/npy_array.hpp"
#include "options.hpp"
#include "rayint/core/error.hpp"
#include "rayint/core/format.hpp"
#include "rayint/input/scene_reader.hpp"
#include "rayint/render/float_image.hpp"
#include "rayint/report/convergence_json.hpp"
#include "rayint/scene/effect.hpp"
#include "rayint/scene/grid_field.hpp"
#include "rayint/scene/pipeline.hpp"
#include "rayint/studies/convergence.hpp"

namespace rayint::cli {

namespace {

Image render(const Scene& scene, unsigned threads) {
  ScenePipeline pipeline(scene, threads);
  SceneRenderOptions ro;
  ro.threads = threads;
  return pipeline.render(ro).image;
}

std::string replace_all(std::string s, const std::string& key, const std::string& value) {
  for (std::size_t p = s.find(key); p != std::string::npos; p = s.find(key, p + value.size()))
    s.replace(p, key.size(), value);
  return s;
}

std::string step_text(double h) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", h);
  return buf;
}

// Largest channel difference per pixel.
std::vector<double> pixel_differences(const Image& a, const Image& b) {
  std::vector<double> d;
  d.reserve(a.pixels.size());
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    double m = 0.0;
    for (int c = 0; c < kChannels; ++c) {
      const double x = std::abs(a.pixels[i][static_cast<std::size_t>(c)] - b.pixels[i][static_cast<std::size_t>(c)]);
      m = std::isnan(x) ? x : std::max(m, x);
    }
    d.push_back(m);
  }
  return d;
}

// The n largest of `d` (largest first; ties by pixel index), with both images' values and the
// pixel centre's ray.
std::vector<WorstPixel> worst_pixels(const std::vector<double>& d, const Image& img, const Image& exact,
                                     const Scene& scene, std::size_t n) {
  std::vector<std::size_t> order(d.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  n = std::min(n, order.size());
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(n), order.end(),
                    [&](std::size_t a, std::size_t b) { return d[a] > d[b] || (d[a] == d[b] && a < b); });
  std::vector<WorstPixel> out;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = order[k];
    WorstPixel w;
    w.x = static_cast<int>(i % static_cast<std::size_t>(exact.width));
    w.y = static_cast<int>(i / static_cast<std::size_t>(exact.width));
    w.error = d[i];
    for (std::size_t c = 0; c < 3; ++c) {
      w.candidate[c] = img.pixels[i][c];
      w.exact[c] = exact.pixels[i][c];
    }
    const ViewRay ray = scene.camera ? scene.camera->ray_at(w.x + 0.5, w.y + 0.5)
                                     : scene.rays[static_cast<std::size_t>(w.x)];
    for (Eigen::Index c = 0; c < 3; ++c) {
      w.origin[static_cast<std::size_t>(c)] = ray.origin[c];
      w.direction[static_cast<std::size_t>(c)] = ray.direction[c];
    }
    out.push_back(w);
  }
  return out;
}

}  // namespace

void set_converge_command(CLI::App& app) {
  struct Options {
    std::string input, output, methods, command, metric = "median", out_ext = ".pfm", error_map_dir;
    unsigned worst = 0;
    std::vector<double> steps;
    double expect_order = std::nan(""), order_tolerance = 0.2, invariance_tolerance = 1e-6;
    unsigned threads = 0;
    bool quiet = false;  // converge prints no progress; -q is accepted like every subcommand's
  };
  auto opt = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("converge", "Error of a renderer against the exact image as its sample distance shrinks");
  cmd->add_option("scene", opt->input, "scene JSON (its camera and medium)")->required();
  cmd->add_option("--steps", opt->steps, "sample distances (world units), e.g. 0.4,0.2,0.1,0.05")
      ->required()->delimiter(',');
  cmd->add_option("--methods", opt->methods,
                  "rayint's own method: riemann or nerf[:at=mid|near] (n = ceil(box diagonal / step))");
  cmd->add_option("--command", opt->command, "an external renderer: a shell command with {step} and {out}");
  cmd->add_option("--out-ext", opt->out_ext, "extension of {out} (.pfm, .exr, .npy)");
  cmd->add_option("--metric", opt->metric, "statistic the order is gated on: median, p95, max")
      ->check(CLI::IsMember({"median", "p95", "max"}));
  // Domains (docs/limits.md, "Domains of numeric options"): each checked before the scene is read,
  // one line naming the option, exit 2.
  cmd->add_option("--expect-order", opt->expect_order,
                  "exit 1 when the observed order is below this minus the tolerance (in (0, 100])");
  cmd->add_option("--order-tolerance", opt->order_tolerance,
                  "allowed shortfall of the order (default 0.2; >= 0 and below --expect-order)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--invariance-tolerance", opt->invariance_tolerance,
                  "images within this fraction of the exact peak of the finest are 'invariant to the step' (in [0, 1])");
  cmd->add_option("--worst", opt->worst,
                  "list each step's N worst pixels (error, values, ray) in the JSON (0 .. 100000)");
  cmd->add_option("--error-map-dir", opt->error_map_dir,
                  "write each step's per-pixel error (H x W float64) as DIR/step-<i>.npy");
  add_threads_option(cmd, opt->threads, "worker threads (0: all cores)");
  add_output_option(cmd, opt->output, "write the JSON here (default: stdout)");
  add_quiet_flag(cmd, opt->quiet);
  cmd->callback([opt] {
    if (opt->methods.empty() == opt->command.empty())
      throw InputError("--methods/--command: give exactly one candidate (--methods riemann or --command TEMPLATE)");
    // riemann, or nerf with at=mid|near; converge chooses n itself.
    std::string method_params;  // ":at=..." of nerf, as typed
    if (!opt->methods.empty() && opt->methods != "riemann") {
      const bool nerf = opt->methods.rfind("nerf", 0) == 0 &&
                        (opt->methods.size() == 4 || opt->methods[4] == ':');
      if (!nerf)
        throw InputError("--methods " + opt->methods + ": converge drives riemann or nerf[:at=mid|near] (the step is the parameter)");
      method_params = opt->methods.substr(4);
      MethodSpec trial;
      try {
        trial = parse_effect_method(*find_effect("emission"), "nerf" + method_params);
      } catch (const std::invalid_argument& e) {
        throw InputError("--methods " + opt->methods + ": " + e.what());
      }
      if (trial.has("n")) throw InputError("--methods " + opt->methods + ": n is set by converge from each step");
    }
    if (opt->worst > 100000) throw InputError("--worst: at most 100000 pixels, got " + std::to_string(opt->worst));
    if (!opt->error_map_dir.empty() && std::filesystem::exists(opt->error_map_dir) &&
        !std::filesystem::is_directory(opt->error_map_dir))
      throw InputError("--error-map-dir " + opt->error_map_dir + ": exists and is not a directory");
    if (opt->steps.size() < 2) throw InputError("--steps: give at least 2 sample distances");
    for (double h : opt->steps)
      if (!(std::isfinite(h) && h > 0.0)) throw InputError("--steps: " + step_text(h) + " is not a distance > 0");
    std::vector<double> steps = opt->steps;
    std::sort(steps.begin(), steps.end(), std::greater<double>());
    if (std::adjacent_find(steps.begin(), steps.end()) != steps.end()) throw InputError("--steps: repeated step");
    if (!opt->command.empty() && opt->command.find("{out}") == std::string::npos)
      throw InputError("--command: the template must contain {out} (where the image is written)");
    // An order of convergence is > 0 (riemann's is 1, nerf:at=mid's 2); above 100 a value can
    // only be a typo (every renderer would fail). A tolerance as large as the order would pass a
    // renderer whose error does not fall at all (observed order 0).
    if (std::isfinite(opt->expect_order) && !(opt->expect_order > 0.0 && opt->expect_order <= 100.0))
      throw InputError("--expect-order: must be in (0, 100], got " + format_number(opt->expect_order));
    if (std::isfinite(opt->expect_order) && !(opt->order_tolerance < opt->expect_order))
      throw InputError("--order-tolerance: " + format_number(opt->order_tolerance) + " must be below --expect-order " +
                       format_number(opt->expect_order) + " (else an error that does not fall passes)");
    if (!(opt->invariance_tolerance >= 0.0 && opt->invariance_tolerance <= 1.0))
      throw InputError("--invariance-tolerance: must be in [0, 1] (a fraction of the exact image's peak), got " +
                       format_number(opt->invariance_tolerance));

    const Scene scene = read_scene_file(opt->input);
    if (!exact_along_rays(scene.medium.field()))
      throw InputError(opt->input + ": medium: converge needs the exact image (a grid or homogeneous medium), not " +
                       scene.medium.field().kind());
    Image exact;
    try {
      exact = render(scene, opt->threads);
    } catch (const std::invalid_argument& e) {
      throw InputError(opt->input + ": (root): " + e.what());
    }
    ConvergenceResult result;
    for (const Rgb& p : exact.pixels)
      for (double v : p) result.peak = std::max(result.peak, std::abs(v));
    // Below this the exact image's own rounding (~1e-15 relative, tests [trilinear]) and the
    // float32 of a candidate file can dominate: not fitted.
    result.floor = 1e-12 * result.peak;
    result.metric = opt->metric;
    result.invariance_tolerance = opt->invariance_tolerance;
    if (std::isfinite(opt->expect_order)) {
      result.has_expectation = true;
      result.expected_order = opt->expect_order;
      result.order_tolerance = opt->order_tolerance;
    }
    const double diagonal = (scene.medium.bounds().upper - scene.medium.bounds().lower).norm();
    const std::filesystem::path tmp =
        std::filesystem::temp_directory_path() / ("rayint-converge-" + std::to_string(::getpid()));
    std::filesystem::create_directories(tmp);
    std::vector<Image> images;
    std::vector<std::pair<std::string, std::string>> maps;  // error maps, written after the run
    for (std::size_t i = 0; i < steps.size(); ++i) {
      ConvergenceRow row;
      row.step = steps[i];
      Image img;
      if (!opt->methods.empty()) {
        if (!std::isfinite(diagonal)) throw InputError(opt->input + ": medium: unbounded; riemann has no span to step");
        const double n = std::ceil(diagonal / steps[i]);
        if (n > 1e8) throw InputError("--steps: " + step_text(steps[i]) + " needs more than 1e8 samples per ray");
        Scene s = scene;
        const std::string method = opt->methods == "riemann" ? std::string("riemann") : std::string("nerf");
        const std::string spec =
            method + ":n=" + std::to_string(static_cast<long long>(n)) + (method == "nerf" ? method_params : "");
        for (const std::string& effect : {std::string("absorption"), std::string("emission")})
          if (s.has(effect)) s.methods[effect] = parse_effect_method(*find_effect(effect), spec);
        row.candidate = spec;
        img = render(s, opt->threads);
      } else {
        const std::string out = (tmp / ("step-" + std::to_string(i) + opt->out_ext)).string();
        const std::string command =
            replace_all(replace_all(opt->command, "{step}", step_text(steps[i])), "{out}", out);
        row.candidate = command;
        const int status = std::system(command.c_str());
        if (status != 0) {
          row.failed = true;
          row.failure = "command exited with status " + std::to_string(status);
        } else {
          try {
            img = read_image(out);
            if (img.width != exact.width || img.height != exact.height) {
              row.failed = true;
              row.failure = out + ": " + std::to_string(img.width) + "x" + std::to_string(img.height) +
                            " image, the scene's camera is " + std::to_string(exact.width) + "x" +
                            std::to_string(exact.height);
            }
          } catch (const std::exception& e) {
            row.failed = true;
            row.failure = e.what();
          }
        }
      }
      if (!row.failed) {
        const std::vector<double> d = pixel_differences(img, exact);
        row.error = pixel_error_stats(d);
        if (!std::isfinite(row.error.max)) {
          row.failed = true;
          row.failure = "the image holds a NaN or infinite value";
        } else {
          if (opt->worst > 0) row.worst = worst_pixels(d, img, exact, scene, opt->worst);
          if (!opt->error_map_dir.empty()) {
            row.error_map = (std::filesystem::path(opt->error_map_dir) / ("step-" + std::to_string(i) + ".npy")).string();
            maps.emplace_back(row.error_map, encode_npy_array(d, {static_cast<std::size_t>(exact.height),
                                                                 static_cast<std::size_t>(exact.width)}));
          }
        }
      }
      images.push_back(row.failed ? Image{} : img);
      result.rows.push_back(row);
    }
    std::filesystem::remove_all(tmp);
    const Image& finest = images.back();
    for (std::size_t i = 0; i < images.size(); ++i)
      if (!result.rows[i].failed && !result.rows.back().failed) {
        const std::vector<double> d = pixel_differences(images[i], finest);
        result.rows[i].change_from_finest = d.empty() ? 0.0 : *std::max_element(d.begin(), d.end());
      }
    conclude(result);
    if (!opt->error_map_dir.empty()) {
      std::error_code ec;
      std::filesystem::create_directories(opt->error_map_dir, ec);
      if (ec) throw InputError("--error-map-dir " + opt->error_map_dir + ": " + ec.message());
      for (const auto& [path, bytes] : maps) write_file_atomically(path, bytes);
    }
    emit(convergence_json(result).dump(2) + "\n", opt->output);
    if (!result.passed) throw ChecksFailed{};
  });
}

}  // namespace rayint::cli
