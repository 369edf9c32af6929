// rayint check CASE_OR_SCENE --candidate-image IMAGE: the exact image of a mesh case's camera
// (render/mesh_render.hpp with `exact`), or a scene's reference image (scene/pipeline.hpp
// reference_image), against the renderer's float image, pixel by pixel (render/image_compare.hpp);
// JSON diff, heat map, worst pixels as replayable case (or one-ray scene) files, JUnit.
#include "check_image.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "commands.hpp"
#include "rayint/core/output_dir.hpp"
#include "render_kinds.hpp"
#include "rayint/core/atomic_file.hpp"
#include "rayint/core/error.hpp"
#include "rayint/core/format.hpp"
#include "rayint/input/case_reader.hpp"
#include "rayint/input/json_source.hpp"
#include "rayint/input/mesh_case_reader.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/render/float_image.hpp"
#include "rayint/render/image_compare.hpp"
#include "rayint/render/cell_mesh_render.hpp"
#include "rayint/mesh/quadratic_tets.hpp"
#include "rayint/render/mesh_render.hpp"
#include "rayint/input/scene_reader.hpp"
#include "rayint/scene/pipeline.hpp"
#include "rayint/report/case_writer.hpp"
#include "rayint/report/image_check_json.hpp"
#include "rayint/report/junit.hpp"

