// `rayint render MESHCASE.json -o image.png [--compare METHOD] [--stats stats.json]`: the exact
// image of a mesh case's camera; with --compare, the other method's per-pixel relative error as
// a heat map next to the output (<output stem>.error.png) and the error statistics in the stats
// JSON. Progress on stderr (library callback), threads over image rows.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "commands.hpp"
#include "render_kinds.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/core/atomic_file.hpp"
#include "rayint/input/case_reader.hpp"
#include "rayint/input/mesh_case_reader.hpp"
#include "rayint/render/image.hpp"
#include "rayint/render/mesh_render.hpp"

namespace rayint::cli {
namespace {

std::string heat_map_path(const std::string& output) {
  std::filesystem::path p(output);
  p.replace_extension();
  return p.string() + ".error.png";
}

nlohmann::json cost_json(const MeshRenderCost& c) {
  const double busy = c.traversal_seconds + c.integration_seconds;
  const TraversalStats& t = c.traversal;
  return {{"wall_seconds", c.wall_seconds},
          {"threads", c.threads},
          {"rays", c.rays},
          {"segments", c.segments},
          {"pieces", c.pieces},
          {"rays_per_second", c.wall_seconds > 0 ? static_cast<double>(c.rays) / c.wall_seconds : 0.0},
          {"pieces_per_second", c.wall_seconds > 0 ? static_cast<double>(c.pieces) / c.wall_seconds : 0.0},
          {"traversal_seconds", c.traversal_seconds},
          {"integration_seconds", c.integration_seconds},
          {"traversal_share", busy > 0 ? c.traversal_seconds / busy : 0.0},
          {"integration_share", busy > 0 ? c.integration_seconds / busy : 0.0},
          {"traversal", {{"face_steps", t.face_steps}, {"zero_length_steps", t.zero_length_steps},
                         {"star_searches", t.star_searches}, {"first_hit_queries", t.first_hit_queries},
                         {"budget_exhausted", t.budget_exhausted}}}};
}

}  // namespace

void render_mesh_file(const nlohmann::json& root, const RenderOptions& options) {
  const MeshCase mc = parse_mesh_case(root, options.input);
  if (!mc.camera) throw InputError(options.input + ": camera: required to render a mesh case");
  // Validate the methods before the (long) render.
  const auto exact = make_integrator(parse_method_spec("exact"), mc.transfer);
  std::unique_ptr<RayIntegrator> compare;
  std::string compare_label;
  if (!options.compare.empty()) {
    const MethodSpec spec = parse_method_spec(options.compare);
    compare = make_integrator(spec, mc.transfer);
    compare_label = spec.label();
  }
  const TetTraversal mesh(mc.mesh, mc.mesh_source);
  MeshRenderSettings settings;
  settings.threads = options.threads;
  if (!options.quiet)
    settings.progress = [](int done, int total) {
      std::fprintf(stderr, "\rrayint render: %d/%d rows", done, total);
      if (done == total) std::fputc('\n', stderr);
      std::fflush(stderr);
    };
  const MeshRender r = render_mesh(mc, mesh, *exact, compare.get(), settings);
  PngOptions png;
  png.exposure = options.exposure;
  nlohmann::json stats = {{"case", mc.name},
                          {"source", mc.source},
                          {"mesh", {{"source", mc.mesh_source}, {"points", mc.mesh.points.size()},
                                    {"tets", mc.mesh.tets.size()}, {"boundary_faces", mesh.boundary_face_count()}}},
                          {"width", mc.camera->width},
                          {"height", mc.camera->height},
                          {"method", "exact"},
                          {"shading", mc.shading.enabled},
                          {"cost", cost_json(r.cost)}};
  if (compare) {
    const ErrorSummary& e = r.error;
    stats["compare"] = {{"method", compare_label},
                        {"heat_map", heat_map_path(options.output)},
                        {"pixels", e.pixels},
                        {"max_rel_error", e.max_rel},
                        {"mean_rel_error", e.mean_rel},
                        {"median_rel_error", e.median_rel},
                        {"p99_rel_error", e.p99_rel},
                        {"max_abs_error", e.max_abs},
                        {"non_finite", e.non_finite}};
  }
  write_png(options.output, r.image, png);
  if (compare) write_png(heat_map_path(options.output), error_heat_map(r.rel_error, r.image.width, r.image.height));
  if (!options.stats_path.empty()) write_file_atomically(options.stats_path, stats.dump(2) + "\n");
  if (!options.quiet) {
    const MeshRenderCost& c = r.cost;
    const double busy = c.traversal_seconds + c.integration_seconds;
    std::fprintf(stderr,
                 "rayint render: %ld rays in %.3f s on %u threads: %.3g rays/s, %.3g pieces/s, "
                 "traversal %.0f%% / integration %.0f%%\n",
                 c.rays, c.wall_seconds, c.threads, static_cast<double>(c.rays) / c.wall_seconds,
                 static_cast<double>(c.pieces) / c.wall_seconds, busy > 0 ? 100 * c.traversal_seconds / busy : 0.0,
                 busy > 0 ? 100 * c.integration_seconds / busy : 0.0);
    if (compare)
      std::fprintf(stderr, "rayint render: %s vs exact: max rel %.3g, median %.3g, p99 %.3g -> %s\n",
                   compare_label.c_str(), r.error.max_rel, r.error.median_rel, r.error.p99_rel,
                   heat_map_path(options.output).c_str());
  }
}

}  // namespace rayint::cli
