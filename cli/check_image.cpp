// rayint check CASE --candidate-image IMAGE: the exact image of a mesh case's camera (render/
// mesh_render.hpp with `exact`) against the renderer's float image, pixel by pixel
// (render/image_compare.hpp); JSON diff, heat map, worst pixels as replayable case files, JUnit.
#include "check_image.hpp"

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "commands.hpp"
#include "rayint/core/atomic_file.hpp"
#include "rayint/core/error.hpp"
#include "rayint/core/format.hpp"
#include "rayint/input/case_reader.hpp"
#include "rayint/input/json_source.hpp"
#include "rayint/input/mesh_case_reader.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/render/float_image.hpp"
#include "rayint/render/image_compare.hpp"
#include "rayint/render/mesh_render.hpp"
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

}  // namespace

void run_image_check(const ImageCheckOptions& o) {
  const nlohmann::json root = json_source::parse(json_source::read_text_file(o.case_file), o.case_file);
  if (!root.is_object() || !(root.contains("mesh") || root.contains("mesh_file")))
    throw InputError(o.case_file + ": camera: --candidate-image needs a mesh case with a \"camera\" "
                     "(per-ray cases are checked with --candidate)");
  const MeshCase mc = parse_mesh_case(root, o.case_file);
  if (!mc.camera) throw InputError(o.case_file + ": camera: --candidate-image needs the case's \"camera\"");
  // --candidate-alpha: composite the candidate over the case's background first (render/image_compare.hpp).
  const AlphaMode alpha_mode = o.alpha_mode == "premultiplied" ? AlphaMode::premultiplied
                               : o.alpha_mode == "straight"    ? AlphaMode::straight
                                                               : AlphaMode::ignore;
  const ImageWithAlpha raw = read_image_with_alpha(o.candidate_image);
  Image composited;
  try {
    composited = composite_over(raw.rgb, raw.alpha, mc.background, alpha_mode);
  } catch (const std::invalid_argument& e) {
    throw InputError(o.candidate_image + ": --candidate-alpha " + o.alpha_mode + ": " + e.what());
  }
  const Image candidate = flipped(composited, o.flip_x, o.flip_y);
  if (candidate.width != mc.camera->width || candidate.height != mc.camera->height)
    throw InputError(o.candidate_image + ": (image): " + std::to_string(candidate.width) + " x " +
                     std::to_string(candidate.height) + " pixels, the camera of " + o.case_file +
                     " has " + std::to_string(mc.camera->width) + " x " + std::to_string(mc.camera->height));
  Image variance;
  if (!o.candidate_variance.empty()) {
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
  if (!std::filesystem::is_directory(o.artifacts))
    throw InputError(o.artifacts + ": --artifacts: not a directory");

  const auto exact = make_integrator(parse_method_spec("exact"), mc.transfer);
  const TetTraversal mesh(mc.mesh, mc.mesh_source);
  MeshRenderSettings settings;
  settings.threads = o.threads;
  const MeshRender render = render_mesh(mc, mesh, *exact, nullptr, settings);

  ImageCompareOptions co;
  co.rel_tol = o.rel_tol;
  co.abs_tol = o.abs_tol;
  co.worst = o.worst;
  const ImageComparison cmp = compare_images(render.image, candidate, co);

  ZTestResult z;
  ImageCheckContext ctx;
  if (!o.candidate_variance.empty()) {
    ZTestOptions zo;
    zo.alpha = o.alpha;
    zo.min_fraction = o.min_fraction;
    z = z_test_images(render.image, candidate, variance, zo);
    ctx.z_test = &z;
    ctx.alpha = o.alpha;
    ctx.min_fraction = o.min_fraction;
    ctx.samples = o.samples;
    ctx.variance_source = o.candidate_variance;
  }
  ctx.case_name = mc.name;
  ctx.case_source = o.case_file;
  ctx.candidate_source = o.candidate_image;
  ctx.rel_tol = o.rel_tol;
  ctx.abs_tol = o.abs_tol;
  ctx.flip_x = o.flip_x;
  ctx.flip_y = o.flip_y;
  if (alpha_mode != AlphaMode::ignore) ctx.alpha_mode = o.alpha_mode;
  ctx.heat_map = join(o.artifacts, "error_heat_map.png");
  write_png(ctx.heat_map, error_heat_map(cmp.rel_error, cmp.width, cmp.height));
  // Each worst pixel as a one-ray case: the camera ray of that pixel traced through the mesh,
  // with the case's transfer functions and background, so `rayint eval` replays it.
  if (mc.shading.enabled) {
    ctx.note = "the case has surface shading, which a segment case cannot hold: no worst-pixel case files";
  } else {
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
      ctx.worst_cases.push_back(path);
    }
  }
  emit(image_check_json(ctx, cmp).dump(2) + "\n", o.output);
  if (!o.junit.empty())
    write_file_atomically(o.junit, junit_xml({ctx.z_test ? z_test_junit(mc.name, z, o.min_fraction)
                                                         : image_check_junit(mc.name, cmp)}));
  std::cout.flush();
  if (!o.quiet) std::cerr << image_check_summary_line(ctx, cmp) << std::endl;
  if (!(ctx.z_test ? z.pass : cmp.pass)) throw ChecksFailed{};
}

}  // namespace rayint::cli