namespace rayint::cli {
namespace {

std::string join(const std::string& dir, const std::string& name) {
  return (std::filesystem::path(dir) / name).string();
}

std::string vec_text(const Vec3& v) {
  return "[" + format_number(v.x()) + ", " + format_number(v.y()) + ", " + format_number(v.z()) + "]";
}


// The candidate (and variance) image, flipped, checked against the expected size. `what` names
// the source of the expected size in the message ("the camera of cam.json"). With
// --candidate-alpha, an RGBA candidate is first composited over `background`
// (render/image_compare.hpp); nullptr: no single background colour (scenes), the option is refused.
Image read_candidate(const ImageCheckOptions& o, int width, int height, const std::string& what,
                     const Rgb* background) {
  const AlphaMode alpha_mode = o.alpha_mode == "premultiplied" ? AlphaMode::premultiplied
                               : o.alpha_mode == "straight"    ? AlphaMode::straight
                                                               : AlphaMode::ignore;
  if (alpha_mode != AlphaMode::ignore && background == nullptr)
    throw InputError(o.case_file + ": background: --candidate-alpha " + o.alpha_mode +
                     " needs a mesh case (one background colour to composite over)");
  const auto wrong_size = [&](int w, int h) {
    return InputError(o.candidate_image + ": (image): " + std::to_string(w) + " x " + std::to_string(h) +
                      " pixels, " + what + " has " + std::to_string(width) + " x " + std::to_string(height));
  };
  // The size from the header first: a candidate of another size (a 16384 x 16384 PNG against a
  // 64 x 64 camera) is refused before its pixels are read or decoded.
  const ImageSize declared = read_image_size(o.candidate_image);
  if (declared.width != width || declared.height != height) throw wrong_size(declared.width, declared.height);
  const ImageWithAlpha raw = read_image_with_alpha(o.candidate_image);
  Image composited;
  try {
    composited = alpha_mode == AlphaMode::ignore ? raw.rgb
                                                 : composite_over(raw.rgb, raw.alpha, *background, alpha_mode);
  } catch (const std::invalid_argument& e) {
    throw InputError(o.candidate_image + ": --candidate-alpha " + o.alpha_mode + ": " + e.what());
  }
  const Image candidate = flipped(composited, o.flip_x, o.flip_y);
  if (candidate.width != width || candidate.height != height) throw wrong_size(candidate.width, candidate.height);
  return candidate;
}

// The variance of the candidate's mean per pixel (empty image without --candidate-variance).
Image read_variance(const ImageCheckOptions& o, const Image& candidate) {
  Image variance;
  if (!o.candidate_variance.empty()) {
    const ImageSize declared = read_image_size(o.candidate_variance);  // before reading the pixels
    if (declared.width != candidate.width || declared.height != candidate.height)
      throw InputError(o.candidate_variance + ": (image): " + std::to_string(declared.width) + " x " +
                       std::to_string(declared.height) + " pixels, the candidate has " +
                       std::to_string(candidate.width) + " x " + std::to_string(candidate.height));
    variance = flipped(read_image(o.candidate_variance), o.flip_x, o.flip_y);
    if (variance.width != candidate.width || variance.height != candidate.height)
      throw InputError(o.candidate_variance + ": (image): " + std::to_string(variance.width) + " x " +
                       std::to_string(variance.height) + " pixels, the candidate has " +
                       std::to_string(candidate.width) + " x " + std::to_string(candidate.height));
    for (std::size_t i = 0; i < variance.pixels.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        double& v = variance.pixels[i][c];
        if (!(v >= 0.0) || !std::isfinite(v))
          throw InputError(o.candidate_variance + ": pixel(" + std::to_string(i % static_cast<std::size_t>(variance.width)) +
                           "," + std::to_string(i / static_cast<std::size_t>(variance.width)) +
                           "): variance must be finite and >= 0, got " + format_number(v));
        if (o.samples > 0) v /= static_cast<double>(o.samples);
      }
  } else if (o.samples > 0) {
    throw InputError("--samples: needs --candidate-variance (the per-sample variance image)");
  }
  if (!o.artifacts.empty()) ensure_output_directory(o.artifacts, "--artifacts");
  return variance;
}

// Compares, runs the z-test when there is a variance image, writes the heat map, lets
// `write_worst` write the worst pixels' files into ctx.worst_cases, then the diff and JUnit.
void finish_check(const ImageCheckOptions& o, const Image& expected, const Image& candidate,
                  const Image& variance, ImageCheckContext& ctx,
                  const std::function<void(const ImageComparison&, ImageCheckContext&)>& write_worst) {
  ImageCompareOptions co;
  co.rel_tol = o.rel_tol;
  co.abs_tol = o.abs_tol;
  co.worst = o.worst;
  const ImageComparison cmp = compare_images(expected, candidate, co);

  ZTestResult z;
  if (!o.candidate_variance.empty()) {
    ZTestOptions zo;
    zo.alpha = o.alpha;
    zo.min_fraction = o.min_fraction;
    z = z_test_images(expected, candidate, variance, zo);
    ctx.z_test = &z;
    ctx.alpha = o.alpha;
    ctx.min_fraction = o.min_fraction;
    ctx.samples = o.samples;
    ctx.variance_source = o.candidate_variance;
  }
  ctx.candidate_source = o.candidate_image;
  ctx.rel_tol = o.rel_tol;
  ctx.abs_tol = o.abs_tol;
  ctx.flip_x = o.flip_x;
  ctx.flip_y = o.flip_y;
  if (o.alpha_mode == "premultiplied" || o.alpha_mode == "straight") ctx.alpha_mode = o.alpha_mode;
  if (!o.artifacts.empty()) {  // without --artifacts nothing but the diff (-o) is written
    ctx.heat_map = join(o.artifacts, "error_heat_map.png");
    write_png(ctx.heat_map, error_heat_map(cmp.rel_error, cmp.width, cmp.height));
    write_worst(cmp, ctx);
  }
  emit(image_check_json(ctx, cmp).dump(2) + "\n", o.output);
  if (!o.junit.empty())
    write_file_atomically(o.junit, junit_xml({ctx.z_test ? z_test_junit(ctx.case_name, z, o.min_fraction)
                                                         : image_check_junit(ctx.case_name, cmp)}));
  std::cout.flush();
  if (!o.quiet) std::cerr << image_check_summary_line(ctx, cmp) << std::endl;
  if (!(ctx.z_test ? z.pass : cmp.pass)) throw ChecksFailed{};
}

std::string dir_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

// Every "grid_file" in a scene, made absolute, so a scene written elsewhere still finds it.
void absolute_grid_files(nlohmann::json& j, const std::string& base_dir) {
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      if (it.key() == "grid_file" && it->is_string()) {
        const std::filesystem::path p(it->get<std::string>());
        if (p.is_relative()) *it = std::filesystem::absolute(std::filesystem::path(base_dir) / p).lexically_normal().string();
      } else {
        absolute_grid_files(*it, base_dir);
      }
    }
  } else if (j.is_array()) {
    for (nlohmann::json& e : j) absolute_grid_files(e, base_dir);
  }
}

nlohmann::json vec_json(const Vec3& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); }

