// `rayint render MESHCASE.json -o image.png [--compare METHOD] [--stats stats.json]`: the exact
// image of a mesh case's camera; with --compare, the other method's per-pixel relative error as
// a heat map next to the output (<output stem>.error.png) and the error statistics in the stats
// JSON. Progress on stderr (library callback), threads over image rows.
#include <cstdio>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include <memory>
#include <utility>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "commands.hpp"
#include "progress.hpp"
#include "render_kinds.hpp"
#include "shard.hpp"
#include "rayint/input/shard_reader.hpp"
#include "rayint/report/shard_json.hpp"
#include "rayint/integrators/integrator.hpp"
#include "rayint/core/atomic_file.hpp"
#include "rayint/core/error.hpp"
#include "rayint/core/format.hpp"
#include "rayint/core/limits.hpp"
#include "rayint/geometry/camera_fit.hpp"
#include "rayint/mesh/cell_split.hpp"
#include "rayint/mesh/quadratic_tets.hpp"
#include "rayint/input/case_reader.hpp"
#include "rayint/input/mesh_case_reader.hpp"
#include "rayint/render/float_image.hpp"
#include "rayint/render/image.hpp"
#include "rayint/render/cell_mesh_render.hpp"
#include "rayint/render/mesh_render.hpp"
#include "rayint/report/cell_render_json.hpp"
#include "rayint/report/mesh_render_json.hpp"