// `rayint check SCENE --candidate-image IMAGE`: the expected image is the scene's reference image
// (ScenePipeline::reference_image). A worst pixel cannot be a segment case (a scene's terms are
// not segments), so it is written as the same scene with that pixel's ray as its one explicit ray
// and that pixel's background as a constant colour: `rayint check worst_pixel_<i>.json
// --candidate-image ONE_PIXEL.npy` replays the check of that pixel, and `rayint render
// worst_pixel_<i>.json -o p.npy --errors 1` the scene's own methods and reference on it.
void run_scene_image_check(const ImageCheckOptions& o, const nlohmann::json& root) {
  if (is_slab_scene(root))
    throw InputError(o.case_file + ": medium.type: \"slab\" is a plane-parallel slab with detectors, not an "
                     "image; check its detectors with `rayint slab --scene " + o.case_file + "`");
  Scene scene = parse_scene(root, o.case_file, dir_of(o.case_file));
  std::unique_ptr<ScenePipeline> pipeline;
  try {
    pipeline = std::make_unique<ScenePipeline>(scene, o.threads);
  } catch (const std::invalid_argument& e) {
    throw InputError(o.case_file + ": (root): " + json_source::one_line(e.what()));
  }
  const int width = scene.camera ? scene.camera->width : static_cast<int>(scene.rays.size());
  const int height = scene.camera ? scene.camera->height : 1;
  const Image candidate = read_candidate(o, width, height,
                                         scene.camera ? "the camera of " + o.case_file
                                                      : "the " + std::to_string(width) + " rays (x 1) of " + o.case_file,
                                         nullptr);
  Image variance = read_variance(o, candidate);

  const ReferenceImage ref = pipeline->reference_image(o.threads);
  ImageCheckContext::SceneReference info;
  if (!o.artifacts.empty()) {
    info.image = join(o.artifacts, "reference.npy");
    write_image(info.image, ref.value);
  }
  info.max_error = ref.max_error;
  info.unconverged = ref.unconverged;
  info.evaluations = ref.evaluations;
  info.seconds = ref.seconds;
  if (!o.candidate_variance.empty()) {
    // A Monte Carlo reference (multiple_scattering) has a variance of its own: its error estimate
    // is two standard errors, so (error / 2)^2 joins the candidate's variance of the mean.
    for (std::size_t i = 0; i < variance.pixels.size(); ++i)
      for (int c = 0; c < kChannels; ++c) {
        const double s = 0.5 * ref.error.pixels[i][c];
        variance.pixels[i][c] += s * s;
      }
    info.variance_added = true;
  }
  ImageCheckContext ctx;
  ctx.case_name = scene.name;
  ctx.case_source = o.case_file;
  ctx.scene_reference = &info;
  if (ref.unconverged > 0)
    ctx.note = std::to_string(ref.unconverged) + " pixels' references reported non-convergence "
               "(the scene's \"reference\" tolerances); their expected values are less certain";
  finish_check(o, ref.value, candidate, variance, ctx, [&](const ImageComparison& cmp, ImageCheckContext& c) {
    for (std::size_t i = 0; i < cmp.worst.size(); ++i) {
      const PixelDiff& w = cmp.worst[i];
      const PixelRay pr = pipeline->ray(static_cast<long long>(w.y) * width + w.x);
      nlohmann::json pixel = root;
      absolute_grid_files(pixel, dir_of(o.case_file));
      const std::string name = scene.name + "-pixel-" + std::to_string(w.x) + "-" + std::to_string(w.y);
      pixel["name"] = name;
      pixel["description"] =
          "Generated by `rayint check " + o.case_file + " --candidate-image " + o.candidate_image +
          "`: pixel (" + std::to_string(w.x) + ", " + std::to_string(w.y) + ") of the scene, as its one "
          "explicit ray, with that pixel's background as a constant colour. Candidate " +
          format_number(w.got) + " in channel " + "rgb"[w.channel] + ", reference " + format_number(w.expected) +
          " (reference error estimate " + format_number(ref.error.at(w.x, w.y)[w.channel]) + ").";
      pixel.erase("camera");
      pixel["rays"] = nlohmann::json::array({{{"origin", vec_json(pr.ray.origin)}, {"direction", vec_json(pr.ray.direction)}}});
      pixel["background"] = {{"color", nlohmann::json::array({pr.background[0], pr.background[1], pr.background[2]})}};
      const std::string path = join(o.artifacts, "worst_pixel_" + std::to_string(i) + ".json");
      write_file_atomically(path, pixel.dump(2) + "\n");
      c.worst_cases.push_back(path);
    }
  });
}

// Cells other than tetrahedra in their own interpolation (mesh/cell_traversal.hpp): the expected
// image is the own render; a pixel whose chords failed is NaN there and makes the check fail.
void run_own_cells_image_check(const ImageCheckOptions& o, MeshCase& mc, const Image& candidate, const Image& variance) {
  const CellTraversal mesh(std::move(*mc.cells), mc.mesh_source);
  MeshRenderSettings settings;
  settings.threads = o.threads;
  const CellMeshRender render = render_cell_mesh(mc, mesh, settings);
  if (!o.quiet)
    std::fprintf(stderr, "rayint check: mode own: the expected image integrates the cells in their own (isoparametric) "
                 "interpolation (--cells split: VTK's tetrahedralisation)\n");
  ImageCheckContext ctx;
  ctx.case_name = mc.name;
  ctx.case_source = o.case_file;
  ctx.mode = "own";
  ctx.failed_pixels = render.failed_pixels;
  finish_check(o, render.image, candidate, variance, ctx, [&](const ImageComparison&, ImageCheckContext& c) {
    c.note = "own interpolation of cells other than tetrahedra: a pixel is not a segment case, no worst-pixel case files";
  });
  if (render.failed_pixels > 0) throw ChecksFailed{};
}

}  // namespace

void run_image_check(const ImageCheckOptions& o) {
  const nlohmann::json root = json_source::parse(json_source::read_text_file(o.case_file), o.case_file);
  if (root.is_object() && (root.contains("effects") || root.contains("medium")))
    return run_scene_image_check(o, root);
  if (!root.is_object() || !(root.contains("mesh") || root.contains("mesh_file")))
    throw InputError(o.case_file + ": camera: --candidate-image needs a mesh case with a \"camera\" "
                     "or a scene (per-ray cases are checked with --candidate)");
  MeshCase mc = parse_mesh_case(root, o.case_file, o.mesh);
  if (!mc.camera) throw InputError(o.case_file + ": camera: --candidate-image needs the case's \"camera\"");
  check_camera_reaches_mesh(mc, o.case_file);
  const Image candidate = read_candidate(o, mc.camera->width, mc.camera->height, "the camera of " + o.case_file,
                                         &mc.background);
  const Image variance = read_variance(o, candidate);
  if (mc.cells) return run_own_cells_image_check(o, mc, candidate, variance);

  // Quadratic tetrahedra: render_mesh integrates their chords exactly as polynomials
  // (mesh/quadratic_tets.hpp, QuadraticTraceIntegrator) and does not use `exact` then.
  const auto exact = make_integrator(parse_method_spec("exact"), mc.transfer);
  const TetTraversal mesh(mc.mesh, mc.neighbors, mc.mesh_source);
  MeshRenderSettings settings;
  settings.threads = o.threads;
  const MeshRender render = render_mesh(mc, mesh, *exact, nullptr, settings);

  ImageCheckContext ctx;
  ctx.case_name = mc.name;
  ctx.case_source = o.case_file;
  finish_check(o, render.image, candidate, variance, ctx, [&](const ImageComparison& cmp, ImageCheckContext& c) {
    // Each worst pixel as a one-ray case: the camera ray of that pixel traced through the mesh,
    // with the case's transfer functions and background, so `rayint eval` replays it.
    if (mc.shading.enabled) {
      c.note = "the case has surface shading, which a segment case cannot hold: no worst-pixel case files";
      return;
    }
    if (mesh.quadratic()) {
      c.note = "the mesh has quadratic tetrahedra, whose quadratic chords a segment case cannot hold: no worst-pixel case files";
      return;
    }
    RayTrace trace;
    for (std::size_t i = 0; i < cmp.worst.size(); ++i) {
      const PixelDiff& w = cmp.worst[i];
      const ViewRay vr = mc.camera->ray_for_pixel(w.x, w.y);
      mesh.trace(vr, trace);
      Case pixel;
      pixel.name = mc.name + "-pixel-" + std::to_string(w.x) + "-" + std::to_string(w.y);
      pixel.description = "Generated by `rayint check " + o.case_file + " --candidate-image " +
                          o.candidate_image + "`: pixel (" + std::to_string(w.x) + ", " +
                          std::to_string(w.y) + ") of the camera, ray origin " + vec_text(vr.origin) +
                          ", direction " + vec_text(vr.direction) + ", traced through the mesh. "
                          "Candidate " + format_number(w.got) + " in channel " + "rgb"[w.channel] +
                          ", exact " + format_number(w.expected) + ".";
      pixel.transfer = mc.transfer;
      pixel.rays.push_back(ray_from_trace(trace, mc.background));
      const std::string path = join(o.artifacts, "worst_pixel_" + std::to_string(i) + ".json");
      write_case_file(path, pixel);
      c.worst_cases.push_back(path);
    }
  });
}

}  // namespace rayint::cli