namespace rayint::cli {
namespace {

// Threads and the rows progress line, shared by the tetrahedral and the own-cells renders.
MeshRenderSettings render_settings(const RenderOptions& options) {
  MeshRenderSettings settings;
  settings.threads = options.threads;
  auto progress_line = std::make_shared<ProgressLine>();
  if (!options.quiet)
    settings.progress = [progress_line](int done, int total) {
      progress_line->update("rayint render: " + std::to_string(done) + "/" + std::to_string(total) + " rows",
                            static_cast<double>(done) / total);
      if (done == total) progress_line->finish();
    };
  return settings;
}

std::string heat_map_path(const std::string& output) {
  std::filesystem::path p(output);
  p.replace_extension();
  return p.string() + ".error.png";
}

// The case's mesh points: the tetrahedra's, or the cells' in the own mode.
const std::vector<Vec3>& case_points(const MeshCase& mc) { return mc.cells ? mc.cells->points : mc.mesh.points; }

// --fit: the case's camera (or a 256 x 256 one looking down -z) moved to frame the mesh's bounds.
// Returns the line that states the camera used (a result, printed with -q too), which the caller
// prints once the outputs are written: a render or merge that fails after the fit prints its
// error alone ("one line, once", issue 30).
std::string fit_camera_to_mesh(MeshCase& mc) {
  const std::vector<Vec3>& points = case_points(mc);
  if (points.empty()) throw InputError(mc.mesh_source + ": points: --fit needs a mesh with points");
  Vec3 lo = points.front(), hi = lo;
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  Camera base;
  if (mc.camera) {
    base = *mc.camera;
  } else {
    base.width = 256;
    base.height = 256;
  }
  try {
    mc.camera = fit_camera(base, lo, hi);
  } catch (const std::invalid_argument& e) {
    throw InputError(mc.source + ": camera: --fit: " + e.what());
  }
  const Camera& c = *mc.camera;
  const auto v = [](const Vec3& x) {
    return "[" + format_number(x.x()) + ", " + format_number(x.y()) + ", " + format_number(x.z()) + "]";
  };
  return "rayint render: --fit: \"camera\": {\"position\": " + v(c.position) + ", \"look_at\": " + v(c.look_at) +
         ", \"up\": " + v(c.up) + ", " +
         (c.projection == Camera::Projection::perspective ? "\"fov_deg\": " + format_number(c.fov_deg)
                                                          : "\"ortho_height\": " + format_number(c.ortho_height)) +
         ", \"width\": " + std::to_string(c.width) + ", \"height\": " + std::to_string(c.height) + "}\n";
}

// What both modes write once the render `r` is done: the image (-o), the heat map with --compare
// (`comparison`, else nullptr), stats(comparison) with --stats, the line of the fitted camera
// (--fit) and, unless -q, summary(comparison).
template <class Render, class Stats, class Summary>
void write_render_outputs(const RenderOptions& options, const Render& r, const MeshRenderComparison* comparison,
                          const std::string& fitted, Stats stats, Summary summary) {
  PngOptions png;
  png.exposure = options.exposure;
  write_image(options.output, r.image, png);
  if (comparison) write_png(comparison->heat_map, error_heat_map(r.rel_error, r.image.width, r.image.height));
  if (!options.stats_path.empty()) write_file_atomically(options.stats_path, stats(comparison).dump(2) + "\n");
  std::fputs(fitted.c_str(), stderr);
  if (!options.quiet) std::fputs(summary(comparison).c_str(), stderr);
}

// The own mode (mesh/cell_traversal.hpp): cells other than tetrahedra in their own interpolation.
void render_own_cells(MeshCase& mc, const RenderOptions& options, const json_source::InputFileLog& read);

}  // namespace

void check_camera_memory(const Camera& camera, int images, bool per_pixel_error, const std::string& where) {
  const double pixels = static_cast<double>(camera.width) * camera.height;
  limits::check(limits::kImageBytes,
                pixels * (static_cast<double>(images) * sizeof(Rgb) + (per_pixel_error ? sizeof(double) : 0.0)),
                where + ": " + std::to_string(camera.width) + " x " + std::to_string(camera.height) + " pixels" +
                    (images > 1 ? " (" + std::to_string(images) + " images)" : std::string()));
}

void check_camera_reaches_mesh(const MeshCase& mc, const std::string& where) {
  const std::vector<Vec3>& points = case_points(mc);
  if (!mc.camera || points.empty()) return;
  Vec3 lo = points.front(), hi = lo;
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  // A point at distance D from the origin is represented to D * 2^-52 (one ulp of D, within a
  // factor 2): once that step exceeds the mesh's extent, every crossing of the mesh is lost and
  // the ray returns the background -- a silent miss. Refused instead (issue 30). For a unit
  // mesh the boundary is ~4.5e15; at 1e-3 of the extent the positions already carry 0.1% error.
  const double extent = (hi - lo).norm();
  const Vec3 centre = (lo + hi) / 2;
  const double distance = std::max((mc.camera->position - centre).norm(), (mc.camera->look_at - centre).norm());
  const double step = distance * std::numeric_limits<double>::epsilon();
  if (!(step < extent))
    throw InputError(where + ": camera.position: " + format_number(distance) + " from the mesh (extent " +
                     format_number(extent) + "): a double's step there (" + format_number(step) +
                     ") exceeds the mesh, every ray would miss it; move the camera closer");
}

void render_mesh_file(const nlohmann::json& root, const RenderOptions& options) {
  const json_source::InputFileLog read;  // the mesh files the case names: shard inputs
  SlowStage reading("rayint render: reading the mesh of " + options.input, options.quiet);
  MeshCase mc = parse_mesh_case(root, options.input, MeshReadOptions{options.strict_mesh, options.split_cells});
  if (mc.cells) {
    reading.done(std::to_string(mc.cells->cell_count()) + " cells, " + std::to_string(mc.cells->points.size()) + " points");
    render_own_cells(mc, options, read);
    return;
  }
  reading.done(std::to_string(mc.mesh.tets.size()) + " tets, " + std::to_string(mc.mesh.points.size()) + " points");
  if (mc.split && !options.quiet) {
    long cells = 0;
    for (const auto& [type, n] : mc.split->cells) cells += type == "tetra" ? 0 : n;
    HeldLines::instance().hold("rayint render: --cells split: " + std::to_string(cells) + " cells tetrahedralised into " +
                               std::to_string(mc.mesh.tets.size()) + " tetrahedra as VTK's vtkDataSetTriangleFilter "
                               "does (an approximation of the cells' own interpolation)");
  }
  const std::string fitted = options.fit ? fit_camera_to_mesh(mc) : std::string();
  if (!mc.camera) throw InputError(options.input + ": camera: required to render a mesh case");
  check_camera_reaches_mesh(mc, options.input);
  // The image, with --compare the compared image and the per-pixel error: before any is taken.
  check_camera_memory(*mc.camera, options.compare.empty() ? 1 : 2, !options.compare.empty(),
                      options.input + ": camera");
  if (!options.compare.empty()) refuse_quadratic_tets(mc.mesh, mc.mesh_source, "render --compare");
  if (mc.shading.enabled) refuse_quadratic_tets(mc.mesh, mc.mesh_source, "render with \"shading\"");
  // Validate the methods before the (long) render.
  const auto exact = make_integrator(parse_method_spec("exact"), mc.transfer);
  std::unique_ptr<RayIntegrator> compare;
  MeshRenderComparison comparison;
  if (!options.compare.empty()) {
    const MethodSpec spec = parse_method_spec(options.compare);
    compare = make_integrator(spec, mc.transfer);
    comparison = {spec.label(), heat_map_path(options.output)};
  }
  // The mesh moves into the traversal (one copy of it in memory, not two: issue 33); the case
  // keeps its other fields.
  SlowStage building("rayint render: building the traversal", options.quiet);
  const TetTraversal mesh(std::move(mc.mesh), std::move(mc.neighbors), mc.mesh_source);
  building.done(std::to_string(mesh.face_count()) + " faces, " + std::to_string(mesh.boundary_face_count()) + " on the boundary");
  MeshRenderSettings settings = render_settings(options);
  // --shard I/N: render the shard's band of rows and write it as a shard file (-o); merging:
  // the image and its figures assembled from the shards' bands, written as a single run would.
  const bool in_shard = !options.shard.empty();
  settings.shard = begin_shard(options.shard, options.output);
  const std::vector<std::string> inputs = run_inputs({options.input}, read);
  if (in_shard) {
    const MeshRender part = render_mesh(mc, mesh, *exact, compare.get(), settings);
    write_shard(options.output, "render", settings.shard, inputs, to_json(mesh_render_part(part, settings.shard)));
    std::fputs(fitted.c_str(), stderr);
    return;
  }
  MeshRender r;
  if (merging()) {
    r = assemble_mesh_render(merged_parts("render", inputs, mesh_render_part_from_json, check_row_band));
  } else {
    r = render_mesh(mc, mesh, *exact, compare.get(), settings);
  }
#ifdef __GLIBC__
  // The render's freed buffers back to the kernel before the outputs are encoded: the heap keeps
  // its free top (main.cpp's M_TOP_PAD / M_TRIM_THRESHOLD), and the encoding's buffers would come
  // on top of it at the render's peak. Issue 33, render at 512 x 512, peak RSS (/usr/bin/time %M)
  // without this call / with it: 50,000 / 46,800 KiB (105k-tet ball), 221,600 / 220,700 KiB
  // (1.05M; before main.cpp's malloc settings: 47,100 and 221,000 KiB).
  malloc_trim(0);
#endif
  write_render_outputs(
      options, r, compare ? &comparison : nullptr, fitted,
      [&](const MeshRenderComparison* c) { return mesh_render_json(mc, mesh, r, c); },
      [&](const MeshRenderComparison* c) { return mesh_render_summary(r, c); });
}

}  // namespace rayint::cli

namespace rayint::cli {
namespace {

void render_own_cells(MeshCase& mc, const RenderOptions& options, const json_source::InputFileLog& read) {
  const std::string fitted = options.fit ? fit_camera_to_mesh(mc) : std::string();
  if (!mc.camera) throw InputError(options.input + ": camera: required to render a mesh case");
  check_camera_reaches_mesh(mc, options.input);
  const bool comparing = !options.compare.empty();
  check_camera_memory(*mc.camera, comparing ? 2 : 1, comparing, options.input + ": camera");
  // --compare METHOD: the method on VTK's split of the same cells (what `--cells split` renders)
  // against the own interpolation: the per-pixel error of the split and the method together.
  std::unique_ptr<RayIntegrator> compare;
  MeshRenderComparison comparison;
  std::unique_ptr<TetTraversal> split;
  if (comparing) {
    const MethodSpec spec = parse_method_spec(options.compare);
    compare = make_integrator(spec, mc.transfer);
    comparison = {spec.label() + " on --cells split", heat_map_path(options.output)};
  }
  const std::vector<std::string> inputs = run_inputs({options.input}, read);
  MeshRenderSettings settings = render_settings(options);
  const bool in_shard = !options.shard.empty();
  settings.shard = begin_shard(options.shard, options.output);
  SlowStage building("rayint render: building the cell traversal", options.quiet);
  if (comparing && !merging()) {
    TetMesh tets = split_cells(*mc.cells);
    repair_tet_mesh(tets, mc.mesh_source);
    split = std::make_unique<TetTraversal>(std::move(tets), mc.mesh_source);
  }
  const CellTraversal mesh(std::move(*mc.cells), mc.mesh_source);
  building.done(std::to_string(mesh.face_count()) + " faces, " + std::to_string(mesh.boundary_face_count()) + " on the boundary");
  if (!options.quiet && !merging()) {
    std::string types;
    for (const auto& [type, n] : cell_counts(mesh.mesh())) types += (types.empty() ? "" : ", ") + std::to_string(n) + " " + type;
    HeldLines::instance().hold("rayint render: mode own: " + types + " integrated in their own (isoparametric) "
                               "interpolation (--cells split: VTK's tetrahedralisation instead)");
    if (mc.repairs.zero_volume > 0)
      HeldLines::instance().hold("rayint render: mode own: " + std::to_string(mc.repairs.zero_volume) +
                                 " zero-volume cells dropped (no volume, no length along any ray; --strict-mesh "
                                 "refuses them)");
  }
  // One band (--shard), the merged bands (rayint merge), or the whole image.
  const auto render_band = [&] {
    CellMeshRender band = render_cell_mesh(mc, mesh, settings);
    if (compare) {
      MeshRenderSettings quiet = settings;
      quiet.progress = nullptr;
      const MeshRender other = render_mesh(mc, *split, *compare, nullptr, quiet);
      compare_cell_mesh_render(band, other.image, settings.shard);
    }
    return band;
  };
  if (in_shard) {
    const CellMeshRender part = render_band();
    write_shard(options.output, "render", settings.shard, inputs, to_json(cell_mesh_render_part(part, settings.shard)));
    return;
  }
  CellMeshRender r;
  if (merging()) {
    const std::vector<CellMeshRenderPart> parts =
        merged_parts("render", inputs, cell_mesh_render_part_from_json, check_row_band);
    try {
      r = assemble_cell_mesh_render(parts);
    } catch (const std::invalid_argument& e) {
      throw InputError(shard_context().files.front() + ": data: " + e.what());
    }
    if (r.image.width != mc.camera->width || r.image.height != mc.camera->height || r.compared.pixels.empty() == comparing)
      throw InputError(shard_context().files.front() + ": data: the shards were rendered with another camera or --compare");
  } else {
    r = render_band();
  }
  write_render_outputs(
      options, r, comparing ? &comparison : nullptr, fitted,
      [&](const MeshRenderComparison* c) { return cell_mesh_render_json(mc, mesh, r, c); },
      [&](const MeshRenderComparison* c) { return cell_mesh_render_summary(r, c); });
  if (r.failed_pixels > 0) {
    std::fprintf(stderr, "rayint render: %ld pixels failed (a cell chord not located or not integrated): NaN in the image\n",
                 r.failed_pixels);
    throw ChecksFailed{};  // written, failures marked: exit 1
  }
}

}  // namespace
}  // namespace rayint::cli
